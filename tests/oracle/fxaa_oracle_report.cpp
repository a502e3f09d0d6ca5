// fxaa_oracle_report: how far the original FXAA shaders on llvmpipe's other filtering paths
// are from aalab's FXAA (which the oracle tests prove bit-exact with the float32, no-FMA
// path). Prints, per method, the share of pixels that differ and the largest difference in
// 8-bit levels, over the oracle test frames. Reports, asserts nothing.
//
//   fxaa_oracle_report --sampling 8bit   llvmpipe's default RGBA8 path: 8-bit filter weights,
//                                        as GPUs filter (what a GPU's FXAA may look like)
//   fxaa_oracle_report --fma on          float32 filtering with the CPU's FMA in the lerps
//   fxaa_oracle_report                   the oracle's own mode (expect 100% identical)
// Needs ../shared/seeds (or AALAB_SEEDS_DIR) and Mesa's EGL + llvmpipe.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "methods/fxaa311.h"
#include "methods/registry.h"
#include "tests/oracle/gl_oracle.h"
#include "tests/oracle/oracle_frames.h"
#include "tests/oracle/seed_shaders.h"

namespace aalab {
namespace {

struct Tally {
  long pixels = 0, differing = 0, over1 = 0;
  int max_diff = 0;
  void Add(const Image8& a, const Image8& b) {
    for (int y = 0; y < a.Height(); ++y) {
      for (int x = 0; x < a.Width(); ++x) {
        int m = 0;
        for (int c = 0; c < 3; ++c) m = std::max(m, std::abs(a.Pixel(x, y)[c] - b.Pixel(x, y)[c]));
        ++pixels;
        differing += m > 0;
        over1 += m > 1;
        max_diff = std::max(max_diff, m);
      }
    }
  }
  void Print(const std::string& name) const {
    std::printf("%-14s %9ld px  differ %7.3f%%  differ by >1 level %7.3f%%  max %3d levels\n", name.c_str(), pixels,
                100.0 * differing / pixels, 100.0 * over1 / pixels, max_diff);
  }
};

int Run(int argc, char** argv) {
  oracle::GlMode mode;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const std::string v = i + 1 < argc ? argv[i + 1] : "";
    if (a == "--sampling" && (v == "8bit" || v == "float")) {
      mode.float_sampling = v == "float";
      ++i;
    } else if (a == "--fma" && (v == "on" || v == "off")) {
      mode.fma = v == "on";
      ++i;
    } else {
      std::fprintf(stderr, "fxaa_oracle_report: bad argument '%s' (allowed: --sampling float|8bit, --fma on|off)\n",
                   a.c_str());
      return 2;
    }
  }
  if (!oracle::SeedsPresent()) {
    std::fprintf(stderr, "fxaa_oracle_report: needs the seeds with the original shaders at %s\n",
                 oracle::SeedsDir().c_str());
    return 1;
  }
  const std::string err = oracle::StartGl(mode);
  if (!err.empty()) {
    std::fprintf(stderr, "fxaa_oracle_report: %s\n", err.c_str());
    return 1;
  }
  std::printf("llvmpipe: %s; sampling %s, FMA %s\n", oracle::GlRenderer().c_str(),
              mode.float_sampling ? "float32 (GALLIVM_PERF=no_aos_sampling)" : "default (8-bit weights)",
              mode.fma ? "on" : "off");
  const auto frames = oracle::OracleFrames();
  Tally all, scenes;  // scenes: the 8 rendered library frames (the last 8 frames) only
  const size_t first_scene = frames.size() - 8;
  auto preset = [&](const std::string& name, const Fxaa311Params& p, int id) {
    Tally t;
    for (size_t i = 0; i < frames.size(); ++i) {
      const Image8& img = frames[i].img;
      const Image8 ours = Fxaa311(img, p, nullptr);
      const Image8 gl = oracle::RunFxaa311Shader(Fxaa311LumaFrame(img, p.luma), id, false, p.subpix, p.edge_threshold,
                                                 p.edge_threshold_min);
      t.Add(ours, gl);
      all.Add(ours, gl);
      if (i >= first_scene) scenes.Add(ours, gl);
    }
    t.Print(name);
  };
  for (int id : Fxaa311PresetIds()) {
    Fxaa311Params p;
    p.steps = Fxaa311PresetSteps(id);
    preset("fxaa311-p" + std::to_string(id), p, id);
  }
  const std::pair<const char*, int> levels[] = {{"low", 22}, {"medium", 27}, {"high", 39}};
  for (const auto& [level, id] : levels) {
    Fxaa311Params p = FxaaTutorialHighParams();
    p.steps = FxaaTutorialSteps(level);
    preset(std::string("fxaa-") + level, p, id);
  }
  const Fxaa311Params p = *MakeMethod("fxaa-iter12").Config<Fxaa311Params>();  // the registry row's parameters
  Tally t;
  for (size_t i = 0; i < frames.size(); ++i) {
    const Image8 ours = Fxaa311(frames[i].img, p, nullptr);
    const Image8 gl = oracle::RunIter12Shader(frames[i].img);
    t.Add(ours, gl);
    all.Add(ours, gl);
    if (i >= first_scene) scenes.Add(ours, gl);
  }
  t.Print("fxaa-iter12");
  all.Print("all");
  scenes.Print("scenes only");
  return 0;
}

}  // namespace
}  // namespace aalab

int main(int argc, char** argv) { return aalab::Run(argc, argv); }
