/// Hashes: FNV-1a 64 for content (output hashes, fingerprints, cache keys) and counter-based
/// hashing for deterministic jitter: a sample's random numbers are a function of (pixel,
/// sample index, seed, dimension), never of a shared generator's state.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

namespace aalab {

/// FNV-1a 64 of `size` bytes, continuing from `h` (the offset basis starts a new hash): the
/// output hashes of the report, the scene fingerprint and the reference cache's keys and
/// checksums.
constexpr uint64_t kFnv1aOffset = 0xcbf29ce484222325ULL;
inline uint64_t Fnv1a64(const void* data, size_t size, uint64_t h = kFnv1aOffset) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= 0x100000001b3ULL;
  }
  return h;
}

/// FNV-1a 64 of bytes, as 16 lowercase hex digits (the report's `output_hash`).
inline std::string HashBytes(const void* data, size_t size) {
  const uint64_t h = Fnv1a64(data, size);
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

/// 64-bit mixer (SplitMix64 finaliser).
inline uint64_t MixBits(uint64_t v) {
  v ^= v >> 30;
  v *= 0xbf58476d1ce4e5b9ULL;
  v ^= v >> 27;
  v *= 0x94d049bb133111ebULL;
  v ^= v >> 31;
  return v;
}

/// 32-bit mixer (the "lowbias32" finaliser: xor-shift, multiply, twice), for synthetic test
/// frames of the GPU tool.
inline uint32_t MixBits32(uint32_t v) {
  v ^= v >> 16;
  v *= 0x7feb352dU;
  v ^= v >> 15;
  v *= 0x846ca68bU;
  v ^= v >> 16;
  return v;
}

/// Hash of a tuple of integers, order-sensitive.
inline uint64_t HashTuple(uint64_t a, uint64_t b, uint64_t c, uint64_t d, uint64_t e = 0) {
  uint64_t h = MixBits(a + 0x9e3779b97f4a7c15ULL);
  h = MixBits(h ^ (b + 0x632be59bd9b4e019ULL));
  h = MixBits(h ^ (c + 0x85157af5a2a6b5f1ULL));
  h = MixBits(h ^ (d + 0xd6e8feb86659fd93ULL));
  h = MixBits(h ^ (e + 0xa0761d6478bd642fULL));
  return h;
}

/// A float in [0, 1) from the top 24 bits of a hash (exactly representable).
inline float HashToUnitFloat(uint64_t h) { return static_cast<float>(h >> 40) * (1.0f / 16777216.0f); }

/// Jitter value in [0, 1) for pixel (x, y), sample index s, seed, dimension dim.
inline float SampleJitter(int x, int y, int s, uint64_t seed, int dim) {
  return HashToUnitFloat(HashTuple(static_cast<uint32_t>(x), static_cast<uint32_t>(y), static_cast<uint32_t>(s), seed,
                                   static_cast<uint32_t>(dim)));
}

}  // namespace aalab
