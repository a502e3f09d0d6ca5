// The CPU side of the GPU timings through the CLI: `aalab export-frames` writes the frames a
// run's post filters see, and `aalab merge-gpu` attaches aalab_gpu's JSON to a report.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "io/image_io.h"
#include "io/ppm.h"
#include "tests/cli/cli_util.h"

namespace aalab {
namespace {

namespace fs = std::filesystem;
using clitest::Aalab;
using clitest::RunCommand;
using clitest::TempDir;

std::string ReadText(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// One small run shared by the tests: 33×17 (odd), wedges, none + two post filters.
const fs::path& RunDir() {
  static const fs::path dir = [] {
    const fs::path d = TempDir("gpu-cli") / "run";
    const auto r = Aalab(
        "run --scenes wedges --methods none,fxaa1-p3,fxaa311-p39 --size 33x17 --ref-spp 4 "
        "--repeat 1 --quiet --out " +
        d.string());
    EXPECT_EQ(r.code, 0) << r.output;
    return d;
  }();
  return dir;
}

TEST(ExportFrames, WritesTheRunsFrameAndTheRenderScaleFrame) {
  const fs::path out = TempDir("gpu-export") / "frames";
  const auto r = Aalab("export-frames --scenes wedges --sizes 33x17 --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string tsv = ReadText(out / "frames.tsv");
  EXPECT_NE(tsv.find("wedges\t1x\t33\t17\twedges-33x17.ppm\n"), std::string::npos) << tsv;
  EXPECT_NE(tsv.find("wedges\tscaled\t33\t17\twedges-33x17-scaled.ppm\n"), std::string::npos) << tsv;
  const Image8 frame = ReadPpm((out / "wedges-33x17.ppm").string());
  // scale43 renders at round(4/3 · size): 33 → 44, 17 → 22.67 → 23.
  const Image8 scaled = ReadPpm((out / "wedges-33x17-scaled.ppm").string());
  EXPECT_EQ(scaled.Width(), 44);
  EXPECT_EQ(scaled.Height(), 23);
  // The 1x frame is the `none` output of `aalab run` at the same size and seed, byte for byte.
  const auto report = nlohmann::json::parse(ReadText(RunDir() / "report.json"));
  std::string none_png;
  for (const auto& row : report.at("rows")) {
    if (row.at("method") == "none") none_png = row.at("images").at("output").get<std::string>();
  }
  ASSERT_FALSE(none_png.empty());
  const Image8 none = ReadImage8((RunDir() / none_png).string());
  ASSERT_EQ(frame.Width(), 33);
  ASSERT_EQ(frame.Height(), 17);
  EXPECT_EQ(frame.Data(), none.Data());
}

TEST(ExportFrames, BadSizeIsAnErrorAndLeavesNothing) {
  const fs::path out = TempDir("gpu-export-bad") / "frames";
  const auto r = Aalab("export-frames --scenes wedges --sizes 33x0 --out " + out.string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("33x0"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(out.string() + ".partial"));
}

TEST(ExportFrames, TaaFramesAreJitteredRendersWithTheirPreviousPositions) {
  const fs::path dir = TempDir("gpu-export-taa");
  const fs::path out = dir / "frames";
  const auto r = Aalab("export-frames --scenes wedges --sizes 33x17 --no-scaled --taa-frames 3 --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string tsv = ReadText(out / "frames.tsv");
  for (int t = 0; t < 3; ++t) {
    const std::string stem = "wedges-33x17-taa-f" + std::to_string(t);
    EXPECT_NE(tsv.find("wedges\ttaa-" + std::to_string(t) + "\t33\t17\t" + stem + ".ppm\n"), std::string::npos) << tsv;
    EXPECT_EQ(fs::exists(out / (stem + ".prev")), t > 0) << stem;
  }
  // Frame 0 is taa's first render: `aalab run --methods taa` on one frame has no history, so its
  // output is that render decoded and encoded again (EncodeSrgb8(SrgbDecode8(k)) = k).
  const fs::path run = dir / "run";
  const auto rr =
      Aalab("run --scenes wedges --methods taa --size 33x17 --ref-spp 4 --repeat 1 --quiet --out " + run.string());
  ASSERT_EQ(rr.code, 0) << rr.output;
  std::string taa_png;
  const auto report = nlohmann::json::parse(ReadText(run / "report.json"));
  for (const auto& row : report.at("rows")) {
    if (row.at("method") == "taa") taa_png = row.at("images").at("output").get<std::string>();
  }
  ASSERT_FALSE(taa_png.empty());
  EXPECT_EQ(ReadPpm((out / "wedges-33x17-taa-f0.ppm").string()).Data(), ReadImage8((run / taa_png).string()).Data());
  // Frames 0 and 1 are jittered differently (Halton points 1 and 2), so they differ on edges.
  EXPECT_NE(ReadPpm((out / "wedges-33x17-taa-f0.ppm").string()).Data(),
            ReadPpm((out / "wedges-33x17-taa-f1.ppm").string()).Data());
  // wedges is still: every pixel's sample reprojects to its own centre (the jitter is taken
  // back out), up to the float rounding of the projection.
  const std::vector<float> prev = ReadPreviousPositions((out / "wedges-33x17-taa-f2.prev").string(), 33, 17);
  for (int y = 0; y < 17; ++y) {
    for (int x = 0; x < 33; ++x) {
      const size_t i = 2 * (static_cast<size_t>(y) * 33 + x);
      EXPECT_NEAR(prev[i], x + 0.5, 1e-3) << x << "," << y;
      EXPECT_NEAR(prev[i + 1], y + 0.5, 1e-3) << x << "," << y;
    }
  }
}

TEST(ExportFrames, TaaFramesBeyondAMovingScenesSequenceAreRefused) {
  const fs::path out = TempDir("gpu-export-taa-bad") / "frames";
  const auto r = Aalab("export-frames --scenes motion-pan --sizes 33x17 --taa-frames 65 --out " + out.string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("motion-pan"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("64"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST(MergeGpu, AddsBlocksToMatchingRowsAndRedrawsThePage) {
  const fs::path dir = TempDir("gpu-merge") / "run";
  fs::copy(RunDir(), dir, fs::copy_options::recursive);
  const fs::path gpu = dir.parent_path() / "gpu.json";
  std::ofstream(gpu) << R"({"schema": "aalab-gpu-timings", "schema_version": 1,
    "generated_utc": "2026-11-22T20:00:00Z", "device": {"name": "NVIDIA H100 80GB HBM3"},
    "driver": "580.159.04", "cuda_runtime": "13.0", "results": [
    {"scene": "wedges", "size": "1920x1080", "method": "copy", "kernels": "copy",
     "median_ms": 0.016, "min_ms": 0.015, "max_ms": 0.017, "ratio_to_copy": 1},
    {"scene": "wedges", "size": "1920x1080", "method": "fxaa311-p39", "kernels": "luma-rec601 + fxaa311",
     "median_ms": 0.052, "min_ms": 0.051, "max_ms": 0.06, "ratio_to_copy": 3.25,
     "fidelity": {"identical_share": 0.9991, "max_diff": 12}}]})";
  const auto r = Aalab("merge-gpu " + dir.string() + " " + gpu.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("into 1 of 3 rows"), std::string::npos) << r.output;
  const auto report = nlohmann::json::parse(ReadText(dir / "report.json"));
  int blocks = 0;
  for (const auto& row : report.at("rows")) {
    if (!row.contains("gpu")) continue;
    ++blocks;
    EXPECT_EQ(row.at("method"), "fxaa311-p39");
    EXPECT_EQ(row.at("gpu").at("device"), "NVIDIA H100 80GB HBM3");
    EXPECT_DOUBLE_EQ(row.at("gpu").at("sizes").at("1920x1080").at("median_ms").get<double>(), 0.052);
    EXPECT_DOUBLE_EQ(row.at("gpu").at("sizes").at("1920x1080").at("copy_ms").get<double>(), 0.016);
  }
  EXPECT_EQ(blocks, 1);
  EXPECT_NE(ReadText(dir / "index.html").find("NVIDIA H100 80GB HBM3"), std::string::npos);
}

TEST(MergeGpu, FileMatchingNoRowIsAnErrorAndChangesNothing) {
  const fs::path dir = TempDir("gpu-merge-none") / "run";
  fs::copy(RunDir(), dir, fs::copy_options::recursive);
  const std::string before = ReadText(dir / "report.json");
  const fs::path gpu = dir.parent_path() / "gpu.json";
  std::ofstream(gpu) << R"({"schema": "aalab-gpu-timings", "schema_version": 1, "generated_utc": "x",
    "device": {"name": "G"}, "driver": "1", "cuda_runtime": "13.0", "results": [
    {"scene": "circle", "size": "8x8", "method": "fxaa1-p3", "kernels": "fxaa1",
     "median_ms": 1, "min_ms": 1, "max_ms": 1, "ratio_to_copy": 1}]})";
  const auto r = Aalab("merge-gpu " + dir.string() + " " + gpu.string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("none of the report's rows"), std::string::npos) << r.output;
  EXPECT_EQ(ReadText(dir / "report.json"), before);
}

// The default run's GPU recipe in miniature, on the user's path: one `aalab run` takes an
// aalab_raster file and an aalab_gpu file as a comma list and an aalab_vk file (aalab-gpu-
// timings schema, tool aalab_vk) by repeating the option, merged in that order. The raster
// file's aaa row (the 1x frame) gives aaa its block; its scale43 row (the render at 44x23 for
// 33x17: 4/3 of 17 = 22.67 rounds to 23) is the render part of scale43-fxaa-high, whose
// FXAA + rescale block comes from the CUDA file; cmaa2-high's block from the Vulkan file. The
// files and their numbers are written here, so every expected value follows from them.
TEST(MergeGpu, SeveralFilesFromOneRunPutEveryPartOnThePage) {
  const fs::path dir = TempDir("gpu-merge-many");
  const std::string raster_row = R"({"scene": "wedges", "width": 33, "height": 17, "method": "M", "samples": 1,X
     "total": {"median_ms": T, "min_ms": 0.1, "max_ms": 9}, "draw": {"median_ms": 0.1, "min_ms": 0, "max_ms": 0},
     "resolve": {"median_ms": 0, "min_ms": 0, "max_ms": 0}, "encode": {"median_ms": 0.1, "min_ms": 0, "max_ms": 0}})";
  auto row = [&](const std::string& m, const std::string& t, const std::string& extra) {
    std::string r = raster_row;
    r.replace(r.find("\"M\""), 3, "\"" + m + "\"");
    r.replace(r.find("X\n"), 1, extra);
    r.replace(r.find("T,"), 1, t);
    return r;
  };
  std::ofstream(dir / "raster.json") << R"({"schema": "aalab-raster-timings", "schema_version": 1,
    "device": "GL H100", "gl_version": "4.5", "egl_platform": "device", "target_format": "rgba16f",
    "msaa_resolve": "shader", "rows": [)"
                                     << row("none", "0.5", "") << ",\n"
                                     << row("aaa", "0.625", "") << ",\n"
                                     << row("scale43", "0.875", R"( "render_width": 44, "render_height": 23,)") << "]}";
  std::ofstream(dir / "cuda.json") << R"({"schema": "aalab-gpu-timings", "schema_version": 1, "generated_utc": "x",
    "device": {"name": "CUDA H100"}, "driver": "1", "cuda_runtime": "13.0", "results": [
    {"scene": "wedges", "size": "33x17", "method": "copy", "kernels": "copy", "median_ms": 0.01, "min_ms": 0.01,
     "max_ms": 0.01, "ratio_to_copy": 1},
    {"scene": "wedges", "size": "33x17", "method": "scale43-fxaa-high", "kernels": "fxaa + rescale",
     "median_ms": 0.0625, "min_ms": 0.06, "max_ms": 0.07, "ratio_to_copy": 6.25}]})";
  std::ofstream(dir / "vk.json") << R"J({"schema": "aalab-gpu-timings", "schema_version": 1, "tool": "aalab_vk",
    "generated_utc": "x", "device": {"name": "VK H100"}, "driver": "NVIDIA 1", "cuda_runtime": "none (Vulkan 1.4)",
    "results": [
    {"scene": "wedges", "size": "33x17", "method": "copy", "kernels": "copy", "median_ms": 0.01, "min_ms": 0.01,
     "max_ms": 0.01, "ratio_to_copy": 1},
    {"scene": "wedges", "size": "33x17", "method": "cmaa2-high", "kernels": "EdgesColor2x2CS + ...",
     "median_ms": 0.0375, "min_ms": 0.03, "max_ms": 0.04, "ratio_to_copy": 3.75}]})J";
  // A missing file in the list is refused before the run writes anything.
  const std::string run =
      "run --scenes wedges --methods none,aaa,cmaa2-high,scale43-fxaa-high --size 33x17 "
      "--ref-spp 4 --repeat 1 --quiet --out ";
  auto r = Aalab(run + (dir / "r0").string() + " --gpu-timings " + (dir / "raster.json").string() + "," +
                 (dir / "nothere.json").string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("nothere.json"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "r0"));
  r = Aalab(run + (dir / "r").string() + " --gpu-timings " + (dir / "raster.json").string() + "," +
            (dir / "cuda.json").string() + " --gpu-timings " + (dir / "vk.json").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("raster.json into 3 of 4 rows"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("cuda.json into 1 of 4 rows"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("vk.json into 1 of 4 rows"), std::string::npos) << r.output;
  const auto report = nlohmann::json::parse(ReadText(dir / "r" / "report.json"));
  std::map<std::string, nlohmann::json> rows;
  for (const auto& j : report.at("rows")) rows[j.at("spec").get<std::string>()] = j;
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_DOUBLE_EQ(rows.at("aaa").at("gpu_raster").at("sizes").at("33x17").at("ratio_to_1x").get<double>(), 1.25);
  EXPECT_FALSE(rows.at("aaa").contains("gpu"));
  EXPECT_DOUBLE_EQ(rows.at("cmaa2-high").at("gpu").at("sizes").at("33x17").at("median_ms").get<double>(), 0.0375);
  EXPECT_EQ(rows.at("cmaa2-high").at("gpu").at("device"), "VK H100");
  EXPECT_FALSE(rows.at("cmaa2-high").contains("gpu_raster"));
  const auto& scale = rows.at("scale43-fxaa-high");
  EXPECT_EQ(scale.at("render_size"), nlohmann::json::array({44, 23}));  // the run's own render agrees with the file
  EXPECT_EQ(scale.at("gpu_raster").at("part"), "render");
  EXPECT_EQ(scale.at("gpu_raster").at("sizes").at("33x17").at("render_size"), "44x23");
  EXPECT_DOUBLE_EQ(scale.at("gpu_raster").at("sizes").at("33x17").at("median_ms").get<double>(), 0.875);
  EXPECT_DOUBLE_EQ(scale.at("gpu").at("sizes").at("33x17").at("median_ms").get<double>(), 0.0625);
  EXPECT_EQ(scale.at("gpu").at("device"), "CUDA H100");
  EXPECT_FALSE(rows.at("none").contains("gpu"));
  // The page (headless Chromium, as the browser tests load it): scale43-fxaa-high's GPU raster
  // cell is render + FXAA/rescale = total (core.js fmtMs: 3 decimals below 1 ms; 0.0625 and
  // 0.9375 are ties that toFixed rounds up), the tooltip naming the render target and both devices.
  const fs::path dom = dir / "dom.html";
  const auto b = RunCommand(
      "timeout 180 /usr/bin/chromium --headless --no-sandbox --disable-gpu "
      "--disable-dev-shm-usage --no-first-run --user-data-dir='" +
      (dir / "profile").string() + "' --virtual-time-budget=10000 --dump-dom 'file://" +
      fs::absolute(dir / "r" / "index.html").string() + "' > '" + dom.string() + "' 2>/dev/null");
  ASSERT_EQ(b.code, 0) << b.output;
  const std::string page = ReadText(dom);
  const size_t at = page.find("<tr data-spec=\"scale43-fxaa-high\"");
  ASSERT_NE(at, std::string::npos) << dom;
  const std::string tr = page.substr(at, page.find("</tr>", at) - at);
  EXPECT_NE(tr.find(">0.875 + 0.063 = 0.938</td>"), std::string::npos) << tr;
  EXPECT_NE(tr.find("the render 0.875 ms (44x23 target) drawn by the raster path on GL H100"), std::string::npos) << tr;
  EXPECT_NE(tr.find("by the CUDA twin on CUDA H100"), std::string::npos) << tr;
  // A later merge with a file that matches no row leaves the report as it was, even when an
  // earlier file in the same list matched.
  const std::string before = ReadText(dir / "r" / "report.json");
  std::ofstream(dir / "other.json") << R"({"schema": "aalab-gpu-timings", "schema_version": 1, "generated_utc": "x",
    "device": {"name": "G"}, "driver": "1", "cuda_runtime": "13.0", "results": [
    {"scene": "circle", "size": "8x8", "method": "fxaa1-p3", "kernels": "fxaa1",
     "median_ms": 1, "min_ms": 1, "max_ms": 1, "ratio_to_copy": 1}]})";
  r = Aalab("merge-gpu " + (dir / "r").string() + " " + (dir / "vk.json").string() + " " +
            (dir / "other.json").string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("other.json' has timings for none of the report's rows"), std::string::npos) << r.output;
  EXPECT_EQ(ReadText(dir / "r" / "report.json"), before);
}

TEST(SamplerOption, GpuTextureIsRecordedAndChangesOnlyTheFilters) {
  // --sampler gpu-texture: the report records it, the render and `none` keep their bits
  // (nothing samples there), the filters run. The default run does not name a sampler.
  const fs::path dir = TempDir("sampler-option");
  const std::string common =
      "run --scenes wedges --methods none,fxaa311-p39,smaa-high,scale43 --size 61x37 "
      "--ref-spp 4 --repeat 1 --quiet --out ";
  auto r = Aalab(common + (dir / "gl").string());
  ASSERT_EQ(r.code, 0) << r.output;
  r = Aalab(common + (dir / "hw").string() + " --sampler gpu-texture");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto gl = nlohmann::json::parse(ReadText(dir / "gl" / "report.json"));
  const auto hw = nlohmann::json::parse(ReadText(dir / "hw" / "report.json"));
  EXPECT_FALSE(gl["settings"].contains("sampler"));
  EXPECT_EQ(hw["settings"]["sampler"], "gpu-texture");
  ASSERT_EQ(gl["rows"].size(), hw["rows"].size());
  for (size_t i = 0; i < gl["rows"].size(); ++i) {
    ASSERT_EQ(gl["rows"][i]["spec"], hw["rows"][i]["spec"]);
    if (gl["rows"][i]["spec"] == "none") {
      EXPECT_EQ(gl["rows"][i]["output_hash"], hw["rows"][i]["output_hash"]);
    }
  }
  EXPECT_NE(ReadText(dir / "hw" / "index.html").find("gpu-texture"), std::string::npos);
}

TEST(SamplerOption, UnknownSamplerIsRefusedNamingTheChoices) {
  const fs::path dir = TempDir("sampler-bad");
  auto r = Aalab("run --scenes wedges --methods none --size 16x9 --ref-spp 4 --quiet --sampler hw --out " +
                 (dir / "out").string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("unknown sampler 'hw' (allowed: gl, gpu-texture)"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
  r = Aalab("apply --method fxaa311-p39 --sampler hw " + (dir / "in.png").string() + " " + (dir / "o.png").string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("unknown sampler 'hw'"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "o.png"));
}

}  // namespace
}  // namespace aalab
