// Preset tuning: one method over a parameter grid, references rendered once per scene.
// Rules (objective means, Pareto front, heatmap aggregation, tie-break) in sweep.h and
// docs/regression.md.
#include "harness/run/sweep.h"

#include <algorithm>
#include <cctype>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/input_files.h"
#include "core/parallel.h"
#include "core/params.h"
#include "core/timer.h"
#include "io/image_io.h"
#include "harness/run/image_scene.h"
#include "harness/run/out_folder.h"
#include "harness/run/pipeline.h"
#include "harness/run/reference_cache.h"
#include "harness/run/runner.h"
#include "methods/registry.h"
#include "metrics/viewing.h"
#include "metrics/metric.h"
#include "reports/html_page.h"
#include "reports/sweep_page.h"
#include "reports/report_json.h"
#include "scenes/render.h"

namespace aalab {
namespace fs = std::filesystem;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string SpecText(const std::string& name, const std::vector<std::pair<std::string, std::string>>& overrides) {
  return overrides.empty() ? name : name + ":" + JoinOverrides(overrides);
}

/// Progress on stderr.
void Progress(bool quiet, int done, int total, const std::string& what, const Stopwatch& clock) {
  if (quiet) return;
  const double elapsed = clock.ElapsedMs() / 1000.0;
  const double eta = done > 0 ? elapsed / done * (total - done) : 0.0;
  std::fprintf(stderr, "[%4d/%d] %-52s elapsed %6.1fs  eta %6.1fs\n", done, total, what.c_str(), elapsed, eta);
  std::fflush(stderr);
}

// The pixels of window [x, y, w, h] (clipped to the image).
Image8 CropImage(const Image8& img, const std::array<int, 4>& win) {
  const int x0 = std::clamp(win[0], 0, img.Width()), y0 = std::clamp(win[1], 0, img.Height());
  const int w = std::clamp(win[2], 0, img.Width() - x0), h = std::clamp(win[3], 0, img.Height() - y0);
  Image8 out(std::max(w, 1), std::max(h, 1), img.Channels());
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < img.Channels(); ++c) out.At(x, y, c) = img.At(x0 + x, y0 + y, c);
    }
  }
  return out;
}

// Writes crops/<scene>/reference-w<k>.png and crops/<scene>/p<point>-w<k>.png for the default,
// the suggestion, each objective's pick and the grid's first and last points (one file per
// point; its roles joined), and lists them in res->crops.
void WriteSweepCrops(SweepResult* res, const std::vector<std::vector<std::vector<Image8>>>& point_crops,
                     const std::vector<std::vector<Image8>>& reference_crops, const fs::path& dir) {
  std::vector<std::pair<size_t, std::string>> roles;
  auto add = [&roles](size_t p, const std::string& role) {
    for (auto& [q, r] : roles) {
      if (q == p) {
        r += ", " + role;
        return;
      }
    }
    roles.emplace_back(p, role);
  };
  if (res->default_point) add(*res->default_point, "default");
  if (res->suggested) add(*res->suggested, "suggested");
  for (const auto& o : res->objectives) {
    if (res->best.count(o)) add(res->best.at(o), "best " + o);
  }
  if (!res->points.empty()) {
    add(0, "extreme " + JoinOverrides(res->points.front().overrides));
    add(res->points.size() - 1, "extreme " + JoinOverrides(res->points.back().overrides));
  }
  res->crops.clear();
  for (size_t si = 0; si < point_crops.size() && si < res->report.scenes.size(); ++si) {
    const std::string& scene = res->report.scenes[si].name;
    std::string folder;  // scene names may be paths: keep letters, digits, '-', '_', '.'
    for (char c : scene)
      folder += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.' ? c : '_';
    folder = "s" + std::to_string(si) + "-" + folder;
    fs::create_directories(dir / "crops" / folder);
    for (size_t k = 0; k < reference_crops[si].size(); ++k) {
      const std::string rel = "crops/" + folder + "/reference-w" + std::to_string(k) + ".png";
      WriteImage8((dir / rel).string(), reference_crops[si][k]);
      res->crops.push_back({scene, "reference", "", static_cast<int>(k), rel});
    }
    for (const auto& [p, role] : roles) {
      for (size_t k = 0; k < point_crops[si][p].size(); ++k) {
        const std::string rel = "crops/" + folder + "/p" + std::to_string(p) + "-w" + std::to_string(k) + ".png";
        WriteImage8((dir / rel).string(), point_crops[si][p][k]);
        res->crops.push_back({scene, role, res->points[p].spec, static_cast<int>(k), rel});
      }
    }
  }
}

}  // namespace

std::vector<GridAxis> ParseGrid(const std::vector<std::string>& args, const std::string& base_spec) {
  if (args.empty()) {
    throw UserError("give at least one --grid NAME=V1,V2,... (the method's parameters: aalab list methods)");
  }
  const Spec base = ParseSpec(base_spec);
  std::vector<GridAxis> axes;
  std::vector<std::string> given;
  for (const auto& arg : args) {
    const auto eq = arg.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == arg.size()) {
      throw UserError("--grid '" + arg + "' is not NAME=V1,V2,... (e.g. --grid edge_threshold=0.063,0.125,0.25)");
    }
    GridAxis axis;
    axis.name = arg.substr(0, eq);
    for (size_t i = 0; i < axes.size(); ++i) {
      if (axes[i].name == axis.name) {
        throw UserError("parameter '" + axis.name + "' is given twice (--grid " + given[i] + " and --grid " + arg +
                        ")");
      }
    }
    for (const auto& [k, v] : base.overrides) {
      if (k == axis.name) {
        throw UserError("parameter '" + axis.name + "' is set both in --method '" + base_spec + "' and in --grid " +
                        arg);
      }
    }
    const std::string list = arg.substr(eq + 1);
    size_t pos = 0;
    while (true) {
      const size_t comma = list.find(',', pos);
      const std::string v = list.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
      if (v.empty()) throw UserError("--grid '" + arg + "' has an empty value");
      if (std::find(axis.values.begin(), axis.values.end(), v) != axis.values.end()) {
        throw UserError("--grid '" + arg + "' lists value '" + v + "' twice");
      }
      axis.values.push_back(v);
      if (comma == std::string::npos) break;
      pos = comma + 1;
    }
    axes.push_back(axis);
    given.push_back(arg);
  }
  return axes;
}

std::vector<std::string> ExpandGrid(const std::string& base_spec, std::vector<GridAxis>* axes) {
  const Spec base = ParseSpec(base_spec);
  size_t count = 1;
  std::string shape;
  for (const auto& a : *axes) {
    count = std::min(count * a.values.size(), kMaxSweepPoints + 1);
    shape += (shape.empty() ? "" : " x ") + a.name + " (" + std::to_string(a.values.size()) + ")";
  }
  if (count > kMaxSweepPoints) {
    size_t exact = 1;
    bool overflow = false;
    for (const auto& a : *axes) {
      if (exact > std::numeric_limits<size_t>::max() / a.values.size()) overflow = true;
      exact *= a.values.size();
    }
    throw UserError("the grid " + shape + " has " + (overflow ? std::string("too many") : std::to_string(exact)) +
                    " points; the limit is " + std::to_string(kMaxSweepPoints) +
                    " (sweep fewer values or split the sweep)");
  }
  // Each value through the method's own parameter table, to its canonical text.
  for (auto& a : *axes) {
    std::vector<std::string> canon;
    for (const auto& v : a.values) {
      auto overrides = base.overrides;
      overrides.emplace_back(a.name, v);
      const MethodPlan plan = MakeMethod(SpecText(base.name, overrides));
      std::string text;
      for (const auto& [k, val] : plan.params.Ordered()) {
        if (k == a.name) text = val;
      }
      AALAB_CHECK(!text.empty(), "a resolved parameter has a value");
      for (size_t i = 0; i < canon.size(); ++i) {
        if (canon[i] == text) {
          throw UserError("--grid " + a.name + ": values '" + a.values[i] + "' and '" + v + "' are the same value (" +
                          text + ")");
        }
      }
      canon.push_back(text);
    }
    a.values = canon;
  }
  std::vector<std::string> specs;
  std::vector<size_t> odo(axes->size(), 0);
  for (size_t n = 0; n < count; ++n) {
    auto overrides = base.overrides;
    for (size_t k = 0; k < axes->size(); ++k) overrides.emplace_back((*axes)[k].name, (*axes)[k].values[odo[k]]);
    specs.push_back(MakeMethod(SpecText(base.name, overrides)).spec);
    for (size_t k = axes->size(); k-- > 0;) {
      if (++odo[k] < (*axes)[k].values.size()) break;
      odo[k] = 0;
    }
  }
  return specs;
}

std::vector<size_t> ParetoFront(const std::vector<double>& t, const std::vector<std::optional<double>>& q,
                                Better better, const std::vector<double>& noise) {
  AALAB_CHECK(t.size() == q.size(), "one time per quality");
  AALAB_CHECK(noise.empty() || noise.size() == t.size(), "one noise per time");
  auto at_least = [better](double a, double b) { return better == Better::kHigher ? a >= b : a <= b; };
  auto strictly = [better](double a, double b) { return better == Better::kHigher ? a > b : a < b; };
  std::vector<size_t> front;
  for (size_t i = 0; i < t.size(); ++i) {
    if (!q[i]) continue;
    bool dominated = false;
    for (size_t j = 0; j < t.size() && !dominated; ++j) {
      if (j == i || !q[j]) continue;
      // With noise: "as fast" is within the two points' spreads, "faster" beyond them. An
      // unknown spread (NaN: fewer than 2 repeats) lets time rank only points of different
      // quality: of two equally good points neither is "faster" on one sample.
      const bool unknown = !noise.empty() && (std::isnan(noise[i]) || std::isnan(noise[j]));
      const double n = noise.empty() || unknown ? 0.0 : noise[i] + noise[j];
      const bool faster = !unknown && t[j] < t[i] - n;
      dominated = t[j] <= t[i] + n && at_least(*q[j], *q[i]) && (faster || strictly(*q[j], *q[i]));
    }
    if (!dominated) front.push_back(i);
  }
  std::sort(front.begin(), front.end(), [&t](size_t a, size_t b) { return t[a] != t[b] ? t[a] < t[b] : a < b; });
  return front;
}

ObjectiveMean MeanOverScenes(const std::vector<const ResultRow*>& rows, const std::string& metric) {
  ObjectiveMean m;
  const auto dir = MetricDirection(metric);
  double sum = 0;
  bool inf = false;
  std::string inf_scene;
  for (const ResultRow* r : rows) {
    const MetricResult* found = nullptr;
    for (const auto& x : r->metrics) {
      if (x.name == metric) found = &x;
    }
    if (!found) {
      m.null_reason = "absent on scene " + r->scene;
      return m;
    }
    if (found->value) {
      sum += *found->value;
    } else if (found->null_reason == "identical" && dir && *dir == Better::kHigher) {
      inf = true;
      if (inf_scene.empty()) inf_scene = r->scene;
    } else {
      m.null_reason = "null on scene " + r->scene + ": " + found->null_reason;
      return m;
    }
  }
  if (rows.empty()) {
    m.null_reason = "no scenes";
    return m;
  }
  m.mean = inf ? kInf : sum / static_cast<double>(rows.size());
  if (inf) m.null_reason = "identical to the reference on scene " + inf_scene;
  return m;
}

SweepResult RunSweep(const SweepSettings& s) {
  SetThreadCount(s.threads);
  // Validate everything before any work.
  if (s.repeat < 1 || s.repeat > 1000)
    throw UserError("--repeat " + std::to_string(s.repeat) + " is out of range (1..1000)");
  const int ref_grid = ReferenceGridForSpp(s.ref_spp);
  if (s.scenes.empty()) throw UserError("give the scenes to sweep with --scenes a,b (see aalab list scenes)");
  if (s.method.empty()) throw UserError("give the method to tune with --method NAME (see aalab list methods)");
  SweepResult res;
  res.method = MakeMethod(s.method).name;
  if (MakeMethod(s.method).make_state) {
    // A sweep scores one still frame per point; a method with memory only shows its quality
    // over a sequence.
    throw UserError("method '" + res.method +
                    "' accumulates over frames, and sweep scores single frames: compare its " +
                    "variants with aalab run --frames N --methods " + res.method + ":...,...");
  }
  const ViewingCondition viewing = ResolveViewing(s.viewing);
  res.axes = ParseGrid(s.grid, s.method);
  const std::vector<std::string> specs = ExpandGrid(s.method, &res.axes);
  const std::vector<MethodPlan> plans = ResolveMethods(specs);

  const std::vector<std::string> produced = ImageMetricKeys();
  auto is_produced = [&produced](const std::string& m) {
    return std::find(produced.begin(), produced.end(), m) != produced.end();
  };
  res.objectives = s.objectives;
  if (res.objectives.empty()) {
    // FLIP first: edge PSNR (a mean squared error) is lowest for the conditional mean, so it
    // rewards blur; FLIP's feature term penalises lost edges (docs/regression.md). Edge PSNR
    // second, so its pick and any disagreement are shown.
    if (is_produced("flip_mean")) res.objectives.push_back("flip_mean");
    res.objectives.push_back(is_produced("edge_psnr_db") ? "edge_psnr_db" : "psnr_db");
    if (res.objectives[0] != "flip_mean") {
      res.objective_note = "objective " + res.objectives[0] + ": the default flip_mean is not computed by this build";
    }
  }
  for (size_t i = 0; i < res.objectives.size(); ++i) {
    const std::string& o = res.objectives[i];
    if (!MetricDirection(o))
      throw UserError("--objective: unknown metric '" + o + "' (known: " + KnownMetricsText() + ")");
    if (!is_produced(o)) {
      throw UserError("--objective: metric '" + o +
                      "' is not computed by this build (computed: " + JoinNames(produced) + ")");
    }
    for (size_t j = 0; j < i; ++j) {
      if (res.objectives[j] == o) throw UserError("--objective: metric '" + o + "' is listed twice");
    }
  }
  std::vector<SceneSource> scenes = LoadSceneSources(s.scenes);
  const bool exact = CheckReferenceKind(s.reference, scenes);
  for (const auto& src : scenes) {
    if (src.view && !RunsOnImageScenes(plans.front())) {
      throw UserError("sweep: method '" + s.method + "' needs the renderer, and scene '" + src.Name() +
                      "' is a view of image scene '" + src.view->manifest +
                      "' (only the 1x frame): sweep a post filter (FXAA, SMAA, ...) on image scenes");
    }
  }

  std::vector<std::string> inputs = {s.ref_cache};
  for (const auto& name : s.scenes) {
    if (fs::exists(name)) inputs.push_back(name);  // a scene file or manifest (not a library name)
  }
  // Every file the scenes were built from: meshes, glTF buffers and textures, image-scene
  // frames and captures (core/input_files.h).
  for (const auto& file : InputFilesRead()) inputs.push_back(file);
  OutFolder out(s.out_dir, "sweep", inputs);
  res.out_dir = s.out_dir;

  Report& report = res.report;
  for (const auto& [k, v] : ContextFacts()) report.context[k] = v;
  std::string grid_text;
  for (const auto& a : res.axes) {
    std::string values;
    for (const auto& v : a.values) values += (values.empty() ? "" : ",") + v;
    grid_text += (grid_text.empty() ? "" : "; ") + a.name + "=" + values;
  }
  report.settings = {{"scenes", JoinNames(s.scenes)},
                     {"method", s.method},
                     {"grid", grid_text},
                     {"objectives", JoinNames(res.objectives)},
                     {"size", std::to_string(s.width) + "x" + std::to_string(s.height)},
                     {"ref_spp", exact ? std::string("exact") : std::to_string(s.ref_spp)},
                     {"seed", std::to_string(s.seed)},
                     {"threads", std::to_string(ThreadCount())},
                     {"repeat", std::to_string(s.repeat)},
                     {"warmup", "1"}};
  for (auto& kv : viewing.Settings()) report.settings.push_back(std::move(kv));

  // A shard runs its share of the grid points on every scene (each scene's reference once,
  // from the cache when there); the summary is the merge's (harness/run/merge.h).
  const std::vector<size_t> share = ShardShare(plans.size(), s.shard);
  if (s.shard.Active()) {
    ShardInfo info{s.shard.index, s.shard.count, "grid point", static_cast<int>(plans.size()), {}};
    for (size_t p : share) info.units.push_back(plans[p].spec);
    report.shard = info;
  }
  std::optional<ReferenceCache> cache;
  if (!s.ref_cache.empty()) cache.emplace(s.ref_cache);
  const int total = static_cast<int>(scenes.size() * (share.size() + 1));
  int done = 0;
  Stopwatch clock;
  report.rows.reserve(scenes.size() * share.size());
  // Crops of every point's output in the scene's crop windows (small; the sweep writes those of
  // the default, the suggestion, each objective's pick and the grid's extremes), and of the
  // reference. A shard keeps none: the merge writes no crops.
  std::vector<std::vector<std::vector<Image8>>> point_crops;  // [scene][point][window]
  std::vector<std::vector<Image8>> reference_crops;           // [scene][window]
  for (auto& source : scenes) {
    if (share.empty()) break;  // a shard beyond the grid's points: nothing to render
    const std::string name = source.Name();
    const auto prepared = PrepareSource(source, s.width, s.height, ref_grid, s.seed, s.repeat, exact, nullptr,
                                        cache ? &*cache : nullptr, 0, viewing.ppd);
    if (prepared->tracer) ++res.reference_renders;  // an image-scene view renders nothing
    report.scenes.push_back(prepared->info);
    Progress(s.quiet, ++done, total, name + " reference", clock);
    const auto& windows = prepared->info.crops;
    if (!s.shard.Active()) {
      point_crops.emplace_back(plans.size());
      reference_crops.emplace_back();
      const Image8 ref8 = ToUnorm8(prepared->ref.image);
      for (const auto& w : windows) reference_crops.back().push_back(CropImage(ref8, w));
    }
    for (size_t p : share) {
      MethodOutput mo = RunMethod(*prepared, plans[p], MethodRunSettings{s.seed, s.repeat});
      if (!s.shard.Active()) {
        for (const auto& w : windows) point_crops.back()[p].push_back(CropImage(mo.output, w));
      }
      report.rows.push_back(std::move(mo.row));
      res.row_point.push_back(p);
      Progress(s.quiet, ++done, total, name + " " + plans[p].spec, clock);
    }
  }
  res.specs = specs;
  res.base_spec = s.method;
  const fs::path tmp = out.Begin();
  if (s.shard.Active()) {
    // A shard's sweep.json holds its rows; the summary and the page are written by the merge.
    WriteTextFile((tmp / "sweep.json").string(), SweepToJson(res).dump(2) + "\n");
  } else {
    SummarizeSweep(&res, plans);
    WriteSweepCrops(&res, point_crops, reference_crops, tmp);
    WriteTextFile((tmp / "sweep.json").string(), SweepToJson(res).dump(2) + "\n");
    WriteTextFile((tmp / "index.html").string(), SweepHtml(res));
  }
  out.Commit();
  return res;
}

double DistanceFromDefaults(const SweepPoint& pt, const std::vector<GridAxis>& axes,
                            const std::vector<std::pair<std::string, std::string>>& defaults) {
  double d = 0;
  for (const auto& [name, value] : pt.overrides) {
    std::string def;
    for (const auto& [k, v] : defaults) {
      if (k == name) def = v;
    }
    const GridAxis* axis = nullptr;
    for (const auto& a : axes) {
      if (a.name == name) axis = &a;
    }
    char* end_v = nullptr;
    char* end_d = nullptr;
    const double x = std::strtod(value.c_str(), &end_v), x0 = std::strtod(def.c_str(), &end_d);
    if (axis && !value.empty() && !def.empty() && *end_v == '\0' && *end_d == '\0') {
      double lo = x0, hi = x0;  // the span of the axis's values and the default
      for (const auto& s : axis->values) {
        const double y = std::strtod(s.c_str(), nullptr);
        lo = std::min(lo, y);
        hi = std::max(hi, y);
      }
      d += hi > lo ? std::fabs(x - x0) / (hi - lo) : 0.0;
    } else {
      d += value == def ? 0.0 : 1.0;
    }
  }
  return d;
}

void SummarizeSweep(SweepResult* result, const std::vector<MethodPlan>& plans) {
  SweepResult& res = *result;
  const Report& report = res.report;
  std::vector<std::vector<const ResultRow*>> per_point(plans.size());
  AALAB_CHECK(res.row_point.size() == report.rows.size(), "a point per row");
  for (size_t i = 0; i < report.rows.size(); ++i) per_point.at(res.row_point[i]).push_back(&report.rows[i]);
  res.points.clear();
  res.best.clear();
  res.best_ties.clear();
  res.suggested_preset.clear();
  std::vector<bool> noise_known;
  for (size_t p = 0; p < plans.size(); ++p) {
    SweepPoint pt;
    pt.spec = plans[p].spec;
    for (const auto& a : res.axes) {
      for (const auto& [k, v] : plans[p].params.Ordered()) {
        if (k == a.name) pt.overrides.emplace_back(k, v);
      }
    }
    for (const auto& o : res.objectives) pt.objectives[o] = MeanOverScenes(per_point[p], o);
    double t = 0, spread = 0;
    bool measured = true;  // every scene timed at least twice: a spread to go by
    for (const ResultRow* r : per_point[p]) {
      const Timing mt = MethodTime(*r);
      t += mt.median_ms;
      spread += mt.max_ms - mt.min_ms;
      measured = measured && mt.samples_ms.size() >= 2;
    }
    const double n = static_cast<double>(per_point[p].size());
    pt.mean_time_ms = per_point[p].empty() ? 0.0 : t / n;
    pt.time_spread_ms = per_point[p].empty() ? 0.0 : spread / n;
    noise_known.push_back(measured && !per_point[p].empty());
    res.points.push_back(pt);
  }
  const std::string& primary = res.objectives.front();
  const Better primary_dir = *MetricDirection(primary);
  std::vector<double> times, noise;
  for (size_t p = 0; p < res.points.size(); ++p) {
    times.push_back(res.points[p].mean_time_ms);
    noise.push_back(noise_known[p] ? res.points[p].time_spread_ms : std::numeric_limits<double>::quiet_NaN());
  }
  {
    std::vector<std::optional<double>> q;
    for (const auto& pt : res.points) q.push_back(pt.objectives.at(primary).mean);
    res.pareto_front = ParetoFront(times, q, primary_dir, noise);
    for (size_t i : res.pareto_front) res.points[i].pareto = true;
  }
  // Ties go to the point closest to the preset it sweeps from (--method: its defaults and
  // overrides), then the first in grid order.
  const std::vector<std::pair<std::string, std::string>> defaults =
      MakeMethod(res.base_spec.empty() ? res.method : res.base_spec).params.Ordered();
  std::vector<double> distance;
  for (const auto& pt : res.points) distance.push_back(DistanceFromDefaults(pt, res.axes, defaults));
  for (const auto& o : res.objectives) {
    const Better dir = *MetricDirection(o);
    std::optional<size_t> best;
    for (size_t p = 0; p < res.points.size(); ++p) {
      const auto& m = res.points[p].objectives.at(o).mean;
      if (!m) continue;
      const auto& b = best ? res.points[*best].objectives.at(o).mean : std::optional<double>();
      if (!best || StrictlyBetter(m, b, dir) || (*m == *b && distance[p] < distance[*best])) best = p;
    }
    if (best) {
      res.best[o] = *best;
      int ties = 0;
      for (size_t p = 0; p < res.points.size(); ++p) {
        if (p != *best && res.points[p].objectives.at(o).mean == res.points[*best].objectives.at(o).mean) ++ties;
      }
      res.best_ties[o] = ties;
    }
  }
  // The suggestion: the best mean of the first objective; among tied points, those no tied
  // point is faster than beyond both points' time spreads (so the suggestion is on the
  // noise-aware front), then the closest to the defaults, then grid order.
  if (res.best.count(primary)) {
    const auto best_mean = res.points[res.best.at(primary)].objectives.at(primary).mean;
    std::vector<size_t> tied;
    for (size_t p = 0; p < res.points.size(); ++p) {
      if (res.points[p].objectives.at(primary).mean == best_mean) tied.push_back(p);
    }
    std::optional<size_t> pick;
    for (size_t p : tied) {
      bool slower = false;
      for (size_t q : tied) {
        // Time ranks tied points only when both spreads are measured (>= 2 repeats).
        slower =
            slower || (!std::isnan(noise[p]) && !std::isnan(noise[q]) && times[q] < times[p] - (noise[p] + noise[q]));
      }
      if (slower) continue;
      if (!pick || distance[p] < distance[*pick]) pick = p;
    }
    AALAB_CHECK(pick.has_value(), "the fastest tied point is never slower than another");
    AALAB_CHECK(res.points[*pick].pareto, "the suggestion lies on the noise-aware front");
    res.suggested = *pick;
    res.suggested_preset = res.points[*pick].spec;
    res.suggestion_rule = "the best " + primary + " mean" +
                          (tied.size() > 1 ? " (" + std::to_string(tied.size()) +
                                                 " points tie: the faster beyond the repeats' time spread, then the "
                                                 "closest to the defaults)"
                                           : std::string()) +
                          "; on the " + primary + " vs time front, times within the repeats' spread counted as equal";
  }
  // The shipped default: the point whose swept values are the --method's own.
  res.default_point.reset();
  res.default_note.clear();
  for (size_t p = 0; p < res.points.size(); ++p) {
    if (distance[p] == 0.0 && !res.default_point) res.default_point = p;
  }
  if (!res.default_point) {
    std::string vals;
    for (const auto& a : res.axes) {
      for (const auto& [k, v] : defaults) {
        if (k == a.name) vals += (vals.empty() ? "" : ",") + k + "=" + v;
      }
    }
    res.default_note = "the defaults (" + vals + ") are not on the grid: add them to compare the suggestion with them";
  }
  // Objectives that disagree with the first one.
  res.disagreements.clear();
  if (res.best.count(primary)) {
    for (const auto& o : res.objectives) {
      if (o == primary || !res.best.count(o)) continue;
      const size_t pick = *res.suggested, other = res.best.at(o);
      if (res.points[pick].objectives.at(o).mean == res.points[other].objectives.at(o).mean) continue;  // tied there
      res.disagreements.push_back(o + " picks " + JoinOverrides(res.points[other].overrides) + " (" +
                                  SweepMeanText(o, res.points[other].objectives.at(o)) + "), " + primary + " picks " +
                                  JoinOverrides(res.points[pick].overrides) + " (" + o + " there " +
                                  SweepMeanText(o, res.points[pick].objectives.at(o)) +
                                  "): the objectives disagree, look at the crops before choosing");
    }
  }
  // Per scene: the suggestion against the default.
  res.scene_changes.clear();
  if (res.default_point && res.suggested) {
    for (const auto& sc : report.scenes) {
      const ResultRow *d = nullptr, *g = nullptr;
      for (size_t i = 0; i < report.rows.size(); ++i) {
        if (report.rows[i].scene != sc.name) continue;
        if (res.row_point[i] == *res.default_point) d = &report.rows[i];
        if (res.row_point[i] == *res.suggested) g = &report.rows[i];
      }
      if (!d || !g) continue;
      SweepSceneChange c;
      c.scene = sc.name;
      for (const auto& o : res.objectives) {
        const ObjectiveMean a = MeanOverScenes({d}, o), b = MeanOverScenes({g}, o);
        c.values.push_back({o, a.mean, b.mean});
      }
      const Timing td = MethodTime(*d), tg = MethodTime(*g);
      c.default_ms = td.median_ms;
      c.suggested_ms = tg.median_ms;
      c.default_spread_ms = td.max_ms - td.min_ms;
      c.suggested_spread_ms = tg.max_ms - tg.min_ms;
      res.scene_changes.push_back(c);
    }
  }
}

std::string SweepSummaryText(const SweepResult& r) {
  std::ostringstream o;
  std::string shape;
  for (const auto& a : r.axes)
    shape += (shape.empty() ? "" : " x ") + a.name + " (" + std::to_string(a.values.size()) + ")";
  o << "sweep: " << r.method << " over " << shape << " = " << r.points.size() << " points on " << r.report.scenes.size()
    << " scenes; " << r.reference_renders << " reference renders\n";
  if (!r.objective_note.empty()) o << "note: " << r.objective_note << "\n";
  for (const auto& obj : r.objectives) {
    auto it = r.best.find(obj);
    if (it == r.best.end()) {
      o << "best " << obj << ": none (every point's mean is null: " << r.points.front().objectives.at(obj).null_reason
        << ")\n";
      continue;
    }
    const SweepPoint& p = r.points[it->second];
    o << "best " << obj << " (mean over " << r.report.scenes.size()
      << " scenes): " << SweepMeanText(obj, p.objectives.at(obj)) << " at " << JoinOverrides(p.overrides)
      << " (method time " << FormatFixed(p.mean_time_ms, 3) << " ms)";
    const int ties = r.best_ties.at(obj);
    if (ties > 0) o << "; " << ties << " other point(s) tie, the one closest to the defaults is shown";
    o << "\n";
  }
  const std::string& primary = r.objectives.front();
  o << "pareto front (" << primary << " vs method time, " << r.pareto_front.size() << " points):\n";
  for (size_t i : r.pareto_front) {
    const SweepPoint& p = r.points[i];
    o << "  " << FormatFixed(p.mean_time_ms, 3) << " ms  " << SweepMeanText(primary, p.objectives.at(primary)) << "  "
      << JoinOverrides(p.overrides) << "\n";
  }
  for (const auto& d : r.disagreements) o << "NOTE: " << d << "\n";
  if (r.suggested_preset.empty()) {
    o << "suggested preset: none (no point has a defined " << primary << ")\n";
  } else {
    o << "suggested preset: " << r.suggested_preset << " (" << r.suggestion_rule << ")\n";
  }
  if (!r.default_point) {
    o << "against the default: " << r.default_note << "\n";
  } else if (r.suggested && *r.suggested == *r.default_point) {
    o << "against the default: the suggestion is the default (" << r.points[*r.default_point].spec << ")\n";
  } else {
    o << "against the default (" << JoinOverrides(r.points[*r.default_point].overrides) << "), per scene:\n";
    for (const auto& c : r.scene_changes) {
      o << "  " << c.scene << ":";
      for (const auto& v : c.values) {
        o << " " << v.objective << " ";
        if (v.at_default && v.suggested) {
          const double d = *v.suggested - *v.at_default;
          o << SweepValueText(v.objective, *v.at_default) << " -> " << SweepValueText(v.objective, *v.suggested) << " ("
            << (d >= 0 ? "+" : "") << SweepValueText(v.objective, d) << ")";
        } else {
          o << "null";
        }
        o << ";";
      }
      o << " time " << FormatFixed(c.default_ms, 3) << " -> " << FormatFixed(c.suggested_ms, 3) << " ms (spreads "
        << FormatFixed(c.default_spread_ms, 3) << ", " << FormatFixed(c.suggested_spread_ms, 3) << ")\n";
    }
  }
  if (!r.crops.empty())
    o << "crops: " << r.crops.size() << " images in crops/ (default, suggested, each objective's pick, extremes)\n";
  return o.str();
}

}  // namespace aalab
