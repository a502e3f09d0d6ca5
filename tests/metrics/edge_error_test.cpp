#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "metrics/families.h"
#include "metrics/metric.h"

namespace aalab {
namespace {

// Scene (32×16, all channels equal):
//  - left half x < 16: detail texture, a checkerboard of 0.25 / 0.75;
//  - right half: black (0) left of a slanted edge, white (1) right of it. The edge crosses
//    row y at e(y) = 20 + y/2, so the reference (exact area coverage) has, in odd rows,
//    pixel floor(e) = 20 + (y−1)/2 half covered: value 0.5; in even rows pixel e is fully
//    white. All values are exact in float.
//  - mask: the three pixels floor(e)−1 .. floor(e)+1 of every row: 16·3 = 48 pixels; the
//    interior is the other 512 − 48 = 464 pixels.
constexpr int kW = 32, kH = 16;

int EdgeColumn(int y) { return 20 + y / 2; }  // floor(20 + y/2)

void Set(ImageF& img, int x, int y, float v) {
  for (int c = 0; c < 3; ++c) img.At(x, y, c) = v;
}

ImageF Reference() {
  ImageF img(kW, kH, 3, 0.0f);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      float v;
      if (x < 16) {
        v = ((x + y) % 2 == 0) ? 0.25f : 0.75f;
      } else {
        const int e = EdgeColumn(y);
        v = x < e ? 0.0f : (x > e ? 1.0f : (y % 2 == 1 ? 0.5f : 1.0f));
      }
      Set(img, x, y, v);
    }
  }
  return img;
}

ImageF Mask() {
  ImageF m(kW, kH, 1, 0.0f);
  for (int y = 0; y < kH; ++y) {
    for (int x = EdgeColumn(y) - 1; x <= EdgeColumn(y) + 1; ++x) m.At(x, y, 0) = 1.0f;
  }
  return m;
}

// Aliased edge: point-sampling the pixel centre. In odd rows the centre of pixel floor(e)
// lies exactly on the edge and is taken as black: error 0.5 on 8 pixels, 0 elsewhere.
ImageF Staircase(ImageF img) {
  for (int y = 1; y < kH; y += 2) Set(img, EdgeColumn(y), y, 0.0f);
  return img;
}

// Texture fully blurred to its mean 0.5: error 0.25 on all 256 texture pixels.
ImageF BlurTexture(ImageF img) {
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < 16; ++x) Set(img, x, y, 0.5f);
  return img;
}

std::vector<MetricValue> RunEdge(const ImageF& image, const ImageF& ref, const ImageF* mask,
                                 const ImageF* none = nullptr) {
  MetricInput in;
  in.image = &image;
  in.reference = &ref;
  in.edge_mask = mask;
  in.none_image = none;
  return EdgeErrorMetrics().at(0).compute(in);
}

const MetricValue& Get(const std::vector<MetricValue>& v, const std::string& name) {
  for (const auto& m : v)
    if (m.name == name) return m;
  throw std::runtime_error("no value " + name);
}

TEST(EdgeError, StaircaseHurtsEdgeOnly) {
  const ImageF ref = Reference(), mask = Mask();
  const auto v = RunEdge(Staircase(ref), ref, &mask);
  // Edge MSE = 8 pixels · 0.5² / 48 = 1/24; PSNR = 10·log10(24) = 13.8021 dB;
  // RMSE = sqrt(1/24) = 0.2041241.
  EXPECT_NEAR(*Get(v, "edge_psnr_db").value, 10.0 * std::log10(24.0), 1e-12);
  EXPECT_NEAR(*Get(v, "edge_rmse").value, std::sqrt(1.0 / 24.0), 1e-15);
  // Interior untouched: identical, PSNR infinite → null.
  EXPECT_FALSE(Get(v, "interior_psnr_db").value.has_value());
  EXPECT_EQ(Get(v, "interior_psnr_db").null_reason, "identical");
}

TEST(EdgeError, BlurHurtsInteriorOnly) {
  const ImageF ref = Reference(), mask = Mask();
  const auto aliased = RunEdge(Staircase(ref), ref, &mask);
  const auto blurred = RunEdge(BlurTexture(Staircase(ref)), ref, &mask);
  // Interior MSE = 256 · 0.25² / 464 = 16/464 = 1/29; PSNR = 10·log10(29) = 14.6240 dB,
  // down from infinite (null) without the blur.
  EXPECT_NEAR(*Get(blurred, "interior_psnr_db").value, 10.0 * std::log10(29.0), 1e-12);
  // The edge numbers do not move at all.
  EXPECT_EQ(*Get(blurred, "edge_psnr_db").value, *Get(aliased, "edge_psnr_db").value);
  EXPECT_EQ(*Get(blurred, "edge_rmse").value, *Get(aliased, "edge_rmse").value);
  // Blur alone (AA-perfect edge): edge identical, interior as above.
  const auto blur_only = RunEdge(BlurTexture(ref), ref, &mask);
  EXPECT_EQ(Get(blur_only, "edge_psnr_db").null_reason, "identical");
  EXPECT_EQ(*Get(blur_only, "edge_rmse").value, 0.0);
  EXPECT_NEAR(*Get(blur_only, "interior_psnr_db").value, 10.0 * std::log10(29.0), 1e-12);
}

TEST(EdgeError, ErrorRemovedHandComputed) {
  const ImageF ref = Reference(), mask = Mask(), none = Staircase(ref);
  // none: MSE_edge = 8 · 0.25 / 48 = 1/24.
  // Half fix: the 8 odd-row edge pixels at 0.25 (error 0.25): MSE_edge = 8 · 0.0625 / 48
  // = 1/96 → removed = 1 − (1/96)/(1/24) = 1 − 1/4 = 0.75.
  ImageF half = ref;
  for (int y = 1; y < kH; y += 2) Set(half, EdgeColumn(y), y, 0.25f);
  EXPECT_NEAR(*Get(RunEdge(half, ref, &mask, &none), "edge_error_removed").value, 0.75, 1e-15);
  // Perfect AA: removed = 1. No change: removed = 0.
  EXPECT_EQ(*Get(RunEdge(ref, ref, &mask, &none), "edge_error_removed").value, 1.0);
  EXPECT_EQ(*Get(RunEdge(none, ref, &mask, &none), "edge_error_removed").value, 0.0);
  // Worse than none: the staircase plus 8 more edge pixels off by 0.5 (even rows, pixel
  // floor(e)+1 set from 1 to 0.5): MSE_edge = 16 · 0.25 / 48 = 1/12 → 1 − 2 = −1.
  ImageF worse = none;
  for (int y = 0; y < kH; y += 2) Set(worse, EdgeColumn(y) + 1, y, 0.5f);
  EXPECT_NEAR(*Get(RunEdge(worse, ref, &mask, &none), "edge_error_removed").value, -1.0, 1e-15);
}

TEST(EdgeError, NullReasons) {
  const ImageF ref = Reference(), mask = Mask(), none = Staircase(ref);
  // No none frame.
  auto v = RunEdge(none, ref, &mask);
  EXPECT_FALSE(Get(v, "edge_error_removed").value);
  EXPECT_EQ(Get(v, "edge_error_removed").null_reason, "no none frame");
  // The none frame has no edge error: the ratio is undefined.
  v = RunEdge(none, ref, &mask, &ref);
  EXPECT_EQ(Get(v, "edge_error_removed").null_reason, "none has no edge error");
  // Empty mask.
  const ImageF empty(kW, kH, 1, 0.0f);
  v = RunEdge(none, ref, &empty, &none);
  for (const char* n : {"edge_psnr_db", "edge_rmse", "edge_error_removed"}) {
    EXPECT_FALSE(Get(v, n).value) << n;
    EXPECT_EQ(Get(v, n).null_reason, "empty mask") << n;
  }
  EXPECT_TRUE(Get(v, "interior_psnr_db").value);  // the whole image is interior
  // Mask covering everything: no interior.
  const ImageF full(kW, kH, 1, 1.0f);
  v = RunEdge(none, ref, &full, &none);
  EXPECT_EQ(Get(v, "interior_psnr_db").null_reason, "mask covers every pixel");
  // No mask at all.
  v = RunEdge(none, ref, nullptr, &none);
  ASSERT_EQ(v.size(), 4u);
  for (const auto& m : v) {
    EXPECT_FALSE(m.value);
    EXPECT_EQ(m.null_reason, "no edge mask");
  }
}

TEST(EdgeError, BadMaskIsUserError) {
  const ImageF ref = Reference();
  const ImageF small(kW - 1, kH, 1, 1.0f), rgb(kW, kH, 3, 1.0f);
  EXPECT_THROW(RunEdge(ref, ref, &small), UserError);
  EXPECT_THROW(RunEdge(ref, ref, &rgb), UserError);
}

}  // namespace
}  // namespace aalab
