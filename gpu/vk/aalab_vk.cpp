// aalab_vk: the GPU cost of CMAA2, FSR 1 and FSR 2 as their ORIGINAL shaders, through Vulkan
// (docs/gpu.md "Original shaders through Vulkan"). Reads the frames `aalab export-frames`
// wrote and the SPIR-V modules scripts/vk_shaders.sh compiled, runs each method's pass chain
// with vkCmdWriteTimestamp around every pass (warm-up, then timed repetitions back to back),
// and writes the JSON `aalab merge-gpu` reads (schema aalab-gpu-timings 1; reports/
// gpu_timings.h). --frames DIR writes each output frame as PPM, for comparison with aalab's
// CPU ports. FSR 2 (fsr2-*) runs a synthetic sequence built from the first scene's frame at
// each size (gpu/vk/vk_fsr2.cpp), once per size. Exit codes: 0 done, 1 bad arguments or input (one message), 2 Vulkan
// failed.
#include <algorithm>
#include <cstdlib>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/vk/vk_fsr2.h"
#include "gpu/vk/vk_methods.h"
#include "gpu/vk/vk_runner.h"

namespace fs = std::filesystem;
using namespace aalab::vk;

namespace {

struct BadInput : std::runtime_error {
  using std::runtime_error::runtime_error;
};

const char* const kUsage =
    "usage: aalab_vk --shaders DIR --input DIR [options]\n"
    "  --shaders DIR    SPIR-V modules written by scripts/vk_shaders.sh DIR\n"
    "  --input DIR      frames written by `aalab export-frames` (DIR/frames.tsv + PPM)\n"
    "  --json FILE      write the timings (schema aalab-gpu-timings 1, for `aalab merge-gpu`)\n"
    "  --frames DIR     write each output frame as DIR/<scene>-<W>x<H>-<method>.ppm\n"
    "  --compare DIR    compare each output with DIR/<scene>-<W>x<H>-<method>.ppm where that exists (aalab's\n"
    "                   CPU output: gpu/vk/pack.sh); the JSON gets a fidelity block per compared result\n"
    "  --methods LIST   comma-separated, default all: copy is always run first (the floor)\n"
    "  --warmup N       untimed runs of each method's chain before timing (default 200; FSR 2: frames)\n"
    "  --repeat N       timed runs (default 200; FSR 2: frames, each timed)\n"
    "  --device NAME    the first Vulkan device whose name contains NAME (default: a discrete GPU, else the first)\n";

struct Options {
  std::string shaders, input, json, frames, compare, device;
  std::vector<std::string> methods;
  int warmup = 200, repeat = 200;
};

int ParseCount(const std::string& flag, const std::string& v, int lo, int hi) {
  size_t used = 0;
  int n = 0;
  try {
    n = std::stoi(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != v.size() || n < lo || n > hi) {
    throw BadInput(flag + " '" + v + "' is not an integer in " + std::to_string(lo) + ".." + std::to_string(hi));
  }
  return n;
}

std::vector<std::string> SplitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

Options Parse(int argc, char** argv) {
  Options o;
  std::string methods;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      std::exit(0);
    }
    if (i + 1 >= argc) throw BadInput("option '" + a + "' needs a value (or is unknown)\n" + kUsage);
    const std::string v = argv[++i];
    if (a == "--shaders") {
      o.shaders = v;
    } else if (a == "--input") {
      o.input = v;
    } else if (a == "--json") {
      o.json = v;
    } else if (a == "--frames") {
      o.frames = v;
    } else if (a == "--compare") {
      o.compare = v;
    } else if (a == "--methods") {
      methods = v;
    } else if (a == "--device") {
      o.device = v;
    } else if (a == "--warmup") {
      o.warmup = ParseCount(a, v, 0, 100000);
    } else if (a == "--repeat") {
      o.repeat = ParseCount(a, v, 1, 100000);
    } else {
      throw BadInput("unknown option '" + a + "'\n" + kUsage);
    }
  }
  if (o.shaders.empty() || o.input.empty())
    throw BadInput(std::string("--shaders and --input are required\n") + kUsage);
  std::string known;
  for (const MethodInfo& m : Methods()) known += (known.empty() ? "" : ", ") + m.spec;
  o.methods = {"copy"};
  for (const std::string& m : methods.empty() ? std::vector<std::string>{} : SplitList(methods)) {
    if (!FindMethod(m)) throw BadInput("--methods: unknown method '" + m + "' (known: " + known + ")");
    if (std::find(o.methods.begin(), o.methods.end(), m) == o.methods.end()) o.methods.push_back(m);
  }
  if (methods.empty()) {
    for (const MethodInfo& m : Methods()) {
      if (m.spec != "copy") o.methods.push_back(m.spec);
    }
  }
  return o;
}

// A binary PPM (P6, maxval 255) as RGBA rows.
Frame ReadPpm(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  if (!f) throw BadInput("frame '" + p.string() + "' cannot be read");
  std::string magic;
  int w = 0, h = 0, maxval = 0;
  f >> magic >> w >> h >> maxval;
  f.get();
  if (!f || magic != "P6" || maxval != 255 || w <= 0 || h <= 0 || w > 16384 || h > 16384) {
    throw BadInput("frame '" + p.string() + "' is not a binary 8-bit PPM (P6, maxval 255, sides 1..16384)");
  }
  std::vector<uint8_t> rgb(static_cast<size_t>(w) * static_cast<size_t>(h) * 3);
  f.read(reinterpret_cast<char*>(rgb.data()), static_cast<std::streamsize>(rgb.size()));
  if (!f) throw BadInput("frame '" + p.string() + "' is truncated");
  Frame fr{w, h, std::vector<uint8_t>(static_cast<size_t>(w) * static_cast<size_t>(h) * 4, 255)};
  for (size_t i = 0; i < static_cast<size_t>(w) * static_cast<size_t>(h); ++i) {
    for (size_t c = 0; c < 3; ++c) fr.rgba[i * 4 + c] = rgb[i * 3 + c];
  }
  return fr;
}

void WritePpm(const fs::path& p, const Frame& fr) {
  std::string s = "P6\n" + std::to_string(fr.width) + " " + std::to_string(fr.height) + "\n255\n";
  for (size_t i = 0; i < static_cast<size_t>(fr.width) * static_cast<size_t>(fr.height); ++i) {
    for (size_t c = 0; c < 3; ++c) s += static_cast<char>(fr.rgba[i * 4 + c]);
  }
  const fs::path tmp = p.string() + ".partial";
  {
    std::ofstream f(tmp, std::ios::binary);
    f << s;
    if (!f) throw BadInput("'" + p.string() + "' cannot be written");
  }
  fs::rename(tmp, p);
}

// One scene at one output size: its frames by role.
struct FrameSet {
  std::string scene;
  int width = 0, height = 0;
  std::map<std::string, fs::path> roles;
};

std::vector<FrameSet> ReadFrameList(const std::string& dir) {
  const fs::path list = fs::path(dir) / "frames.tsv";
  std::ifstream f(list);
  if (!f)
    throw BadInput("'" + list.string() + "' cannot be read (give --input the folder `aalab export-frames` wrote)");
  std::vector<FrameSet> sets;
  std::string line;
  int n = 0;
  while (std::getline(f, line)) {
    ++n;
    if (line.empty() || line[0] == '#') continue;
    std::stringstream ss(line);
    std::string scene, role, w, h, file;
    if (!std::getline(ss, scene, '\t') || !std::getline(ss, role, '\t') || !std::getline(ss, w, '\t') ||
        !std::getline(ss, h, '\t') || !std::getline(ss, file, '\t')) {
      throw BadInput(list.string() + ":" + std::to_string(n) +
                     ": not 5 tab-separated fields (scene, role, width, height, file)");
    }
    const int wi = ParseCount(list.string() + ":" + std::to_string(n) + " width", w, 1, 16384);
    const int hi = ParseCount(list.string() + ":" + std::to_string(n) + " height", h, 1, 16384);
    auto it = std::find_if(sets.begin(), sets.end(),
                           [&](const FrameSet& s) { return s.scene == scene && s.width == wi && s.height == hi; });
    if (it == sets.end()) {
      sets.push_back({scene, wi, hi, {}});
      it = sets.end() - 1;
    }
    it->roles[role] = fs::path(dir) / file;
  }
  if (sets.empty()) throw BadInput("'" + list.string() + "' lists no frames");
  return sets;
}

struct Stats {
  double median = 0, min = 0, max = 0;
};

Stats Summarise(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  Stats s;
  s.min = v.front();
  s.max = v.back();
  const size_t n = v.size();
  s.median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  return s;
}

std::string Num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

std::string Q(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') {
      o += '\\';
      o += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char b[8];
      std::snprintf(b, sizeof b, "\\u%04x", c);
      o += b;
    } else {
      o += c;
    }
  }
  return o + "\"";
}

std::string StatsJson(const Stats& s) {
  return "{\"median_ms\": " + Num(s.median) + ", \"min_ms\": " + Num(s.min) + ", \"max_ms\": " + Num(s.max) + "}";
}

// How far an output is from the CPU port's: the share of pixels whose three bytes are equal,
// the largest difference of a byte, and the pixels that differ.
struct Fidelity {
  bool has = false;
  double identical_share = 0;
  int max_diff = 0;
  long differing = 0;
};

Fidelity Compare(const Frame& out, const fs::path& reference) {
  Fidelity f;
  if (reference.empty() || !fs::exists(reference)) return f;
  const Frame ref = ReadPpm(reference);
  if (ref.width != out.width || ref.height != out.height) {
    throw BadInput("reference '" + reference.string() + "' is " + std::to_string(ref.width) + "x" +
                   std::to_string(ref.height) + ", the output " + std::to_string(out.width) + "x" +
                   std::to_string(out.height));
  }
  const size_t n = static_cast<size_t>(out.width) * static_cast<size_t>(out.height);
  for (size_t i = 0; i < n; ++i) {
    bool same = true;
    for (size_t c = 0; c < 3; ++c) {
      const int d = std::abs(int(out.rgba[i * 4 + c]) - int(ref.rgba[i * 4 + c]));
      f.max_diff = std::max(f.max_diff, d);
      same = same && d == 0;
    }
    f.differing += same ? 0 : 1;
  }
  f.has = true;
  f.identical_share = 1.0 - static_cast<double>(f.differing) / static_cast<double>(n);
  return f;
}

// One result line of the JSON.
std::string ResultJson(const FrameSet& fs, const std::string& method, const std::string& kernels, const MethodResult& r,
                       double copy_ms, const Fidelity& fid) {
  const Stats whole = Summarise(r.timings.whole);
  std::string j =
      "{\"scene\": " + Q(fs.scene) + ", \"size\": " + Q(std::to_string(fs.width) + "x" + std::to_string(fs.height)) +
      ", \"method\": " + Q(method) + ", \"kernels\": " + Q(kernels) + ", \"median_ms\": " + Num(whole.median) +
      ", \"min_ms\": " + Num(whole.min) + ", \"max_ms\": " + Num(whole.max) +
      ", \"ratio_to_copy\": " + Num(copy_ms > 0 ? whole.median / copy_ms : 1.0);
  if (r.pass_names.size() > 1) {
    j += ", \"passes\": {";
    for (size_t k = 0; k < r.pass_names.size(); ++k) {
      std::vector<double> v;
      for (const auto& run : r.timings.ms) v.push_back(run[k]);
      j += (k ? ", " : "") + Q(std::to_string(k + 1) + " " + r.pass_names[k]) + ": " + StatsJson(Summarise(v));
    }
    j += "}";
  }
  if (!r.note.empty()) j += ", \"input\": " + Q(r.note);
  if (r.check.has) {
    j += ", \"output_check\": {\"nonfinite\": " + std::to_string(r.check.nonfinite) + ", \"min\": " + Num(r.check.min) +
         ", \"max\": " + Num(r.check.max) + ", \"mean_abs_error\": " + Num(r.check.mean_abs_error) +
         ", \"mean_abs_error_nearest\": " + Num(r.check.mean_abs_error_nearest) +
         ", \"against\": \"the last frame of the sequence rendered at display size (rgb, 0..1)\"}";
  }
  if (fid.has) {
    j += ", \"fidelity\": {\"identical_share\": " + Num(fid.identical_share) +
         ", \"max_diff\": " + std::to_string(fid.max_diff) +
         ", \"differing_pixels\": " + std::to_string(fid.differing) +
         ", \"against\": \"aalab's CPU port (the --compare folder)\"}";
  }
  return j + "}";
}

std::string NowUtc() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

int Run(const Options& o) {
  const std::vector<FrameSet> sets = ReadFrameList(o.input);
  if (!fs::is_directory(o.shaders)) throw BadInput("--shaders '" + o.shaders + "' is not a folder");
  for (const std::string& spec : o.methods) {
    for (const std::string& m : ModulesOf(spec)) {
      const fs::path p = fs::path(o.shaders) / (m + ".spv");
      if (!fs::is_regular_file(p)) {
        throw BadInput("SPIR-V module '" + p.string() + "' (for " + spec +
                       ") is missing: compile the modules with scripts/vk_shaders.sh " + o.shaders);
      }
    }
  }
  if (!o.compare.empty() && !fs::is_directory(o.compare))
    throw BadInput("--compare '" + o.compare + "' is not a folder");
  if (!o.frames.empty()) fs::create_directories(o.frames);
  Device device(o.device);
  const DeviceFacts& facts = device.Facts();
  std::fprintf(stderr, "aalab_vk: %s (%s, Vulkan %s), warm-up %d, repeat %d\n", facts.name.c_str(),
               facts.driver.c_str(), facts.api.c_str(), o.warmup, o.repeat);
  std::vector<std::string> results;
  std::set<std::string> fsr2_sizes;  // sizes FSR 2 ran at (once per size: its sequence is synthetic)
  for (const FrameSet& set : sets) {
    const std::string size = std::to_string(set.width) + "x" + std::to_string(set.height);
    const bool fsr2_here = fsr2_sizes.insert(size).second;
    double copy_ms = 0;
    auto run = [&](const std::string& spec, const std::string& label) {
      const MethodInfo* m = FindMethod(spec);
      if (const Fsr2Preset* f = FindFsr2Preset(spec)) {
        if (!fsr2_here) return;
        if (Fsr2RenderSide(set.width, f->ratio) < 1 || Fsr2RenderSide(set.height, f->ratio) < 1) {
          std::fprintf(stderr, "aalab_vk: %s %dx%d is too small for %s (its render size would be empty): not run\n",
                       set.scene.c_str(), set.width, set.height, spec.c_str());
          return;
        }
      }
      const auto it = set.roles.find(m->input);
      if (it == set.roles.end()) {
        std::fprintf(stderr, "aalab_vk: %s %dx%d has no '%s' frame: %s not run\n", set.scene.c_str(), set.width,
                     set.height, m->input.c_str(), spec.c_str());
        return;
      }
      const Frame in = ReadPpm(it->second);
      const MethodResult r = RunMethod(device, o.shaders, spec, in, set.width, set.height, o.warmup, o.repeat);
      const double median = Summarise(r.timings.whole).median;
      if (label == "copy") copy_ms = median;
      const std::string stem =
          set.scene + "-" + std::to_string(set.width) + "x" + std::to_string(set.height) + "-" + spec;
      const Fidelity fid = Compare(
          r.output, o.compare.empty() || label == "copy-after" ? fs::path() : fs::path(o.compare) / (stem + ".ppm"));
      results.push_back(ResultJson(set, label, m->kernels, r, copy_ms, fid));
      std::fprintf(stderr, "  %s %dx%d %-20s %.4f ms (%.2f x copy)", set.scene.c_str(), set.width, set.height,
                   label.c_str(), median, copy_ms > 0 ? median / copy_ms : 1.0);
      if (fid.has)
        std::fprintf(stderr, "  %.4f %% identical to the CPU, max diff %d", 100 * fid.identical_share, fid.max_diff);
      std::fprintf(stderr, "\n");
      if (!o.frames.empty() && label != "copy-after") {
        WritePpm(fs::path(o.frames) / (stem + ".ppm"), r.output);
      }
    };
    for (const std::string& spec : o.methods) run(spec, spec);
    run("copy", "copy-after");  // the floor again: how much the clocks moved meanwhile
  }
  if (!o.json.empty()) {
    std::ostringstream j;
    j << "{\n  \"schema\": \"aalab-gpu-timings\",\n  \"schema_version\": 1,\n  \"tool\": \"aalab_vk\",\n";
    j << "  \"generated_utc\": " << Q(NowUtc()) << ",\n";
    j << "  \"device\": {\"name\": " << Q(facts.name) << ", \"vulkan_api\": " << Q(facts.api)
      << ", \"timestamp_period_ns\": " << Num(facts.timestamp_period_ns)
      << ", \"timestamp_valid_bits\": " << facts.timestamp_valid_bits
      << ", \"robust_image_access\": " << (facts.robust_image_access ? "true" : "false") << "},\n";
    j << "  \"driver\": " << Q(facts.driver) << ",\n";
    j << "  \"cuda_runtime\": " << Q("none (Vulkan " + facts.api + ")") << ",\n";
    j << "  \"timing\": {\"method\": \"vkCmdWriteTimestamp (BOTTOM_OF_PIPE) before the first pass and after each "
         "pass's "
         "barrier; the method's chain recorded warmup times in one command buffer (untimed), then repeat times in "
         "another, back to back; median/min/max over the timed runs\", \"warmup\": "
      << o.warmup << ", \"repeat\": " << o.repeat
      << ", \"clocks\": \"not locked\", \"floor\": \"copy (texelFetch + imageStore, RGBA8)\", \"fsr2\": \"one "
         "chain = one frame of the six passes; warmup frames (the first resets), then repeat frames each timed; "
         "median/min/max over the timed frames; run at the first scene of each size only\"},\n";
    j << "  \"results\": [\n";
    for (size_t i = 0; i < results.size(); ++i)
      j << "    " << results[i] << (i + 1 < results.size() ? "," : "") << "\n";
    j << "  ]\n}\n";
    const std::string tmp = o.json + ".partial";
    {
      std::ofstream f(tmp);
      f << j.str();
      if (!f) throw BadInput("'" + o.json + "' cannot be written");
    }
    fs::rename(tmp, o.json);
    std::fprintf(stderr, "aalab_vk: wrote %zu results to %s\n", results.size(), o.json.c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  try {
    o = Parse(argc, argv);
    return Run(o);
  } catch (const BadInput& e) {
    std::fprintf(stderr, "aalab_vk: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "aalab_vk: %s\n", e.what());
    return 2;
  }
}
