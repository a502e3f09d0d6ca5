// aalab_bench — `make bench`: what the harness costs, measured against limits measured in the
// same run on the same machine.
//
//   post filters   Mpix/s on a rendered 1920x1080 1x frame (real content) and on an
//                  edge-dense frame, at 1 and 2 threads; limit: a plain read+write pass over
//                  the same frame at the same thread count (the memory-bandwidth floor).
//   tracing        reference rendering of every library scene in Mrays/s; limit: the bare
//                  Embree loop (Tracer::BareTrace: rtcIntersect16, coherent primary rays, no
//                  shading) on the same scene, size and samples per pixel.
//   metrics        ms per 1080p pair; side by side with scikit-image (SSIM, PSNR) and
//                  OpenImageIO's idiff when installed, timed the same way.
//   suite          wall time of `aalab run` at three sizes and at 1 vs 2 threads.
//   msaa           msaa-4x vs ssaa-rgss per library scene (bench/bench_msaa.cpp).
//
// Timing: Google Benchmark runs each figure (wall clock, UseRealTime) as `repetitions`
// repetitions after one untimed warm-up call; every figure reports the median, min and max
// over the repetitions. Suite runs are timed here directly (one process per repetition).
// Every optimised post filter is also run through its reference implementation and the
// outputs compared byte for byte: any difference fails the benchmark (exit 2).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "bench/bench_stats.h"
#include "bench/bench_bigmesh.h"
#include "bench/bench_metrics.h"
#include "bench/bench_msaa.h"
#include "bench/bench_taa.h"
#include "harness/core/color.h"
#include "harness/core/parallel.h"
#include "harness/io/image_io.h"
#include "bench/bench_smaa.h"
#include "methods/fxaa1.h"
#include "methods/fxaa311.h"
#include "methods/rescale.h"
#include "metrics/metric.h"
#include "metrics/metrics.h"
#include "scenes/library.h"
#include "scenes/render.h"
#include "scenes/tracer.h"
#include "bench/bench_aaa.h"

namespace aalab {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// ------------------------------------------------------------------------------------------
// Settings (command line).

struct Settings {
  std::string json_path = "bench.json";
  std::string aalab_bin = AALAB_BIN_PATH;
  std::string python = "/usr/bin/python3";
  std::string script_dir = AALAB_BENCH_DIR;
  int reps = 5;            // repetitions for post filters and metrics
  int trace_reps = 3;      // repetitions for tracing
  int suite_reps = 2;      // repetitions per suite configuration
  double min_time = 0.05;  // Google Benchmark min time per repetition, seconds
  int trace_w = 320, trace_h = 180, trace_grid = 8;
  bool quick = false;      // a small subset, for checking the benchmark itself
};

// ------------------------------------------------------------------------------------------
// Collecting Google Benchmark repetitions.

using Stats = SampleStats;  // samples: seconds per operation, one per repetition

std::map<std::string, Stats>& Collected() {
  static std::map<std::string, Stats> m;
  return m;
}

class CollectingReporter : public benchmark::BenchmarkReporter {
 public:
  bool ReportContext(const Context&) override { return true; }
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs) {
      if (r.run_type != Run::RT_Iteration) continue;
      if (r.error_occurred) {
        std::fprintf(stderr, "benchmark %s failed: %s\n", r.run_name.function_name.c_str(), r.error_message.c_str());
        std::exit(3);
      }
      // Seconds per iteration, wall clock.
      const double secs = r.real_accumulated_time / static_cast<double>(r.iterations);
      Collected()[r.run_name.function_name].samples.push_back(secs);
      std::fprintf(stderr, "  %-60s %10.3f ms\n", r.run_name.function_name.c_str(), secs * 1e3);
    }
  }
};

// Process CPU time (all threads, user + system), seconds.
double ProcessCpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + (u.ru_utime.tv_usec + u.ru_stime.tv_usec) / 1e6;
}

// Cores the process actually got while a figure ran: CPU seconds / wall seconds, one value
// per repetition. On a machine shared with other work, 2 worker threads may get less than 2.
std::map<std::string, std::vector<double>>& CoresUsed() {
  static std::map<std::string, std::vector<double>> m;
  return m;
}

// Registers `body` as one figure: `threads` worker threads, one warm-up call, then
// `reps` repetitions of at least min_time each.
void Register(const std::string& name, int threads, int reps, double min_time, std::function<void()> body) {
  auto* b = benchmark::RegisterBenchmark(name.c_str(), [name, threads, body](benchmark::State& st) {
    SetThreadCount(threads);
    body();  // warm-up (also first touch of any buffer)
    const double cpu0 = ProcessCpuSeconds();
    const auto w0 = std::chrono::steady_clock::now();
    for (auto _ : st) body();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
    if (wall > 0) CoresUsed()[name].push_back((ProcessCpuSeconds() - cpu0) / wall);
  });
  b->UseRealTime()->Repetitions(reps)->MinTime(min_time);
}

// ------------------------------------------------------------------------------------------
// Frames.

Image8 RenderFrame1x(const std::string& scene_name, int w, int h) {
  const Scene scene = LoadScene(scene_name);
  const Tracer tracer(scene);
  return RenderFrame(tracer, w, h, RenderSpec{}, 1, nullptr);
}

// The memory-bandwidth floor: a plain read+write pass, input rgb to output with alpha 255
// (what an FXAA early exit writes), rows in parallel chunks as the filters use.
void PlainPass(const Image8& in, Image8& out) {
  const int w = in.Width();
  ParallelForChunks(in.Height(), 8, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const uint8_t* s = in.Row(y);
      uint8_t* d = out.Row(y);
      for (int x = 0; x < w; ++x) {
        uint32_t v;
        std::memcpy(&v, s + 4 * x, 4);
        v |= 0xFF000000u;
        std::memcpy(d + 4 * x, &v, 4);
      }
    }
  });
}

[[noreturn]] void FailIdentity(const std::string& what) {
  std::fprintf(stderr, "\n*** BIT-IDENTITY FAILURE: %s: the optimised path differs from its reference ***\n", what.c_str());
  std::exit(2);
}

std::string Fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string Now() {
  const std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&t));
  return buf;
}

std::string CpuModel() {
  std::ifstream f("/proc/cpuinfo");
  std::string line;
  while (std::getline(f, line)) {
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  }
  return "unknown";
}

std::string LoadAverage() {
  std::ifstream f("/proc/loadavg");
  std::string a, b, c;
  f >> a >> b >> c;
  return a + " " + b + " " + c;
}

std::string RunCapture(const std::string& cmd) {
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  pclose(p);
  return out;
}

Json StatsJson(const std::vector<double>& v, double scale) {
  Stats s{v};
  Json j;
  j["median"] = s.Median() * scale;
  j["min"] = s.Min() * scale;
  j["max"] = s.Max() * scale;
  j["repeats"] = v.size();
  return j;
}

// ------------------------------------------------------------------------------------------

int Main(int argc, char** argv) {
  Settings cfg;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", a.c_str());
        std::exit(1);
      }
      return argv[++i];
    };
    if (a == "--json") cfg.json_path = next();
    else if (a == "--aalab") cfg.aalab_bin = next();
    else if (a == "--reps") cfg.reps = std::stoi(next());
    else if (a == "--quick") cfg.quick = true;
    else if (a == "--only-aaa") {  // bench/bench_aaa.cpp's figures alone, printed as markdown
      std::string table;
      const auto figs = BenchAnalyticAa(i + 1 < argc ? std::stoi(argv[++i]) : 5, &table);
      std::printf("%s\n%s\n", table.c_str(), Json(figs).dump(1).c_str());
      return 0;
    } else {
      std::fprintf(stderr, "usage: aalab_bench [--json FILE] [--aalab BIN] [--reps N] [--quick] | --only-aaa [REPS]\n");
      return 1;
    }
  }
  if (cfg.quick) {
    cfg.reps = 3;
    cfg.trace_reps = 2;
    cfg.suite_reps = 1;
    cfg.min_time = 0.01;
  }
  const auto wall_start = std::chrono::steady_clock::now();
  Json report;
  report["schema_version"] = 1;
  Json ctx;  // ordered_json is vector-backed: keep no reference into `report` while adding keys
  ctx["date"] = Now();
  ctx["cpu"] = CpuModel();
  ctx["hardware_threads"] = ThreadCount();
  ctx["load_average_at_start"] = LoadAverage();
  ctx["git_commit"] = RunCapture("git -C " AALAB_SOURCE_DIR " rev-parse --short=12 HEAD 2>/dev/null");
  if (!ctx["git_commit"].get<std::string>().empty() && ctx["git_commit"].get<std::string>().back() == '\n') {
    std::string c = ctx["git_commit"];
    c.pop_back();
    ctx["git_commit"] = c;
  }
  ctx["timing"] = "wall clock; one untimed warm-up call, then " + std::to_string(cfg.reps) +
                  " repetitions (tracing " + std::to_string(cfg.trace_reps) + ", suite " +
                  std::to_string(cfg.suite_reps) + "); median, min, max over repetitions";
  std::fprintf(stderr, "aalab_bench: %s, %s, load %s\n", ctx["date"].get<std::string>().c_str(),
               ctx["cpu"].get<std::string>().c_str(), LoadAverage().c_str());

  // ---------------------------------------------------------------- frames
  const int FW = 1920, FH = 1080;
  std::fprintf(stderr, "rendering the 1080p frames...\n");
  SetThreadCount(0);
  struct Frame {
    std::string key, desc;
    Image8 img;
  };
  std::vector<Frame> frames;
  frames.push_back({"real", "mesh 1920x1080 1x (rendered suite frame)", RenderFrame1x("mesh", FW, FH)});
  frames.push_back({"dense", "checker-plane 1920x1080 1x (edge-dense)", RenderFrame1x("checker-plane", FW, FH)});
  // Scaled frame for the rescale figures: 4/3 of 1080p, as scale43 renders it.
  const Image8 scaled = RenderFrame1x("mesh", 2560, 1440);

  // ---------------------------------------------------------------- post filters
  struct Post {
    std::string name;
    std::function<Image8(const Image8&, PostStats*)> fast, ref;
  };
  std::vector<Post> posts;
  for (int preset = 0; preset <= 5; ++preset) {
    const Fxaa1Params p = Fxaa1Preset(preset);
    posts.push_back({"fxaa1-p" + std::to_string(preset),
                     [p](const Image8& f, PostStats* s) { return Fxaa1(f, p, "", s); },
                     [p](const Image8& f, PostStats* s) { return Fxaa1Reference(f, p, "", s); }});
  }
  for (int id : Fxaa311PresetIds()) {
    Fxaa311Params p;
    p.steps = Fxaa311PresetSteps(id);
    if (cfg.quick && id != 12 && id != 39) continue;
    posts.push_back({"fxaa311-p" + std::to_string(id), [p](const Image8& f, PostStats* s) { return Fxaa311(f, p, s); },
                     [p](const Image8& f, PostStats* s) { return Fxaa311Reference(f, p, s); }});
  }
  {
    const Fxaa311Params high = FxaaTutorialHighParams();
    posts.push_back({"fxaa-high", [high](const Image8& f, PostStats* s) { return Fxaa311(f, high, s); },
                     [high](const Image8& f, PostStats* s) { return Fxaa311Reference(f, high, s); }});
    Fxaa311Params iter12;
    iter12.steps = Fxaa311PresetSteps(39);
    iter12.edge_threshold = 0.125f;
    iter12.edge_threshold_min = 0.0312f;
    iter12.luma = Fxaa311Params::Luma::kRec601Rgb;
    iter12.order = Fxaa311Params::Order::kSeed003Glsl;
    posts.push_back({"fxaa-iter12", [iter12](const Image8& f, PostStats* s) { return Fxaa311(f, iter12, s); },
                     [iter12](const Image8& f, PostStats* s) { return Fxaa311Reference(f, iter12, s); }});
  }
  if (cfg.quick) posts.erase(posts.begin() + 1, posts.begin() + 6);  // keep fxaa1-p0 only
  for (auto& c : bench::SmaaPostCases()) posts.push_back({c.name, c.fast, c.ref});  // bench/bench_smaa.cpp

  // Bit-identity: every optimised filter against its reference on both frames (2 threads).
  std::fprintf(stderr, "checking optimised filters against their references...\n");
  Json identity = Json::array();
  for (const auto& f : frames) {
    for (const auto& p : posts) {
      PostStats a, b;
      const Image8 x = p.fast(f.img, &a);
      const Image8 y = p.ref(f.img, &b);
      if (!(x == y) || a.taps != b.taps) FailIdentity(p.name + " on " + f.key);
      identity.push_back(p.name + " on " + f.key + ": identical (" + std::to_string(a.taps) + " taps)");
    }
  }
  report["bit_identity"] = identity;

  auto out_frame = std::make_shared<Image8>(FW, FH, 4);
  for (int threads : {1, 2}) {
    for (const auto& f : frames) {
      const Image8* in = &f.img;
      const std::string suffix = "/" + f.key + "/t" + std::to_string(threads);
      Register("floor" + suffix, threads, cfg.reps, cfg.min_time, [in, out_frame] { PlainPass(*in, *out_frame); });
      for (const auto& p : posts) {
        auto fn = p.fast;
        Register(p.name + suffix, threads, cfg.reps, cfg.min_time, [in, fn] {
          Image8 o = fn(*in, nullptr);
          benchmark::DoNotOptimize(o.Data().data());
        });
      }
    }
    // Rescale 2560x1440 -> 1920x1080 (Mpix/s of output pixels); floor: read the scaled frame
    // and write the output (a plain pass over each).
    const Image8* sc = &scaled;
    auto big_out = std::make_shared<Image8>(2560, 1440, 4);
    const std::string t = "/t" + std::to_string(threads);
    Register("floor-rescale" + t, threads, cfg.reps, cfg.min_time, [sc, big_out] { PlainPass(*sc, *big_out); });
    for (auto [name, kind] : {std::pair{"rescale-bilinear", Rescale::kBilinear}, std::pair{"rescale-bicubic", Rescale::kBicubic}}) {
      Register(std::string(name) + t, threads, cfg.reps, cfg.min_time, [sc, kind = kind] {
        Image8 o = RescaleFrame(*sc, 1920, 1080, kind, nullptr);
        benchmark::DoNotOptimize(o.Data().data());
      });
    }
  }

  // SSAA resolve: the 2x2 samples of the real frame's scene, resolved to 1080p.
  std::fprintf(stderr, "tracing 2x2 samples for the SSAA resolve figure...\n");
  const Scene resolve_scene = LoadScene("mesh");
  auto samples = std::make_shared<std::vector<SampleResult>>(static_cast<size_t>(FW) * FH * 4);
  {
    const Tracer tracer(resolve_scene);
    const auto offs = [] {  // named fields: RenderSpec grows a member per render-time family
      RenderSpec r;
      r.pattern = SamplePattern::kOrderedGrid;
      r.grid = 2;
      return r.FixedOffsets();
    }();
    ParallelForChunks(FH, 8, [&](int y0, int y1) {
      std::vector<SamplePos> pos(static_cast<size_t>(FW) * 4);
      for (int y = y0; y < y1; ++y) {
        for (int x = 0; x < FW; ++x) {
          for (int s = 0; s < 4; ++s) pos[static_cast<size_t>(x) * 4 + s] = {x + offs[s].first, y + offs[s].second};
        }
        tracer.Trace(pos.data(), FW * 4, FW, FH, samples->data() + static_cast<size_t>(y) * FW * 4, nullptr);
      }
    });
  }
  const Display resolve_display = resolve_scene.display;
  for (int threads : {1, 2}) {
    const std::string t = "/t" + std::to_string(threads);
    Register("ssaa-resolve-2x2" + t, threads, cfg.reps, cfg.min_time, [samples, out_frame, resolve_display] {
      ParallelForChunks(FH, 8, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
          for (int x = 0; x < FW; ++x) {
            ResolveBoxPixel(resolve_display, samples->data() + (static_cast<size_t>(y) * FW + x) * 4, 4, out_frame->Pixel(x, y));
          }
        }
      });
    });
    // Floor: read the 4 samples of every pixel, write the pixel.
    Register("floor-resolve" + t, threads, cfg.reps, cfg.min_time, [samples, out_frame] {
      ParallelForChunks(FH, 8, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
          const SampleResult* r = samples->data() + static_cast<size_t>(y) * FW * 4;
          uint8_t* d = out_frame->Row(y);
          for (int x = 0; x < FW; ++x) {
            uint32_t acc = 0;
            for (int s = 0; s < 4; ++s) {
              uint32_t v[sizeof(SampleResult) / 4];  // every word of the sample
              std::memcpy(v, &r[4 * x + s], sizeof(v));
              for (uint32_t w : v) acc ^= w;
            }
            std::memcpy(d + 4 * x, &acc, 4);
          }
        }
      });
    });
  }

  // ---------------------------------------------------------------- tracing
  // The synthetic library; the glTF real-* scenes are measured by their suite
  // (docs/real-content.md) and the big-mesh section below, keeping make bench under 10 min.
  std::vector<std::string> scenes;
  for (const auto& n : LibrarySceneNames()) {
    if (n.rfind("real-", 0) != 0) scenes.push_back(n);
  }
  if (cfg.quick) scenes = {"wedges", "shadow-stipple"};
  struct Traced {
    std::unique_ptr<Scene> scene;
    std::unique_ptr<Tracer> tracer;
    uint64_t rays = 0;  // primary + shadow rays of one reference render
  };
  auto traced = std::make_shared<std::map<std::string, Traced>>();
  for (const auto& name : scenes) {
    Traced t;
    t.scene = std::make_unique<Scene>(LoadScene(name));
    t.tracer = std::make_unique<Tracer>(*t.scene);
    TraceCounters c;
    RenderReference(*t.tracer, cfg.trace_w, cfg.trace_h, cfg.trace_grid, 1, &c);
    t.rays = c.primary_rays + c.shadow_rays;
    (*traced)[name] = std::move(t);
  }
  for (int threads : {1, 2}) {
    for (const auto& name : scenes) {
      const Tracer* tr = (*traced)[name].tracer.get();
      const std::string t = "/t" + std::to_string(threads);
      const int w = cfg.trace_w, h = cfg.trace_h, g = cfg.trace_grid;
      Register("reference/" + name + t, threads, cfg.trace_reps, cfg.min_time, [tr, w, h, g] {
        Reference r = RenderReference(*tr, w, h, g, 1, nullptr);
        benchmark::DoNotOptimize(r.image.Data().data());
      });
      Register("bare-embree/" + name + t, threads, cfg.trace_reps, cfg.min_time, [tr, w, h, g] {
        benchmark::DoNotOptimize(tr->BareTrace(w, h, g));
      });
    }
  }

  // ---------------------------------------------------------------- metrics
  std::fprintf(stderr, "rendering the 1080p metric pair...\n");
  SetThreadCount(0);
  auto pair_ref = std::make_shared<Reference>();
  auto pair_img = std::make_shared<ImageF>();
  auto pair_none = std::make_shared<ImageF>();
  {
    const Scene scene = LoadScene("mesh");
    const Tracer tracer(scene);
    *pair_ref = RenderReference(tracer, FW, FH, 2, 1, nullptr);
    Fxaa311Params p;
    p.steps = Fxaa311PresetSteps(39);
    *pair_img = ToFloat(Fxaa311(frames[0].img, p, nullptr), 3);
    *pair_none = ToFloat(frames[0].img, 3);
  }
  for (int threads : {1, 2}) {
    const std::string t = "/t" + std::to_string(threads);
    Register("metric-psnr" + t, threads, cfg.reps, cfg.min_time, [pair_ref, pair_img] {
      benchmark::DoNotOptimize(MeanSquaredError(*pair_img, pair_ref->image).mse);
    });
    Register("metric-ssim" + t, threads, cfg.reps, cfg.min_time, [pair_ref, pair_img] {
      benchmark::DoNotOptimize(ComputeSsim(*pair_img, pair_ref->image).ssim);
    });
    // SSIM as a run computes it per method: the reference's half prepared once per scene.
    Register("metric-ssim-run" + t, threads, cfg.reps, cfg.min_time, [pair_ref, pair_img] {
      static const std::shared_ptr<const SsimReferenceSide> side = PrepareSsimReference(pair_ref->image);
      benchmark::DoNotOptimize(ComputeSsim(*pair_img, *side).ssim);
    });
    // FLIP as a run computes it per method (the reference's half reused after the first
    // method of a scene), and from scratch (the first method of a scene, or `aalab metrics`).
    Register("metric-flip" + t, threads, cfg.reps, cfg.min_time, [pair_ref, pair_img] {
      static const std::shared_ptr<const flip::ReferenceSide> side = flip::PrepareReference(pair_ref->image, kFlipDefaultPpd);
      benchmark::DoNotOptimize(PoolFlip(flip::ErrorValues(*side, *pair_img)).mean);
    });
    Register("metric-flip-uncached" + t, threads, cfg.reps, cfg.min_time, [pair_ref, pair_img] {
      benchmark::DoNotOptimize(PoolFlip(flip::ErrorValues(pair_ref->image, *pair_img, kFlipDefaultPpd)).mean);
    });
    Register("metric-edge" + t, threads, cfg.reps, cfg.min_time, [pair_ref, pair_img, pair_none] {
      for (const auto& e : MetricRegistry()) {
        if (e.name != "edge") continue;
        MetricInput in;
        in.image = pair_img.get();
        in.reference = &pair_ref->image;
        in.edge_mask = &pair_ref->edge_mask;
        in.none_image = pair_none.get();
        benchmark::DoNotOptimize(e.compute(in).size());
      }
    });
    Register("metric-all" + t, threads, cfg.reps, cfg.min_time, [pair_ref, pair_img, pair_none] {
      MetricInput in;
      in.image = pair_img.get();
      in.reference = &pair_ref->image;
      in.edge_mask = &pair_ref->edge_mask;
      in.none_image = pair_none.get();
      benchmark::DoNotOptimize(ComputeAllMetrics(in).size());
    });
  }

  // ---------------------------------------------------------------- run the registered figures
  std::fprintf(stderr, "running %s figures (Google Benchmark %s)...\n", "registered", "repetitions");
  CollectingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  SetThreadCount(0);
  auto& C = Collected();
  auto get = [&](const std::string& k) -> const Stats& {
    auto it = C.find(k);
    if (it == C.end()) {
      std::fprintf(stderr, "missing figure %s\n", k.c_str());
      std::exit(3);
    }
    return it->second;
  };

  // ---------------------------------------------------------------- external metric tools
  std::fprintf(stderr, "external tools on the same pair...\n");
  const fs::path tmp = fs::temp_directory_path() / ("aalab_bench_" + std::to_string(getpid()));
  fs::create_directories(tmp);
  auto write_raw = [&](const ImageF& img, const fs::path& p) {
    std::ofstream f(p, std::ios::binary);
    for (int y = 0; y < img.Height(); ++y) {
      for (int x = 0; x < img.Width(); ++x) {
        for (int c = 0; c < 3; ++c) {
          const float v = img.At(x, y, c);
          f.write(reinterpret_cast<const char*>(&v), 4);
        }
      }
    }
  };
  write_raw(*pair_img, tmp / "a.f32");
  write_raw(pair_ref->image, tmp / "b.f32");
  Json external;
  const bench::NvidiaFlipRun nvidia_flip =  // bench/bench_metrics.cpp
      bench::RunNvidiaFlip(ToUnorm8(pair_ref->image), ToUnorm8(*pair_img), std::max(3, cfg.reps / 2 + 1), tmp.string());
  {
    const std::string cmd = cfg.python + " " + cfg.script_dir + "/external_metrics.py " + (tmp / "a.f32").string() + " " +
                            (tmp / "b.f32").string() + " " + std::to_string(FW) + " " + std::to_string(FH) + " " +
                            std::to_string(std::max(3, cfg.reps / 2 + 1)) + " 2>/dev/null";
    const std::string out = RunCapture(cmd);
    try {
      external["skimage"] = Json::parse(out);
    } catch (...) {
      external["skimage"] = Json{{"error", "scikit-image run failed: " + out}};
    }
  }
  {
    WriteImageF((tmp / "a.exr").string(), *pair_img);
    WriteImageF((tmp / "b.exr").string(), pair_ref->image);
    const bool have_idiff = std::system("command -v idiff >/dev/null 2>&1") == 0;
    if (have_idiff) {
      std::vector<double> ms;
      const std::string cmd = "idiff -fail 1 -warn 1 " + (tmp / "a.exr").string() + " " + (tmp / "b.exr").string() + " >/dev/null 2>&1";
      std::system(cmd.c_str());  // warm-up (page cache)
      for (int i = 0; i < std::max(3, cfg.reps / 2 + 1); ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        std::system(cmd.c_str());
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      }
      external["idiff"] = Json{{"samples_ms", ms}, {"what", "idiff process: load two 1080p float EXRs, compare (mean/RMS error, PSNR)"}};
    } else {
      external["idiff"] = Json{{"error", "idiff not installed"}};
    }
  }
  fs::remove_all(tmp);

  // ---------------------------------------------------------------- suite wall time
  struct SuiteRun {
    std::string size;
    int w, h, threads;
    std::vector<double> secs;
    std::vector<double> cpu;  // child CPU seconds (user + system)
  };
  const std::string suite_methods = "none,ssaa-2x2,fxaa1-p3,fxaa311-p12,fxaa311-p39,fxaa-high,scale43-fxaa-high";
  const std::string suite_name = "quick";
  const int suite_spp = 16;
  std::vector<SuiteRun> suite = {{"480x270", 480, 270, 2, {}, {}}, {"960x540", 960, 540, 2, {}, {}},
                                 {"1920x1080", 1920, 1080, 2, {}, {}}, {"960x540", 960, 540, 1, {}, {}}};
  if (cfg.quick) suite = {{"480x270", 480, 270, 2, {}, {}}, {"960x540", 960, 540, 2, {}, {}}};
  const fs::path suite_out = fs::temp_directory_path() / ("aalab_bench_suite_" + std::to_string(getpid()));
  for (auto& s : suite) {
    const int reps = s.w >= 1920 ? 1 : cfg.suite_reps;  // 1080p: one run (keeps make bench under 10 min)
    for (int r = 0; r < reps; ++r) {
      fs::remove_all(suite_out);
      const std::string cmd = cfg.aalab_bin + " run --suite " + suite_name + " --methods " + suite_methods +
                              " --size " + s.size + " --ref-spp " + std::to_string(suite_spp) + " --repeat 1 --threads " +
                              std::to_string(s.threads) + " --quiet --out " + suite_out.string() + " >/dev/null";
      std::fprintf(stderr, "  suite %s threads %d (%d/%d)...\n", s.size.c_str(), s.threads, r + 1, reps);
      rusage c0{}, c1{};
      getrusage(RUSAGE_CHILDREN, &c0);
      const auto t0 = std::chrono::steady_clock::now();
      const int rc = std::system(cmd.c_str());
      const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      getrusage(RUSAGE_CHILDREN, &c1);
      auto secs = [](const rusage& u) {
        return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + (u.ru_utime.tv_usec + u.ru_stime.tv_usec) / 1e6;
      };
      s.cpu.push_back(secs(c1) - secs(c0));
      if (rc != 0) {
        std::fprintf(stderr, "suite run failed (%d): %s\n", rc, cmd.c_str());
        return 3;
      }
      s.secs.push_back(sec);
    }
  }
  fs::remove_all(suite_out);

  // The default run, as `make run` does it with the binary prebuilt (not in --quick): wall,
  // CPU and peak memory of that one process (wait4's rusage of the child).
  struct DefaultRun {
    bool ok = false;
    double wall_s = 0, cpu_s = 0, max_rss_mb = 0;
  } default_run;
  if (!cfg.quick) {
    fs::remove_all(suite_out);
    std::fprintf(stderr, "  default run (aalab run)...\n");
    const auto t0 = std::chrono::steady_clock::now();
    const pid_t pid = fork();
    if (pid == 0) {
      const int null_fd = open("/dev/null", O_WRONLY);
      if (null_fd >= 0) dup2(null_fd, 1);
      execl(cfg.aalab_bin.c_str(), cfg.aalab_bin.c_str(), "run", "--quiet", "--out", suite_out.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    int status = 0;
    rusage ru{};
    if (pid > 0 && wait4(pid, &status, 0, &ru) == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0) {
      default_run.ok = true;
      default_run.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      default_run.cpu_s = static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
                          (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec) / 1e6;
      default_run.max_rss_mb = static_cast<double>(ru.ru_maxrss) / 1024.0;  // kB
    } else {
      std::fprintf(stderr, "the default run failed (status %d)\n", status);
      return 3;
    }
    fs::remove_all(suite_out);
  }

  // ---------------------------------------------------------------- table and JSON
  std::ostringstream tab;
  auto line = [&](const std::string& s) { tab << s << "\n"; };
  auto range = [](const Stats& s, double scale, const char* f) {
    return Fmt(f, s.Median() * scale) + " (" + Fmt(f, s.Min() * scale) + "–" + Fmt(f, s.Max() * scale) + ")";
  };
  auto cores = [&](const std::string& k) {
    auto it = CoresUsed().find(k);
    return it == CoresUsed().end() || it->second.empty() ? 0.0 : Stats{it->second}.Median();
  };
  Json figures = Json::array();
  const double fpx = static_cast<double>(FW) * FH / 1e6;  // Mpix per frame

  line("## Post filters — Mpix/s, 1920x1080; ratio = time / plain read+write pass (same frame, same threads)");
  line("");
  line("| filter | frame | threads | Mpix/s median (min–max) | × floor | cores used |");
  line("|---|---|---|---|---|---|");
  auto mpix = [&](const Stats& s, double mp) {  // Mpix/s from seconds: median of rates = mp / median time
    Stats r;
    for (double v : s.samples) r.samples.push_back(mp / v);
    return r;
  };
  for (const auto& f : frames) {
    for (int threads : {1, 2}) {
      const std::string suffix = "/" + f.key + "/t" + std::to_string(threads);
      const Stats& floor = get("floor" + suffix);
      line("| *floor: plain read+write* | " + f.key + " | " + std::to_string(threads) + " | " + range(mpix(floor, fpx), 1, "%.0f") + " | 1 | " +
           Fmt("%.2f", cores("floor" + suffix)) + " |");
      figures.push_back({{"group", "post"}, {"name", "floor"}, {"frame", f.desc}, {"threads", threads}, {"unit", "Mpix/s"},
                         {"value", StatsJson(mpix(floor, fpx).samples, 1)}, {"ms", StatsJson(floor.samples, 1e3)}});
      for (const auto& p : posts) {
        const Stats& s = get(p.name + suffix);
        const double ratio = s.Median() / floor.Median();
        line("| " + p.name + " | " + f.key + " | " + std::to_string(threads) + " | " + range(mpix(s, fpx), 1, "%.1f") + " | " + Fmt("%.1f", ratio) +
             " | " + Fmt("%.2f", cores(p.name + suffix)) + " |");
        figures.push_back({{"group", "post"}, {"name", p.name}, {"frame", f.desc}, {"threads", threads}, {"unit", "Mpix/s"},
                           {"value", StatsJson(mpix(s, fpx).samples, 1)}, {"ms", StatsJson(s.samples, 1e3)},
                           {"limit", "floor"}, {"ratio_to_limit", ratio}, {"cores_used", cores(p.name + suffix)}});
      }
    }
  }
  for (int threads : {1, 2}) {
    const std::string t = "/t" + std::to_string(threads);
    const Stats& floor = get("floor-rescale" + t);
    line("| *floor: plain pass 2560x1440* | mesh | " + std::to_string(threads) + " | " + range(mpix(floor, 2560.0 * 1440 / 1e6), 1, "%.0f") + " | 1 | " +
         Fmt("%.2f", cores("floor-rescale" + t)) + " |");
    for (const char* name : {"rescale-bilinear", "rescale-bicubic"}) {
      const Stats& s = get(std::string(name) + t);
      const double ratio = s.Median() / floor.Median();
      line("| " + std::string(name) + " 2560x1440→1080p | mesh | " + std::to_string(threads) + " | " + range(mpix(s, fpx), 1, "%.1f") + " | " +
           Fmt("%.1f", ratio) + " | " + Fmt("%.2f", cores(std::string(name) + t)) + " |");
      figures.push_back({{"group", "post"}, {"name", name}, {"frame", "mesh 2560x1440 -> 1920x1080"}, {"threads", threads}, {"unit", "Mpix/s (output)"},
                         {"value", StatsJson(mpix(s, fpx).samples, 1)}, {"ms", StatsJson(s.samples, 1e3)},
                         {"limit", "plain read+write pass over the 2560x1440 frame"}, {"ratio_to_limit", ratio}});
    }
    const Stats& rf = get("floor-resolve" + t);
    const Stats& rs = get("ssaa-resolve-2x2" + t);
    const double ratio = rs.Median() / rf.Median();
    line("| *floor: read 4 samples, write pixel* | mesh | " + std::to_string(threads) + " | " + range(mpix(rf, fpx), 1, "%.0f") + " | 1 | " +
         Fmt("%.2f", cores("floor-resolve" + t)) + " |");
    line("| ssaa-resolve 2x2→1080p | mesh | " + std::to_string(threads) + " | " + range(mpix(rs, fpx), 1, "%.1f") + " | " + Fmt("%.1f", ratio) +
         " | " + Fmt("%.2f", cores("ssaa-resolve-2x2" + t)) + " |");
    figures.push_back({{"group", "post"}, {"name", "ssaa-resolve-2x2"}, {"frame", "mesh 1920x1080, 4 samples/px"}, {"threads", threads}, {"unit", "Mpix/s"},
                       {"value", StatsJson(mpix(rs, fpx).samples, 1)}, {"ms", StatsJson(rs.samples, 1e3)},
                       {"limit", "read the samples, write the pixels"}, {"ratio_to_limit", ratio}});
  }

  line("");
  line("## Tracing — reference render, " + std::to_string(cfg.trace_w) + "x" + std::to_string(cfg.trace_h) + ", " +
       std::to_string(cfg.trace_grid * cfg.trace_grid) + " spp; ratio = reference Mrays/s / bare Embree loop Mrays/s");
  line("");
  line("| scene | threads | reference Mrays/s | bare Embree Mrays/s | reference / bare | cores used (ref) |");
  line("|---|---|---|---|---|---|");
  std::map<std::string, double> trace_ratio_t1, trace_scaling;
  for (int threads : {1, 2}) {
    for (const auto& name : scenes) {
      const std::string t = "/t" + std::to_string(threads);
      const Stats& rs = get("reference/" + name + t);
      const Stats& bs = get("bare-embree/" + name + t);
      const double ref_mr = static_cast<double>((*traced)[name].rays) / 1e6;
      const double bare_mr = static_cast<double>(cfg.trace_w) * cfg.trace_h * cfg.trace_grid * cfg.trace_grid / 1e6;
      const Stats rr = mpix(rs, ref_mr), br = mpix(bs, bare_mr);
      const double ratio = rr.Median() / br.Median();
      if (threads == 1) trace_ratio_t1[name] = ratio;
      else trace_scaling[name] = get("reference/" + name + "/t1").Median() / rs.Median();
      line("| " + name + " | " + std::to_string(threads) + " | " + range(rr, 1, "%.1f") + " | " + range(br, 1, "%.1f") + " | " + Fmt("%.0f%%", 100 * ratio) +
           " | " + Fmt("%.2f", cores("reference/" + name + t)) + " |");
      figures.push_back({{"group", "tracing"}, {"name", name}, {"threads", threads}, {"unit", "Mrays/s"},
                         {"reference", StatsJson(rr.samples, 1)}, {"bare_embree", StatsJson(br.samples, 1)},
                         {"reference_rays", (*traced)[name].rays}, {"limit", "bare Embree loop"}, {"ratio_to_limit", ratio}});
    }
  }

  // ---------------------------------------------------------------- a million triangles
  {
    std::fprintf(stderr, "building and tracing the 1M-triangle torus...\n");
    const BigMeshFigures bm = MeasureBigMesh(1024, 512, 960, 540, 3);
    line("");
    line("## Big mesh — a procedural torus of " + std::to_string(bm.triangles) + " triangles, 960x540 1x frame (best of 3)");
    line("");
    line("| BVH build ms | scene arrays MB | RSS added by the tracer MB | 1x Mrays/s t1 | t2 | bare Embree Mrays/s t1 | t2 |");
    line("|---|---|---|---|---|---|---|");
    line("| " + Fmt("%.0f", bm.bvh_build_ms) + " | " + Fmt("%.1f", bm.scene_mb) + " | " + Fmt("%.1f", bm.rss_bvh_mb) + " | " +
         Fmt("%.2f", bm.render_mrays_t1) + " | " + Fmt("%.2f", bm.render_mrays_t2) + " | " + Fmt("%.2f", bm.bare_mrays_t1) +
         " | " + Fmt("%.2f", bm.bare_mrays_t2) + " |");
    figures.push_back({{"group", "bigmesh"}, {"name", "torus"}, {"triangles", bm.triangles}, {"bvh_build_ms", bm.bvh_build_ms},
                       {"scene_mb", bm.scene_mb}, {"rss_tracer_mb", bm.rss_bvh_mb}, {"render_mrays_t1", bm.render_mrays_t1},
                       {"render_mrays_t2", bm.render_mrays_t2}, {"bare_mrays_t1", bm.bare_mrays_t1}, {"bare_mrays_t2", bm.bare_mrays_t2}});
  }

  line("");
  line("## Metrics — ms per 1920x1080 pair (fxaa311-p39 output vs the mesh reference)");
  line("");
  line("| metric | threads | aalab ms median (min–max) | external tool, same pair | aalab speed-up |");
  line("|---|---|---|---|---|");
  auto ext_stats = [&](const Json& j) -> std::optional<Stats> {
    if (!j.contains("samples_ms")) return std::nullopt;
    Stats s;
    for (double v : j["samples_ms"]) s.samples.push_back(v / 1e3);
    return s;
  };
  std::optional<Stats> sk_ssim, sk_psnr, idiff_s;
  if (external["skimage"].contains("ssim")) sk_ssim = ext_stats(external["skimage"]["ssim"]);
  if (external["skimage"].contains("psnr")) sk_psnr = ext_stats(external["skimage"]["psnr"]);
  idiff_s = ext_stats(external["idiff"]);
  double ssim_speedup = 0.0;
  for (int threads : {1, 2}) {
    const std::string t = "/t" + std::to_string(threads);
    for (const char* m : {"psnr", "ssim", "ssim-run", "flip", "flip-uncached", "edge", "all"}) {
      const Stats& s = get(std::string("metric-") + m + t);
      std::string ext = "—", speed = "—";
      Json fj = {{"group", "metrics"}, {"name", m}, {"threads", threads}, {"unit", "ms"}, {"value", StatsJson(s.samples, 1e3)}};
      const std::optional<Stats>* e = nullptr;
      std::string tool;
      if ((std::string(m) == "ssim" || std::string(m) == "ssim-run") && sk_ssim) {
        e = &sk_ssim, tool = "scikit-image structural_similarity (float64)";
      }
      if (std::string(m) == "psnr" && sk_psnr) e = &sk_psnr, tool = "scikit-image peak_signal_noise_ratio (float64)";
      if (e) {
        ext = tool + " " + range(**e, 1e3, "%.1f") + " ms";
        const double sp = (*e)->Median() / s.Median();
        speed = Fmt("%.1f×", sp);
        fj["external"] = {{"tool", tool}, {"ms", StatsJson((*e)->samples, 1e3)}, {"speedup", sp}};
        if (std::string(m) == "ssim-run" && threads == 1) ssim_speedup = sp;
      }
      if (std::string(m) == "psnr" && idiff_s && threads == 1) {
        ext += "; idiff process " + range(*idiff_s, 1e3, "%.0f") + " ms";
        fj["external_idiff"] = {{"tool", "idiff (whole process: load two float EXRs + compare)"}, {"ms", StatsJson(idiff_s->samples, 1e3)}};
      }
      const std::string label = std::string(m) == "all"             ? "all metrics (ComputeAllMetrics, as a run)"
                                : std::string(m) == "edge"          ? "edge/interior error (edge mask)"
                                : std::string(m) == "flip"          ? "flip (reference half reused, as in a run)"
                                : std::string(m) == "ssim"          ? "ssim (from scratch)"
                                : std::string(m) == "ssim-run"      ? "ssim (reference half reused, as in a run)"
                                : std::string(m) == "flip-uncached" ? "flip (from scratch)"
                                                                    : m;
      line("| " + label + " | " + std::to_string(threads) + " | " + range(s, 1e3, "%.1f") + " | " + ext + " | " + speed + " |");
      figures.push_back(fj);
    }
  }

  const std::vector<bench::BenchGoal> nvidia_flip_goals = bench::ReportNvidiaFlip(
      nvidia_flip, [&](int th) { return get("metric-flip/t" + std::to_string(th)).Median() * 1e3; }, line, &figures);
  {  // analytical AA (bench/bench_aaa.cpp)
    std::string aaa_table;
    for (auto& f : BenchAnalyticAa(cfg.reps, &aaa_table)) figures.push_back(f);
    tab << aaa_table;
  }
  double taa_ratio = 0.0;
  {  // TAA vs fxaa311-p39 (bench/bench_taa.cpp)
    const TaaBench taa = RunTaaBench(cfg.reps, 2);
    line("");
    for (const auto& l : taa.lines) line(l);
    for (const auto& f : taa.figures) figures.push_back(f);
    taa_ratio = taa.ratio;
  }
  line("");
  line("## Suite — wall time of `aalab run --suite " + suite_name + " --ref-spp " + std::to_string(suite_spp) +
       " --repeat 1` with 7 methods (" + suite_methods + ")");
  line("");
  line("| size | threads | runs | wall s median (min–max) | wall s per Mpix (/ 1080p's) | CPU s median | CPU s per Mpix (/ 1080p's) | cores used |");
  line("|---|---|---|---|---|---|---|---|");
  double per_mpix_1080 = 0.0, cpu_per_mpix_1080 = 0.0;
  for (const auto& s : suite) {
    if (s.w == 1920 && s.threads == 2) {
      per_mpix_1080 = Stats{s.secs}.Median() / (s.w * s.h / 1e6);
      cpu_per_mpix_1080 = Stats{s.cpu}.Median() / (s.w * s.h / 1e6);
    }
  }
  double linear_worst = 0.0, linear_worst_cpu = 0.0;
  double suite_t1 = 0, suite_t2 = 0;
  for (const auto& s : suite) {
    const Stats st{s.secs}, sc{s.cpu};
    const double mp = s.w * s.h / 1e6;
    const double per = st.Median() / mp, cper = sc.Median() / mp;
    const double rel = per_mpix_1080 > 0 ? per / per_mpix_1080 : 0.0;
    const double crel = cpu_per_mpix_1080 > 0 ? cper / cpu_per_mpix_1080 : 0.0;
    if (s.threads == 2 && per_mpix_1080 > 0) {
      linear_worst = std::max(linear_worst, std::fabs(rel - 1.0));
      linear_worst_cpu = std::max(linear_worst_cpu, std::fabs(crel - 1.0));
    }
    if (s.w == 960 && s.threads == 1) suite_t1 = st.Median();
    if (s.w == 960 && s.threads == 2) suite_t2 = st.Median();
    const bool two = s.threads == 2 && per_mpix_1080 > 0;
    line("| " + s.size + " | " + std::to_string(s.threads) + " | " + std::to_string(s.secs.size()) + " | " + range(st, 1, "%.1f") +
         " | " + Fmt("%.1f", per) + (two ? " (" + Fmt("%.2f", rel) + ")" : "") + " | " + Fmt("%.1f", sc.Median()) + " | " +
         Fmt("%.1f", cper) + (two ? " (" + Fmt("%.2f", crel) + ")" : "") + " | " + Fmt("%.2f", sc.Median() / st.Median()) + " |");
    figures.push_back({{"group", "suite"}, {"size", s.size}, {"threads", s.threads}, {"unit", "s"}, {"value", StatsJson(s.secs, 1)},
                       {"cpu_s", StatsJson(s.cpu, 1)}, {"s_per_mpix", per}, {"cpu_s_per_mpix", cper}, {"suite", suite_name},
                       {"methods", suite_methods}, {"ref_spp", suite_spp}});
  }

  if (default_run.ok) {
    line("");
    line("## Default run — `aalab run` with its defaults (11 scenes × 12 methods, 960x540, 64 spp, 2 timed repeats), prebuilt");
    line("");
    line("| wall s | CPU s | cores used | peak memory (max RSS) |");
    line("|---|---|---|---|");
    line("| " + Fmt("%.1f", default_run.wall_s) + " | " + Fmt("%.1f", default_run.cpu_s) + " | " +
         Fmt("%.2f", default_run.cpu_s / default_run.wall_s) + " | " + Fmt("%.0f MB", default_run.max_rss_mb) + " |");
    figures.push_back({{"group", "default-run"}, {"unit", "s"}, {"wall_s", default_run.wall_s}, {"cpu_s", default_run.cpu_s},
                       {"max_rss_mb", default_run.max_rss_mb}});
  }
  AppendMsaaBench(cfg.quick, tab, report);  // bench/bench_msaa.cpp
  // ---------------------------------------------------------------- goals
  line("");
  line("## Goals");
  line("");
  line("| goal | measured | met |");
  line("|---|---|---|");
  Json goals = Json::array();
  auto goal = [&](const std::string& g, const std::string& measured, bool met) {
    line("| " + g + " | " + measured + " | " + (met ? "yes" : "**no**") + " |");
    goals.push_back({{"goal", g}, {"measured", measured}, {"met", met}});
  };
  {
    const Stats& s = get("fxaa311-p39/real/t1");
    const double r = s.Median() / get("floor/real/t1").Median();
    goal("FXAA 3.11 p39 within 6× of the bandwidth floor, real content (1 thread)", Fmt("%.1f×", r), r <= 6.0);
    const Stats& s2 = get("fxaa311-p39/real/t2");
    const double r2 = s2.Median() / get("floor/real/t2").Median();
    goal("FXAA 3.11 p39 within 6× of the bandwidth floor, real content (2 threads)", Fmt("%.1f×", r2), r2 <= 6.0);
  }
  {
    double worst = 1e9;
    std::string worst_name;
    for (const auto& [n, r] : trace_ratio_t1) {
      if (r < worst) worst = r, worst_name = n;
    }
    int below = 0;
    for (const auto& [n, r] : trace_ratio_t1) below += r < 0.7;
    goal("reference tracing ≥ 70% of the bare Embree loop (every scene, 1 thread)",
         "worst " + worst_name + " " + Fmt("%.0f%%", 100 * worst) + "; " + std::to_string(below) + " of " +
             std::to_string(trace_ratio_t1.size()) + " scenes below 70%",
         below == 0);
  }
  for (const auto& g : nvidia_flip_goals) goal(g.goal, g.measured, g.met);
  goal("SSIM as in a run ≥ 15× faster than scikit-image's Gaussian SSIM (1 thread)",
       ssim_speedup > 0 ? Fmt("%.1f×", ssim_speedup) : "skimage missing", ssim_speedup >= 15.0);
  {
    const double sp = get("metric-ssim-run/t1").Median() / get("metric-ssim-run/t2").Median();
    goal("SSIM as in a run: 2 threads ≥ 1.8× one thread", Fmt("%.2f×", sp) + "; the 2-thread runs got " +
         Fmt("%.2f", cores("metric-ssim-run/t2")) + " cores", sp >= 1.8);
  }
  goal("TAA temporal step ≤ 2× fxaa311-p39's time (1080p, 2 threads)", Fmt("%.2f×", taa_ratio), taa_ratio > 0 && taa_ratio <= 2.0);
  {
    double worst = 1e9;
    std::string worst_name;
    for (const auto& [n, s] : trace_scaling) {
      if (s < worst) worst = s, worst_name = n;
    }
    std::vector<double> tc;
    for (const auto& name : scenes) tc.push_back(cores("reference/" + name + "/t2"));
    goal("2 threads ≥ 1.8× one thread, tracing (reference, every scene)",
         "worst " + worst_name + " " + Fmt("%.2f×", worst) + "; the 2-thread runs got " + Fmt("%.2f", Stats{tc}.Median()) +
             " cores (median CPU s / wall s)",
         worst >= 1.8);
    double pw = 1e9;
    std::string pn;
    for (const auto& p : posts) {
      for (const auto& f : frames) {
        const double sp = get(p.name + "/" + f.key + "/t1").Median() / get(p.name + "/" + f.key + "/t2").Median();
        if (sp < pw) pw = sp, pn = p.name + " on " + f.key;
      }
    }
    std::vector<double> pc;
    for (const auto& p : posts) {
      for (const auto& f : frames) pc.push_back(cores(p.name + "/" + f.key + "/t2"));
    }
    goal("2 threads ≥ 1.8× one thread, post filters (every filter and frame)",
         "worst " + pn + " " + Fmt("%.2f×", pw) + "; the 2-thread runs got " + Fmt("%.2f", Stats{pc}.Median()) + " cores",
         pw >= 1.8);
  }
  bench::SmaaGoals([&](const std::string& k) { return get(k).Median(); }, goal);  // bench/bench_smaa.cpp
  if (per_mpix_1080 > 0) {
    goal("suite time linear in pixel count within 15% (wall s per Mpix vs 1080p's, 2 threads)", Fmt("worst deviation %.0f%%", 100 * linear_worst),
         linear_worst <= 0.15);
    goal("(same on CPU seconds, less exposed to other load)", Fmt("worst deviation %.0f%%", 100 * linear_worst_cpu), linear_worst_cpu <= 0.15);
  }
  if (suite_t1 > 0 && suite_t2 > 0) {
    goal("quick suite at 960x540: 2 threads ≥ 1.85× one thread", Fmt("%.2f×", suite_t1 / suite_t2), suite_t1 / suite_t2 >= 1.85);
  }

  if (default_run.ok) {
    goal("default run (`aalab run`, prebuilt) ≤ 30 s wall and ≤ 300 MB peak memory",
         Fmt("%.1f s", default_run.wall_s) + " wall (" + Fmt("%.1f", default_run.cpu_s) + " CPU s), " +
             Fmt("%.0f MB", default_run.max_rss_mb) + " peak",
         default_run.wall_s <= 30.0 && default_run.max_rss_mb <= 300.0);
  }

  const double total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  ctx["load_average_at_end"] = LoadAverage();
  ctx["bench_wall_s"] = total_s;
  line("");
  line("Machine: " + ctx["cpu"].get<std::string>() + ", " + std::to_string(ctx["hardware_threads"].get<int>()) +
       " hardware threads; " + ctx["date"].get<std::string>() + "; load average " + ctx["load_average_at_start"].get<std::string>() +
       " at start, " + ctx["load_average_at_end"].get<std::string>() + " at end; bench wall time " + Fmt("%.0f s", total_s) + ".");
  report["context"] = ctx;
  report["figures"] = figures;
  report["external"] = external;
  report["goals"] = goals;
  report["table_markdown"] = tab.str();
  std::ofstream(cfg.json_path) << report.dump(2) << "\n";
  std::printf("%s\nwrote %s\n", tab.str().c_str(), cfg.json_path.c_str());
  return 0;
}

}  // namespace
}  // namespace aalab

int main(int argc, char** argv) {
  try {
    return aalab::Main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "aalab_bench: %s\n", e.what());
    return 3;
  }
}
