// aalab_raster — the raster path (docs/gpu.md "The raster path"): draws the scenes that
// `aalab export-geometry` wrote with OpenGL 4.5 through EGL without a display, for each
// render-time method and size, writes the 8-bit frames (PPM) and times each stage with
// GL_TIME_ELAPSED queries (warm-up, then repeats; median, min, max), into a JSON that
// `aalab run --gpu-timings` and `aalab merge-gpu` read. `aaa` is drawn as the 1x frame on
// scenes without disks (aalab renders triangles under aaa as under none) and skipped, with
// the reason under "not_drawn", on scenes with disks; `scale43` is the render of a
// render-scale method alone (its 4/3 target; rows keep the output size W x H and add
// render_width / render_height), whose rescale and FXAA the CUDA twins time.
//
//   aalab_raster --geometry DIR [--sizes 1920x1080,3840x2160] [--methods none,msaa-4x,...]
//                [--warmup 50] [--repeat 100] [--budget-ms 1000] [--min-repeat 5]
//                [--json FILE] [--frames DIR]
//                [--format rgba16f|rgba32f] [--resolve shader|blit] [--egl auto|device|surfaceless]
//
// Exit status: 0 done, 1 bad input or no OpenGL context (one message on stderr), 2 some
// timings refused (a query without a result, 0 ns for a stage that drew, a GL error or a
// lost context: each named on stderr and under "refused" in the JSON, which holds only the
// rows whose every frame was checked).
#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/raster_geometry.h"
#include "gpu/raster/egl_context.h"
#include "gpu/raster/raster_renderer.h"

namespace aalab::raster {
namespace {
namespace fs = std::filesystem;

struct Options {
  std::string geometry, json, frames, compare;
  std::vector<std::pair<int, int>> sizes{{1920, 1080}, {3840, 2160}};
  std::vector<RasterMethod> methods;
  int warmup = 50, repeat = 100, min_repeat = 5;
  double budget_ms = 1000;
  TargetFormat format = TargetFormat::kRgba16f;
  ResolveKind resolve = ResolveKind::kShader;
  EglPlatform egl = EglPlatform::kAuto;
};

[[noreturn]] void Bad(const std::string& msg) { throw UserError(msg); }

std::vector<std::string> Split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

int ParseInt(const std::string& s, const std::string& opt, int lo, int hi) {
  size_t used = 0;
  int v = 0;
  try {
    v = std::stoi(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != s.size() || s.empty() || v < lo || v > hi) {
    Bad(opt + " '" + s + "' is not an integer in " + std::to_string(lo) + ".." + std::to_string(hi));
  }
  return v;
}

const char* kUsage =
    "usage: aalab_raster --geometry DIR|FILE.geom [options]\n"
    "  --geometry P     a folder written by `aalab export-geometry` (every .geom in it) or one .geom file\n"
    "  --sizes L        output sizes WxH, comma-separated (default 1920x1080,3840x2160)\n"
    "  --methods L      none, aaa, msaa-2x, msaa-4x, msaa-8x, msaa-16x, ssaa-2x2, ssaa-4x4, scale43, taa, taa@N\n"
    "                   (default none,msaa-2x,msaa-4x,msaa-8x,ssaa-2x2,ssaa-4x4,taa); aaa: the 1x frame, only on\n"
    "                   scenes without disks; scale43: its render, round(4/3 W) x round(4/3 H), no rescale\n"
    "  --warmup N       untimed frames before timing each method (default 50)\n"
    "  --repeat N       timed frames (default 100); 0: draw one frame, time nothing\n"
    "  --budget-ms B    GPU time for each scene, size and method's timed frames (default 1000): one probe\n"
    "                   frame sets repeat = clamp(B / probe, min-repeat, N) and warm-up = min(N, B / 2 / probe);\n"
    "                   0: exactly --warmup and --repeat frames\n"
    "  --min-repeat N   fewest timed frames under a budget (default 5)\n"
    "  --json FILE      write the timings (docs/gpu.md \"The raster path\")\n"
    "  --frames DIR     write each frame as DIR/<scene>-<W>x<H>-<method>.ppm\n"
    "  --compare DIR    compare each frame with aalab's in DIR (aalab export-frames [--render-methods ...]):\n"
    "                   <scene>-<W>x<H>.ppm (none, aaa), -<method>.ppm (MSAA, SSAA), -taa-f<N>.ppm (taa@N),\n"
    "                   -scaled.ppm (scale43)\n"
    "  --format F       colour target: rgba16f (default) or rgba32f\n"
    "  --resolve R      MSAA resolve: shader (box average, default) or blit (glBlitFramebuffer)\n"
    "  --egl E          auto (default: EGL_EXT_platform_device, then EGL_MESA_platform_surfaceless), device, "
    "surfaceless\n"
    "exit status: 0 done; 1 bad input or no OpenGL context; 2 some timings refused (named on stderr and under\n"
    "\"refused\" in the JSON, which keeps the checked rows)\n";

Options ParseArgs(int argc, char** argv) {
  Options o;
  std::string methods = "none,msaa-2x,msaa-4x,msaa-8x,ssaa-2x2,ssaa-4x4,taa";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      std::exit(0);
    }
    if (i + 1 >= argc) Bad("option '" + a + "' needs a value (or is unknown)\n" + kUsage);
    const std::string v = argv[++i];
    if (a == "--geometry")
      o.geometry = v;
    else if (a == "--json")
      o.json = v;
    else if (a == "--frames")
      o.frames = v;
    else if (a == "--compare") {
      if (!fs::is_directory(v)) Bad("--compare '" + v + "' is not a folder (write one with aalab export-frames)");
      o.compare = v;
    } else if (a == "--methods")
      methods = v;
    else if (a == "--warmup")
      o.warmup = ParseInt(v, a, 0, 100000);
    else if (a == "--repeat")
      o.repeat = ParseInt(v, a, 0, 100000);
    else if (a == "--min-repeat")
      o.min_repeat = ParseInt(v, a, 1, 100000);
    else if (a == "--budget-ms")
      o.budget_ms = ParseInt(v, a, 0, 3600000);
    else if (a == "--sizes") {
      o.sizes.clear();
      for (const auto& s : Split(v)) {
        const size_t x = s.find('x');
        if (x == std::string::npos) Bad("--sizes entry '" + s + "' is not WxH (e.g. 1920x1080)");
        o.sizes.emplace_back(ParseInt(s.substr(0, x), "--sizes width", 1, 16384),
                             ParseInt(s.substr(x + 1), "--sizes height", 1, 16384));
      }
      if (o.sizes.empty()) Bad("--sizes is empty (give e.g. 1920x1080,3840x2160)");
    } else if (a == "--format") {
      if (v == "rgba16f")
        o.format = TargetFormat::kRgba16f;
      else if (v == "rgba32f")
        o.format = TargetFormat::kRgba32f;
      else
        Bad("--format '" + v + "' is not allowed (allowed: rgba16f, rgba32f)");
    } else if (a == "--resolve") {
      if (v == "shader")
        o.resolve = ResolveKind::kShader;
      else if (v == "blit")
        o.resolve = ResolveKind::kBlit;
      else
        Bad("--resolve '" + v + "' is not allowed (allowed: shader, blit)");
    } else if (a == "--egl") {
      if (!ParseEglPlatform(v, &o.egl)) Bad("--egl '" + v + "' is not allowed (allowed: auto, device, surfaceless)");
    } else {
      Bad("unknown option '" + a + "'\n" + kUsage);
    }
  }
  if (o.geometry.empty()) Bad(std::string("--geometry is required\n") + kUsage);
  for (const auto& m : Split(methods)) {
    RasterMethod rm;
    std::string why;
    if (!ParseRasterMethod(m, &rm, &why)) Bad("--methods: " + why);
    o.methods.push_back(rm);
  }
  if (o.methods.empty()) Bad("--methods is empty");
  return o;
}

std::string ReadFile(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  if (!f) Bad("cannot read '" + p.string() + "'");
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

std::vector<RasterScene> LoadGeometry(const std::string& path) {
  std::vector<fs::path> files;
  if (fs::is_directory(path)) {
    for (const auto& e : fs::directory_iterator(path)) {
      if (e.path().extension() == ".geom") files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    if (files.empty())
      Bad("--geometry folder '" + path + "' holds no .geom file (write them with aalab export-geometry)");
  } else if (fs::is_regular_file(path)) {
    files.push_back(path);
  } else {
    Bad("--geometry '" + path + "' is neither a folder nor a file");
  }
  std::vector<RasterScene> out;
  for (const auto& f : files) out.push_back(ParseRasterScene(ReadFile(f), f.string()));
  return out;
}

void WritePpm(const fs::path& p, int w, int h, const std::vector<uint8_t>& rgb) {
  std::ofstream f(p, std::ios::binary);
  f << "P6\n" << w << " " << h << "\n255\n";
  f.write(reinterpret_cast<const char*>(rgb.data()), static_cast<std::streamsize>(rgb.size()));
  if (!f) throw std::runtime_error("cannot write '" + p.string() + "'");
}

/// A binary PPM (P6, maxval 255) as written by aalab export-frames; empty when unreadable.
std::vector<uint8_t> ReadPpm(const fs::path& p, int* w, int* h) {
  std::ifstream f(p, std::ios::binary);
  std::string magic;
  int maxval = 0;
  if (!(f >> magic >> *w >> *h >> maxval) || magic != "P6" || maxval != 255 || *w <= 0 || *h <= 0) return {};
  f.get();
  std::vector<uint8_t> px(static_cast<size_t>(*w) * *h * 3);
  f.read(reinterpret_cast<char*>(px.data()), static_cast<std::streamsize>(px.size()));
  if (!f) return {};
  return px;
}

/// The frame against aalab's: pixels identical, pixels within 1 code per channel, largest
/// channel difference; "" when there is no frame to compare with.
std::string FidelityJson(const fs::path& ref, const std::vector<uint8_t>& rgb, int w, int h, std::string* line) {
  int rw = 0, rh = 0;
  const std::vector<uint8_t> a = ReadPpm(ref, &rw, &rh);
  if (a.empty()) return "";
  if (rw != w || rh != h)
    throw UserError("--compare: '" + ref.string() + "' is " + std::to_string(rw) + "x" + std::to_string(rh) + ", not " +
                    std::to_string(w) + "x" + std::to_string(h));
  size_t same = 0, within1 = 0;
  int worst = 0;
  const size_t n = static_cast<size_t>(w) * h;
  for (size_t i = 0; i < n; ++i) {
    int m = 0;
    for (int c = 0; c < 3; ++c) m = std::max(m, std::abs(int(a[3 * i + c]) - int(rgb[3 * i + c])));
    same += m == 0;
    within1 += m <= 1;
    worst = std::max(worst, m);
  }
  char b[256];
  std::snprintf(b, sizeof b, "identical %.6f, within 1 code %.6f, max diff %d", double(same) / n, double(within1) / n,
                worst);
  *line = b;
  std::snprintf(b, sizeof b,
                "{\"identical_share\": %.6f, \"within_1_share\": %.6f, \"max_diff\": %d, \"pixels_over_1\": %zu}",
                double(same) / n, double(within1) / n, worst, n - within1);
  return b;
}

std::string JsonString(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      char b[8];
      std::snprintf(b, sizeof b, "\\u%04x", c);
      o += b;
    } else {
      o += c;
    }
  }
  return o + "\"";
}

struct Stat {
  double median = 0, min = 0, max = 0;
};
Stat Stats(std::vector<double> v) {
  if (v.empty()) return {};
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  const double med = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  return {med, v.front(), v.back()};
}
std::string StatJson(const Stat& s) {
  char b[160];
  std::snprintf(b, sizeof b, "{\"median_ms\": %.6f, \"min_ms\": %.6f, \"max_ms\": %.6f}", s.median, s.min, s.max);
  return b;
}

/// The refusal path's test hook: AALAB_RASTER_TEST_ZERO_STAGE=<method>:<draw|resolve|encode>
/// makes that method's stage read as 0 ns (raster_cli_test); −1 without it.
int TestZeroStage(const std::string& method) {
  const char* env = std::getenv("AALAB_RASTER_TEST_ZERO_STAGE");
  if (!env) return -1;
  const std::string v = env;
  for (int k = 0; k < 3; ++k) {
    if (v == method + ":" + std::array<const char*, 3>{"draw", "resolve", "encode"}[static_cast<size_t>(k)]) return k;
  }
  return -1;
}

int Main(int argc, char** argv) {
  const Options o = ParseArgs(argc, argv);
  const std::vector<RasterScene> scenes = LoadGeometry(o.geometry);
  if (!o.frames.empty()) fs::create_directories(o.frames);
  GlDeviceInfo dev;
  if (const std::string why = MakeHeadlessGlContext(o.egl, &dev); !why.empty()) {
    Bad("no OpenGL 4.5 context: " + why +
        " (needs an EGL with EGL_EXT_platform_device, e.g. the NVIDIA driver, or Mesa's surfaceless platform)");
  }
  std::fprintf(stderr, "aalab_raster: %s (%s, %s) via %s\n", dev.renderer.c_str(), dev.vendor.c_str(),
               dev.version.c_str(), dev.platform.c_str());
  std::ostringstream rows, not_drawn, refused;
  bool first = true, lost = false;
  for (const auto& scene : scenes) {
    if (lost) break;
    RasterRenderer r(scene);
    for (const auto& [w, h] : o.sizes) {
      if (lost) break;
      for (const auto& m : o.methods) {
        // A method this scene has no raster form of (aaa on analytic disks) is skipped with
        // its reason, listed in the JSON like a capability skip.
        if (const std::string why = RasterMethodRefusal(m, scene); !why.empty()) {
          std::fprintf(stderr, "aalab_raster: warning: skipped %s on %s at %dx%d: %s\n", m.name.c_str(),
                       scene.name.c_str(), w, h, why.c_str());
          not_drawn << (not_drawn.tellp() > 0 ? ", " : "")
                    << JsonString(scene.name + " " + std::to_string(w) + "x" + std::to_string(h) + " " + m.name + ": " +
                                  why);
          continue;
        }
        // What this GL cannot allocate (more samples than GL_MAX_SAMPLES, a target past
        // GL_MAX_TEXTURE_SIZE) is skipped with a warning and listed in the JSON.
        try {
          r.Configure(m, w, h, o.format, o.resolve);
        } catch (const CapabilityError& e) {
          std::fprintf(stderr, "aalab_raster: warning: skipped %s on %s at %dx%d: %s\n", m.name.c_str(),
                       scene.name.c_str(), w, h, e.what());
          not_drawn << (not_drawn.tellp() > 0 ? ", " : "")
                    << JsonString(scene.name + " " + std::to_string(w) + "x" + std::to_string(h) + " " + m.name + ": " +
                                  e.what());
          continue;
        }
        r.RenderFrame();
        const int want = m.kind == RasterMethod::Kind::kMsaa ? m.samples : 1;
        if (r.Samples() != want) {
          std::fprintf(stderr, "aalab_raster: warning: %s got %d samples per pixel from this GL, not %d\n",
                       m.name.c_str(), r.Samples(), want);
        }
        int fw = 0, fh = 0;  // the frame drawn (scale43: its render size)
        RasterFrameSize(m, w, h, &fw, &fh);
        std::string fidelity;
        if (!o.compare.empty()) {
          const std::string base = scene.name + "-" + std::to_string(w) + "x" + std::to_string(h);
          const std::string ref = m.kind == RasterMethod::Kind::kOne     ? base + ".ppm"
                                  : m.kind == RasterMethod::Kind::kScale ? base + "-scaled.ppm"
                                  : m.kind == RasterMethod::Kind::kTaa
                                      ? base + "-taa-f" + std::to_string(m.taa_frame) + ".ppm"
                                      : base + "-" + m.name + ".ppm";
          std::string line;
          fidelity = FidelityJson(fs::path(o.compare) / ref, r.ReadRgb8(), fw, fh, &line);
          std::fprintf(stderr, "%s %dx%d %-9s against %s: %s\n", scene.name.c_str(), w, h, m.name.c_str(), ref.c_str(),
                       fidelity.empty() ? "no such frame" : line.c_str());
        }
        if (!o.frames.empty()) {
          const std::string file =
              scene.name + "-" + std::to_string(w) + "x" + std::to_string(h) + "-" +
              (m.kind == RasterMethod::Kind::kTaa ? "taa-f" + std::to_string(m.taa_frame) : m.name) + ".ppm";
          WritePpm(fs::path(o.frames) / file, fw, fh, r.ReadRgb8());
        }
        if (o.repeat == 0) {
          if (!fidelity.empty()) {
            rows << (first ? "" : ",\n") << "    {\"scene\": " << JsonString(scene.name) << ", \"width\": " << w
                 << ", \"height\": " << h << ", \"method\": " << JsonString(m.name) << ", \"samples\": " << r.Samples()
                 << ", \"fidelity\": " << fidelity << "}";
            first = false;
          }
          continue;
        }
        TimingPlan plan;
        plan.warmup = o.warmup;
        plan.repeat = o.repeat;
        plan.min_repeat = o.min_repeat;
        plan.budget_ms = o.budget_ms;
        plan.zero_stage = TestZeroStage(m.name);
        TimedFrames timed;
        try {
          timed = r.TimeFrames(plan);
        } catch (const TimingError& e) {
          // Refused, loudly: no time for this row rather than a wrong one.
          const std::string what = scene.name + " " + std::to_string(w) + "x" + std::to_string(h) + " " + m.name;
          std::fprintf(stderr, "aalab_raster: error: timing of %s refused: %s\n", what.c_str(), e.what());
          refused << (refused.tellp() > 0 ? ",\n    " : "") << JsonString(what + ": " + e.what());
          if (e.context_lost) {
            lost = true;
            break;
          }
          continue;
        }
        const std::vector<StageTimes>& t = timed.frames;
        std::vector<double> draw, resolve, encode, total;
        for (const auto& s : t) {
          draw.push_back(s.draw);
          resolve.push_back(s.resolve);
          encode.push_back(s.encode);
          total.push_back(s.Total());
        }
        const Stat tot = Stats(total);
        std::fprintf(stderr, "%s %dx%d %-9s %.4f ms (draw %.4f, resolve %.4f, encode %.4f; %d+%d frames)\n",
                     scene.name.c_str(), w, h, m.name.c_str(), tot.median, Stats(draw).median, Stats(resolve).median,
                     Stats(encode).median, timed.warmup, static_cast<int>(t.size()));
        rows << (first ? "" : ",\n") << "    {\"scene\": " << JsonString(scene.name) << ", \"width\": " << w
             << ", \"height\": " << h << ", \"method\": " << JsonString(m.name) << ", \"samples\": " << r.Samples()
             << (m.kind == RasterMethod::Kind::kScale
                     ? ", \"render_width\": " + std::to_string(fw) + ", \"render_height\": " + std::to_string(fh)
                     : "")
             << ", \"triangles\": " << scene.triangles.size() << ", \"warmup\": " << timed.warmup
             << ", \"repeat\": " << t.size() << ", \"probe_ms\": " << timed.probe_ms
             << ",\n     \"total\": " << StatJson(tot) << ",\n     \"draw\": " << StatJson(Stats(draw))
             << ", \"resolve\": " << StatJson(Stats(resolve)) << ", \"encode\": " << StatJson(Stats(encode))
             << (fidelity.empty() ? "" : ",\n     \"fidelity\": " + fidelity) << "}";
        first = false;
      }
    }
  }
  if (!o.json.empty()) {
    std::ostringstream j;
    j << "{\n  \"schema\": \"aalab-raster-timings\",\n  \"schema_version\": 1,\n  \"tool\": \"aalab_raster\",\n  "
         "\"device\": "
      << JsonString(dev.renderer) << ",\n  \"vendor\": " << JsonString(dev.vendor)
      << ",\n  \"gl_version\": " << JsonString(dev.version) << ",\n  \"egl_platform\": " << JsonString(dev.platform)
      << ",\n  \"target_format\": \"" << (o.format == TargetFormat::kRgba32f ? "rgba32f" : "rgba16f")
      << "\",\n  \"msaa_resolve\": \"" << (o.resolve == ResolveKind::kBlit ? "blit" : "shader")
      << "\",\n  \"reset_notification\": " << (dev.reset_notification ? "true" : "false")
      << ",\n  \"warmup\": " << o.warmup << ",\n  \"repeat\": " << o.repeat << ",\n  \"min_repeat\": " << o.min_repeat
      << ",\n  \"budget_ms\": " << o.budget_ms << ",\n  \"not_drawn\": [" << not_drawn.str() << "],\n  \"refused\": ["
      << refused.str() << "],\n  \"rows\": [\n"
      << rows.str() << "\n  ]\n}\n";
    const std::string tmp = o.json + ".partial";
    {
      std::ofstream f(tmp, std::ios::binary);
      f << j.str();
      if (!f) throw std::runtime_error("cannot write '" + tmp + "'");
    }
    fs::rename(tmp, o.json);
  }
  if (refused.tellp() > 0) {
    std::fprintf(stderr, "aalab_raster: error: some timings were refused (listed above%s)%s\n",
                 o.json.empty() ? "" : " and under \"refused\" in the JSON",
                 lost ? "; the GL context was lost, so the rows after it were not drawn" : "");
    return 2;
  }
  return 0;
}

}  // namespace
}  // namespace aalab::raster

int main(int argc, char** argv) {
  try {
    return aalab::raster::Main(argc, argv);
  } catch (const aalab::UserError& e) {
    std::fprintf(stderr, "aalab_raster: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "aalab_raster: %s\n", e.what());
    return 1;
  }
}
