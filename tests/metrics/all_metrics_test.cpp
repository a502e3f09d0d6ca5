#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/parallel.h"
#include "metrics/metrics.h"
#include "tests/metrics/test_images.h"

namespace aalab {
namespace {

std::vector<std::string> AllOutputs() {
  return ImageMetricKeys();  // what ComputeAllMetrics returns (the sequence rows are not in it)
}

const MetricValue& Get(const std::vector<MetricValue>& v, const std::string& name) {
  for (const auto& m : v)
    if (m.name == name) return m;
  throw std::runtime_error("no value " + name);
}

// Every value is finite or null with a reason: never NaN or Inf.
void ExpectWellFormed(const std::vector<MetricValue>& values, const std::string& what) {
  ASSERT_EQ(values.size(), AllOutputs().size()) << what;
  for (size_t i = 0; i < values.size(); ++i) {
    EXPECT_EQ(values[i].name, AllOutputs()[i]) << what;
    if (values[i].value) {
      EXPECT_TRUE(std::isfinite(*values[i].value)) << what << " " << values[i].name;
    } else {
      EXPECT_FALSE(values[i].null_reason.empty()) << what << " " << values[i].name;
    }
  }
}

MetricInput Input(const ImageF& img, const ImageF& ref, const ImageF* mask = nullptr, const ImageF* none = nullptr) {
  MetricInput in;
  in.image = &img;
  in.reference = &ref;
  in.edge_mask = mask;
  in.none_image = none;
  return in;
}

TEST(AllMetrics, RegistryListsEveryFamily) {
  std::vector<std::string> rows;
  for (const auto& r : MetricRegistry()) rows.push_back(r.name);
  EXPECT_EQ(rows, (std::vector<std::string>{"psnr", "edge", "ssim", "flip", "abs_error", "coverage_bias", "temporal",
                                            "temporal_perceptual"}));
  EXPECT_EQ(AllOutputs(), (std::vector<std::string>{"psnr_db",
                                                    "mse",
                                                    "edge_psnr_db",
                                                    "edge_rmse",
                                                    "interior_psnr_db",
                                                    "edge_error_removed",
                                                    "ssim",
                                                    "flip_mean",
                                                    "flip_median_weighted",
                                                    "flip_max",
                                                    "abs_err_p50",
                                                    "abs_err_p95",
                                                    "abs_err_p99",
                                                    "abs_err_max",
                                                    "area_bias_px2",
                                                    "area_bias_abs_rel",
                                                    "area_bias_rel_r0_1",
                                                    "area_bias_rel_r1_2",
                                                    "area_bias_rel_r2_4",
                                                    "area_bias_rel_r4_8",
                                                    "area_bias_rel_r8_16",
                                                    "area_bias_rel_r16_64"}));
}

TEST(AllMetrics, NoMaskMakesEdgeValuesNull) {
  const auto [a, b] = testimg::MakePair(24, 16, 2);
  const auto v = ComputeAllMetrics(Input(b, a));
  ExpectWellFormed(v, "no mask");
  for (const char* n : {"edge_psnr_db", "edge_rmse", "interior_psnr_db", "edge_error_removed"}) {
    EXPECT_FALSE(Get(v, n).value) << n;
    EXPECT_EQ(Get(v, n).null_reason, "no edge mask") << n;
  }
  EXPECT_TRUE(Get(v, "psnr_db").value);
  EXPECT_TRUE(Get(v, "ssim").value);
}

TEST(AllMetrics, NeverNaN) {
  struct Size {
    int w, h;
  };
  for (Size s : {Size{1, 1}, Size{1, 7}, Size{7, 1}, Size{11, 11}, Size{16, 12}}) {
    const ImageF black(s.w, s.h, 3, 0.0f), white(s.w, s.h, 3, 1.0f);
    ImageF mask(s.w, s.h, 1, 0.0f);
    mask.At(0, 0, 0) = 1.0f;
    const std::string tag = std::to_string(s.w) + "x" + std::to_string(s.h);
    for (const ImageF* m : {static_cast<const ImageF*>(nullptr), static_cast<const ImageF*>(&mask)}) {
      ExpectWellFormed(ComputeAllMetrics(Input(black, black, m, &black)), "black/black " + tag);
      ExpectWellFormed(ComputeAllMetrics(Input(white, black, m, &white)), "white/black " + tag);
      ExpectWellFormed(ComputeAllMetrics(Input(black, white, m)), "black/white " + tag);
    }
    // Black vs black: PSNR null (identical), FLIP and abs error exactly 0.
    const auto same = ComputeAllMetrics(Input(black, black, &mask, &black));
    EXPECT_EQ(Get(same, "psnr_db").null_reason, "identical");
    EXPECT_EQ(Get(same, "edge_error_removed").null_reason, "none has no edge error");
    for (const char* n : {"flip_mean", "flip_median_weighted", "flip_max", "abs_err_max"})
      EXPECT_EQ(*Get(same, n).value, 0.0) << n << " " << tag;
    // White vs black: MSE 1 → PSNR 10·log10(1) = 0 dB; every FLIP pixel 0.9673798.
    const auto wb = ComputeAllMetrics(Input(white, black));
    EXPECT_EQ(*Get(wb, "psnr_db").value, 0.0);
    EXPECT_NEAR(*Get(wb, "flip_max").value, 0.9673797615, 1e-6);  // float32 path: a few ulp
    EXPECT_EQ(*Get(wb, "flip_median_weighted").value, *Get(wb, "flip_max").value);
    EXPECT_EQ(*Get(wb, "abs_err_p50").value, 1.0);
    if (s.w >= 11 && s.h >= 11) {
      // Constant 1 vs 0: SSIM = C1/(1 + C1) = 1e-4/1.0001.
      EXPECT_NEAR(*Get(wb, "ssim").value, 1e-4 / 1.0001, 1e-15);
      EXPECT_EQ(*Get(same, "ssim").value, 1.0);
    } else {
      EXPECT_EQ(Get(wb, "ssim").null_reason, "image smaller than the 11x11 SSIM window");
    }
  }
}

TEST(AllMetrics, NonFiniteInputGivesNullNotNaN) {
  ImageF a(12, 12, 3, 0.5f), b(12, 12, 3, 0.5f);
  b.At(3, 3, 1) = std::nanf("");
  const auto v = ComputeAllMetrics(Input(b, a));
  ExpectWellFormed(v, "nan input");
  EXPECT_EQ(Get(v, "ssim").null_reason, "non-finite result (input has NaN/Inf pixels)");
}

TEST(AllMetrics, ShapeMismatchIsUserError) {
  ImageF a(4, 4, 3), b(4, 5, 3);
  EXPECT_THROW(ComputeAllMetrics(Input(a, b)), UserError);
}

TEST(AllMetrics, BitIdenticalAcrossThreadCounts) {
  const auto [a, b] = testimg::MakePair(96, 64, 3);
  ImageF mask(96, 64, 1, 0.0f);
  for (int y = 0; y < 64; ++y) mask.At(y + 10, y, 0) = 1.0f;
  SetThreadCount(1);
  const auto one = ComputeAllMetrics(Input(b, a, &mask, &b));
  SetThreadCount(2);
  const auto two = ComputeAllMetrics(Input(b, a, &mask, &b));
  SetThreadCount(0);
  ASSERT_EQ(one.size(), two.size());
  for (size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].value, two[i].value) << one[i].name;  // exact, including null-ness
    EXPECT_EQ(one[i].null_reason, two[i].null_reason);
  }
}

}  // namespace
}  // namespace aalab
