// The commands of sharded runs through the executable, as a Slurm array task or a
// Kubernetes pod types them (docs/cluster.md): run --shard K/N, merge, same-results and their
// exit codes and messages.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "cli_util.h"

namespace aalab {
namespace {
namespace fs = std::filesystem;
using clitest::Aalab;
using clitest::TempDir;

const char* kArgs =
    " --scenes circle,wedges,thin-wires --methods none,fxaa311-p39,ssaa-2x2 --size 47x29 --ref-spp 16 "
    "--repeat 1 --quiet";

TEST(ClusterCli, ShardMergeAndSameResults) {
  const fs::path dir = TempDir("cluster-cli");
  const std::string d = dir.string();
  ASSERT_EQ(Aalab(std::string("run") + kArgs + " --out " + d + "/single").code, 0);
  for (int k = 0; k < 2; ++k) {
    const auto r = Aalab(std::string("run") + kArgs + " --shard " + std::to_string(k) + "/2 --ref-cache " + d +
                         "/cache --out " + d + "/s" + std::to_string(k));
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("shard " + std::to_string(k) + "/2: " + (k == 0 ? "2" : "1") + " of 3 scenes"),
              std::string::npos)
        << r.output;
  }
  auto merged = Aalab("merge " + d + "/s1 " + d + "/s0 --out " + d + "/merged");
  ASSERT_EQ(merged.code, 0) << merged.output;
  EXPECT_NE(merged.output.find("merged 2 run shards: 3 scenes, 9 results"), std::string::npos) << merged.output;
  auto same = Aalab("same-results " + d + "/single " + d + "/merged");
  EXPECT_EQ(same.code, 0) << same.output;
  // One byte of one image changed: exit 1, the file named.
  const fs::path png = dir / "merged" / "images" / "wedges" / "fxaa311-p39.png";
  std::string bytes;
  {
    std::ifstream f(png, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  }
  ASSERT_GT(bytes.size(), 100u);
  bytes[bytes.size() - 20] ^= 0x10;
  std::ofstream(png, std::ios::binary | std::ios::trunc) << bytes;
  same = Aalab("same-results " + d + "/single " + d + "/merged");
  EXPECT_EQ(same.code, 1) << same.output;
  EXPECT_NE(same.output.find("images/wedges/fxaa311-p39.png: the bytes differ"), std::string::npos) << same.output;
  // Could not compare: exit 2.
  same = Aalab("same-results " + d + "/single " + d + "/nowhere");
  EXPECT_EQ(same.code, 2) << same.output;
  EXPECT_NE(same.output.find("holds neither report.json nor sweep.json"), std::string::npos) << same.output;
  fs::remove_all(dir);
}

TEST(ClusterCli, BadShardArgumentsAreRefusedBeforeAnyWork) {
  const fs::path dir = TempDir("cluster-cli-bad");
  const std::string d = dir.string();
  auto r = Aalab(std::string("run") + kArgs + " --shard 2/2 --out " + d + "/x");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("--shard '2/2': K must be below N"), std::string::npos) << r.output;
  r = Aalab(std::string("sweep --scenes circle --method fxaa311-p39 --grid subpix=0,1 --shard 1 --out ") + d + "/y");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("--shard '1': not of the form K/N"), std::string::npos) << r.output;
  r = Aalab(std::string("run") + kArgs + " --references-only --shard 0/2");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("--references-only needs --ref-cache DIR"), std::string::npos) << r.output;
  r = Aalab("merge " + d + " --out " + d + "/m");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("holds neither report.json nor sweep.json"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "x"));
  EXPECT_FALSE(fs::exists(dir / "y"));
  EXPECT_FALSE(fs::exists(dir / "m"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace aalab
