// CMAA2 through the real binary: `aalab run` runs the rows as post filters on the 1x frame
// (checked against the port on the run's own saved `none` frame), `aalab apply` runs one on a
// user's image, and a bad parameter is refused with the allowed values and exit code 1 (docs/cli.md).
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "cli_util.h"
#include "io/image_io.h"
#include "methods/cmaa2.h"

namespace {

using aalab::clitest::Aalab;
using aalab::clitest::TempDir;

TEST(Cmaa2Cli, RunAndApplyMatchThePort) {
  const auto dir = TempDir("cmaa2-cli");
  const auto r = Aalab("run --scenes wedges --size 96x54 --ref-spp 4 --repeat 1 --quiet --out " + dir.string() +
                       " --methods none,cmaa2-low,cmaa2-high:extra_sharpness=1 2>&1");
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream f(dir / "report.json");
  const auto doc = nlohmann::json::parse(f);
  std::map<std::string, nlohmann::json> rows;
  for (const auto& row : doc["rows"]) rows[row["spec"].get<std::string>()] = row;
  ASSERT_EQ(rows.size(), 3u);
  const auto none_png = dir / rows["none"]["images"]["output"].get<std::string>();
  const aalab::Image8 none = aalab::ReadImage8(none_png.string());
  aalab::Cmaa2Params low;
  low.preset = 0;
  aalab::Cmaa2Params sharp;
  sharp.extra_sharpness = true;
  const aalab::Image8 low_out =
      aalab::ReadImage8((dir / rows["cmaa2-low"]["images"]["output"].get<std::string>()).string());
  const aalab::Image8 sharp_out =
      aalab::ReadImage8((dir / rows["cmaa2-high:extra_sharpness=1"]["images"]["output"].get<std::string>()).string());
  EXPECT_TRUE(low_out == aalab::Cmaa2(none, low));
  EXPECT_TRUE(sharp_out == aalab::Cmaa2(none, sharp));
  EXPECT_FALSE(low_out == none);
  // apply on the same frame gives the same bytes.
  const auto out = dir / "applied.png";
  const auto a = Aalab("apply --method cmaa2-low " + none_png.string() + " " + out.string() + " 2>&1");
  ASSERT_EQ(a.code, 0) << a.output;
  EXPECT_TRUE(aalab::ReadImage8(out.string()) == low_out);
}

TEST(Cmaa2Cli, BadParameterIsRefused) {
  const auto dir = TempDir("cmaa2-cli-bad");
  const auto r = Aalab("run --scenes wedges --size 32x18 --ref-spp 4 --quiet --out " + dir.string() +
                       " --methods cmaa2-high:edges=rgb 2>&1");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("edges"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("luma"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "report.json"));
}

}  // namespace
