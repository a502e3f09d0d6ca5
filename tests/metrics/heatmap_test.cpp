#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "metrics/heatmap.h"

namespace aalab {
namespace {

std::array<uint8_t, 3> Px(const Image8& img, int x) { return {img.At(x, 0, 0), img.At(x, 0, 1), img.At(x, 0, 2)}; }

TEST(Heatmap, PublishedEndpoints) {
  // First/last entries of the published tables (matplotlib _cm_listed.py):
  // viridis #0 (0.267004, 0.004874, 0.329415), #255 (0.993248, 0.906157, 0.143936);
  // magma   #0 (0.001462, 0.000466, 0.013866), #255 (0.987053, 0.991438, 0.749504).
  const auto v0 = ColormapEntry(Colormap::kViridis, 0), v255 = ColormapEntry(Colormap::kViridis, 255);
  const auto m0 = ColormapEntry(Colormap::kMagma, 0), m255 = ColormapEntry(Colormap::kMagma, 255);
  EXPECT_EQ(v0, (std::array<float, 3>{0.267004f, 0.004874f, 0.329415f}));
  EXPECT_EQ(v255, (std::array<float, 3>{0.993248f, 0.906157f, 0.143936f}));
  EXPECT_EQ(m0, (std::array<float, 3>{0.001462f, 0.000466f, 0.013866f}));
  EXPECT_EQ(m255, (std::array<float, 3>{0.987053f, 0.991438f, 0.749504f}));
}

TEST(Heatmap, EndpointsAndClamping) {
  // Values: 0, vmax, 2·vmax (clamped), −1 (clamped), NaN (→ 0), vmax/2 (→ round(127.5) = 128).
  ImageF map(6, 1, 1, 0.0f);
  const float vmax = 0.2f;
  map.At(1, 0, 0) = vmax;
  map.At(2, 0, 0) = 2 * vmax;
  map.At(3, 0, 0) = -1.0f;
  map.At(4, 0, 0) = std::nanf("");
  map.At(5, 0, 0) = 0.1f;
  for (Colormap cm : {Colormap::kViridis, Colormap::kMagma}) {
    const Image8 img = Heatmap(map, vmax, cm);
    ASSERT_EQ(img.Channels(), 4);
    auto q = [&](int index) {
      const auto e = ColormapEntry(cm, index);
      return std::array<uint8_t, 3>{static_cast<uint8_t>(std::lround(e[0] * 255.0f)),
                                    static_cast<uint8_t>(std::lround(e[1] * 255.0f)),
                                    static_cast<uint8_t>(std::lround(e[2] * 255.0f))};
    };
    EXPECT_EQ(Px(img, 0), q(0));
    EXPECT_EQ(Px(img, 1), q(255));
    EXPECT_EQ(Px(img, 2), q(255));
    EXPECT_EQ(Px(img, 3), q(0));
    EXPECT_EQ(Px(img, 4), q(0));
    EXPECT_EQ(Px(img, 5), q(128));  // 0.1f/0.2f = 0.5 exactly: 127.5 rounds half up to 128
    for (int x = 0; x < 6; ++x) EXPECT_EQ(img.At(x, 0, 3), 255);
  }
  // In 8 bits: viridis #0 = (68, 1, 84), #255 = (253, 231, 37); magma #255 = (252, 253, 191).
  EXPECT_EQ(Px(Heatmap(map, vmax, Colormap::kViridis), 0), (std::array<uint8_t, 3>{68, 1, 84}));
  EXPECT_EQ(Px(Heatmap(map, vmax, Colormap::kViridis), 1), (std::array<uint8_t, 3>{253, 231, 37}));
  EXPECT_EQ(Px(Heatmap(map, vmax, Colormap::kMagma), 1), (std::array<uint8_t, 3>{252, 253, 191}));
}

TEST(Heatmap, Errors) {
  ImageF one(2, 2, 1, 0.0f), three(2, 2, 3, 0.0f);
  EXPECT_THROW(Heatmap(one, 0.0f, Colormap::kViridis), UserError);
  EXPECT_THROW(Heatmap(one, -1.0f, Colormap::kViridis), UserError);
  EXPECT_THROW(Heatmap(one, std::nanf(""), Colormap::kViridis), UserError);
  EXPECT_THROW(Heatmap(three, 1.0f, Colormap::kViridis), UserError);
  EXPECT_EQ(ParseColormap("magma"), Colormap::kMagma);
  EXPECT_EQ(ColormapName(ParseColormap("viridis")), "viridis");
  EXPECT_THROW(ParseColormap("jet"), UserError);
}

}  // namespace
}  // namespace aalab
