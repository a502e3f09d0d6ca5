// `--reference exact` and the aaa family through the CLI: refusals name the scene and the
// disqualifying field and leave nothing behind; a run on sdf-circles writes an exact
// reference with a null noise floor (and says why) and the aaa cost counters.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_util.h"

namespace aalab::clitest {
namespace {
namespace fs = std::filesystem;

TEST(CliExactReference, RefusesNonFlatScenesAndUnknownKinds) {
  const fs::path dir = TempDir("exact_ref_bad");
  const std::string out = (dir / "r").string();
  CmdResult r = Aalab("run --scenes circle --reference exact --methods none --size 64x36 --out " + out + " 2>&1");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("scene 'circle' cannot have --reference exact: /effects declares 'lambert'"),
            std::string::npos)
      << r.output;
  r = Aalab("run --scenes sdf-circles --reference analytic --methods none --size 64x36 --out " + out + " 2>&1");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("--reference 'analytic' is not allowed (allowed: sampled, exact)"), std::string::npos)
      << r.output;
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(CliExactReference, RunWritesTheExactReferenceAndAaaCounters) {
  const fs::path dir = TempDir("exact_ref_run");
  const fs::path out = dir / "r";
  const CmdResult r = Aalab(
      "run --scenes sdf-circles --reference exact --methods none,aaa --size 240x135 --repeat 1 "
      "--quiet --out " +
      out.string() + " 2>&1");
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream f(out / "report.json");
  const auto doc = nlohmann::json::parse(f);
  const auto& ref = doc.at("scenes").at(0).at("reference");
  EXPECT_EQ(ref.at("kind"), "exact");
  EXPECT_TRUE(ref.at("noise_floor_psnr_db").is_null());
  bool saw_setting = false;
  for (auto it = doc.at("settings").begin(); it != doc.at("settings").end(); ++it) {
    if (it.key() == "ref_spp") saw_setting = it.value() == "exact";
  }
  EXPECT_TRUE(saw_setting);
  const auto& aaa = doc.at("rows").at(1);
  ASSERT_EQ(aaa.at("method"), "aaa");
  const double share = aaa.at("cost").at("analytic_edge_share").get<double>();
  EXPECT_GT(share, 0.5);
  EXPECT_LE(share, 1.0);
  EXPECT_FALSE(doc.at("rows").at(0).at("cost").contains("analytic_edge_share"));
  // aaa beats none against the exact truth on its own test card.
  EXPECT_GT(aaa.at("metrics").at("psnr_db").get<double>(),
            doc.at("rows").at(0).at("metrics").at("psnr_db").get<double>() + 5);
  std::ifstream h(out / "index.html");
  std::stringstream ss;
  ss << h.rdbuf();
  EXPECT_NE(ss.str().find("infinite: the exact reference has no sampling noise"), std::string::npos);
}

}  // namespace
}  // namespace aalab::clitest
