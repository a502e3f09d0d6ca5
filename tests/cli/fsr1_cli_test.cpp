// FSR 1 through the real binary: `aalab run` renders the EASU rows at the reduced size, runs
// EASU as the rescale and RCAS after it (MethodPlan::sharpen), and `rcas` as a post filter;
// checked against the port's functions on the run's own saved frames.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli_util.h"
#include "io/image_io.h"
#include "methods/fsr1.h"

namespace {

using aalab::clitest::Aalab;
using aalab::clitest::TempDir;

TEST(Fsr1Cli, EasuAndRcasRunInTheirStages) {
  const auto dir = TempDir("fsr1-cli");
  const auto r = Aalab("run --scenes wedges --size 96x54 --ref-spp 4 --repeat 1 --quiet --out " + dir.string() +
                       " --methods none,scale43-easu,scale43-easu-rcas:upscale=1.5,rcas:sharpness=0 2>&1");
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream f(dir / "report.json");
  const auto doc = nlohmann::json::parse(f);
  std::map<std::string, nlohmann::json> rows;
  for (const auto& row : doc["rows"]) rows[row["spec"].get<std::string>()] = row;
  ASSERT_EQ(rows.size(), 4u);
  // 96·0.75 = 72, 54·0.75 = 40.5 -> 41; 96/1.5 = 64, 54/1.5 = 36.
  EXPECT_EQ(rows["scale43-easu"]["render_size"], nlohmann::json::array({72, 41}));
  EXPECT_EQ(rows["scale43-easu-rcas:upscale=1.5"]["render_size"], nlohmann::json::array({64, 36}));
  // Taps per output pixel: EASU's 12 gathers, + RCAS's 5 loads, RCAS alone 5.
  EXPECT_EQ(rows["scale43-easu"]["cost"]["taps_per_px"].get<double>(), 12.0);
  EXPECT_EQ(rows["scale43-easu-rcas:upscale=1.5"]["cost"]["taps_per_px"].get<double>(), 17.0);
  EXPECT_EQ(rows["rcas:sharpness=0"]["cost"]["taps_per_px"].get<double>(), 5.0);
  // `rcas` is RCAS of the 1x frame (`none`'s output), at sharpness 0.
  const aalab::Image8 none = aalab::ReadImage8((dir / rows["none"]["images"]["output"].get<std::string>()).string());
  const aalab::Image8 rcas =
      aalab::ReadImage8((dir / rows["rcas:sharpness=0"]["images"]["output"].get<std::string>()).string());
  EXPECT_TRUE(rcas == aalab::Fsr1Rcas(none, 0.0f, nullptr));
  EXPECT_FALSE(rcas == none);
}

}  // namespace
