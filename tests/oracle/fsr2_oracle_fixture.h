// What the FSR 2 oracle's test files share (tests/oracle/fsr2_oracle_test.cpp,
// tests/oracle/fsr2_accumulate_oracle_test.cpp, tests/oracle/fsr2_chain_oracle_test.cpp): the
// Fsr2Oracle fixture (one class for the whole test suite, as GoogleTest requires), the
// deterministic generator of their inputs and lavapipe's exp2 / log2 / sin (LavapipeMath).
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "tests/oracle/fsr2_shader.h"
#include "tests/skip_or_fail.h"

namespace aalab {

/// A small deterministic generator (no std:: distributions: their output is library-defined).
struct Lcg {
  uint32_t s;
  float Next() {
    s = s * 1664525u + 1013904223u;
    return static_cast<float>(s >> 8) / 16777216.0f;
  }
};

/// Skips (fails under CI) when the FSR2 sources, glslang or lavapipe are missing.
class Fsr2Oracle : public ::testing::Test {
 protected:
  void SetUp() override {
    // lavapipe's LINEAR filter of 8-bit UNORM textures in float (fractions in float32), not its
    // default 8-bit-fraction path: the model the port follows (fsr2_internal.h, SampleLinear).
    // Set before lavapipe starts (the first test's SetUp); the other passes sample no 8-bit texture.
    setenv("GALLIVM_PERF", "no_aos_sampling", 1);
    const std::string why = oracle::Fsr2ShaderAvailable();
    if (!why.empty()) AALAB_SKIP_OR_FAIL_UNDER_CI("FSR2 oracle unavailable: " + why);
  }
};

// exp2, log2 and sin as lavapipe evaluates them: each argument the port asks for is looked up;
// those not known yet are answered by the C library and evaluated on lavapipe by Fill, so
// that the port, rerun until it asks for nothing new, runs on lavapipe's values throughout.
class LavapipeMath : public Fsr2Math {
 public:
  float Exp2(float x) const override { return Look(0, x); }
  float Log2(float x) const override { return Look(1, x); }
  float Sin(float x) const override { return Look(2, x); }
  /// Evaluates the pending arguments on lavapipe; false when there were none.
  bool Fill() {
    std::vector<float> x[3];
    for (int f = 0; f < 3; ++f) {
      for (uint32_t b : pending_[f]) {
        float v;
        std::memcpy(&v, &b, 4);
        x[f].push_back(v);
      }
      pending_[f].clear();
    }
    if (x[0].empty() && x[1].empty() && x[2].empty()) return false;
    const std::vector<float> y = oracle::RunGlslExp2Log2Sin(x[0], x[1], x[2]);
    size_t at = 0;
    for (int f = 0; f < 3; ++f)
      for (float v : x[f]) known_[f][Bits(v)] = y[at++];
    return true;
  }
  /// How many arguments evaluated on lavapipe differ from the C library's result.
  long Differing() const {
    long n = 0;
    for (int f = 0; f < 3; ++f) {
      for (const auto& [b, y] : known_[f]) {
        float x;
        std::memcpy(&x, &b, 4);
        const float c = f == 0 ? std::exp2(x) : f == 1 ? std::log2(x) : std::sin(x);
        n += std::memcmp(&c, &y, 4) != 0;
      }
    }
    return n;
  }
  long Known() const { return static_cast<long>(known_[0].size() + known_[1].size() + known_[2].size()); }

 private:
  static uint32_t Bits(float x) {
    uint32_t b;
    std::memcpy(&b, &x, 4);
    return b;
  }
  float Look(int f, float x) const {
    const auto it = known_[f].find(Bits(x));
    if (it != known_[f].end()) return it->second;
    pending_[f].insert(Bits(x));
    return f == 0 ? std::exp2(x) : f == 1 ? std::log2(x) : std::sin(x);
  }
  std::map<uint32_t, float> known_[3];
  mutable std::set<uint32_t> pending_[3];
};

}  // namespace aalab
