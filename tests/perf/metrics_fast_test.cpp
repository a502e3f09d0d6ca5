// Production metric kernels against their simple reference implementations, bit for bit.
#include <gtest/gtest.h>

#include <cstring>

#include "harness/core/parallel.h"
#include "metrics/flip.h"
#include "metrics/ssim.h"
#include "tests/perf/frames.h"

namespace aalab {
namespace {

ImageF RandomImage(int w, int h, int channels, uint64_t seed, bool wild) {
  ImageF img(w, h, channels);
  for (float& v : img.Data()) {
    const uint64_t r = perf_test::NextRandom(seed);
    v = static_cast<float>(r >> 40) / 16777216.0f;
    if (wild && (r & 15) == 0) v = v * 4.0f - 2.0f;  // out-of-range values too
  }
  return img;
}

void ExpectSsimResultSame(const SsimResult& fast, const SsimResult& ref, const std::string& what) {
  ASSERT_EQ(fast.ssim.has_value(), ref.ssim.has_value()) << what;
  EXPECT_EQ(fast.null_reason, ref.null_reason) << what;
  if (fast.ssim) {
    EXPECT_EQ(std::memcmp(&*fast.ssim, &*ref.ssim, sizeof(double)), 0) << what << " " << *fast.ssim << " vs " << *ref.ssim;
  }
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(std::memcmp(&fast.per_channel[c], &ref.per_channel[c], sizeof(double)), 0) << what << " channel " << c;
  }
}

// The streaming production path and the prepared-reference path (the reference's half formed
// once, as a run does) against the reference implementation.
void ExpectSsimSame(const ImageF& a, const ImageF& b, const std::string& what) {
  const SsimResult ref = ComputeSsimReference(a, b);
  ExpectSsimResultSame(ComputeSsim(a, b), ref, what);
  ExpectSsimResultSame(ComputeSsim(a, *PrepareSsimReference(b)), ref, what + " (prepared reference)");
}

TEST(FastPath, SsimEqualsReferenceOnRandomAndRenderedImages) {
  for (auto [w, h] : std::vector<std::pair<int, int>>{{11, 11}, {12, 30}, {31, 11}, {64, 64}, {203, 117}, {10, 40}, {300, 80}, {523, 11}}) {
    for (int channels : {3, 4}) {
      const ImageF a = RandomImage(w, h, channels, 7 + w, false);
      const ImageF b = RandomImage(w, h, channels, 99 + h, true);
      ExpectSsimSame(a, b, std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(channels));
      ExpectSsimSame(a, a, "identical");
    }
  }
  const auto& frames = perf_test::SceneFrames();
  for (size_t i = 0; i + 1 < frames.size(); ++i) {
    ExpectSsimSame(ToFloat(frames[i].img), ToFloat(frames[i + 1].img), frames[i].name + " vs " + frames[i + 1].name);
  }
}

TEST(FastPath, SsimSameAtOneAndTwoThreads) {
  const ImageF a = RandomImage(150, 90, 3, 1, false);
  const ImageF b = RandomImage(150, 90, 3, 2, false);
  SetThreadCount(1);
  const SsimResult one = ComputeSsim(a, b);
  SetThreadCount(2);
  const SsimResult two = ComputeSsim(a, b);
  const SsimResult two_prepared = ComputeSsim(a, *PrepareSsimReference(b));
  SetThreadCount(1);
  const SsimResult one_prepared = ComputeSsim(a, *PrepareSsimReference(b));
  SetThreadCount(0);
  EXPECT_EQ(std::memcmp(&*one.ssim, &*two.ssim, sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(&*one.ssim, &*one_prepared.ssim, sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(&*one.ssim, &*two_prepared.ssim, sizeof(double)), 0);
}

TEST(FastPath, SsimPreparedReferenceRefusesAnotherSize) {
  const ImageF reference = RandomImage(40, 30, 3, 5, false);
  const auto side = PrepareSsimReference(reference);
  EXPECT_THROW(ComputeSsim(RandomImage(41, 30, 3, 6, false), *side), UserError);
  const ImageF grey(40, 30, 1);
  EXPECT_THROW(PrepareSsimReference(grey), UserError);
}

TEST(FastPath, FlipWithReusedReferenceEqualsFreshComputation) {
  const auto& frames = perf_test::SceneFrames();
  const ImageF ref_a = ToFloat(frames[0].img);
  const ImageF ref_b = ToFloat(frames[1].img);
  ImageF ref_a_changed = ref_a;
  ref_a_changed.Data()[12345] = 0.5f;  // one value differs: the cached half must not be reused
  const std::vector<std::pair<const ImageF*, const ImageF*>> calls = {
      {&ref_a, &ref_b}, {&ref_a, &ref_a_changed}, {&ref_a, &ref_a}, {&ref_a_changed, &ref_b}, {&ref_a, &ref_b}, {&ref_b, &ref_a}};
  for (double ppd : {67.0, 30.0}) {  // consecutive calls with one reference: cache hits
    for (size_t k = 0; k < calls.size(); ++k) {
      const std::vector<double> fast = flip::ErrorValues(*calls[k].first, *calls[k].second, ppd);
      const std::vector<double> ref = flip::ErrorValuesUncached(*calls[k].first, *calls[k].second, ppd);
      ASSERT_EQ(fast.size(), ref.size());
      EXPECT_EQ(std::memcmp(fast.data(), ref.data(), fast.size() * sizeof(double)), 0) << "call " << k << " ppd " << ppd;
    }
  }
}

}  // namespace
}  // namespace aalab
