// What the FSR 2 oracle's test files share (tests/oracle/fsr2_oracle_test.cpp,
// tests/oracle/fsr2_accumulate_oracle_test.cpp): the Fsr2Oracle fixture (one class for the
// whole test suite, as GoogleTest requires) and the deterministic generator of their inputs.
#pragma once
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <string>

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

}  // namespace aalab
