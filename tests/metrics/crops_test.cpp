#include "metrics/crops.h"

#include <gtest/gtest.h>

namespace aalab {
namespace {

TEST(Crops, PicksHottestWindowsWithoutOverlap) {
  ImageF s(40, 20, 1, 0.0f);
  s.At(30, 5, 0) = 5.0f;  // hottest spot
  s.At(5, 15, 0) = 2.0f;  // second, far away
  s.At(31, 6, 0) = 1.0f;  // next to the hottest: must not produce an overlapping window
  const auto crops = PickCrops(s, 8, 3);
  ASSERT_EQ(crops.size(), 2u);  // only two windows have a non-zero sum once overlaps are excluded
  // First window holds both hot pixels (sum 6); the tie-break takes the first top-left corner
  // in row-major order: x = 31 − 7 = 24, y = 6 − 7 → clipped at 0.
  EXPECT_EQ(crops[0].x, 24);
  EXPECT_EQ(crops[0].y, 0);
  EXPECT_EQ(crops[0].w, 8);
  EXPECT_LE(crops[1].x, 5);
  EXPECT_GT(crops[1].x + 8, 5);
  EXPECT_LE(crops[1].y, 15);
}

TEST(Crops, ClipsToSmallImagesAndSkipsZeroScore) {
  ImageF s(5, 3, 1, 0.0f);
  EXPECT_TRUE(PickCrops(s, 8, 2).empty());
  s.At(2, 1, 0) = 1.0f;
  const auto c = PickCrops(s, 8, 2);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].w, 5);
  EXPECT_EQ(c[0].h, 3);
}

TEST(Crops, ScoreIsMaskedMeanAbsError) {
  ImageF a(2, 1, 3, 0.0f), b(2, 1, 3, 0.0f), mask(2, 1, 1, 0.0f);
  b.At(0, 0, 0) = 0.3f;
  b.At(1, 0, 2) = 0.6f;
  mask.At(1, 0, 0) = 1.0f;
  const ImageF s = CropScore(a, b, &mask);
  EXPECT_FLOAT_EQ(s.At(0, 0, 0), 0.0f);
  EXPECT_FLOAT_EQ(s.At(1, 0, 0), 0.2f);
}

}  // namespace
}  // namespace aalab
