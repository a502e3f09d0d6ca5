// aalab_vk (gpu/vk, docs/gpu.md "Original shaders through Vulkan") as the lead runs it on the
// H100, here on lavapipe at 96x54: scripts/vk_shaders.sh compiles the original CMAA2.hlsl and
// ffx_fsr1.h (../shared/third_party) to SPIR-V, `aalab export-frames` writes the frames,
// aalab_vk times copy, CMAA2 (each preset), RCAS and EASU (warm-up 1, repeat 2) and writes the
// JSON and its output frames, `aalab merge-gpu` takes the JSON into a report of the same
// scenes. The frames are checked against `aalab run`'s outputs of the same methods (the CPU
// ports): copy must give back the frame, RCAS and EASU the CPU's bytes exactly, CMAA2 nearly
// all of them (lavapipe's sRGB decode and pow, and the order its atomics run in, move some
// pixels by a few levels: measured below). FSR 2 (its six GLSL passes, the tool's synthetic
// 8-frame sequence) is checked for what the JSON must hold, sizes, and an output that is finite,
// in range and closer to the sequence's last frame rendered at display size than the render-size
// frame scaled up by nearest neighbour. Times on lavapipe mean nothing; only that they
// exist and are positive is checked. Without glslang, spirv-tools, the sources or lavapipe the
// tests skip, and fail under CI.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/image.h"
#include "io/image_io.h"
#include "io/ppm.h"
#include "tests/cli/cli_util.h"
#include "tests/skip_or_fail.h"

namespace aalab {
namespace {

namespace fs = std::filesystem;
using clitest::CmdResult;
using clitest::RunCommand;

std::string LavapipeIcd() {
  for (const char* dir : {"/usr/share/vulkan/icd.d", "/etc/vulkan/icd.d"}) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
      if (e.path().filename().string().rfind("lvp_icd", 0) == 0) return e.path().string();
    }
  }
  return "";
}

std::string ThirdParty() {
  const char* env = std::getenv("AALAB_THIRD_PARTY_DIR");
  return env && *env ? env : std::string(AALAB_SOURCE_DIR) + "/../shared/third_party";
}

// aalab_vk on lavapipe, one thread (atomics in dispatch order), AVX lanes (as the oracles).
CmdResult Vk(const std::string& args) {
  const std::string icd = LavapipeIcd();
  return RunCommand("VK_DRIVER_FILES=" + icd + " VK_ICD_FILENAMES=" + icd +
                    " LP_NUM_THREADS=1 GALLIUM_OVERRIDE_CPU_CAPS=avx " + AALAB_BINARY_DIR + "/aalab_vk " + args +
                    " 2>&1");
}

const char* const kFsr2Methods = "fsr2-quality,fsr2-balanced,fsr2-performance,fsr2-ultra-performance,fsr2-native";

// Everything the tests read, made once: SPIR-V, frames, the CPU run, aalab_vk's JSON and frames.
struct Workspace {
  std::string missing;  // why the tests cannot run here, or ""
  std::string failure;  // a step that failed, with its output
  fs::path dir;
};

const Workspace& Shared() {
  static const Workspace w = [] {
    Workspace s;
    if (LavapipeIcd().empty()) s.missing = "no lavapipe ICD: install mesa-vulkan-drivers";
    if (std::system("glslangValidator --version > /dev/null 2>&1") != 0 ||
        std::system("spirv-as --version > /dev/null 2>&1") != 0) {
      s.missing = "glslangValidator or spirv-as not found: install glslang-tools spirv-tools";
    }
    if (!fs::exists(ThirdParty() + "/cmaa2/CMAA2.hlsl") || !fs::exists(ThirdParty() + "/fidelityfx-fsr1/ffx_fsr1.h")) {
      s.missing = "the original sources are not in " + ThirdParty() + " (set AALAB_THIRD_PARTY_DIR)";
    }
    if (!s.missing.empty()) return s;
    s.dir = clitest::TempDir("vk-tool");
    const std::string d = s.dir.string();
    const std::pair<std::string, std::string> steps[] = {
        {"vk_shaders.sh", std::string(AALAB_SOURCE_DIR) + "/scripts/vk_shaders.sh " + d + "/spv 2>&1"},
        {"export-frames", std::string(AALAB_BINARY_DIR) +
                              "/aalab export-frames --scenes wedges,mesh --sizes 96x54 --no-scaled "
                              "--render-methods scale43-easu --out " +
                              d + "/frames 2>&1"},
        {"run",
         std::string(AALAB_BINARY_DIR) +
             "/aalab run --scenes wedges,mesh --size 96x54 --methods none,cmaa2-low,cmaa2-high,rcas,scale43-easu,"
             "scale43-easu-rcas --out " +
             d + "/run 2>&1"}};
    for (const auto& [name, cmd] : steps) {
      const CmdResult r = RunCommand(cmd);
      if (r.code != 0) {
        s.failure = name + " failed: " + r.output;
        return s;
      }
    }
    const CmdResult r = Vk("--shaders " + d + "/spv --input " + d + "/frames --json " + d + "/vk.json --frames " + d +
                           "/out --warmup 1 --repeat 2 --methods cmaa2-low,cmaa2-medium,cmaa2-high,cmaa2-ultra,rcas,"
                           "scale43-easu,scale43-easu-rcas");
    if (r.code != 0) s.failure = "aalab_vk failed: " + r.output;
    // FSR 2: the tool's whole 8-frame sequence (6 untimed frames, the first resetting, then 2 timed).
    const CmdResult f = Vk("--shaders " + d + "/spv --input " + d + "/frames --json " + d + "/vk-fsr2.json --frames " +
                           d + "/out-fsr2 --warmup 6 --repeat 2 --methods " + kFsr2Methods);
    if (f.code != 0) s.failure += "aalab_vk (FSR 2) failed: " + f.output;
    return s;
  }();
  return w;
}

class VkTool : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!Shared().missing.empty()) AALAB_SKIP_OR_FAIL_UNDER_CI("aalab_vk test unavailable: " + Shared().missing);
    ASSERT_TRUE(Shared().failure.empty()) << Shared().failure;
  }
  static fs::path Dir() { return Shared().dir; }
};

nlohmann::json ReadJson(const fs::path& p) {
  std::ifstream f(p);
  return nlohmann::json::parse(f);
}

TEST_F(VkTool, WritesTheGpuTimingsSchemaWithPositiveTimesForEveryPass) {
  const nlohmann::json j = ReadJson(Dir() / "vk.json");
  EXPECT_EQ(j.at("schema"), "aalab-gpu-timings");
  EXPECT_EQ(j.at("schema_version"), 1);
  EXPECT_NE(j.at("device").at("name").get<std::string>().find("llvmpipe"), std::string::npos);
  EXPECT_EQ(j.at("device").at("robust_image_access"), true);  // lavapipe offers it, as the oracles use it
  EXPECT_EQ(j.at("timing").at("warmup"), 1);
  EXPECT_EQ(j.at("timing").at("repeat"), 2);
  const std::vector<std::string> methods = {"copy", "cmaa2-low",    "cmaa2-medium",      "cmaa2-high", "cmaa2-ultra",
                                            "rcas", "scale43-easu", "scale43-easu-rcas", "copy-after"};
  ASSERT_EQ(j.at("results").size(), 2 * methods.size());
  for (size_t i = 0; i < j.at("results").size(); ++i) {
    const nlohmann::json& r = j.at("results")[i];
    const std::string what = r.dump();
    EXPECT_EQ(r.at("scene"), i < methods.size() ? "wedges" : "mesh") << what;
    EXPECT_EQ(r.at("size"), "96x54") << what;
    EXPECT_EQ(r.at("method"), methods[i % methods.size()]) << what;
    const double med = r.at("median_ms"), lo = r.at("min_ms"), hi = r.at("max_ms");
    EXPECT_GT(lo, 0) << what;
    EXPECT_LE(lo, med) << what;
    EXPECT_LE(med, hi) << what;
    const double copy = j.at("results")[i - i % methods.size()].at("median_ms");
    // The tool prints every figure with %.6g: ratio, median and copy each carry up to 5e-6 relative
    // rounding, so the recomputed ratio may differ by up to ~1.5e-5 of itself.
    EXPECT_NEAR(r.at("ratio_to_copy").get<double>(), med / copy, 2e-5 * med / copy + 1e-6) << what;
    const std::string m = methods[i % methods.size()];
    const size_t passes = m.rfind("cmaa2", 0) == 0 ? 5 : m == "scale43-easu-rcas" ? 2 : 0;
    ASSERT_EQ(r.contains("passes") ? r.at("passes").size() : 0, passes) << what;
    if (passes == 5) {
      EXPECT_TRUE(r.at("passes").contains("1 EdgesColor2x2CS")) << what;
      EXPECT_TRUE(r.at("passes").contains("3 ProcessCandidatesCS")) << what;
      EXPECT_TRUE(r.at("passes").contains("5 DeferredColorApply2x2CS")) << what;
      EXPECT_EQ(r.at("kernels"),
                "EdgesColor2x2CS + ComputeDispatchArgsCS + ProcessCandidatesCS + ComputeDispatchArgsCS + "
                "DeferredColorApply2x2CS");
    }
    if (r.contains("passes")) {
      for (const auto& [name, p] : r.at("passes").items()) EXPECT_GT(p.at("min_ms").get<double>(), 0) << name;
    }
  }
}

TEST_F(VkTool, MergeGpuPutsCmaa2AndFsr1TimesIntoTheReport) {
  const fs::path report = Dir() / "run-merged";
  fs::remove_all(report);
  fs::copy(Dir() / "run", report, fs::copy_options::recursive);
  const CmdResult r = clitest::Aalab("merge-gpu " + report.string() + " " + (Dir() / "vk.json").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const nlohmann::json j = ReadJson(report / "report.json");
  int with_gpu = 0;
  for (const auto& row : j.at("rows")) {
    if (!row.contains("gpu")) continue;
    ++with_gpu;
    const std::string spec = row.at("spec");
    EXPECT_TRUE(spec == "cmaa2-low" || spec == "cmaa2-high" || spec == "rcas" || spec == "scale43-easu" ||
                spec == "scale43-easu-rcas")
        << spec;
  }
  EXPECT_EQ(with_gpu, 10);  // 5 methods x 2 scenes; `none` has no GPU row
}

// Share of pixels whose three bytes are equal.
double Identical(const Image8& a, const Image8& b, int* max_diff) {
  EXPECT_EQ(a.Width(), b.Width());
  EXPECT_EQ(a.Height(), b.Height());
  if (a.Width() != b.Width() || a.Height() != b.Height()) return 0;
  long same = 0;
  *max_diff = 0;
  for (int y = 0; y < a.Height(); ++y) {
    for (int x = 0; x < a.Width(); ++x) {
      bool eq = true;
      for (int c = 0; c < 3; ++c) {
        const int d = std::abs(int(a.Pixel(x, y)[c]) - int(b.Pixel(x, y)[c]));
        eq = eq && d == 0;
        *max_diff = std::max(*max_diff, d);
      }
      same += eq ? 1 : 0;
    }
  }
  return static_cast<double>(same) / (static_cast<double>(a.Width()) * a.Height());
}

TEST_F(VkTool, OutputFramesEqualTheCpuPorts) {
  for (const std::string scene : {"wedges", "mesh"}) {
    const Image8 frame = ReadPpm((Dir() / "frames" / (scene + "-96x54.ppm")).string());
    auto gpu = [&](const std::string& m) {
      return ReadPpm((Dir() / "out" / (scene + "-96x54-" + m + ".ppm")).string());
    };
    auto cpu = [&](const std::string& m) {
      return ReadImage8((Dir() / "run" / "images" / scene / (m + ".png")).string());
    };
    int diff = 0;
    EXPECT_EQ(Identical(gpu("copy"), frame, &diff), 1.0) << scene;
    EXPECT_EQ(Identical(cpu("none"), frame, &diff), 1.0) << scene;
    // RCAS: every byte (the FSR 1 oracle proves the floats on llvmpipe; lavapipe is the same compiler).
    const double rcas = Identical(gpu("rcas"), cpu("rcas"), &diff);
    std::printf("%s rcas: %.4f%% identical, max diff %d\n", scene.c_str(), 100 * rcas, diff);
    EXPECT_EQ(rcas, 1.0) << scene << " max diff " << diff;
    // CMAA2 HIGH: measured 99.42 % (wedges) and 97.51 % (mesh) identical, largest difference
    // 1 and 4 levels; LOW 99.42 % and 98.21 %, 1 level (lavapipe 22.3.6). Unlike the oracle
    // (tests/oracle/cmaa2_oracle_test.cpp: linear floats in and out, at most 1 byte in 10 000 differs), here lavapipe
    // decodes the sRGB texture and evaluates the shader's pow(x, 1/2.4) itself, with its own approximations; the cause
    // of each pixel was not isolated (docs/gpu.md). LOW too (its threshold is twice HIGH's): a preset compiled under
    // the wrong name fails.
    for (const std::string m : {"cmaa2-high", "cmaa2-low"}) {
      const double cmaa2 = Identical(gpu(m), cpu(m), &diff);
      std::printf("%s %s: %.4f%% identical, max diff %d\n", scene.c_str(), m.c_str(), 100 * cmaa2, diff);
      EXPECT_GE(cmaa2, 0.97) << scene << " " << m << " max diff " << diff;
      EXPECT_LE(diff, 4) << scene << " " << m;
    }
    EXPECT_LT(Identical(gpu("cmaa2-high"), gpu("cmaa2-low"), &diff), 1.0) << scene << ": LOW and HIGH alike";
    const Image8 c = gpu("cmaa2-high");
    int changed = 0;
    EXPECT_LT(Identical(c, frame, &changed), 0.99) << scene << ": CMAA2 changed almost nothing";
    // EASU (and EASU + RCAS): the port against the shader through the texture unit's gather.
    for (const std::string m : {"scale43-easu", "scale43-easu-rcas"}) {
      const double easu = Identical(gpu(m), cpu(m), &diff);
      std::printf("%s %s: %.4f%% identical, max diff %d\n", scene.c_str(), m.c_str(), 100 * easu, diff);
      EXPECT_EQ(easu, 1.0) << scene << " " << m << " max diff " << diff;
    }
  }
}

// `img` as RGBA (alpha 255), what WritePpm takes.
Image8 Rgba(const Image8& img) {
  Image8 out(img.Width(), img.Height(), 4, 255);
  for (int y = 0; y < img.Height(); ++y) {
    for (int x = 0; x < img.Width(); ++x) {
      for (int c = 0; c < 3; ++c) out.Pixel(x, y)[c] = img.Pixel(x, y)[c];
    }
  }
  return out;
}

// --compare: the fidelity block of each result whose reference exists (here the run's CPU
// outputs as PPM, as gpu/vk/pack.sh makes them with `aalab apply`), counted as the test counts.
TEST_F(VkTool, CompareWritesTheFidelityBlockMergeGpuReads) {
  const fs::path refs = Dir() / "refs";
  fs::create_directories(refs);
  for (const std::string scene : {"wedges", "mesh"}) {
    for (const std::string m : {"cmaa2-high", "rcas"}) {
      WritePpm((refs / (scene + "-96x54-" + m + ".ppm")).string(),
               Rgba(ReadImage8((Dir() / "run" / "images" / scene / (m + ".png")).string())));
    }
  }
  const fs::path json = Dir() / "compared.json";
  const std::string d = Dir().string();
  const CmdResult r = Vk("--shaders " + d + "/spv --input " + d + "/frames --methods cmaa2-high,rcas --compare " +
                         refs.string() + " --json " + json.string() + " --warmup 0 --repeat 1");
  ASSERT_EQ(r.code, 0) << r.output;
  const nlohmann::json j = ReadJson(json);
  int compared = 0;
  for (const auto& row : j.at("results")) {
    const std::string m = row.at("method");
    ASSERT_EQ(row.contains("fidelity"), m == "cmaa2-high" || m == "rcas") << row.dump();
    if (!row.contains("fidelity")) continue;
    ++compared;
    const std::string scene = row.at("scene");
    int diff = 0;
    const double share = Identical(ReadPpm((Dir() / "out" / (scene + "-96x54-" + m + ".ppm")).string()),
                                   ReadPpm((refs / (scene + "-96x54-" + m + ".ppm")).string()), &diff);
    EXPECT_NEAR(row.at("fidelity").at("identical_share").get<double>(), share, 1e-6) << row.dump();
    EXPECT_EQ(row.at("fidelity").at("max_diff"), diff) << row.dump();
    EXPECT_EQ(row.at("fidelity").at("differing_pixels").get<long>(), std::lround((1 - share) * 96 * 54)) << row.dump();
  }
  EXPECT_EQ(compared, 4);
  // A reference of another size is refused, naming it.
  WritePpm((refs / "mesh-96x54-rcas.ppm").string(), Image8(10, 10, 4, 255));
  const CmdResult bad = Vk("--shaders " + d + "/spv --input " + d + "/frames --methods rcas --compare " +
                           refs.string() + " --warmup 0 --repeat 1");
  EXPECT_EQ(bad.code, 1) << bad.output;
  EXPECT_NE(bad.output.find("mesh-96x54-rcas.ppm' is 10x10, the output 96x54"), std::string::npos) << bad.output;
}

TEST_F(VkTool, RefusesBadInputWithOneMessage) {
  const std::string d = Dir().string();
  const fs::path json = Dir() / "refused.json";
  struct Case {
    std::string args, says;
  };
  const Case cases[] = {
      {"--shaders " + d + "/spv --input " + d + "/nothing", "frames.tsv' cannot be read"},
      {"--shaders " + d + "/frames --input " + d + "/frames", "copy.spv' (for copy) is missing"},
      {"--shaders " + d + "/spv --input " + d + "/frames --methods rcas,cmaa2-hgh",
       "unknown method 'cmaa2-hgh' (known: copy,"},
      {"--shaders " + d + "/spv --input " + d + "/frames --repeat 0", "--repeat '0' is not an integer in 1..100000"},
      {"--input " + d + "/frames", "--shaders and --input are required"},
  };
  for (const Case& c : cases) {
    const CmdResult r = Vk(c.args + " --json " + json.string());
    EXPECT_EQ(r.code, 1) << c.args << ": " << r.output;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << c.args << ": " << r.output;
    EXPECT_FALSE(fs::exists(json)) << c.args;
  }
}

// Render sizes by hand: (uint32)(96 / ratio) x (uint32)(54 / ratio) in float.
struct Fsr2Case {
  const char* method;
  const char* render;
};
const Fsr2Case kFsr2Cases[] = {{"fsr2-quality", "64x36"},
                               {"fsr2-balanced", "56x31"},  // 56.47, 31.76
                               {"fsr2-performance", "48x27"},
                               {"fsr2-ultra-performance", "32x18"},
                               {"fsr2-native", "96x54"}};

// One test (each VkTool test rebuilds the workspace in its own process: about 25 s here).
TEST_F(VkTool, Fsr2TimesItsSixPassesPerFrameOnceForEachSizeWithAFiniteOutputBetterThanNearest) {
  const nlohmann::json j = ReadJson(Dir() / "vk-fsr2.json");
  EXPECT_EQ(j.at("timing").at("warmup"), 6);
  EXPECT_EQ(j.at("timing").at("repeat"), 2);
  EXPECT_TRUE(j.at("timing").contains("fsr2"));
  // FSR 2 runs at the first scene of a size only: wedges gets copy, the five, copy-after; mesh
  // its two copies.
  const nlohmann::json& res = j.at("results");
  ASSERT_EQ(res.size(), 9u);
  EXPECT_EQ(res[0].at("method"), "copy");
  EXPECT_EQ(res[6].at("method"), "copy-after");
  EXPECT_EQ(res[7].at("scene"), "mesh");
  EXPECT_EQ(res[7].at("method"), "copy");
  EXPECT_EQ(res[8].at("method"), "copy-after");
  const char* const passes[] = {"1 compute_luminance_pyramid",
                                "2 reconstruct_previous_depth",
                                "3 depth_clip",
                                "4 lock",
                                "5 accumulate",
                                "6 rcas"};
  for (size_t i = 0; i < 5; ++i) {
    const nlohmann::json& r = res[i + 1];
    const std::string what = r.dump();
    EXPECT_EQ(r.at("scene"), "wedges") << what;
    EXPECT_EQ(r.at("size"), "96x54") << what;
    EXPECT_EQ(r.at("method"), kFsr2Cases[i].method) << what;
    EXPECT_EQ(r.at("kernels"),
              "compute_luminance_pyramid + reconstruct_previous_depth + depth_clip + lock + accumulate + rcas");
    EXPECT_EQ(r.at("input").get<std::string>().rfind(std::string("render ") + kFsr2Cases[i].render + " ", 0), 0u)
        << what;
    const double med = r.at("median_ms"), lo = r.at("min_ms"), hi = r.at("max_ms");
    EXPECT_GT(lo, 0) << what;
    EXPECT_LE(lo, med) << what;
    EXPECT_LE(med, hi) << what;
    // %.6g on all three figures: up to ~1.5e-5 relative (an absolute 1e-4 failed for ratios above ~40).
    const double ratio = med / res[0].at("median_ms").get<double>();
    EXPECT_NEAR(r.at("ratio_to_copy").get<double>(), ratio, 2e-5 * ratio + 1e-6) << what;
    ASSERT_EQ(r.at("passes").size(), 6u) << what;
    double pass_min_sum = 0;
    for (const char* p : passes) {
      ASSERT_TRUE(r.at("passes").contains(p)) << p << " " << what;
      EXPECT_GT(r.at("passes").at(p).at("min_ms").get<double>(), 0) << p;
      pass_min_sum += r.at("passes").at(p).at("min_ms").get<double>();
    }
    EXPECT_LE(pass_min_sum, hi * (1 + 1e-9)) << what;  // a frame holds its six passes

    // The output of the last frame: finite, in range, closer to the display-size rendering.
    const nlohmann::json& c = r.at("output_check");
    EXPECT_EQ(c.at("nonfinite"), 0) << what;
    // The scene's values are 0..1; RCAS and the Lanczos upsample ring a little past them
    // (measured: -0.015 .. 1.15).
    EXPECT_GE(c.at("min").get<double>(), -0.1) << what;
    EXPECT_LE(c.at("max").get<double>(), 1.3) << what;
    EXPECT_LT(c.at("mean_abs_error").get<double>(), 0.06) << what;  // measured 0.028 .. 0.049
    if (std::string(kFsr2Cases[i].method) != "fsr2-native") {
      EXPECT_LT(c.at("mean_abs_error").get<double>(), c.at("mean_abs_error_nearest").get<double>()) << what;
    }
    const Image8 out =
        ReadPpm((Dir() / "out-fsr2" / (std::string("wedges-96x54-") + kFsr2Cases[i].method + ".ppm")).string());
    EXPECT_EQ(out.Width(), 96);
    EXPECT_EQ(out.Height(), 54);
  }
  EXPECT_FALSE(fs::exists(Dir() / "out-fsr2" / "mesh-96x54-fsr2-quality.ppm"));
}

}  // namespace
}  // namespace aalab
