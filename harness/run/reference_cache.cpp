// The reference cache (harness/run/reference_cache.h). File layout, native byte order (the
// key text names the program, and a program runs on one byte order):
//   "AALABREF" | u32 version (1) | u32 key length | key text
//   | 3 images (reference, edge mask, raw edge mask): i32 w, h, c, w·h·c f32
//   | i32 grid | f64 MSE of the halves | u64 primary, shadow, texture-lookup counters
//   | f64 render ms
//   | u64 FNV-1a 64 of every byte before it
#include "harness/run/reference_cache.h"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "build_info.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/timer.h"
#include "io/image_io.h"
#include "metrics/metric.h"
#include "scenes/exact_reference.h"
#include "scenes/scene_hash.h"

namespace aalab {
namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'A', 'A', 'L', 'A', 'B', 'R', 'E', 'F'};
constexpr uint32_t kVersion = 1;

/// FNV-1a 64 of the running executable's bytes, computed once.
const std::string& ExecutableHash() {
  static const std::string hash = [] {
    std::ifstream f("/proc/self/exe", std::ios::binary);
    if (!f) return std::string("unknown");
    uint64_t h = kFnv1aOffset;
    std::vector<char> buf(1 << 20);
    while (f) {
      f.read(buf.data(), static_cast<std::streamsize>(buf.size()));
      h = Fnv1a64(buf.data(), static_cast<size_t>(f.gcount()), h);
    }
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
    return std::string(text);
  }();
  return hash;
}

class Writer {
 public:
  void Raw(const void* p, size_t n) {
    const size_t at = bytes_.size();
    bytes_.resize(at + n);
    if (n > 0) std::memcpy(bytes_.data() + at, p, n);
  }
  template <typename T>
  void Pod(T v) {
    Raw(&v, sizeof v);
  }
  void Img(const ImageF& im) {
    Pod<int32_t>(im.Width());
    Pod<int32_t>(im.Height());
    Pod<int32_t>(im.Channels());
    Raw(im.Data().data(), im.Data().size() * sizeof(float));
  }
  std::vector<char>& Bytes() { return bytes_; }

 private:
  std::vector<char> bytes_;
};

class Reader {
 public:
  Reader(const std::vector<char>& b, std::string path) : b_(b), path_(std::move(path)) {}
  void Raw(void* p, size_t n) {
    if (n > b_.size() - pos_) Fail("it is shorter than its header says");
    std::memcpy(p, b_.data() + pos_, n);
    pos_ += n;
  }
  template <typename T>
  T Pod() {
    T v;
    Raw(&v, sizeof v);
    return v;
  }
  ImageF Img() {
    const int32_t w = Pod<int32_t>(), h = Pod<int32_t>(), c = Pod<int32_t>();
    if (w < 0 || h < 0 || c < 0 || w > 16384 || h > 16384 || c > 4) Fail("an image size is out of range");
    if (c == 0) return ImageF();  // a default (empty) image
    ImageF im(w, h, c);
    Raw(im.Data().data(), im.Data().size() * sizeof(float));
    return im;
  }
  size_t Pos() const { return pos_; }
  [[noreturn]] void Fail(const std::string& why) const {
    throw UserError("reference cache entry '" + path_ + "' is damaged: " + why + "; delete it and run again");
  }

 private:
  const std::vector<char>& b_;
  std::string path_;
  size_t pos_ = 0;
};

}  // namespace

ReferenceCache::ReferenceCache(std::string dir) : dir_(std::move(dir)) {
  if (dir_.empty()) throw UserError("--ref-cache must not be empty");
  std::error_code ec;
  if (fs::exists(dir_, ec) && !fs::is_directory(dir_, ec)) {
    throw UserError("--ref-cache '" + dir_ + "' exists and is not a folder");
  }
  fs::create_directories(dir_, ec);
  if (ec || !fs::is_directory(dir_)) {
    throw UserError("--ref-cache '" + dir_ + "' cannot be created: " +
                    (ec ? ec.message() : std::string("a file or broken link of that name is in the way")));
  }
}

std::string ReferenceCache::Key(const Scene& scene, int width, int height, int grid, uint64_t seed, bool exact) {
  char content[17];
  std::snprintf(content, sizeof content, "%016llx", static_cast<unsigned long long>(SceneContentHash(scene)));
  std::ostringstream k;
  k << "aalab-reference v1; tool " << AALAB_VERSION << "; commit " << AALAB_GIT_COMMIT << "; executable "
    << ExecutableHash() << "; scene " << scene.name << "; content " << content << "; size " << width << "x" << height
    << "; " << (exact ? std::string("exact") : "grid " + std::to_string(grid) + "; seed " + std::to_string(seed));
  return k.str();
}

std::string ReferenceCache::PathOf(const std::string& key) const {
  char name[24];
  std::snprintf(name, sizeof name, "%016llx.ref", static_cast<unsigned long long>(Fnv1a64(key.data(), key.size())));
  return (fs::path(dir_) / name).string();
}

std::optional<CachedReference> ReferenceCache::Load(const std::string& key) const {
  const std::string path = PathOf(key);
  std::ifstream f(path, std::ios::binary);
  if (!f) return std::nullopt;
  const std::vector<char> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  Reader r(bytes, path);
  if (bytes.size() < sizeof kMagic + 8 + 8) r.Fail("it is too short");
  uint64_t stored_sum = 0;
  std::memcpy(&stored_sum, bytes.data() + bytes.size() - 8, 8);
  if (Fnv1a64(bytes.data(), bytes.size() - 8) != stored_sum) r.Fail("its checksum does not match");
  char magic[8];
  r.Raw(magic, 8);
  if (std::memcmp(magic, kMagic, 8) != 0) r.Fail("it is not an aalab reference cache file");
  if (r.Pod<uint32_t>() != kVersion) r.Fail("it was written by another cache version");
  const uint32_t key_len = r.Pod<uint32_t>();
  if (key_len > 4096) r.Fail("its key is too long");
  std::string stored_key(key_len, '\0');
  r.Raw(stored_key.data(), key_len);
  if (stored_key != key) r.Fail("it holds another reference (key '" + stored_key + "')");
  CachedReference e;
  e.ref.image = r.Img();
  e.ref.edge_mask = r.Img();
  e.ref.edge_mask_raw = r.Img();
  e.ref.grid = r.Pod<int32_t>();
  e.halves_mse = r.Pod<double>();
  e.primary_rays = r.Pod<uint64_t>();
  e.shadow_rays = r.Pod<uint64_t>();
  e.texture_lookups = r.Pod<uint64_t>();
  e.render_ms = r.Pod<double>();
  if (r.Pos() != bytes.size() - 8) r.Fail("it has bytes after the entry");
  return e;
}

void ReferenceCache::Store(const std::string& key, const CachedReference& e) const {
  Writer w;
  w.Raw(kMagic, 8);
  w.Pod<uint32_t>(kVersion);
  w.Pod<uint32_t>(static_cast<uint32_t>(key.size()));
  w.Raw(key.data(), key.size());
  for (const ImageF* im : {&e.ref.image, &e.ref.edge_mask, &e.ref.edge_mask_raw}) w.Img(*im);
  w.Pod<int32_t>(e.ref.grid);
  w.Pod<double>(e.halves_mse);
  w.Pod<uint64_t>(e.primary_rays);
  w.Pod<uint64_t>(e.shadow_rays);
  w.Pod<uint64_t>(e.texture_lookups);
  w.Pod<double>(e.render_ms);
  w.Pod<uint64_t>(Fnv1a64(w.Bytes().data(), w.Bytes().size()));
  // Checked and atomic; the temporary name is unique across threads, processes and hosts
  // (io/image_io.h), and an interruption removes it.
  WriteTextFile(PathOf(key), std::string(w.Bytes().data(), w.Bytes().size()));
}

CachedReference ObtainReference(const Scene& scene, const Tracer& tracer, int W, int H, int grid, uint64_t seed,
                                bool exact, const ReferenceCache* cache, bool* from_cache) {
  const std::string key = cache ? ReferenceCache::Key(scene, W, H, grid, seed, exact) : std::string();
  if (cache) {
    if (auto hit = cache->Load(key)) {
      if (from_cache) *from_cache = true;
      return std::move(*hit);
    }
  }
  if (from_cache) *from_cache = false;
  CachedReference e;
  Stopwatch clock;
  TraceCounters c;
  e.ref = exact ? RenderExactReference(scene, W, H) : RenderReference(tracer, W, H, grid, seed, &c);
  e.render_ms = clock.ElapsedMs();
  e.halves_mse = MeanSquaredError(e.ref.half_a, e.ref.half_b).mse;
  e.primary_rays = c.primary_rays;
  e.shadow_rays = c.shadow_rays;
  e.texture_lookups = c.texture_lookups;
  if (cache) cache->Store(key, e);
  return e;
}

}  // namespace aalab
