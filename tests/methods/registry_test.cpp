#include "methods/registry.h"

#include <gtest/gtest.h>

#include <set>

#include "core/error.h"

namespace aalab {
namespace {

TEST(MethodRegistry, NamesAreUniqueKebabCase) {
  std::set<std::string> seen;
  for (const auto& e : MethodRegistry()) {
    EXPECT_TRUE(seen.insert(e.name).second) << e.name;
    for (char c : e.name) {
      EXPECT_TRUE((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-') << e.name;
    }
    EXPECT_FALSE(e.help.empty()) << e.name;
  }
}

TEST(MethodRegistry, SupersamplePlans) {
  EXPECT_EQ(MakeMethod("none").render.SamplesPerPixel(), 1);
  EXPECT_EQ(MakeMethod("ssaa-2x2").render.SamplesPerPixel(), 4);
  EXPECT_EQ(MakeMethod("ssaa-4x4").render.SamplesPerPixel(), 16);
  EXPECT_EQ(MakeMethod("ssaa-rgss").render.SamplesPerPixel(), 4);
  EXPECT_EQ(MakeMethod("ssaa-jitter:spp=32").render.SamplesPerPixel(), 32);
  EXPECT_EQ(MakeMethod("ssaa-jitter:spp=32").spec, "ssaa-jitter:spp=32");
  EXPECT_EQ(MakeMethod("ssaa-jitter").spec, "ssaa-jitter");
}

TEST(MethodRegistry, RgssHasOneSamplePerRowAndColumn) {
  // A rotated grid puts exactly one sample in each row and column of the 4x4 sub-grid.
  auto offs = MakeMethod("ssaa-rgss").render.FixedOffsets();
  std::set<int> rows, cols;
  for (auto [x, y] : offs) {
    cols.insert(static_cast<int>(x * 4));
    rows.insert(static_cast<int>(y * 4));
  }
  EXPECT_EQ(rows.size(), 4u);
  EXPECT_EQ(cols.size(), 4u);
}

TEST(MethodRegistry, OrderedGridOffsets) {
  auto offs = MakeMethod("ssaa-2x2").render.FixedOffsets();
  ASSERT_EQ(offs.size(), 4u);
  EXPECT_FLOAT_EQ(offs[0].first, 0.25f);
  EXPECT_FLOAT_EQ(offs[3].second, 0.75f);
}

TEST(MethodRegistry, ErrorsNameValidChoices) {
  try {
    MakeMethod("fxaa9");
    FAIL();
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("ssaa-4x4"), std::string::npos);
  }
  EXPECT_THROW(MakeMethod("none:spp=2"), UserError);
  EXPECT_THROW(MakeMethod("ssaa-jitter:spp=0"), UserError);
}

// Whole-number overrides and ranges read as the user wrote them: "corner_rounding=20", not the
// "2e+01" printf's shortest "%.1g" gave, in the canonical spec (report rows, compare keys) and in
// `aalab list methods` (SMAA's ranges [0..20], [0..100], [0..10] as methods/smaa.cpp documents).
TEST(MethodRegistry, WholeNumbersSpelledInFull) {
  EXPECT_EQ(MakeMethod("smaa-ultra:corner_rounding=20").spec, "smaa-ultra:corner_rounding=20");
  EXPECT_EQ(MakeMethod("smaa-high:max_search_steps_diag=20,corner_rounding=100").spec,
            "smaa-high:max_search_steps_diag=20,corner_rounding=100");
  std::string help;
  for (const auto& e : MethodRegistry()) {
    for (const auto& p : e.params) help += p.Describe() + "\n";
  }
  EXPECT_NE(help.find("max_search_steps_diag=16 [0..20] integer"), std::string::npos);
  EXPECT_NE(help.find("corner_rounding=25 [0..100] integer"), std::string::npos);
  EXPECT_NE(help.find("local_contrast=2 [0..10]"), std::string::npos);
  EXPECT_EQ(help.find("e+0"), std::string::npos) << help;
}

}  // namespace
}  // namespace aalab
