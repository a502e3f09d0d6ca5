// The raster path's timings file (reports/raster_timings.h): reader, merge into rows, and
// the row block's JSON.
#include "reports/raster_timings.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace aalab {

namespace {

nlohmann::json Parse(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw UserError("GPU raster timings '" + path + "' cannot be read");
  std::stringstream ss;
  ss << f.rdbuf();
  try {
    return nlohmann::json::parse(ss.str());
  } catch (const nlohmann::json::parse_error& e) {
    throw UserError("GPU raster timings '" + path + "' is not valid JSON: " + e.what());
  }
}

}  // namespace

bool IsRasterTimingsFile(const std::string& path) {
  try {
    const nlohmann::json doc = Parse(path);
    return doc.is_object() && doc.contains("schema") && doc.at("schema") == "aalab-raster-timings";
  } catch (const UserError&) {
    return false;
  }
}

RasterTimingsFile ReadRasterTimingsFile(const std::string& path) {
  const nlohmann::json doc = Parse(path);
  RasterTimingsFile g;
  try {
    if (doc.at("schema").get<std::string>() != "aalab-raster-timings") {
      throw UserError("'" + path + "' is not an aalab_raster file (schema '" + doc.at("schema").get<std::string>() +
                      "', expected 'aalab-raster-timings')");
    }
    const int version = doc.at("schema_version").get<int>();
    if (version != 1) {
      throw UserError("'" + path + "': schema_version " + std::to_string(version) +
                      " is not supported (this aalab reads 1)");
    }
    g.device = doc.at("device").get<std::string>();
    g.gl_version = doc.at("gl_version").get<std::string>();
    g.egl_platform = doc.at("egl_platform").get<std::string>();
    g.target_format = doc.at("target_format").get<std::string>();
    g.msaa_resolve = doc.at("msaa_resolve").get<std::string>();
    for (const auto& j : doc.at("rows")) {
      if (!j.contains("total")) continue;  // a --repeat 0 row: fidelity only, no timing
      RasterResult r;
      r.scene = j.at("scene").get<std::string>();
      r.size = std::to_string(j.at("width").get<int>()) + "x" + std::to_string(j.at("height").get<int>());
      r.method = j.at("method").get<std::string>();
      if (j.contains("render_width")) {
        r.render_size =
            std::to_string(j.at("render_width").get<int>()) + "x" + std::to_string(j.at("render_height").get<int>());
      }
      r.samples = j.at("samples").get<int>();
      r.median_ms = j.at("total").at("median_ms").get<double>();
      r.min_ms = j.at("total").at("min_ms").get<double>();
      r.max_ms = j.at("total").at("max_ms").get<double>();
      r.draw_ms = j.at("draw").at("median_ms").get<double>();
      r.resolve_ms = j.at("resolve").at("median_ms").get<double>();
      r.encode_ms = j.at("encode").at("median_ms").get<double>();
      if (!(r.median_ms > 0) || !(r.min_ms > 0) || r.min_ms > r.median_ms || r.median_ms > r.max_ms) {
        throw UserError("'" + path + "': " + r.scene + " " + r.size + " " + r.method +
                        " has timings that are not 0 < min <= median <= max");
      }
      g.results.push_back(r);
    }
  } catch (const nlohmann::json::exception& e) {
    throw UserError("'" + path + "' is not an aalab_raster file (" + std::string(e.what()) + ")");
  }
  if (g.results.empty()) throw UserError("'" + path + "' has no timed rows (aalab_raster ran with --repeat 0?)");
  return g;
}

std::vector<std::string> RasterSpecsOf(const std::string& raster_method, bool* render_only) {
  *render_only = raster_method == "scale43";
  if (*render_only) return {"scale43", "scale43-fxaa-high"};
  return {raster_method};
}

int MergeRasterTimings(Report& report, const RasterTimingsFile& file) {
  auto one_x = [&file](const std::string& scene, const std::string& size) {
    for (const auto& r : file.results) {
      if (r.scene == scene && r.size == size && r.method == "none") return r.median_ms;
    }
    return 0.0;
  };
  int matched = 0;
  for (ResultRow& row : report.rows) {
    RasterTiming t;
    t.device = file.device;
    t.gl_version = file.gl_version;
    t.egl_platform = file.egl_platform;
    t.target_format = file.target_format;
    t.msaa_resolve = file.msaa_resolve;
    for (const auto& r : file.results) {
      bool render_only = false;
      const std::vector<std::string> specs = RasterSpecsOf(r.method, &render_only);
      if (r.scene != row.scene || std::find(specs.begin(), specs.end(), row.spec) == specs.end()) continue;
      t.samples = r.samples;
      t.part = render_only ? "render" : "";
      const double base = one_x(r.scene, r.size);
      t.sizes.push_back({r.size, r.median_ms, r.min_ms, r.max_ms, r.draw_ms, r.resolve_ms, r.encode_ms,
                         base > 0 ? r.median_ms / base : 0.0, r.render_size});
    }
    if (t.sizes.empty()) continue;
    row.gpu_raster = t;
    ++matched;
  }
  if (matched > 0) {
    report.context["gpu_raster_timings"] = file.device + ", " + file.gl_version + " (" + file.target_format +
                                           " target, MSAA resolve by " + file.msaa_resolve + ")";
  }
  return matched;
}

nlohmann::ordered_json RasterTimingJson(const RasterTiming& t) {
  nlohmann::ordered_json j;
  j["device"] = t.device;
  j["gl_version"] = t.gl_version;
  j["egl_platform"] = t.egl_platform;
  j["target_format"] = t.target_format;
  j["msaa_resolve"] = t.msaa_resolve;
  j["samples"] = t.samples;
  if (!t.part.empty()) j["part"] = t.part;
  nlohmann::ordered_json sizes = nlohmann::ordered_json::object();
  for (const auto& s : t.sizes) {
    sizes[s.size] = {{"median_ms", s.median_ms},    {"min_ms", s.min_ms},         {"max_ms", s.max_ms},
                     {"draw_ms", s.draw_ms},        {"resolve_ms", s.resolve_ms}, {"encode_ms", s.encode_ms},
                     {"ratio_to_1x", s.ratio_to_1x}};
    if (!s.render_size.empty()) sizes[s.size]["render_size"] = s.render_size;
  }
  j["sizes"] = sizes;
  return j;
}

RasterTiming RasterTimingFrom(const nlohmann::ordered_json& j) {
  RasterTiming t;
  t.device = j.at("device").get<std::string>();
  t.gl_version = j.at("gl_version").get<std::string>();
  t.egl_platform = j.at("egl_platform").get<std::string>();
  t.target_format = j.at("target_format").get<std::string>();
  t.msaa_resolve = j.at("msaa_resolve").get<std::string>();
  t.samples = j.at("samples").get<int>();
  t.part = j.value("part", std::string());
  for (auto it = j.at("sizes").begin(); it != j.at("sizes").end(); ++it) {
    const auto& v = it.value();
    t.sizes.push_back({it.key(), v.at("median_ms").get<double>(), v.at("min_ms").get<double>(),
                       v.at("max_ms").get<double>(), v.at("draw_ms").get<double>(), v.at("resolve_ms").get<double>(),
                       v.at("encode_ms").get<double>(), v.at("ratio_to_1x").get<double>(),
                       v.value("render_size", std::string())});
  }
  return t;
}

}  // namespace aalab
