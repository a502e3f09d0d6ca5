#include "core/params.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace aalab {
namespace {

std::vector<ParamDef> Defs() {
  return {FloatParam("subpix", 0.75, 0.0, 1.0, "sub-pixel amount"), IntParam("steps", 12, 1, 64, "search steps"),
          ChoiceParam("luma", "rec601", {"rec601", "green"}, "luma source")};
}

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

TEST(Params, ParseSpec) {
  Spec s = ParseSpec("fxaa311-p39:subpix=0.5,luma=green");
  EXPECT_EQ(s.name, "fxaa311-p39");
  ASSERT_EQ(s.overrides.size(), 2u);
  EXPECT_EQ(s.overrides[1].first, "luma");
  EXPECT_EQ(ParseSpec("none").overrides.size(), 0u);
}

TEST(Params, ParseSpecErrors) {
  EXPECT_NE(ErrorOf([] { ParseSpec(":a=1"); }).find("empty name"), std::string::npos);
  EXPECT_NE(ErrorOf([] { ParseSpec("x:"); }).find("no key=value"), std::string::npos);
  EXPECT_NE(ErrorOf([] { ParseSpec("x:a"); }).find("not key=value"), std::string::npos);
  EXPECT_NE(ErrorOf([] { ParseSpec("x:a=1,a=2"); }).find("given twice"), std::string::npos);
}

TEST(Params, ResolveDefaultsAndOverrides) {
  ParamValues v = ResolveParams("m", Defs(), {{"steps", "16"}});
  EXPECT_DOUBLE_EQ(v.Number("subpix"), 0.75);
  EXPECT_EQ(v.Int("steps"), 16);
  EXPECT_EQ(v.Choice("luma"), "rec601");
  ASSERT_EQ(v.Overridden().size(), 1u);
}

TEST(Params, ResolveErrorsListAllowed) {
  auto e = ErrorOf([] { ResolveParams("method 'm'", Defs(), {{"sub", "1"}}); });
  EXPECT_NE(e.find("unknown parameter 'sub'"), std::string::npos);
  EXPECT_NE(e.find("subpix=0.75 [0..1]"), std::string::npos);
  e = ErrorOf([] { ResolveParams("m", Defs(), {{"subpix", "1.5"}}); });
  EXPECT_NE(e.find("out of range"), std::string::npos);
  e = ErrorOf([] { ResolveParams("m", Defs(), {{"subpix", "abc"}}); });
  EXPECT_NE(e.find("not a number"), std::string::npos);
  e = ErrorOf([] { ResolveParams("m", Defs(), {{"subpix", "nan"}}); });
  EXPECT_NE(e.find("not a number"), std::string::npos);
  e = ErrorOf([] { ResolveParams("m", Defs(), {{"steps", "2.5"}}); });
  EXPECT_NE(e.find("integer"), std::string::npos);
  e = ErrorOf([] { ResolveParams("m", Defs(), {{"luma", "blue"}}); });
  EXPECT_NE(e.find("rec601, green"), std::string::npos);
  e = ErrorOf([] { ResolveParams("m", {}, {{"x", "1"}}); });
  EXPECT_NE(e.find("takes no parameters"), std::string::npos);
}

TEST(Params, SplitCommaList) {
  EXPECT_EQ(SplitCommaList("a,b,c", "--x"), (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_TRUE(SplitCommaList("", "--x").empty());
  EXPECT_NE(ErrorOf([] { SplitCommaList("a,,b", "--x"); }).find("--x 'a,,b' has an empty item"), std::string::npos);
  EXPECT_NE(ErrorOf([] { SplitCommaList(",a", "--x"); }).find("has an empty item"), std::string::npos);
  EXPECT_NE(ErrorOf([] { SplitCommaList("a,", "--x"); }).find("ends with a comma"), std::string::npos);
}

TEST(Params, FormatNumberShortestRoundTrip) {
  EXPECT_EQ(FormatNumber(0.125), "0.125");
  EXPECT_EQ(FormatNumber(16), "16");
  EXPECT_EQ(FormatNumber(0.166), "0.166");
  EXPECT_EQ(FormatNumber(1.0 / 3.0), "0.3333333333333333");  // 16 digits suffice
}

}  // namespace
}  // namespace aalab
