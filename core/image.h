/// Image containers: interleaved channels, row-major, origin top-left, y down.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/error.h"

namespace aalab {

/// std::allocator, except that a value constructed without arguments is default-initialised
/// (left unset for arithmetic T) instead of value-initialised (zeroed): Image's storage, so that
/// an image made with kUninitialized costs no fill. Copies, fills and comparisons are as
/// std::vector's.
template <typename T>
struct DefaultInitAllocator : std::allocator<T> {
  using value_type = T;
  template <typename U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() noexcept = default;
  template <typename U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}  // NOLINT: converting, as std::allocator's
  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// Tag for Image's constructor that leaves the values unset: only for an image whose every
/// value the caller writes before anything reads it (a filter's output written whole).
struct Uninitialized {};
inline constexpr Uninitialized kUninitialized{};

/// For tests: every image made with kUninitialized from now on has every byte set to `byte`
/// (0..255) instead of left unset, so that a value its maker forgot to write shows; -1 (the
/// default) turns it off. Process-wide; set it while no image is being made.
void SetUninitializedPoison(int byte);
/// The byte SetUninitializedPoison set, or -1.
int UninitializedPoison();

/// An interleaved image of `channels` values of type T per pixel. Pixel (x, y) covers
/// [x, x+1) × [y, y+1); its centre is (x + 0.5, y + 0.5).
template <typename T>
class Image {
 public:
  /// The values, interleaved: a std::vector whose allocator leaves new values unset unless
  /// given one (see DefaultInitAllocator).
  using Storage = std::vector<T, DefaultInitAllocator<T>>;

  Image() = default;
  /// A width × height image with `channels` channels, every value set to `fill`.
  Image(int width, int height, int channels, T fill = T{}) : width_(width), height_(height), channels_(channels) {
    AALAB_CHECK(width >= 0 && height >= 0 && channels > 0, "bad image dimensions");
    data_.assign(static_cast<size_t>(width) * height * channels, fill);
  }
  /// A width × height image with `channels` channels whose values are left unset (no fill
  /// pass): the caller writes every value before anything reads the image.
  Image(int width, int height, int channels, Uninitialized) : width_(width), height_(height), channels_(channels) {
    AALAB_CHECK(width >= 0 && height >= 0 && channels > 0, "bad image dimensions");
    data_.resize(static_cast<size_t>(width) * height * channels);
    if (const int poison = UninitializedPoison(); poison >= 0 && !data_.empty()) {
      std::memset(static_cast<void*>(data_.data()), poison, data_.size() * sizeof(T));
    }
  }
  /// A width × height image taking over `data` (width·height·channels values, interleaved).
  Image(int width, int height, int channels, Storage data)
      : width_(width), height_(height), channels_(channels), data_(std::move(data)) {
    AALAB_CHECK(
        width >= 0 && height >= 0 && channels > 0 && data_.size() == static_cast<size_t>(width) * height * channels,
        "bad image dimensions or data size");
  }

  int Width() const { return width_; }
  int Height() const { return height_; }
  int Channels() const { return channels_; }
  bool Empty() const { return width_ == 0 || height_ == 0; }
  size_t PixelCount() const { return static_cast<size_t>(width_) * height_; }

  /// Value of channel c at pixel (x, y); no bounds check beyond the debug-free invariant.
  T& At(int x, int y, int c) { return data_[Index(x, y) + c]; }
  const T& At(int x, int y, int c) const { return data_[Index(x, y) + c]; }
  /// Pointer to the first channel of pixel (x, y).
  T* Pixel(int x, int y) { return &data_[Index(x, y)]; }
  const T* Pixel(int x, int y) const { return &data_[Index(x, y)]; }
  T* Row(int y) { return &data_[Index(0, y)]; }
  const T* Row(int y) const { return &data_[Index(0, y)]; }

  Storage& Data() { return data_; }
  const Storage& Data() const { return data_; }

  bool operator==(const Image& o) const {
    return width_ == o.width_ && height_ == o.height_ && channels_ == o.channels_ && data_ == o.data_;
  }

 private:
  size_t Index(int x, int y) const { return (static_cast<size_t>(y) * width_ + x) * channels_; }
  int width_ = 0;
  int height_ = 0;
  int channels_ = 0;
  Storage data_;
};

/// Float image: linear or sRGB-encoded values, as the owner documents (usually 3 channels).
using ImageF = Image<float>;
/// 8-bit RGBA frame, the "back buffer": values k/255 when read as UNORM.
using Image8 = Image<uint8_t>;

/// Converts an 8-bit frame to float (k / 255), keeping the first `channels` channels.
ImageF ToFloat(const Image8& img, int channels = 3);
/// Quantizes float values in [0, 1] (clamped) to 8 bits with round-to-nearest, as a UNORM
/// store does; output is RGBA with alpha = 255 when the input has 3 channels.
Image8 ToUnorm8(const ImageF& img);

}  // namespace aalab
