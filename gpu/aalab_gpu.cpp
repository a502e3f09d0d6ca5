// aalab_gpu — the post filters' and TAA's CUDA twins, timed and checked on a GPU (docs/gpu.md).
//
// Reads the frames `aalab export-frames` wrote (DIR/frames.tsv + binary PPMs, and TAA's
// sequences with --taa-frames), runs every method's kernels on them (SMAA also each pass
// alone; TAA over each sequence with its history on the GPU, gpu/taa_gpu.cpp), and writes
// one JSON file:
//   timing    CUDA events around each launch (chain of kernels), `--warmup` untimed launches,
//             then `--repeat` timed ones: median / min / max in ms. Clocks are not locked:
//             the GPU runs at whatever boost clock it chooses (nvidia-smi readings before and
//             after are recorded). The frames stay resident between launches, so a 1080p
//             frame (8 MB in + 8 MB out) is served from the 50 MB L2 of an H100, as a frame
//             just rendered would be; 4K is partly L2-resident.
//   floor     two copy kernels of the same frame at the output size, in the same run: through
//             the texture path (point fetch + surface write, what the filters use) and as
//             plain 16-byte loads/stores of a linear buffer. Each method's ratio is its median
//             over the texture-path copy's median.
//   fidelity  each GPU output against the CPU method (the same registry code aalab runs,
//             built into this tool) on the same frame: share of pixels whose rgb is
//             identical, largest difference in 8-bit levels, pixels that differ. Every output
//             is poisoned before the check run and must have alpha 255 everywhere afterwards;
//             a second GPU run must give the same bytes. The same kernels with every bilinear
//             fetch done in float32 from point fetches (the CPU's arithmetic, "software
//             filter") must match the CPU bit for bit: what differs is the texture unit's.
//             The CPU with --sampler gpu-texture (the texture unit's arithmetic,
//             core/sampler.h) must match the texture path bit for bit, and the
//             probe's samples must all follow that rule (CheckTextureRule).
// `--probe-dump DIR` writes the raw probe data (gpu/texture_probe.h) and exits.
// `--self-test` runs the same on synthetic frames (noise, hard-edged shapes, odd sizes)
// without files; `--check` makes the exit status 1 when a check fails (make test-gpu).
// Exit status: 0 ok, 1 a failed check or bad input, 3 a CUDA or internal error.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "gpu/gpu_methods.h"
#include "gpu/main_json.h"
#include "gpu/measure.h"
#include "gpu/taa_gpu.h"
#include "io/ppm.h"
#include "gpu/texture_probe.h"
#include "core/color.h"
#include "core/error.h"
#include "core/exit_code.h"
#include "core/hash.h"
#include "core/params.h"

namespace aalab {
namespace {

namespace fs = std::filesystem;

struct Options {
  std::string frames_dir, json_path, outputs_dir, outputs_scene, probe_dump;
  std::vector<std::string> methods, taa_methods;
  std::vector<std::pair<int, int>> sizes;  // --sizes: extra self-test sets (timing at 1080p, 4K)
  int warmup = 20, repeat = 200;
  bool self_test = false, check = false, timing = true;
};

// "a,b:x=1,y=2,c": a comma followed by key=value continues the current spec.
std::vector<std::string> SplitSpecs(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (item.empty()) throw UserError("--methods: empty item in '" + text + "'");
    if (!out.empty() && out.back().find(':') != std::string::npos && item.find('=') != std::string::npos &&
        item.find(':') == std::string::npos) {
      out.back() += "," + item;
    } else {
      out.push_back(item);
    }
  }
  return out;
}

int ParseInt(const std::string& flag, const std::string& v, int lo, int hi) {
  size_t used = 0;
  int n = 0;
  try {
    n = std::stoi(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != v.size() || n < lo || n > hi) {
    throw UserError(flag + " '" + v + "' must be an integer in " + std::to_string(lo) + ".." + std::to_string(hi));
  }
  return n;
}

// "1920x1080,3840x2160" → the sizes (each side 1..16384).
std::vector<std::pair<int, int>> ParseSizes(const std::string& text) {
  std::vector<std::pair<int, int>> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const size_t x = item.find('x');
    if (x == std::string::npos) throw UserError("--sizes: '" + item + "' is not WxH (e.g. 1920x1080)");
    out.emplace_back(ParseInt("--sizes width", item.substr(0, x), 1, 16384),
                     ParseInt("--sizes height", item.substr(x + 1), 1, 16384));
  }
  if (out.empty()) throw UserError("--sizes: no size in '" + text + "'");
  return out;
}

Options ParseArgs(int argc, char** argv) {
  Options o;
  auto value = [&](int& i, const std::string& flag) -> std::string {
    if (i + 1 >= argc) throw UserError(flag + " needs a value");
    return argv[++i];
  };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--frames")
      o.frames_dir = value(i, a);
    else if (a == "--json")
      o.json_path = value(i, a);
    else if (a == "--outputs")
      o.outputs_dir = value(i, a);
    else if (a == "--outputs-scene")
      o.outputs_scene = value(i, a);
    else if (a == "--methods")
      o.methods = SplitSpecs(value(i, a));
    else if (a == "--taa-methods")
      o.taa_methods = SplitSpecs(value(i, a));
    else if (a == "--warmup")
      o.warmup = ParseInt(a, value(i, a), 0, 100000);
    else if (a == "--repeat")
      o.repeat = ParseInt(a, value(i, a), 1, 100000);
    else if (a == "--self-test")
      o.self_test = true;
    else if (a == "--sizes")
      o.sizes = ParseSizes(value(i, a));
    else if (a == "--probe-dump")
      o.probe_dump = value(i, a);
    else if (a == "--check")
      o.check = true;
    else if (a == "--no-timing")
      o.timing = false;
    else if (a == "--help" || a == "-h") {
      std::printf(
          "usage: aalab_gpu (--frames DIR | --self-test [--sizes WxH,...]) [--json FILE] [--methods SPECS] [--repeat "
          "N]\n"
          "                 [--warmup N] [--no-timing] [--check] [--outputs DIR --outputs-scene NAME]\n"
          "  --frames DIR     frames written by `aalab export-frames` (DIR/frames.tsv)\n"
          "  --self-test      synthetic frames (noise, shapes, odd sizes) instead of files\n"
          "  --sizes WxH,...  with --self-test: also the shapes frames and TAA sequence (with depth) at\n"
          "                   these sizes, e.g. 1920x1080,3840x2160 for timings\n"
          "  --json FILE      write timings and fidelity as JSON (aalab merge-gpu reads it)\n"
          "  --methods SPECS  comma-separated method specs (default: every post filter with a CUDA twin)\n"
          "  --taa-methods SPECS  TAA specs run over each sequence (default: taa, taa-prod; --self-test\n"
          "                   adds taa-prod variants covering each of its switches)\n"
          "  --repeat N       timed launches per method (default 200), after --warmup N (default 20)\n"
          "  --no-timing      fidelity checks only\n"
          "  --check          exit 1 when a check fails (copy not exact, output not written, GPU\n"
          "                   runs differ, identical share under the per-method floor)\n"
          "  --outputs DIR    write the GPU outputs on one frame as PPM; --outputs-scene SCENE-WxH names it\n"
          "  --probe-dump DIR write the texture unit's raw bilinear probe data into DIR and exit\n"
          "                   (scripts/fit_texture_rule.py fits the sampler rule to it; docs/gpu.md)\n");
      std::exit(ToInt(ExitCode::kOk));
    } else {
      throw UserError("unknown argument '" + a + "' (see --help)");
    }
  }
  if (!o.probe_dump.empty()) return o;
  if (o.self_test == !o.frames_dir.empty()) throw UserError("give exactly one of --frames DIR or --self-test");
  if (!o.outputs_dir.empty() && o.outputs_scene.empty()) throw UserError("--outputs needs --outputs-scene SCENE-WxH");
  if (o.methods.empty()) o.methods = DefaultGpuMethodSpecs();
  if (!o.sizes.empty() && !o.self_test) throw UserError("--sizes needs --self-test");
  if (o.taa_methods.empty()) {
    o.taa_methods = DefaultGpuTaaSpecs();
    if (o.self_test) {
      for (const char* v :
           {"taa-prod:precision=rgba16f", "taa-prod:dilate=off,history=bilinear,clip=minmax,feedback=fixed",
            "taa-prod:history=catmull-rom-5,disocclusion=off,clip=none,luma_weight=on,precision=rgba16f"}) {
        o.taa_methods.push_back(v);
      }
    }
  }
  return o;
}

// ---------------------------------------------------------------------------------------
// Frames.

struct FrameSet {
  std::string scene;
  int width = 0, height = 0;  // output size
  Image8 frame1x;
  Image8 scaled;  // empty when not exported
  TaaInput taa;   // TAA's sequence (export-frames --taa-frames); empty when not exported
};

std::vector<FrameSet> ReadManifest(const std::string& dir) {
  const std::string path = (fs::path(dir) / "frames.tsv").string();
  std::ifstream in(path);
  if (!in) throw UserError("'" + path + "' cannot be read (write it with `aalab export-frames --out " + dir + "`)");
  std::vector<FrameSet> sets;
  std::string line;
  int lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string field;
    while (std::getline(ss, field, '\t')) f.push_back(field);
    const std::string where = path + ":" + std::to_string(lineno);
    if (f.size() != 5) throw UserError(where + ": expected 5 tab-separated fields (scene, role, width, height, file)");
    const bool taa = f[1].rfind("taa-", 0) == 0;
    if (f[1] != "1x" && f[1] != "scaled" && !taa) {
      throw UserError(where + ": role '" + f[1] + "' (allowed: 1x, scaled, taa-<frame>)");
    }
    const int w = ParseInt(where + " width", f[2], 1, 65536);
    const int h = ParseInt(where + " height", f[3], 1, 65536);
    FrameSet* set = nullptr;
    for (auto& s : sets) {
      if (s.scene == f[0] && s.width == w && s.height == h) set = &s;
    }
    if (!set) {
      sets.push_back(FrameSet{f[0], w, h, {}, {}, {}});
      set = &sets.back();
    }
    Image8 img = ReadPpm((fs::path(dir) / f[4]).string());
    if (taa) {
      const int t = ParseInt(where + " TAA frame", f[1].substr(4), 0, 255);
      if (t != static_cast<int>(set->taa.frames.size())) {
        throw UserError(where + ": TAA frame " + std::to_string(t) + " out of order (expected " +
                        std::to_string(set->taa.frames.size()) + ")");
      }
      if (img.Width() != w || img.Height() != h)
        throw UserError(where + ": '" + f[4] + "' is not " + f[2] + "x" + f[3]);
      std::vector<float> prev;
      if (t > 0) {
        const std::string stem = f[4].size() > 4 ? f[4].substr(0, f[4].size() - 4) : f[4];
        prev = ReadPreviousPositions((fs::path(dir) / (stem + ".prev")).string(), w, h);
      }
      set->taa.frames.push_back(std::move(img));
      set->taa.previous.push_back(std::move(prev));
    } else if (f[1] == "1x") {
      if (img.Width() != w || img.Height() != h)
        throw UserError(where + ": '" + f[4] + "' is not " + f[2] + "x" + f[3]);
      set->frame1x = std::move(img);
    } else {
      set->scaled = std::move(img);
    }
  }
  for (const auto& s : sets) {
    if (s.frame1x.Empty()) throw UserError(path + ": scene '" + s.scene + "' has no 1x frame");
  }
  if (sets.empty()) throw UserError(path + ": no frames");
  return sets;
}

// Noise: every pixel an independent hash; the worst case for FXAA (edges everywhere).
Image8 NoiseFrame(int w, int h) {
  Image8 img(w, h, 4, 255);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const uint32_t r = MixBits32(static_cast<uint32_t>(y * 65537 + x) * 2654435761u);
      uint8_t* p = img.Pixel(x, y);
      p[0] = r & 255;
      p[1] = (r >> 8) & 255;
      p[2] = (r >> 16) & 255;
    }
  }
  return img;
}

// Hard-edged shapes on a gradient: a disc, a slanted half-plane, thin lines, as rendered
// 1 spp (each pixel takes the colour at its centre). Sizes scale with the frame.
Image8 ShapesFrame(int w, int h) {
  Image8 img(w, h, 4, 255);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const double u = (x + 0.5) / w, v = (y + 0.5) / h;
      double r = 0.2 + 0.3 * u, g = 0.25 + 0.2 * v, b = 0.4;
      if ((u - 0.35) * (u - 0.35) * w * w + (v - 0.5) * (v - 0.5) * h * h < 0.09 * h * h) r = 0.95, g = 0.85, b = 0.1;
      if (v > 0.1 + 0.23 * u && v < 0.16 + 0.23 * u) r = 0.05, g = 0.05, b = 0.05;
      if (u > 0.6 && (v - 0.9 + 0.6 * (u - 0.6)) > 0) r = 0.1, g = 0.7, b = 0.3;
      if (std::fmod(u * 7.3, 1.0) < 0.4 / w * 7.3 && v < 0.4) r = g = b = 1.0;
      uint8_t* p = img.Pixel(x, y);
      p[0] = QuantizeUnorm8(static_cast<float>(r));
      p[1] = QuantizeUnorm8(static_cast<float>(g));
      p[2] = QuantizeUnorm8(static_cast<float>(b));
    }
  }
  return img;
}

std::vector<FrameSet> SelfTestFrames(const std::vector<std::pair<int, int>>& sizes) {
  std::vector<FrameSet> sets;
  // Odd sizes; the scaled frames are round(4/3 · size), as scale43 renders them. The TAA
  // sequence of "shapes" carries depth and jitter (taa-prod's dilation and depth test); the
  // others have none (its motion-vector disocclusion test).
  auto add = [&](const std::string& name, Image8 (*make)(int, int), int w, int h, bool depth) {
    const int sw = static_cast<int>(std::lround(4.0 / 3.0 * w));
    const int sh = static_cast<int>(std::lround(4.0 / 3.0 * h));
    sets.push_back(FrameSet{name, w, h, make(w, h), make(sw, sh), SyntheticTaaSequence(w, h, 5, depth)});
  };
  add("noise", NoiseFrame, 97, 61, false);
  add("shapes", ShapesFrame, 331, 187, true);
  add("shapes-1row", ShapesFrame, 64, 1, false);
  for (const auto& [w, h] : sizes) add("shapes", ShapesFrame, w, h, true);
  return sets;
}

// ---------------------------------------------------------------------------------------
// Measuring.

// The floor under which the hardware path's identical share fails --check. The exactness of
// the port is checked by the software-filter variant (must be bit-identical); the hardware
// path differs wherever the texture unit's 1/256 weights move a filtered value (measured on
// the H100, docs/gpu.md: at least 0.82 on the default suite's frames, 0.51 on noise). The
// floors sit below those, to catch a wrong texture view or coordinate convention, which
// changes most edge pixels.
double IdenticalFloor(const std::string& scene) { return scene == "noise" ? 0.40 : 0.75; }

std::string Sh(const std::string& cmd) {
  std::string out;
  if (FILE* p = popen(cmd.c_str(), "r")) {
    char buf[256];
    while (std::fgets(buf, sizeof buf, p)) out += buf;
    pclose(p);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
  return out.empty() ? "unknown" : out;
}

// ---------------------------------------------------------------------------------------
// The run's stages (Main runs them in order).

/// --probe-dump DIR: the raw probe data and its check against the texture rule, then exit.
int DumpProbe(const std::string& dir) {
  const TextureProbeData data = CollectTextureProbeData();
  WriteTextureProbeData(data, dir);
  std::printf("texture probe data written to %s\n", dir.c_str());
  const TextureRuleCheck rule = CheckTextureRule(data);
  std::printf("texture rule (core/sampler.h) against the probe: %lld of %lld samples differ\n", rule.Mismatches(),
              rule.pairs + rule.quad8 + rule.coords + rule.quadf);
  return ToInt(ExitCode::kOk);
}

const char kSmiQuery[] =
    "nvidia-smi --query-gpu=driver_version,clocks.sm,clocks.max.sm,clocks.mem,temperature.gpu,power.draw "
    "--format=csv,noheader 2>/dev/null";

/// The device, its driver and nvidia-smi's readings before the measurements, printed.
GpuDeviceFacts QueryDevice() {
  cudaDeviceProp prop{};
  cuda::Check(cudaGetDeviceProperties(&prop, 0), "cudaGetDeviceProperties");
  GpuDeviceFacts d;
  d.name = prop.name;
  d.major = prop.major;
  d.minor = prop.minor;
  d.multiprocessors = prop.multiProcessorCount;
  d.l2_bytes = prop.l2CacheSize;
  d.memory_bytes = static_cast<long long>(prop.totalGlobalMem);
  cudaDriverGetVersion(&d.driver);
  cudaRuntimeGetVersion(&d.runtime);
  d.smi_before = Sh(kSmiQuery);
  d.nvidia_driver = Sh("nvidia-smi --query-gpu=driver_version --format=csv,noheader 2>/dev/null");
  std::printf("device: %s (sm_%d%d, %d SMs, L2 %d MB), driver %s, CUDA driver API %d, runtime %d\n", prop.name,
              prop.major, prop.minor, prop.multiProcessorCount, prop.l2CacheSize >> 20, d.nvidia_driver.c_str(),
              d.driver, d.runtime);
  return d;
}

/// The texture unit's filter probed and printed.
TextureProbe ProbeAndPrint() {
  const TextureProbe probe = ProbeTextureFilter();
  std::printf(
      "texture filter probe: %d distinct values over %d fractions; max error vs float fraction %.4f, "
      "vs fraction rounded to 1/256 %.4f, truncated %.4f (8-bit levels)\n",
      probe.distinct_values, probe.samples, probe.err_float, probe.err_round256, probe.err_trunc256);
  std::printf(
      "point fetches: %d of 256 UNORM8 values differ from k/255.0f, %d from the CPU's k*fl(1/255); "
      "half-texel fetches: %d of %d pairs (a, b) differ from the CPU sampler, largest difference %.3g\n",
      probe.unorm_mismatches, probe.unorm_mismatches_cpu, probe.half_mismatches, probe.half_pairs, probe.half_max_err);
  return probe;
}

/// What every measurement shares: the options, the device's sRGB decode table and stream,
/// the result rows and the failed checks.
struct GpuRun {
  GpuRun(const Options& options, const float* device_decode) : o(options), decode(device_decode) {}
  const Options& o;
  const float* decode = nullptr;  ///< SrgbDecode8's table on the device (the sqrt-luminance pre-pass)
  cudaStream_t stream{};
  std::vector<Entry> entries;
  int failures = 0;
  void Fail(const std::string& what) {
    ++failures;
    std::printf("CHECK FAILED: %s\n", what.c_str());
  }
};

/// The copy floors of one frame set at its output size, and the texture-path copy's exactness.
struct CopyFloors {
  double texture_ms = 0, linear_ms = 0;
};

CopyFloors MeasureCopies(GpuRun& run, const FrameSet& set, const std::string& size, GpuPipeline& p1) {
  const Options& o = run.o;
  Entry copy = MakeEntry(set.scene, size, "copy", "copy (point fetch + surface write)");
  Entry copy_lin = MakeEntry(set.scene, size, "copy-linear", "copy (16-byte global loads/stores)");
  p1.PoisonOutput();
  p1.RunCopyTexture(run.stream);
  cuda::Check(cudaStreamSynchronize(run.stream), "copy");
  copy.has_fidelity = true;
  copy.fid = Compare(p1.Output(), set.frame1x);
  if (copy.fid.differing != 0) run.Fail(set.scene + " " + size + ": texture-path copy is not exact");
  if (o.timing) {
    copy.timed = copy_lin.timed = true;
    copy.t = TimeLaunches([&] { p1.RunCopyTexture(run.stream); }, o.warmup, o.repeat, run.stream);
    copy_lin.t = TimeLaunches([&] { p1.RunCopyLinear(run.stream); }, o.warmup, o.repeat, run.stream);
    copy.ratio = 1.0;
    copy_lin.ratio = copy_lin.t.median / copy.t.median;
  }
  const CopyFloors floors{copy.t.median, copy_lin.t.median};
  copy.ratio_linear = copy.t.median / floors.linear_ms;
  copy_lin.ratio_linear = 1.0;
  run.entries.push_back(copy);
  run.entries.push_back(copy_lin);
  return floors;
}

/// One method on one frame set: the fidelity checks (texture path, software filter, the CPU
/// with --sampler gpu-texture), the optional output file, the timings; printed and recorded.
void MeasureMethod(GpuRun& run, const FrameSet& set, const std::string& size, const GpuMethod& m, GpuPipeline* p,
                   const CopyFloors& floors) {
  const Options& o = run.o;
  cudaStream_t stream = run.stream;
  const Image8& input = m.scaled_input ? set.scaled : set.frame1x;
  if (m.scaled_input) {
    const int rw = std::max(1, static_cast<int>(std::lround(m.plan.render.scale * set.width)));
    const int rh = std::max(1, static_cast<int>(std::lround(m.plan.render.scale * set.height)));
    if (rw != input.Width() || rh != input.Height()) {
      throw UserError(set.scene + " " + size + ": the scaled frame is " + std::to_string(input.Width()) + "x" +
                      std::to_string(input.Height()) + " but '" + m.spec + "' renders at " + std::to_string(rw) + "x" +
                      std::to_string(rh));
    }
  }
  Entry e = MakeEntry(set.scene, size, m.spec, m.kernels);
  p->PoisonOutput();
  p->Run(m, stream);
  cuda::Check(cudaStreamSynchronize(stream), m.spec.c_str());
  cuda::Check(cudaGetLastError(), m.spec.c_str());
  const Image8 gpu = p->Output();
  p->PoisonOutput();
  p->Run(m, stream);
  cuda::Check(cudaStreamSynchronize(stream), m.spec.c_str());
  const Image8 gpu2 = p->Output();
  e.all_written = AllOpaque(gpu);
  e.deterministic = gpu.Data() == gpu2.Data();
  const Image8 cpu = CpuOutput(m, input, set.width, set.height);
  e.has_fidelity = true;
  e.fid = Compare(gpu, cpu);
  p->PoisonOutput();
  p->Run(m, stream, /*software_filter=*/true);
  cuda::Check(cudaStreamSynchronize(stream), m.spec.c_str());
  e.has_soft = true;
  e.soft = Compare(p->Output(), cpu);
  e.has_hw_mode = true;
  e.hw_mode = Compare(gpu, CpuOutput(m, input, set.width, set.height, SamplerArithmetic::kGpuTexture));
  const std::string what = set.scene + " " + size + " " + m.spec;
  if (!e.all_written) run.Fail(what + ": output pixels left unwritten");
  if (!e.deterministic) run.Fail(what + ": two GPU runs differ");
  if (e.soft.differing != 0) {
    run.Fail(what + ": the software-filter variant differs from the CPU on " + std::to_string(e.soft.differing) +
             " pixels (max diff " + std::to_string(e.soft.max_diff) + ")");
  }
  if (e.hw_mode.differing != 0) {
    run.Fail(what + ": the CPU with --sampler gpu-texture differs from the texture path on " +
             std::to_string(e.hw_mode.differing) + " pixels (max diff " + std::to_string(e.hw_mode.max_diff) + ")");
  }
  if (e.fid.identical_share < IdenticalFloor(set.scene)) {
    run.Fail(what + ": identical share " + JsonNumber(e.fid.identical_share) + " < " +
             JsonNumber(IdenticalFloor(set.scene)));
  }
  if (!o.outputs_dir.empty() && set.scene + "-" + size == o.outputs_scene) {
    std::string file = set.scene + "-" + size + "-" + m.spec + ".ppm";
    for (char& c : file) {
      if (c == ':' || c == '=' || c == ',') c = '_';
    }
    WritePpm((fs::path(o.outputs_dir) / file).string(), gpu);
  }
  if (o.timing) {
    e.timed = true;
    e.t = TimeLaunches([&] { p->Run(m, stream); }, o.warmup, o.repeat, stream);
    e.ratio = e.t.median / floors.texture_ms;
    e.ratio_linear = e.t.median / floors.linear_ms;
    if (m.smaa) {
      for (int k = 0; k < 3; ++k) {
        e.passes.emplace_back(kSmaaPassNames[k],
                              TimeLaunches([&] { p->RunSmaaPass(m, k, stream); }, o.warmup, o.repeat, stream));
      }
    }
    if (m.prepass && !m.scaled_input)
      e.pass = TimeLaunches([&] { p->RunPassOnly(m, stream); }, o.warmup, o.repeat, stream);
  }
  std::printf(
      "%-16s %-10s %-34s identical %7.3f%% (sw filter %7.3f%%, cpu gpu-texture %7.3f%% max %d) <=1 %7.3f%% "
      "max %3d  %s\n",
      set.scene.c_str(), size.c_str(), m.spec.c_str(), 100.0 * e.fid.identical_share, 100.0 * e.soft.identical_share,
      100.0 * e.hw_mode.identical_share, e.hw_mode.max_diff, 100.0 * e.fid.within1_share, e.fid.max_diff,
      e.timed ? (JsonNumber(e.t.median) + " ms (" + JsonNumber(e.ratio) + "x copy)").c_str() : "");
  run.entries.push_back(e);
}

/// One TAA spec over the frame set's sequence (gpu/taa_gpu.cpp); printed and recorded.
void MeasureTaa(GpuRun& run, const FrameSet& set, const std::string& size, const std::string& spec,
                const CopyFloors& floors) {
  const Options& o = run.o;
  std::vector<std::string> taa_failures;
  Entry e =
      RunTaaSequence(spec, set.scene, set.taa, run.decode, o.timing, o.warmup, o.repeat, run.stream, &taa_failures);
  for (const auto& f : taa_failures) run.Fail(f);
  if (e.timed) {
    e.ratio = e.t.median / floors.texture_ms;
    e.ratio_linear = e.t.median / floors.linear_ms;
  }
  std::printf("%-16s %-10s %-34s worst frame identical %7.3f%% (sw filter %lld px differ) max %3d  %s\n",
              set.scene.c_str(), size.c_str(), (e.spec + " x" + std::to_string(e.frames)).c_str(),
              100.0 * e.fid.identical_share, e.soft.differing, e.fid.max_diff,
              e.timed ? (JsonNumber(e.t.median) + " ms/frame (" + JsonNumber(e.ratio) + "x copy)").c_str() : "");
  run.entries.push_back(e);
}

/// One frame set: the copy floors, every method, every TAA spec, the copy again after them.
void MeasureFrameSet(GpuRun& run, const FrameSet& set, const std::vector<GpuMethod>& methods) {
  const Options& o = run.o;
  const std::string size = std::to_string(set.width) + "x" + std::to_string(set.height);
  GpuPipeline p1(set.width, set.height, set.width, set.height, run.decode);
  p1.Upload(set.frame1x);
  std::unique_ptr<GpuPipeline> ps;
  if (!set.scaled.Empty()) {
    ps = std::make_unique<GpuPipeline>(set.scaled.Width(), set.scaled.Height(), set.width, set.height, run.decode);
    ps->Upload(set.scaled);
  }
  const CopyFloors floors = MeasureCopies(run, set, size, p1);
  for (const GpuMethod& m : methods) {
    GpuPipeline* p = m.scaled_input ? ps.get() : &p1;
    if (!p) continue;  // no scaled frame exported for this scene and size
    MeasureMethod(run, set, size, m, p, floors);
  }
  for (const std::string& spec : o.taa_methods) {
    if (set.taa.frames.empty()) break;
    MeasureTaa(run, set, size, spec, floors);
  }
  if (o.timing) {
    // The texture-path copy again after the methods: a drift of the clock (or another load on
    // the GPU) during this frame's measurements shows as a difference to "copy".
    Entry after = MakeEntry(set.scene, size, "copy-after", "copy (point fetch + surface write), after the methods");
    after.timed = true;
    after.t = TimeLaunches([&] { p1.RunCopyTexture(run.stream); }, o.warmup, o.repeat, run.stream);
    after.ratio = after.t.median / floors.texture_ms;
    after.ratio_linear = after.t.median / floors.linear_ms;
    run.entries.push_back(after);
  }
}

int Main(int argc, char** argv) {
  const Options o = ParseArgs(argc, argv);
  if (!o.probe_dump.empty()) return DumpProbe(o.probe_dump);
  std::vector<GpuMethod> methods;
  for (const auto& s : o.methods) methods.push_back(ResolveGpuMethod(s));
  for (const auto& s : o.taa_methods) CheckGpuTaaSpec(s);
  const std::vector<FrameSet> sets = o.self_test ? SelfTestFrames(o.sizes) : ReadManifest(o.frames_dir);

  GpuDeviceFacts device = QueryDevice();
  const TextureProbe probe = ProbeAndPrint();
  float decode_host[256];
  for (int k = 0; k < 256; ++k) decode_host[k] = SrgbDecode8(static_cast<uint8_t>(k));
  float* decode = nullptr;
  cuda::Check(cudaMalloc(reinterpret_cast<void**>(&decode), sizeof decode_host), "cudaMalloc");
  cuda::Check(cudaMemcpy(decode, decode_host, sizeof decode_host, cudaMemcpyHostToDevice), "upload");
  GpuRun run(o, decode);
  cuda::Check(cudaStreamCreate(&run.stream), "cudaStreamCreate");

  const TextureRuleCheck rule = CheckTextureRule(CollectTextureProbeData());
  std::printf(
      "texture rule (core/sampler.h, --sampler gpu-texture) against this device: pairs %lld/%lld, "
      "RGBA8 quads %lld/%lld, coordinates %lld/%lld, RGBA32F quads %lld/%lld differ\n",
      rule.pair_mismatches, rule.pairs, rule.quad8_mismatches, rule.quad8, rule.coord_mismatches, rule.coords,
      rule.quadf_mismatches, rule.quadf);
  if (rule.Mismatches() != 0)
    run.Fail("the texture rule of --sampler gpu-texture does not match this device's texture unit");
  if (!o.outputs_dir.empty()) fs::create_directories(o.outputs_dir);
  for (const FrameSet& set : sets) MeasureFrameSet(run, set, methods);
  device.smi_after = Sh(kSmiQuery);

  if (!o.json_path.empty()) {
    WriteGpuTimingsJson(o.json_path, device, probe, rule, o.warmup, o.repeat, run.entries);
    std::printf("wrote %s (%zu results)\n", o.json_path.c_str(), run.entries.size());
  }
  cudaFree(decode);
  cudaStreamDestroy(run.stream);
  if (run.failures > 0) std::printf("%d check(s) failed\n", run.failures);
  return ToInt(o.check && run.failures > 0 ? ExitCode::kFailure : ExitCode::kOk);
}

}  // namespace
}  // namespace aalab

int main(int argc, char** argv) {
  try {
    return aalab::Main(argc, argv);
  } catch (const aalab::UserError& e) {
    std::fprintf(stderr, "aalab_gpu: error: %s\n", e.what());
    return aalab::ToInt(aalab::ExitCode::kFailure);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "aalab_gpu: internal error: %s\n", e.what());
    return aalab::ToInt(aalab::ExitCode::kInternalError);
  }
}
