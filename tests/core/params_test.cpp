#include "core/params.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "core/error.h"
#include "core/format.h"

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

// Whole numbers whose shortest digits are fewer than their integer digits: printf's "%.1g" read
// back as 20 and printed "2e+01"; `aalab list methods` showed SMAA's ranges as "[0..2e+01]".
// The rule (fewest digits that read back; fixed notation from 1e-4 up to 1e6) worked by hand.
TEST(Params, FormatNumberSpellsWholeNumbersInFull) {
  EXPECT_EQ(FormatNumber(20), "20");
  EXPECT_EQ(FormatNumber(100), "100");
  EXPECT_EQ(FormatNumber(10), "10");
  EXPECT_EQ(FormatNumber(2), "2");
  EXPECT_EQ(FormatNumber(0), "0");
  EXPECT_EQ(FormatNumber(-0.0), "-0");
  EXPECT_EQ(FormatNumber(-300), "-300");
  EXPECT_EQ(FormatNumber(1000), "1000");
  EXPECT_EQ(FormatNumber(250000), "250000");
  EXPECT_EQ(FormatNumber(999999), "999999");
  EXPECT_EQ(FormatNumber(1e6), "1e+06");        // from 1e6 on: scientific, as "%g" by default
  EXPECT_EQ(FormatNumber(1e9), "1e+09");        // scene limits read "<= 1e+09" as before
  EXPECT_EQ(FormatNumber(1234567), "1234567");  // 7 digits needed: "%.7g" is fixed
  EXPECT_EQ(FormatNumber(0.001), "0.001");
  EXPECT_EQ(FormatNumber(0.0001), "0.0001");
  EXPECT_EQ(FormatNumber(2.5e-5), "2.5e-05");  // below 1e-4: scientific
}

TEST(Params, FormatNumberReadsBackAsTheSameDouble) {
  uint64_t x = 0x9E3779B97F4A7C15ull;
  for (int i = 0; i < 20000; ++i) {
    x ^= x << 13, x ^= x >> 7, x ^= x << 17;
    double v = 0;
    std::memcpy(&v, &x, sizeof v);
    if (!std::isfinite(v)) continue;
    const std::string t = FormatNumber(v);
    EXPECT_EQ(std::strtod(t.c_str(), nullptr), v) << t;
    EXPECT_EQ(FormatNumber(std::strtod(t.c_str(), nullptr)), t);
  }
  for (int k = -40; k <= 40; ++k) {
    const double v = std::ldexp(1.0, k) * 3;
    EXPECT_EQ(std::strtod(FormatNumber(v).c_str(), nullptr), v);
  }
}

TEST(Params, RespellSpecNumbersMatchesOlderReportsToTodaysSpecs) {
  EXPECT_EQ(RespellSpecNumbers("smaa-ultra:corner_rounding=2e+01"), "smaa-ultra:corner_rounding=20");
  EXPECT_EQ(RespellSpecNumbers("smaa-high:diag=on,max_search_steps_diag=2e+01,corner_rounding=1e+02"),
            "smaa-high:diag=on,max_search_steps_diag=20,corner_rounding=100");
  EXPECT_EQ(RespellSpecNumbers("none"), "none");
  EXPECT_EQ(RespellSpecNumbers("fxaa311:edge_threshold=0.125"), "fxaa311:edge_threshold=0.125");
  EXPECT_EQ(RespellSpecNumbers("x:k=1e+09"), "x:k=1e+09");  // already today's spelling
  EXPECT_EQ(RespellSpecNumbers("x:mode=edge,k=3E1"), "x:mode=edge,k=30");
  EXPECT_EQ(RespellSpecNumbers("x:k=one,j=e5,m=1e400"), "x:k=one,j=e5,m=1e400");  // not finite numbers
  EXPECT_EQ(RespellSpecNumbers("x:"), "x:");
  EXPECT_EQ(RespellNumber("2e+01"), "20");
  EXPECT_EQ(RespellNumber("green"), "green");
}

// FormatDouble (core/format.h): the text snprintf makes, whole. A goal line of make bench lost
// its last words when the helper cut its output at 63 bytes.
TEST(Format, FormatDoubleIsWholeAtAnyLength) {
  EXPECT_EQ(FormatDouble("%.2f", 1.5), "1.50");
  EXPECT_EQ(FormatDouble("%.1f×", 4.25), "4.2×");  // round half to even: 4.25 is exact
  const std::string head(62, 'a');
  EXPECT_EQ(FormatDouble((head + "%.0f").c_str(), 7.0), head + "7");    // 63 bytes: fits the buffer
  EXPECT_EQ(FormatDouble((head + "%.0f").c_str(), 70.0), head + "70");  // 64 bytes: one past it
  const std::string tail = "; two 1-thread runs at once, same rounds: %.2f× one run's throughput";
  EXPECT_EQ(FormatDouble(tail.c_str(), 1.94), "; two 1-thread runs at once, same rounds: 1.94× one run's throughput");
}

}  // namespace
}  // namespace aalab
