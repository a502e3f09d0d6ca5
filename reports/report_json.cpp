#include "reports/report_json.h"
#include "reports/raster_timings.h"

#include <algorithm>
#include <cmath>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/params.h"

namespace aalab {

void Timing::Summarize() {
  if (samples_ms.empty()) {
    median_ms = min_ms = max_ms = 0;
    return;
  }
  std::vector<double> s = samples_ms;
  std::sort(s.begin(), s.end());
  min_ms = s.front();
  max_ms = s.back();
  const size_t n = s.size();
  median_ms = n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
}

namespace {

using Json = nlohmann::ordered_json;

Json Num(double v) {
  AALAB_CHECK(std::isfinite(v), "non-finite number headed for JSON");
  return v;
}

Json Opt(const std::optional<double>& v) { return v ? Num(*v) : Json(nullptr); }

Json TimingJson(const Timing& t) {
  Json j;
  j["median_ms"] = Num(t.median_ms);
  j["min_ms"] = Num(t.min_ms);
  j["max_ms"] = Num(t.max_ms);
  Json s = Json::array();
  for (double v : t.samples_ms) s.push_back(Num(v));
  j["samples_ms"] = s;
  return j;
}

Timing TimingFrom(const nlohmann::ordered_json& j) {
  Timing t;
  t.median_ms = j.at("median_ms").get<double>();
  t.min_ms = j.at("min_ms").get<double>();
  t.max_ms = j.at("max_ms").get<double>();
  for (const auto& v : j.at("samples_ms")) t.samples_ms.push_back(v.get<double>());
  return t;
}

std::optional<double> OptFrom(const nlohmann::ordered_json& j) {
  if (j.is_null()) return std::nullopt;
  return j.get<double>();
}

// A row's optional `gpu` block (reports/gpu_timings.h).
Json GpuJson(const GpuTiming& g) {
  Json j;
  j["device"] = g.device;
  j["driver"] = g.driver;
  j["cuda_runtime"] = g.cuda_runtime;
  j["measured_utc"] = g.measured_utc;
  j["kernels"] = g.kernels;
  Json sizes = Json::object();
  for (const auto& s : g.sizes) {
    sizes[s.size] = {{"median_ms", Num(s.median_ms)},
                     {"min_ms", Num(s.min_ms)},
                     {"max_ms", Num(s.max_ms)},
                     {"copy_ms", Num(s.copy_ms)},
                     {"ratio_to_copy", Num(s.ratio_to_copy)},
                     {"identical_share", Opt(s.identical_share)},
                     {"max_diff", s.max_diff ? Json(*s.max_diff) : Json(nullptr)},
                     {"measured_utc", s.measured_utc}};
  }
  j["sizes"] = sizes;
  return j;
}

GpuTiming GpuFrom(const nlohmann::ordered_json& j) {
  GpuTiming g;
  g.device = j.at("device").get<std::string>();
  g.driver = j.at("driver").get<std::string>();
  g.cuda_runtime = j.at("cuda_runtime").get<std::string>();
  g.measured_utc = j.at("measured_utc").get<std::string>();
  g.kernels = j.at("kernels").get<std::string>();
  for (auto it = j.at("sizes").begin(); it != j.at("sizes").end(); ++it) {
    GpuTimingAt s;
    s.size = it.key();
    const auto& v = it.value();
    s.median_ms = v.at("median_ms").get<double>();
    s.min_ms = v.at("min_ms").get<double>();
    s.max_ms = v.at("max_ms").get<double>();
    s.copy_ms = v.at("copy_ms").get<double>();
    s.ratio_to_copy = v.at("ratio_to_copy").get<double>();
    s.identical_share = OptFrom(v.at("identical_share"));
    if (!v.at("max_diff").is_null()) s.max_diff = v.at("max_diff").get<int>();
    // Reports written before sizes carried their own time: the block's.
    s.measured_utc = v.contains("measured_utc") ? v.at("measured_utc").get<std::string>() : g.measured_utc;
    g.sizes.push_back(s);
  }
  return g;
}

}  // namespace

nlohmann::ordered_json ReportToJson(const Report& r) {
  Json doc;
  doc["schema_version"] = kSchemaVersion;
  Json ctx = Json::object();
  for (const auto& [k, v] : r.context) ctx[k] = v;
  doc["context"] = ctx;
  Json settings = Json::object();
  for (const auto& [k, v] : r.settings) settings[k] = v;
  doc["settings"] = settings;
  if (r.shard) {
    doc["shard"] = {{"index", r.shard->index},
                    {"count", r.shard->count},
                    {"unit", r.shard->unit},
                    {"total_units", r.shard->total_units},
                    {"units", r.shard->units}};
  }
  Json scenes = Json::array();
  for (const auto& s : r.scenes) {
    Json j;
    j["name"] = s.name;
    j["description"] = s.description;
    j["source"] = s.source;
    j["effects"] = s.effects;
    j["width"] = s.width;
    j["height"] = s.height;
    j["reference"] = {{"kind", s.ref_exact ? "exact" : "sampled"},
                      {"spp", s.ref_spp},
                      {"time_ms", Num(s.reference_ms)},
                      {"halves_psnr_db", Opt(s.ref_halves_psnr_db)},
                      {"noise_floor_psnr_db", Opt(s.ref_floor_psnr_db)},
                      {"primary_rays_per_px", Num(s.ref_primary_rays_per_px)},
                      {"shadow_rays_per_px", Num(s.ref_shadow_rays_per_px)},
                      {"texture_lookups_per_px", Num(s.ref_texture_lookups_per_px)}};
    if (!s.noise_floor_null_reason.empty()) j["reference"]["noise_floor_null_reason"] = s.noise_floor_null_reason;
    if (!s.reference_note.empty()) j["reference"]["note"] = s.reference_note;
    if (s.kind == "image") j["frame_ms_given"] = s.frame_ms_given;
    if (!s.motion_note.empty()) j["motion_vectors"] = s.motion_note;
    if (!s.warnings.empty()) j["warnings"] = s.warnings;
    j["kind"] = s.kind;
    j["edge_mask_source"] = s.edge_mask_source;
    j["bvh_build_ms"] = Num(s.bvh_build_ms);
    if (s.content) {
      j["content"] = {{"triangles", s.content->triangles},
                      {"textures", s.content->textures},
                      {"texture_bytes", s.content->texture_bytes},
                      {"texture_bytes_rgba8", s.content->texture_bytes_rgba8},
                      {"load_ms", Num(s.content->load_ms)}};
    }
    j["edge_pixel_fraction"] = Num(s.edge_pixel_fraction);
    Json im = Json::object();
    for (const auto& [k, v] : s.images) im[k] = v;
    j["images"] = im;
    Json crops = Json::array();
    for (const auto& c : s.crops) crops.push_back({c[0], c[1], c[2], c[3]});
    j["crops"] = crops;
    if (s.frames > 1) {
      j["sequence"] = {{"frames", s.frames},
                       {"moves", s.moves},
                       {"scene_and_bvh_ms", Num(s.sequence_scene_ms)},
                       {"reference_ms", Num(s.sequence_reference_ms)},
                       {"reference_frames", s.frame_images}};
      if (!s.frame_exr_images.empty()) j["sequence"]["reference_frames_exr"] = s.frame_exr_images;
    }
    scenes.push_back(j);
  }
  doc["scenes"] = scenes;
  Json rows = Json::array();
  for (const auto& row : r.rows) {
    Json j;
    j["scene"] = row.scene;
    j["method"] = row.method;
    j["spec"] = row.spec;
    Json params = Json::object();
    for (const auto& [k, v] : row.params) params[k] = v;
    j["params"] = params;
    j["render_size"] = {row.render_width, row.render_height};
    j["samples_per_pixel"] = row.samples_per_pixel;
    Json metrics = Json::object();
    Json reasons = Json::object();
    for (const auto& m : row.metrics) {
      metrics[m.name] = Opt(m.value);
      if (!m.value) reasons[m.name] = m.null_reason;
    }
    j["metrics"] = metrics;
    j["null_reasons"] = reasons;
    j["timing"] = {{"render", TimingJson(row.render)},
                   {"post", TimingJson(row.post)},
                   {"resample", TimingJson(row.resample)},
                   {"total", TimingJson(row.total)},
                   {"render_shared_with_none", row.render_shared}};
    j["cost"] = {{"primary_rays_per_px", Num(row.primary_rays_per_px)},
                 {"shadow_rays_per_px", Num(row.shadow_rays_per_px)},
                 {"texture_lookups_per_px", Num(row.texture_lookups_per_px)},
                 {"taps_per_px", Num(row.taps_per_px)},
                 {"coverage_rays_per_px", Num(row.coverage_rays_per_px)},
                 {"shading_evals_per_px", Num(row.shading_evals_per_px)}};
    if (row.analytic_costs) {
      j["cost"]["analytic_edge_share"] = Opt(row.analytic_edge_share);
      j["cost"]["analytic_pixels_per_px"] = Num(row.analytic_pixels_per_px);
      j["cost"]["distance_evals_per_px"] = Num(row.distance_evals_per_px);
    }
    j["output_hash"] = row.output_hash;
    Json im = Json::object();
    for (const auto& [k, v] : row.images) im[k] = v;
    j["images"] = im;
    if (!row.not_applicable.empty()) j["not_applicable"] = row.not_applicable;
    if (!row.supplied.empty()) j["supplied"] = row.supplied;
    if (!row.frame_images.empty() || !row.frame_series.empty()) {
      Json series = Json::object();
      for (const auto& [name, values] : row.frame_series) {
        Json a = Json::array();
        for (const auto& v : values) a.push_back(Opt(v));
        series[name] = a;
      }
      j["frames"] = {{"series", series}, {"images", row.frame_images}};
    }
    if (row.gpu) j["gpu"] = GpuJson(*row.gpu);
    if (row.gpu_raster) j["gpu_raster"] = RasterTimingJson(*row.gpu_raster);
    rows.push_back(j);
  }
  doc["rows"] = rows;
  if (!r.time_breakdown.empty()) {
    Json stages = Json::array();
    for (const auto& t : r.time_breakdown) {
      stages.push_back({{"stage", t.stage}, {"wall_ms", Num(t.wall_ms)}, {"cpu_ms", Num(t.cpu_ms)}});
    }
    doc["time_breakdown"] = stages;
  }
  return doc;
}

Report ReportFromJson(const nlohmann::ordered_json& doc, const std::string& origin) {
  Report r;
  try {
    r.schema_version = doc.at("schema_version").get<int>();
    if (r.schema_version != kSchemaVersion) {
      throw UserError(origin + ": schema_version " + std::to_string(r.schema_version) +
                      " is not supported (this aalab reads " + std::to_string(kSchemaVersion) + ")");
    }
    for (auto it = doc.at("context").begin(); it != doc.at("context").end(); ++it) {
      r.context[it.key()] = it.value().get<std::string>();
    }
    for (auto it = doc.at("settings").begin(); it != doc.at("settings").end(); ++it) {
      r.settings.emplace_back(it.key(), it.value().get<std::string>());
    }
    if (doc.contains("shard")) {  // a shard's partial report (`--shard K/N`)
      const auto& j = doc.at("shard");
      ShardInfo sh;
      sh.index = j.at("index").get<int>();
      sh.count = j.at("count").get<int>();
      sh.unit = j.at("unit").get<std::string>();
      sh.total_units = j.at("total_units").get<int>();
      sh.units = j.at("units").get<std::vector<std::string>>();
      r.shard = sh;
    }
    for (const auto& j : doc.at("scenes")) {
      SceneResult s;
      s.name = j.at("name").get<std::string>();
      s.description = j.at("description").get<std::string>();
      s.source = j.at("source").get<std::string>();
      s.effects = j.at("effects").get<std::vector<std::string>>();
      s.width = j.at("width").get<int>();
      s.height = j.at("height").get<int>();
      const auto& ref = j.at("reference");
      s.ref_spp = ref.at("spp").get<int>();
      s.ref_exact = ref.value("kind", std::string("sampled")) == "exact";
      s.reference_ms = ref.at("time_ms").get<double>();
      s.ref_halves_psnr_db = OptFrom(ref.at("halves_psnr_db"));
      s.ref_floor_psnr_db = OptFrom(ref.at("noise_floor_psnr_db"));
      s.ref_primary_rays_per_px = ref.at("primary_rays_per_px").get<double>();
      s.ref_shadow_rays_per_px = ref.at("shadow_rays_per_px").get<double>();
      s.ref_texture_lookups_per_px = ref.at("texture_lookups_per_px").get<double>();
      // Optional fields (added after schema 1 first shipped; older reports lack them).
      if (ref.contains("noise_floor_null_reason"))
        s.noise_floor_null_reason = ref.at("noise_floor_null_reason").get<std::string>();
      if (ref.contains("note")) s.reference_note = ref.at("note").get<std::string>();
      s.frame_ms_given = j.value("frame_ms_given", false);
      if (j.contains("motion_vectors")) s.motion_note = j.at("motion_vectors").get<std::string>();
      if (j.contains("warnings")) s.warnings = j.at("warnings").get<std::vector<std::string>>();
      if (j.contains("kind")) s.kind = j.at("kind").get<std::string>();
      if (j.contains("edge_mask_source")) s.edge_mask_source = j.at("edge_mask_source").get<std::string>();
      s.bvh_build_ms = j.at("bvh_build_ms").get<double>();
      if (j.contains("content")) {
        const auto& c = j.at("content");
        SceneResult::Content k;
        k.triangles = c.at("triangles").get<uint64_t>();
        k.textures = c.at("textures").get<int>();
        k.texture_bytes = c.at("texture_bytes").get<uint64_t>();
        k.texture_bytes_rgba8 = c.at("texture_bytes_rgba8").get<uint64_t>();
        if (c.contains("load_ms")) k.load_ms = c.at("load_ms").get<double>();  // added with issue #35
        s.content = k;
      }
      s.edge_pixel_fraction = j.at("edge_pixel_fraction").get<double>();
      for (auto it = j.at("images").begin(); it != j.at("images").end(); ++it) {
        s.images[it.key()] = it.value().get<std::string>();
      }
      for (const auto& c : j.at("crops")) s.crops.push_back(c.get<std::array<int, 4>>());
      if (j.contains("sequence")) {
        const auto& q = j.at("sequence");
        s.frames = q.at("frames").get<int>();
        s.moves = q.at("moves").get<bool>();
        s.sequence_scene_ms = q.at("scene_and_bvh_ms").get<double>();
        s.sequence_reference_ms = q.at("reference_ms").get<double>();
        s.frame_images = q.at("reference_frames").get<std::vector<std::string>>();
        if (q.contains("reference_frames_exr")) {
          s.frame_exr_images = q.at("reference_frames_exr").get<std::vector<std::string>>();
        }
      }
      r.scenes.push_back(s);
    }
    for (const auto& j : doc.at("rows")) {
      ResultRow row;
      row.scene = j.at("scene").get<std::string>();
      row.method = j.at("method").get<std::string>();
      row.spec = RespellSpecNumbers(j.at("spec").get<std::string>());
      for (auto it = j.at("params").begin(); it != j.at("params").end(); ++it) {
        row.params.emplace_back(it.key(), RespellNumber(it.value().get<std::string>()));
      }
      row.render_width = j.at("render_size").at(0).get<int>();
      row.render_height = j.at("render_size").at(1).get<int>();
      row.samples_per_pixel = j.at("samples_per_pixel").get<int>();
      const auto& reasons = j.at("null_reasons");
      for (auto it = j.at("metrics").begin(); it != j.at("metrics").end(); ++it) {
        MetricResult m;
        m.name = it.key();
        m.value = OptFrom(it.value());
        if (!m.value && reasons.contains(m.name)) m.null_reason = reasons.at(m.name).get<std::string>();
        row.metrics.push_back(m);
      }
      const auto& t = j.at("timing");
      row.render = TimingFrom(t.at("render"));
      row.post = TimingFrom(t.at("post"));
      row.resample = TimingFrom(t.at("resample"));
      row.total = TimingFrom(t.at("total"));
      row.render_shared = t.at("render_shared_with_none").get<bool>();
      const auto& c = j.at("cost");
      row.primary_rays_per_px = c.at("primary_rays_per_px").get<double>();
      row.shadow_rays_per_px = c.at("shadow_rays_per_px").get<double>();
      row.texture_lookups_per_px = c.at("texture_lookups_per_px").get<double>();
      row.taps_per_px = c.at("taps_per_px").get<double>();
      // Added with MSAA: reports written before it lack them (read as 0).
      row.coverage_rays_per_px = c.value("coverage_rays_per_px", 0.0);
      row.shading_evals_per_px = c.value("shading_evals_per_px", 0.0);
      if (c.contains("analytic_edge_share")) {
        row.analytic_costs = true;
        row.analytic_edge_share = OptFrom(c.at("analytic_edge_share"));
        row.analytic_pixels_per_px = c.at("analytic_pixels_per_px").get<double>();
        row.distance_evals_per_px = c.at("distance_evals_per_px").get<double>();
      }
      row.output_hash = j.at("output_hash").get<std::string>();
      for (auto it = j.at("images").begin(); it != j.at("images").end(); ++it) {
        row.images[it.key()] = it.value().get<std::string>();
      }
      if (j.contains("not_applicable")) row.not_applicable = j.at("not_applicable").get<std::string>();
      if (j.contains("supplied")) row.supplied = j.at("supplied").get<std::string>();
      if (j.contains("frames")) {
        const auto& fr = j.at("frames");
        for (auto it = fr.at("series").begin(); it != fr.at("series").end(); ++it) {
          std::vector<std::optional<double>> values;
          for (const auto& v : it.value()) values.push_back(OptFrom(v));
          row.frame_series.emplace_back(it.key(), std::move(values));
        }
        row.frame_images = fr.at("images").get<std::vector<std::string>>();
      }
      if (j.contains("gpu")) row.gpu = GpuFrom(j.at("gpu"));
      if (j.contains("gpu_raster")) row.gpu_raster = RasterTimingFrom(j.at("gpu_raster"));
      r.rows.push_back(row);
    }
    if (doc.contains("time_breakdown")) {  // optional: absent in older reports
      for (const auto& j : doc.at("time_breakdown")) {
        r.time_breakdown.push_back(
            {j.at("stage").get<std::string>(), j.at("wall_ms").get<double>(), j.at("cpu_ms").get<double>()});
      }
    }
  } catch (const nlohmann::json::exception& e) {
    throw UserError(origin + ": not an aalab report (" + std::string(e.what()) + ")");
  }
  return r;
}

std::vector<std::string> ReportImages(const Report& r) {
  std::vector<std::string> files;
  for (const auto& s : r.scenes) {
    for (const auto& [role, path] : s.images) files.push_back(path);
    files.insert(files.end(), s.frame_images.begin(), s.frame_images.end());
    files.insert(files.end(), s.frame_exr_images.begin(), s.frame_exr_images.end());
  }
  for (const auto& row : r.rows) {
    for (const auto& [role, path] : row.images) files.push_back(path);
    files.insert(files.end(), row.frame_images.begin(), row.frame_images.end());
  }
  return files;
}

Report ReadReportFile(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) throw UserError("report '" + path + "' does not exist");
  if (fs::is_directory(st)) {
    throw UserError("report '" + path + "' is a folder, not a report file (give " +
                    (fs::path(path) / "report.json").string() + ")");
  }
  if (!fs::is_regular_file(st)) throw UserError("report '" + path + "' is not a regular file (a FIFO or device?)");
  std::ifstream f(path);
  if (!f) throw UserError("report '" + path + "' cannot be read: " + std::strerror(errno));
  std::stringstream ss;
  ss << f.rdbuf();
  nlohmann::ordered_json doc;
  try {
    doc = nlohmann::ordered_json::parse(ss.str());
  } catch (const nlohmann::json::parse_error& e) {
    throw UserError("report '" + path + "' is not valid JSON: " + e.what());
  }
  return ReportFromJson(doc, "report '" + path + "'");
}

}  // namespace aalab
