// The raster path as a user runs it (docs/gpu.md "The raster path"): `aalab export-geometry`,
// then `aalab_raster`, then `aalab run --gpu-timings` / `aalab merge-gpu`; and the refusals
// of each (one message, exit 1, nothing half-written).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/cli/cli_util.h"
#include "tests/skip_or_fail.h"

namespace aalab {
namespace {

namespace fs = std::filesystem;
using clitest::Aalab;
using clitest::CmdResult;
using clitest::RunCommand;

CmdResult Raster(const std::string& args) {
  return RunCommand(std::string(AALAB_BINARY_DIR) + "/aalab_raster " + args + " 2>&1");
}

std::string Slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

/// The pixels of a binary PPM (P6, 255) written by aalab or aalab_raster.
std::string PpmPixels(const fs::path& p, int* w, int* h) {
  std::ifstream f(p, std::ios::binary);
  std::string magic;
  int maxval = 0;
  f >> magic >> *w >> *h >> maxval;
  f.get();
  std::string px(static_cast<size_t>(*w) * *h * 3, '\0');
  f.read(px.data(), static_cast<std::streamsize>(px.size()));
  EXPECT_EQ(magic, "P6");
  EXPECT_TRUE(f.good()) << p;
  return px;
}

/// Whether aalab_raster could make a context here (its message otherwise).
std::string RasterUnavailable(const CmdResult& r) {
  if (r.code == 1 && r.output.find("no OpenGL 4.5 context") != std::string::npos) return r.output;
  return "";
}

TEST(RasterCli, ExportGeometryRefusesWhatTheRasterPathCannotDraw) {
  const fs::path dir = clitest::TempDir("raster-cli-refuse");
  const CmdResult r = Aalab("export-geometry --scenes wedges,thin-wires --out " + (dir / "geo").string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("cannot draw scene 'thin-wires'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("analytic shape"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "geo"));
  EXPECT_FALSE(fs::exists(dir / "geo.partial"));
  // --skip-unsupported takes the synthetic suite's triangle scenes and names the others.
  const CmdResult s = Aalab("export-geometry --suite synthetic --skip-unsupported --out " + (dir / "all").string());
  ASSERT_EQ(s.code, 0) << s.output;
  EXPECT_TRUE(fs::exists(dir / "all" / "wedges.geom"));
  EXPECT_TRUE(fs::exists(dir / "all" / "mesh.geom"));
  EXPECT_TRUE(fs::exists(dir / "all" / "checker-plane.geom"));
  EXPECT_TRUE(fs::exists(dir / "all" / "detail-texture.geom"));
  EXPECT_TRUE(fs::exists(dir / "all" / "sdf-circles.geom"));
  EXPECT_TRUE(fs::exists(dir / "all" / "circle.geom"));
  EXPECT_TRUE(fs::exists(dir / "all" / "hdr-edges.geom"));
  EXPECT_FALSE(fs::exists(dir / "all" / "thin-wires.geom"));
  const std::string tsv = Slurp(dir / "all" / "geometry.tsv");
  EXPECT_NE(tsv.find("# skipped thin-wires: it has an analytic shape"), std::string::npos) << tsv;
  EXPECT_NE(tsv.find("# skipped specular-spheres: it"), std::string::npos) << tsv;
  EXPECT_NE(tsv.find("# skipped sdf-wires: it has an analytic shape"), std::string::npos) << tsv;
  EXPECT_TRUE(fs::exists(dir / "all" / "shadow-stipple.geom"));
  EXPECT_NE(tsv.find("mesh\t3200\tmesh.geom"), std::string::npos) << tsv;
}

TEST(RasterCli, RasterToolRefusesBadInput) {
  const fs::path dir = clitest::TempDir("raster-cli-bad");
  ASSERT_EQ(Aalab("export-geometry --scenes wedges --out " + (dir / "geo").string()).code, 0);
  CmdResult r = Raster("--geometry " + (dir / "geo").string() + " --methods none,msaa-3x");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("unknown raster method 'msaa-3x'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("msaa-4x"), std::string::npos) << r.output;  // says what is allowed
  r = Raster("--geometry " + (dir / "geo").string() + " --sizes 320x");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("--sizes height"), std::string::npos) << r.output;
  r = Raster("--geometry " + (dir / "geo").string() + " --budget-ms -5");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("--budget-ms '-5' is not an integer in 0..3600000"), std::string::npos) << r.output;
  r = Raster("--geometry " + (dir / "geo").string() + " --min-repeat 0");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("--min-repeat '0' is not an integer in 1..100000"), std::string::npos) << r.output;
  // A truncated scene file: the reader names the file and where it ends.
  const std::string bytes = Slurp(dir / "geo" / "wedges.geom");
  std::ofstream(dir / "cut.geom", std::ios::binary) << bytes.substr(0, bytes.size() - 10);
  r = Raster("--geometry " + (dir / "cut.geom").string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("truncated"), std::string::npos) << r.output;
  std::ofstream(dir / "not.geom", std::ios::binary) << "P6\n1 1\n255\nabc";
  r = Raster("--geometry " + (dir / "not.geom").string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("not a raster scene file"), std::string::npos) << r.output;
}

// The default suite on the user's path: export-geometry writes all four scenes (the three
// glTF scenes as AALABRG3 files with their mip chains), aalab_raster draws real-glossy (a
// normal-mapped GGX floor; no cut-outs or silhouettes in view), and its frame is within 1
// code of export-frames' 1× frame at every pixel (raster_test states the tolerance).
TEST(RasterCli, DefaultSuiteGltfSceneReachesTheFrame) {
  const fs::path dir = clitest::TempDir("raster-cli-gltf");
  const CmdResult g = Aalab("export-geometry --suite default --out " + (dir / "geo").string());
  ASSERT_EQ(g.code, 0) << g.output;
  for (const char* name : {"real-foliage", "real-fence", "real-glossy", "wedges"}) {
    EXPECT_TRUE(fs::exists(dir / "geo" / (std::string(name) + ".geom"))) << name;
  }
  EXPECT_EQ(Slurp(dir / "geo" / "real-glossy.geom").substr(0, 8), "AALABRG3");
  EXPECT_EQ(Slurp(dir / "geo" / "geometry.tsv").find("# skipped"), std::string::npos);
  const CmdResult r = Raster("--geometry " + (dir / "geo" / "real-glossy.geom").string() +
                             " --sizes 320x180 --methods none --repeat 0 --frames " + (dir / "fr").string());
  if (const std::string why = RasterUnavailable(r); !why.empty()) AALAB_SKIP_OR_FAIL_UNDER_CI(why);
  ASSERT_EQ(r.code, 0) << r.output;
  ASSERT_EQ(Aalab("export-frames --scenes real-glossy --sizes 320x180 --no-scaled --out " + (dir / "ef").string()).code,
            0);
  int w = 0, h = 0, w2 = 0, h2 = 0;
  const std::string a = PpmPixels(dir / "ef" / "real-glossy-320x180.ppm", &w, &h);
  const std::string b = PpmPixels(dir / "fr" / "real-glossy-320x180-none.ppm", &w2, &h2);
  ASSERT_EQ(w, 320);
  ASSERT_EQ(w2, 320);
  ASSERT_EQ(a.size(), b.size());
  int worst = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    worst = std::max(worst, std::abs(int(static_cast<uint8_t>(a[i])) - int(static_cast<uint8_t>(b[i]))));
  }
  EXPECT_LE(worst, 1);
}

// export-geometry → aalab_raster → the frame, against export-frames' 1× frame of the same
// scene and size (within 1 code per channel: wedges has no pixel centre near an edge at this
// size; raster_test.cpp states the tolerance), then run --gpu-timings → report rows.
TEST(RasterCli, FramesAndTimingsReachTheReport) {
  const fs::path dir = clitest::TempDir("raster-cli-run");
  ASSERT_EQ(Aalab("export-geometry --scenes wedges --out " + (dir / "geo").string()).code, 0);
  const CmdResult r = Raster("--geometry " + (dir / "geo").string() +
                             " --sizes 320x180 --methods none,msaa-4x,ssaa-2x2 --warmup 1 --repeat 3 --frames " +
                             (dir / "fr").string() + " --json " + (dir / "t.json").string());
  if (const std::string why = RasterUnavailable(r); !why.empty()) AALAB_SKIP_OR_FAIL_UNDER_CI(why);
  ASSERT_EQ(r.code, 0) << r.output;
  ASSERT_EQ(Aalab("export-frames --scenes wedges --sizes 320x180 --no-scaled --out " + (dir / "ef").string()).code, 0);
  int w = 0, h = 0, w2 = 0, h2 = 0;
  const std::string a = PpmPixels(dir / "ef" / "wedges-320x180.ppm", &w, &h);
  const std::string b = PpmPixels(dir / "fr" / "wedges-320x180-none.ppm", &w2, &h2);
  ASSERT_EQ(w, 320);
  ASSERT_EQ(h2, 180);
  int worst = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    worst = std::max(worst, std::abs(int(static_cast<uint8_t>(a[i])) - int(static_cast<uint8_t>(b[i]))));
  }
  EXPECT_LE(worst, 1);
  const nlohmann::json t = nlohmann::json::parse(Slurp(dir / "t.json"));
  EXPECT_EQ(t.at("schema"), "aalab-raster-timings");
  ASSERT_EQ(t.at("rows").size(), 3u);
  EXPECT_EQ(t.at("rows")[1].at("method"), "msaa-4x");
  EXPECT_GE(t.at("rows")[1].at("samples").get<int>(), 4);
  // Every row says how many frames it timed (3 wedges frames at 320×180 fit the default
  // 1000 ms budget many times over); nothing was refused.
  EXPECT_EQ(t.at("budget_ms").get<double>(), 1000.0);
  EXPECT_TRUE(t.at("refused").empty());
  for (const auto& row : t.at("rows")) {
    EXPECT_EQ(row.at("repeat").get<int>(), 3);
    EXPECT_EQ(row.at("warmup").get<int>(), 1);
    EXPECT_GT(row.at("draw").at("min_ms").get<double>(), 0.0);
    EXPECT_GT(row.at("encode").at("min_ms").get<double>(), 0.0);
  }

  // A bad timings file is refused before the run writes anything.
  std::ofstream(dir / "bad.json") << R"({"schema": "aalab-raster-timings", "schema_version": 2})";
  CmdResult run = Aalab("run --scenes wedges --methods none --size 160x90 --quiet --out " + (dir / "r0").string() +
                        " --gpu-timings " + (dir / "bad.json").string());
  EXPECT_EQ(run.code, 1);
  EXPECT_NE(run.output.find("schema_version 2 is not supported"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(dir / "r0"));

  run = Aalab("run --scenes wedges --methods none,msaa-4x,fxaa-high --size 160x90 --quiet --out " +
              (dir / "r1").string() + " --gpu-timings " + (dir / "t.json").string());
  ASSERT_EQ(run.code, 0) << run.output;
  EXPECT_NE(run.output.find("merged GPU raster timings"), std::string::npos) << run.output;
  const nlohmann::json rep = nlohmann::json::parse(Slurp(dir / "r1" / "report.json"));
  int with = 0;
  for (const auto& row : rep.at("rows")) {
    if (!row.contains("gpu_raster")) {
      EXPECT_EQ(row.at("spec"), "fxaa-high");  // a post filter: not drawn by the raster path
      continue;
    }
    ++with;
    const auto& s = row.at("gpu_raster").at("sizes").at("320x180");
    EXPECT_GT(s.at("median_ms").get<double>(), 0.0);
    if (row.at("spec") == "none") EXPECT_DOUBLE_EQ(s.at("ratio_to_1x").get<double>(), 1.0);
    EXPECT_EQ(row.at("gpu_raster").at("device"), t.at("device"));
  }
  EXPECT_EQ(with, 2);
  EXPECT_NE(Slurp(dir / "r1" / "index.html").find("gpu_raster"), std::string::npos);
}

// A frame time the tool cannot trust is refused, not written: with msaa-4x's draw query
// reading 0 ns (the H100 run's symptom, injected by the test hook), stderr names the row and
// why, the JSON holds the other rows and lists msaa-4x under "refused", and the exit status
// is 2 (the --json file is still whole: its rows are checked ones).
TEST(RasterCli, ZeroFrameTimesAreRefusedNotReported) {
  const fs::path dir = clitest::TempDir("raster-cli-refuse");
  ASSERT_EQ(Aalab("export-geometry --scenes wedges --out " + (dir / "geo").string()).code, 0);
  const CmdResult r = RunCommand("AALAB_RASTER_TEST_ZERO_STAGE=msaa-4x:draw " + std::string(AALAB_BINARY_DIR) +
                                 "/aalab_raster --geometry " + (dir / "geo").string() +
                                 " --sizes 160x90 --methods none,msaa-4x,ssaa-2x2 --warmup 1 --repeat 3 --json " +
                                 (dir / "t.json").string() + " 2>&1");
  if (const std::string why = RasterUnavailable(r); !why.empty()) AALAB_SKIP_OR_FAIL_UNDER_CI(why);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("timing of wedges 160x90 msaa-4x refused: the draw stage's GL_TIME_ELAPSED query "
                          "returned 0 ns"),
            std::string::npos)
      << r.output;
  const nlohmann::json t = nlohmann::json::parse(Slurp(dir / "t.json"));
  ASSERT_EQ(t.at("rows").size(), 2u);
  EXPECT_EQ(t.at("rows")[0].at("method"), "none");
  EXPECT_EQ(t.at("rows")[1].at("method"), "ssaa-2x2");
  ASSERT_EQ(t.at("refused").size(), 1u);
  EXPECT_NE(t.at("refused")[0].get<std::string>().find("wedges 160x90 msaa-4x"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "t.json.partial"));
}

// The H100's check in miniature: export-frames --render-methods writes aalab's MSAA / SSAA
// frames, aalab_raster --compare measures its own frames against them into the JSON.
TEST(RasterCli, CompareAgainstExportedFrames) {
  const fs::path dir = clitest::TempDir("raster-cli-compare");
  ASSERT_EQ(Aalab("export-geometry --scenes wedges --out " + (dir / "geo").string()).code, 0);
  CmdResult e = Aalab("export-frames --scenes wedges --sizes 320x180 --no-scaled --render-methods fxaa-high --out " +
                      (dir / "bad").string());
  EXPECT_EQ(e.code, 1);
  EXPECT_NE(e.output.find("'fxaa-high' is not an MSAA or ordered-grid SSAA method"), std::string::npos) << e.output;
  EXPECT_FALSE(fs::exists(dir / "bad"));
  e = Aalab("export-frames --scenes wedges --sizes 320x180 --no-scaled --render-methods msaa-4x,ssaa-2x2 --out " +
            (dir / "ef").string());
  ASSERT_EQ(e.code, 0) << e.output;
  const CmdResult r =
      Raster("--geometry " + (dir / "geo").string() + " --sizes 320x180 --methods none,msaa-4x,ssaa-2x2 " +
             "--repeat 0 --compare " + (dir / "ef").string() + " --json " + (dir / "c.json").string());
  if (const std::string why = RasterUnavailable(r); !why.empty()) AALAB_SKIP_OR_FAIL_UNDER_CI(why);
  ASSERT_EQ(r.code, 0) << r.output;
  const nlohmann::json c = nlohmann::json::parse(Slurp(dir / "c.json"));
  ASSERT_EQ(c.at("rows").size(), 3u);
  // none: identical (raster_test); MSAA 4x: the few samples within snapping distance of an
  // edge may flip (measured 4 pixels of 57 600 on llvmpipe); SSAA 2x2: within 1 code.
  EXPECT_EQ(c.at("rows")[0].at("fidelity").at("max_diff"), 0);
  EXPECT_GE(c.at("rows")[1].at("fidelity").at("within_1_share").get<double>(), 0.999);
  EXPECT_LE(c.at("rows")[2].at("fidelity").at("max_diff").get<int>(), 1);
}

// The procedural-texture scenes and a disk on the user's path: export-geometry →
// aalab_raster --compare against export-frames' 1× frames. detail-texture (noise, texel
// centres on pixel centres) and circle (a lambert disk under a point light; no pixel centre
// within the float slack of its outline at this size) within 1 code everywhere;
// shadow-stipple (shadow rays in the fragment shader) identical but for 2 pixels on a box's
// edge (raster_test's rule); checker-plane identical except where a
// pixel centre's uv lies at a checker boundary near the horizon (raster_test's rule; measured 9 pixels of 57 600 on
// llvmpipe).
TEST(RasterCli, TexturedDiskAndShadowScenesMatchExportedFrames) {
  const fs::path dir = clitest::TempDir("raster-cli-surfaces");
  ASSERT_EQ(Aalab("export-geometry --scenes detail-texture,checker-plane,circle,shadow-stipple --out " +
                  (dir / "geo").string())
                .code,
            0);
  ASSERT_EQ(Aalab("export-frames --scenes detail-texture,checker-plane,circle,shadow-stipple --sizes 320x180 "
                  "--no-scaled --out " +
                  (dir / "ef").string())
                .code,
            0);
  const CmdResult r = Raster("--geometry " + (dir / "geo").string() + " --sizes 320x180 --methods none --repeat 0 " +
                             "--compare " + (dir / "ef").string() + " --json " + (dir / "c.json").string());
  if (const std::string why = RasterUnavailable(r); !why.empty()) AALAB_SKIP_OR_FAIL_UNDER_CI(why);
  ASSERT_EQ(r.code, 0) << r.output;
  const nlohmann::json c = nlohmann::json::parse(Slurp(dir / "c.json"));
  ASSERT_EQ(c.at("rows").size(), 4u);
  for (const auto& row : c.at("rows")) {
    const auto& f = row.at("fidelity");
    if (row.at("scene") == "detail-texture" || row.at("scene") == "circle") {
      EXPECT_LE(f.at("max_diff").get<int>(), 1) << row;
    } else {
      EXPECT_TRUE(row.at("scene") == "checker-plane" || row.at("scene") == "shadow-stipple") << row;
      EXPECT_GE(f.at("within_1_share").get<double>(), 0.999) << row;
      EXPECT_GE(f.at("identical_share").get<double>(), 0.999) << row;
    }
  }
}

// `aaa` and `scale43` on the user's path. aaa: aalab renders triangles under aaa exactly as
// under none (methods/aaa.cpp; the run's output hashes say so), so the raster path draws
// aaa's row as the 1× frame on a triangle scene (wedges: identical to export-frames' 1×
// frame, as none is) and refuses it, with the reason under "not_drawn", on a scene with an
// analytic disk (circle), where aalab's coverage comes from the disk's distance. scale43: its
// render at round(4/3·W) × round(4/3·H) (320×180 → 427×240: 426.67 rounds up, 240 exact),
// compared with export-frames' -scaled.ppm (wedges: identical at this size; circle: within
// 1 code, as its 1× frame), the row keeping the output size and naming the render size.
TEST(RasterCli, AaaOnTrianglesAndScale43Render) {
  const fs::path dir = clitest::TempDir("raster-cli-aaa");
  const CmdResult run =
      Aalab("run --scenes wedges --methods none,aaa --size 160x90 --quiet --out " + (dir / "run").string());
  ASSERT_EQ(run.code, 0) << run.output;
  const nlohmann::json rep = nlohmann::json::parse(Slurp(dir / "run" / "report.json"));
  ASSERT_EQ(rep.at("rows").size(), 2u);
  EXPECT_EQ(rep.at("rows")[0].at("output_hash"), rep.at("rows")[1].at("output_hash"));
  ASSERT_EQ(Aalab("export-geometry --scenes wedges,circle --out " + (dir / "geo").string()).code, 0);
  ASSERT_EQ(Aalab("export-frames --scenes wedges,circle --sizes 320x180 --out " + (dir / "ef").string()).code, 0);
  const CmdResult r =
      Raster("--geometry " + (dir / "geo").string() +
             " --sizes 320x180 --methods none,aaa,scale43 --warmup 1 --repeat 2 --compare " + (dir / "ef").string() +
             " --frames " + (dir / "fr").string() + " --json " + (dir / "t.json").string());
  if (const std::string why = RasterUnavailable(r); !why.empty()) AALAB_SKIP_OR_FAIL_UNDER_CI(why);
  ASSERT_EQ(r.code, 0) << r.output;
  const nlohmann::json t = nlohmann::json::parse(Slurp(dir / "t.json"));
  ASSERT_EQ(t.at("not_drawn").size(), 1u);
  const std::string skipped = t.at("not_drawn")[0];
  EXPECT_EQ(skipped.rfind("circle 320x180 aaa: ", 0), 0u) << skipped;
  EXPECT_NE(skipped.find("analytic disk"), std::string::npos) << skipped;
  EXPECT_NE(r.output.find("skipped aaa on circle at 320x180"), std::string::npos) << r.output;
  std::map<std::string, nlohmann::json> rows;
  for (const auto& row : t.at("rows"))
    rows[row.at("scene").get<std::string>() + " " + row.at("method").get<std::string>()] = row;
  ASSERT_EQ(rows.size(), 5u);  // circle: none, scale43; wedges: none, aaa, scale43
  EXPECT_EQ(rows.count("circle aaa"), 0u);
  EXPECT_EQ(rows.at("wedges aaa").at("fidelity").at("max_diff"), 0);
  EXPECT_EQ(Slurp(dir / "fr" / "wedges-320x180-aaa.ppm"), Slurp(dir / "fr" / "wedges-320x180-none.ppm"));
  for (const char* scene : {"wedges", "circle"}) {
    const auto& s = rows.at(std::string(scene) + " scale43");
    EXPECT_EQ(s.at("width"), 320);
    EXPECT_EQ(s.at("height"), 180);
    EXPECT_EQ(s.at("render_width"), 427);
    EXPECT_EQ(s.at("render_height"), 240);
    EXPECT_GT(s.at("draw").at("min_ms").get<double>(), 0.0);
    EXPECT_LE(s.at("fidelity").at("max_diff").get<int>(), std::string(scene) == "wedges" ? 0 : 1) << s;
    int w = 0, h = 0;
    PpmPixels(dir / "fr" / (std::string(scene) + "-320x180-scale43.ppm"), &w, &h);
    EXPECT_EQ(w, 427);
    EXPECT_EQ(h, 240);
  }
  EXPECT_FALSE(rows.at("wedges none").contains("render_width"));
}

}  // namespace
}  // namespace aalab
