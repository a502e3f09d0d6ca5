/// Image containers: interleaved channels, row-major, origin top-left, y down.
#pragma once
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/error.h"

namespace aalab {

/// An interleaved image of `channels` values of type T per pixel. Pixel (x, y) covers
/// [x, x+1) × [y, y+1); its centre is (x + 0.5, y + 0.5).
template <typename T>
class Image {
 public:
  Image() = default;
  /// A width × height image with `channels` channels, every value set to `fill`.
  Image(int width, int height, int channels, T fill = T{}) : width_(width), height_(height), channels_(channels) {
    AALAB_CHECK(width >= 0 && height >= 0 && channels > 0, "bad image dimensions");
    data_.assign(static_cast<size_t>(width) * height * channels, fill);
  }
  /// A width × height image taking over `data` (width·height·channels values, interleaved).
  Image(int width, int height, int channels, std::vector<T> data)
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

  std::vector<T>& Data() { return data_; }
  const std::vector<T>& Data() const { return data_; }

  bool operator==(const Image& o) const {
    return width_ == o.width_ && height_ == o.height_ && channels_ == o.channels_ && data_ == o.data_;
  }

 private:
  size_t Index(int x, int y) const { return (static_cast<size_t>(y) * width_ + x) * channels_; }
  int width_ = 0;
  int height_ = 0;
  int channels_ = 0;
  std::vector<T> data_;
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
