#include "reports/html_report.h"
#include "core/format.h"
#include "reports/html_gpu.h"
#include "reports/html_speed.h"
#include "reports/html_stability.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/color.h"
#include "metrics/heatmap.h"
#include "metrics/metric.h"
#include "reports/html_assets.h"
#include "reports/html_method_style.h"
#include "reports/html_page.h"
#include "reports/report_json.h"
#include "reports/verdict.h"

namespace aalab {

namespace {

using Json = nlohmann::ordered_json;

/// Scores at least this close to the noise floor (dB) are marked.
constexpr double kNearFloorDb = 3.0;

std::string FmtMs(double v) { return FormatDouble(v < 1 ? "%.3f" : v < 100 ? "%.2f" : "%.1f", v); }
std::string FmtCount(double v) { return FormatDouble("%.4g", v); }
/// The registry's printed precision (fixed decimals, else 4 significant digits); names it does
/// not know: 2 decimals for `_db`, else 4 significant digits.
std::string FmtMetric(const std::string& name, double v) {
  const MetricOutput* o = FindMetricOutput(name);
  const int decimals = o ? o->decimals : name.size() > 3 && name.compare(name.size() - 3, 3, "_db") == 0 ? 2 : -1;
  return decimals >= 0 ? FormatDouble(("%." + std::to_string(decimals) + "f").c_str(), v) : FormatDouble("%.4g", v);
}
/// Exact sort key for data-v (round-trips).
std::string Key(double v) { return FormatDouble("%.17g", v); }
std::string Int(long v) { return std::to_string(v); }

std::string Attr(std::string_view s) { return HtmlEscape(s); }

/// Metric names in first-appearance order over `rows` (optionally one scene's).
std::vector<std::string> MetricNames(const std::vector<ResultRow>& rows, const std::string* scene) {
  std::vector<std::string> names;
  std::set<std::string> seen;
  for (const auto& row : rows) {
    if (scene && row.scene != *scene) continue;
    for (const auto& m : row.metrics) {
      if (seen.insert(m.name).second) names.push_back(m.name);
    }
  }
  return names;
}

const MetricResult* FindMetric(const ResultRow& row, const std::string& name) {
  for (const auto& m : row.metrics) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

std::string SettingOf(const Report& r, const std::string& key) {
  for (const auto& [k, v] : r.settings) {
    if (k == key) return v;
  }
  return "";
}

std::string ContextOf(const Report& r, const std::string& key) {
  const auto it = r.context.find(key);
  return it == r.context.end() ? "unknown" : it->second;
}

/// The per-metric facts the script needs (labels, units, direction), the chart axis choices
/// and the default axis.
Json MetaJson(const Report& r) {
  const std::vector<std::string> names = MetricNames(r.rows, nullptr);
  Json meta;
  Json metrics = Json::object();
  std::vector<std::string> axis;
  std::set<std::string> has_value;
  for (const auto& row : r.rows) {
    for (const auto& m : row.metrics) {
      if (m.value) has_value.insert(m.name);
    }
  }
  for (const auto& name : names) {
    const html::MetricInfo info = html::DescribeMetric(name);
    metrics[name] = {{"label", info.label}, {"unit", info.unit},       {"better", info.better},
                     {"help", info.help},   {"rewards", info.rewards}, {"psnr", html::IsPsnrMetric(name)}};
  }
  for (const char* first : {"edge_psnr_db", "psnr_db", "flip_mean"}) {
    if (std::find(names.begin(), names.end(), first) != names.end()) axis.push_back(first);
  }
  for (const auto& name : names) {
    if (html::DescribeMetric(name).better != 0 && std::find(axis.begin(), axis.end(), name) == axis.end()) {
      axis.push_back(name);
    }
  }
  std::string def;
  for (const auto& name : axis) {
    if (has_value.count(name)) {
      def = name;
      break;
    }
  }
  meta["metrics"] = metrics;
  meta["axis"] = axis;
  meta["default_axis"] = def.empty() ? Json(nullptr) : Json(def);
  // The perceptual axis shown beside it: the perceptual temporal error of a motion run, else
  // FLIP (so a method that trades aliasing for blur shows as such on the first screen).
  std::string perceptual;
  for (const char* name : {"temporal_perceptual", "flip_mean"}) {
    if (perceptual.empty() && has_value.count(name) && name != def) perceptual = name;
  }
  meta["perceptual_axis"] = perceptual.empty() ? Json(nullptr) : Json(perceptual);
  meta["near_floor_db"] = kNearFloorDb;
  // The page colours its heatmaps with the same tables as metrics/heatmap.cpp.
  Json maps = Json::object();
  for (const Colormap cm : {Colormap::kViridis, Colormap::kMagma}) {
    Json lut = Json::array();
    for (int k = 0; k < 256; ++k) {
      const auto e = ColormapEntry(cm, k);
      lut.push_back({QuantizeUnorm8(e[0]), QuantizeUnorm8(e[1]), QuantizeUnorm8(e[2])});
    }
    maps[ColormapName(cm)] = lut;
  }
  meta["colormaps"] = maps;
  // One colour and marker per method, the same in every chart (html_method_style.h).
  Json styles = Json::object();
  for (const auto& row : r.rows) {
    if (styles.contains(row.spec)) continue;
    const html::MethodStyle st = html::StyleOfMethod(row.spec);
    styles[row.spec] = {{"colour", st.colour}, {"marker", st.marker}, {"path", st.path}};
  }
  meta["method_styles"] = styles;
  meta["error_heatmap_max"] = kErrorHeatmapMax;
  return meta;
}

void Header(std::string& h, const Report& r) {
  std::set<std::string> specs;
  for (const auto& row : r.rows) specs.insert(row.spec);
  h += "<header class=\"top\">\n<h1>aalab report <span class=\"sub\">suite " + HtmlEscape(SettingOf(r, "suite")) +
       " · " + HtmlEscape(SettingOf(r, "size")) + " · " + Int(static_cast<long>(r.scenes.size())) + " scenes × " +
       Int(static_cast<long>(specs.size())) + " methods</span></h1>\n";
  for (const auto& s : r.scenes) {
    if (s.warnings.empty()) continue;
    h += "<p class=\"mismatch\"><span class=\"warn\">⚠</span> <b>" + HtmlEscape(s.name) +
         "</b>: " + HtmlEscape(s.warnings.front()) + "</p>\n";
  }
  const std::string spp = SettingOf(r, "ref_spp");
  h += "<p class=\"facts\">Reference " + HtmlEscape(spp) +
       (std::isdigit(static_cast<unsigned char>(spp.empty() ? 'x' : spp.back())) ? " spp" : "") + " · seed " +
       HtmlEscape(SettingOf(r, "seed")) + " · " + HtmlEscape(SettingOf(r, "repeat")) + " timed run(s) after " +
       HtmlEscape(SettingOf(r, "warmup")) + " warm-up · " + HtmlEscape(ContextOf(r, "cpu")) + ", " +
       HtmlEscape(ContextOf(r, "threads")) + " of " + HtmlEscape(ContextOf(r, "hardware_threads")) +
       " threads · aalab " + HtmlEscape(ContextOf(r, "tool_version")) + " @ " + HtmlEscape(ContextOf(r, "git_commit")) +
       " (" + HtmlEscape(ContextOf(r, "build_type")) + ")</p>\n";
  if (!SettingOf(r, "ppd").empty()) {
    h += "<p class=\"facts viewing\">Viewing condition <b>" + HtmlEscape(SettingOf(r, "viewing")) +
         "</b>: " + HtmlEscape(SettingOf(r, "display_px")) + " display, " +
         HtmlEscape(SettingOf(r, "display_diagonal_in")) + " in at " + HtmlEscape(SettingOf(r, "viewing_distance_m")) +
         " m → <b>" + HtmlEscape(SettingOf(r, "ppd")) +
         " pixels per degree</b> (FLIP and the perceptual temporal error use it), " + HtmlEscape(SettingOf(r, "fps")) +
         " fps, peak " + HtmlEscape(SettingOf(r, "peak_cd_m2")) + " cd/m², ambient " +
         HtmlEscape(SettingOf(r, "ambient_lux")) + " lux (recorded)</p>\n";
  }
  h += "<p class=\"links\"><a href=\"report.json\">report.json</a> (all numbers, every timed sample) · "
       "<a href=\"#methodology\">timing methodology</a> · <a href=\"#context\">run context</a></p>\n";
  h += "<nav class=\"views\" aria-label=\"Views\"><a href=\"#suite\" data-view=\"suite\">Suite</a>";
  for (const auto& s : r.scenes) {
    h += "<a href=\"#scene-" + Attr(UrlEncodePath(s.name)) + "\" data-view=\"scene-" + Attr(s.name) + "\">" +
         HtmlEscape(s.name) + "</a>";
  }
  h += "</nav>\n</header>\n";
}

/// The quality-vs-cost block (chart + cost-of-accuracy table), drawn by the script.
void QualityCostBlock(std::string& h, const std::string& scope, const std::string* scene) {
  h += "<div class=\"qc\" data-scope=\"" + scope + "\"";
  if (scene) h += " data-scene=\"" + Attr(*scene) + "\"";
  h += "><noscript><p class=\"note\">The quality-vs-cost chart and the cost-of-accuracy table are drawn by "
       "the page's script; enable JavaScript to see them (the numbers are in the tables below and in "
       "report.json).</p></noscript></div>\n";
}

void SceneFacts(std::string& h, const SceneResult& s) {
  h += "<dl class=\"scene-facts\">";
  auto fact = [&h](const std::string& k, const std::string& v) {
    h += "<div><dt>" + k + "</dt><dd>" + v + "</dd></div>";
  };
  fact("output", Int(s.width) + "×" + Int(s.height) + " px");
  fact(
      "effects", s.effects.empty() ? "—" : [&] {
        std::string e;
        for (const auto& x : s.effects) e += (e.empty() ? "" : ", ") + HtmlEscape(x);
        return e;
      }());
  if (s.kind == "image") {  // a user's own frames (docs/own-frames.md): no renderer, no noise floor
    fact("1x frame", s.frame_ms_given
                         ? "the user's own 8-bit frame; render time from the manifest (frame_ms), cost unknown"
                         : "the user's own 8-bit frame; render time and cost unknown (0 here)");
    for (const auto& w : s.warnings) fact("<span class=\"warn\">⚠ mismatch</span>", HtmlEscape(w));
    if (!s.motion_note.empty()) fact("motion vectors", HtmlEscape(s.motion_note));
    fact("reference", HtmlEscape(s.reference_note));
    fact("noise floor", HtmlEscape(s.noise_floor_null_reason));
    fact("edge pixels", FormatDouble("%.2f %%", 100.0 * s.edge_pixel_fraction));
    fact("edge mask", HtmlEscape(s.edge_mask_source));
    fact("image scene", "<code>" + HtmlEscape(s.source) + "</code>");
    h += "</dl>\n";
    return;
  }
  if (s.ref_exact) {
    fact("reference", "exact: closed-form pixel coverage (double), " + FmtMs(s.reference_ms) + " ms");
  } else
    fact("reference", Int(s.ref_spp) + " spp, " + FmtMs(s.reference_ms) + " ms, " +
                          FmtCount(s.ref_primary_rays_per_px) + " + " + FmtCount(s.ref_shadow_rays_per_px) +
                          " rays/px, " + FmtCount(s.ref_texture_lookups_per_px) + " texture lookups/px");
  fact("noise floor",
       s.ref_floor_psnr_db
           ? FormatDouble("%.2f dB", *s.ref_floor_psnr_db) + " (halves " +
                 FormatDouble("%.2f dB", s.ref_halves_psnr_db ? *s.ref_halves_psnr_db : 0.0) + " + 6.02 dB)"
           : std::string(s.ref_exact ? "infinite: the exact reference has no sampling noise"
                                     : "none: the two half-references are identical (nothing to converge)"));
  fact("edge pixels", FormatDouble("%.2f %%", 100.0 * s.edge_pixel_fraction));
  fact("edge mask", HtmlEscape(s.edge_mask_source));
  fact("BVH build", FmtMs(s.bvh_build_ms) + " ms (once per scene, not in method times)");
  if (s.content) {
    fact("content", std::to_string(s.content->triangles) + " triangles, " + std::to_string(s.content->textures) +
                        " textures: mip chains " + FormatDouble("%.1f MB", s.content->texture_bytes / 1e6) +
                        " as stored (RGBA8, half for 16-bit images), " +
                        FormatDouble("%.1f MB", s.content->texture_bytes_rgba8 / 1e6) + " as RGBA8; loaded in " +
                        FmtMs(s.content->load_ms) + " ms");
  }
  fact("scene file", "<code>" + HtmlEscape(s.source) + "</code>");
  h += "</dl>\n";
}

std::string FloorWarning(const SceneResult& s, const std::string& metric, double v) {
  if (!s.ref_floor_psnr_db || !html::IsPsnrMetric(metric) || v < *s.ref_floor_psnr_db - kNearFloorDb) return "";
  std::string why = "Within " + FormatDouble("%.0f", kNearFloorDb) + " dB of the reference's noise floor (" +
                    FormatDouble("%.2f", *s.ref_floor_psnr_db) + " dB at " + Int(s.ref_spp) +
                    " spp): the reference's own noise limits this score, so differences between such "
                    "scores are not meaningful. Re-run with a higher --ref-spp to separate them.";
  if (metric != "psnr_db")
    why += " (The floor is estimated over the whole image; on a subset of pixels it may differ.)";
  return "<span class=\"warn\" role=\"img\" aria-label=\"near the noise floor\" title=\"" + Attr(why) + "\">⚠</span>";
}

void SceneTable(std::string& h, const Report& r, const SceneResult& s, int index) {
  // Metrics null on every row of the scene get no column; the caption names them and why.
  std::vector<std::string> metrics, hidden;
  for (const auto& name : MetricNames(r.rows, &s.name)) {
    bool any = false;
    std::string reason;
    for (const auto& row : r.rows) {
      if (row.scene != s.name) continue;
      const MetricResult* m = FindMetric(row, name);
      if (m && m->value) any = true;
      if (m && !m->value && reason.empty()) reason = m->null_reason;
    }
    if (any) {
      metrics.push_back(name);
    } else {
      hidden.push_back(name + (reason.empty() ? "" : " (" + reason + ")"));
    }
  }
  h += "<div class=\"table-wrap\"><table class=\"metrics sortable\" id=\"table-" + Int(index) + "\" data-scene=\"" +
       Attr(s.name) + "\">\n<caption>Every method on <b>" + HtmlEscape(s.name) + "</b> against the reference (" +
       (s.kind == "image" ? std::string("the user's own") + (s.ref_spp > 0 ? ", " + Int(s.ref_spp) + " spp" : "")
        : s.ref_exact     ? std::string("exact")
                          : Int(s.ref_spp) + " spp") +
       "; noise floor ";
  h += s.ref_floor_psnr_db ? FormatDouble("%.2f dB", *s.ref_floor_psnr_db)
                           : std::string(s.kind == "image" ? "unknown"
                                         : s.ref_exact     ? "infinite"
                                                           : "none");
  h += "). <span class=\"warn\">⚠</span> marks a PSNR within " + FormatDouble("%.0f", kNearFloorDb) +
       " dB of the floor. Click or press Enter on a column header to sort." +
       [&hidden] {
         if (hidden.empty()) return std::string();
         std::string t = " <span class=\"hidden-metrics\">Not shown, null on every row: ";
         for (size_t i = 0; i < hidden.size(); ++i) t += (i ? "; " : "") + HtmlEscape(hidden[i]);
         return t + ".</span>";
       }() +
       "</caption>\n<thead><tr>"
       "<th scope=\"col\" data-type=\"text\"><button type=\"button\">Method</button></th>";
  for (const auto& m : metrics) {
    const html::MetricInfo info = html::DescribeMetric(m);
    const std::string dir = info.better > 0 ? " ↑" : info.better < 0 ? " ↓" : "";
    const std::string dir_text = info.better > 0 ? " Higher is better." : info.better < 0 ? " Lower is better." : "";
    h += "<th scope=\"col\" data-metric=\"" + Attr(m) + "\"" + (info.better > 0 ? " data-first=\"descending\"" : "") +
         " title=\"" + Attr(m + ": " + info.help + dir_text) + "\"><button type=\"button\">" + HtmlEscape(info.label) +
         (info.unit.empty() ? "" : " <span class=\"unit\">" + HtmlEscape(info.unit) + "</span>") + dir +
         "</button></th>";
  }
  h += "<th scope=\"col\" title=\"Wall time per frame of the timed stages (render + post + resample), median "
       "[min–max] over the timed runs. See the timing methodology.\"><button type=\"button\">Time ms "
       "<span class=\"unit\">median [min–max]</span></button></th>" +
       html::GpuHeader(r) +
       "<th scope=\"col\" title=\"Camera rays + shadow rays per output pixel (hardware-independent)\"><button "
       "type=\"button\">Rays/px <span class=\"unit\">primary + shadow</span></button></th>"
       "<th scope=\"col\" title=\"Texture (colour and alpha pattern) evaluations per output pixel\"><button "
       "type=\"button\">Tex lookups/px</button></th>"
       "<th scope=\"col\" title=\"Surface shading evaluations per output pixel: one per sample that hits a surface, "
       "one per primitive and pixel for MSAA\"><button type=\"button\">Shades/px</button></th>"
       "<th scope=\"col\" title=\"Post-filter texture fetches per output pixel (edge search included)\"><button "
       "type=\"button\">Taps/px</button></th></tr></thead>\n<tbody>\n";
  std::map<std::string, std::string> first_with_hash;
  for (const auto& row : r.rows) {
    if (row.scene != s.name) continue;
    h += "<tr class=\"row\" data-scene=\"" + Attr(row.scene) + "\" data-spec=\"" + Attr(row.spec) +
         "\"><th scope=\"row\" data-v=\"" + Attr(row.spec) + "\"><span class=\"method\">" + HtmlEscape(row.spec) +
         "</span>";
    if (row.render_width != s.width || row.render_height != s.height) {
      h += " <small title=\"rendered at a different size, then resampled to the output size\">render " +
           Int(row.render_width) + "×" + Int(row.render_height) + "</small>";
    }
    if (row.samples_per_pixel > 1) h += " <small>" + Int(row.samples_per_pixel) + " spp</small>";
    if (!row.not_applicable.empty()) {
      h += " <small class=\"na\" title=\"" + Attr(row.not_applicable) + "\">not applicable</small>";
    }
    if (!row.supplied.empty()) {
      h += " <small class=\"supplied\" title=\"" + Attr(row.supplied) + "\">supplied, not run</small>";
    }
    if (!row.output_hash.empty()) {
      const auto [it, inserted] = first_with_hash.emplace(row.output_hash, row.spec);
      if (!inserted) {
        h += " <small class=\"same\" title=\"bit-identical output to " + Attr(it->second) + " (same output_hash " +
             Attr(row.output_hash) + ")\">≡ " + HtmlEscape(it->second) + "</small>";
      }
    }
    h += "</th>";
    for (const auto& name : metrics) {
      const MetricResult* m = FindMetric(row, name);
      if (!m) {
        h += "<td class=\"num null\" data-metric=\"" + Attr(name) + "\" title=\"not computed for this row\">—</td>";
      } else if (!m->value) {
        const std::string reason = m->null_reason.empty() ? "no reason given" : m->null_reason;
        h += "<td class=\"num null\" data-metric=\"" + Attr(name) + "\" title=\"" + Attr("null: " + reason) +
             "\">—</td>";
      } else {
        const std::string warn = FloorWarning(s, name, *m->value);
        h += "<td class=\"num" + std::string(warn.empty() ? "" : " near-floor") + "\" data-metric=\"" + Attr(name) +
             "\" data-v=\"" + Key(*m->value) + "\">" + FmtMetric(name, *m->value) + warn + "</td>";
      }
    }
    std::string stages = "render " + FmtMs(row.render.median_ms) + " + post " + FmtMs(row.post.median_ms) +
                         " + resample " + FmtMs(row.resample.median_ms) + " ms (medians of " +
                         Int(static_cast<long>(row.total.samples_ms.size())) + " timed runs)";
    if (row.render_shared) stages += "; the render is the 1x frame shared with none (timed once, for none)";
    if (!row.supplied.empty()) {
      stages = row.total.samples_ms.empty()
                   ? "no time given in the manifest (the output's \"ms\")"
                   : "the time per frame the manifest gives (the output's \"ms\"), not measured by aalab";
    } else if (row.method == "none" && s.kind == "image") {
      stages = s.frame_ms_given ? "the render time per frame the manifest gives (\"frame_ms\"), not measured by aalab"
                                : "unknown: the manifest gives no \"frame_ms\" (recorded as 0)";
    }
    if (!row.not_applicable.empty()) {
      h += "<td class=\"num time null\" title=\"" + Attr("not applicable: " + row.not_applicable) + "\">—</td>";
    } else {
      h += "<td class=\"num time\" data-v=\"" + Key(row.total.median_ms) + "\" title=\"" + Attr(stages) + "\">" +
           FmtMs(row.total.median_ms) + " <span class=\"range\">[" + FmtMs(row.total.min_ms) + "–" +
           FmtMs(row.total.max_ms) + "]</span></td>";
    }
    if (html::AnyGpu(r)) h += html::GpuCell(row);
    h += "<td class=\"num\" data-v=\"" + Key(row.primary_rays_per_px + row.shadow_rays_per_px) + "\">" +
         FmtCount(row.primary_rays_per_px) + " + " + FmtCount(row.shadow_rays_per_px) + "</td>";
    h += "<td class=\"num\" data-v=\"" + Key(row.texture_lookups_per_px) + "\">" +
         FmtCount(row.texture_lookups_per_px) + "</td>";
    h += "<td class=\"num\" data-v=\"" + Key(row.shading_evals_per_px) + "\">" + FmtCount(row.shading_evals_per_px) +
         "</td>";
    h += "<td class=\"num\" data-v=\"" + Key(row.taps_per_px) + "\">" + FmtCount(row.taps_per_px) + "</td></tr>\n";
  }
  h += "</tbody></table></div>\n";
}

/// The scene's one-line verdict (reports/verdict.h), marked when the two axes disagree.
std::string VerdictHtml(const SceneVerdict& v) {
  return "<p class=\"verdict" + std::string(v.disagree ? " disagree" : "") + "\" data-scene=\"" + Attr(v.scene) +
         "\"><b>Verdict:</b> " + HtmlEscape(v.line) + "</p>\n";
}

void SceneSection(std::string& h, const Report& r, const SceneResult& s, int index) {
  h += "<section class=\"view\" id=\"view-scene-" + Attr(s.name) + "\" data-view=\"scene-" + Attr(s.name) +
       "\" data-scene=\"" + Attr(s.name) + "\">\n<h2>Scene <span class=\"name\">" + HtmlEscape(s.name) +
       "</span></h2>\n<p class=\"desc\">" + HtmlEscape(s.description) + "</p>\n";
  h += VerdictHtml(VerdictForScene(r.rows, s.name));
  SceneFacts(h, s);
  h += "<h3>Quality vs cost</h3>\n";
  QualityCostBlock(h, "scene", &s.name);
  h += "<h3>All metrics</h3>\n";
  SceneTable(h, r, s, index);
  if (s.frames > 1) {  // the motion player (reports/html/player.js)
    h += "<h3>Motion: " + Int(s.frames) + " frames</h3>\n<div class=\"player-host\" data-scene=\"" + Attr(s.name) +
         "\"><noscript><p class=\"note\">The player needs JavaScript; the frames are listed in report.json "
         "(scenes[].sequence.reference_frames, rows[].frames.images).</p></noscript></div>\n";
  }
  h += "<h3>Gallery</h3>\n<div class=\"gallery-host\" data-scene=\"" + Attr(s.name) +
       "\"><noscript><p class=\"note\">The gallery needs JavaScript. Images: ";
  for (const auto& [role, path] : s.images) {
    h += "<a href=\"" + Attr(UrlEncodePath(path)) + "\">" + HtmlEscape(role) + "</a> ";
  }
  for (const auto& row : r.rows) {
    if (row.scene != s.name) continue;
    const auto it = row.images.find("output");
    if (it != row.images.end()) {
      h += "<a href=\"" + Attr(UrlEncodePath(it->second)) + "\">" + HtmlEscape(row.spec) + "</a> ";
    }
  }
  h += "</p></noscript></div>\n</section>\n";
}

void Methodology(std::string& h, const Report& r) {
  const std::string repeat = SettingOf(r, "repeat");
  h += "<section id=\"methodology\" class=\"prose\">\n<h2>Timing methodology</h2>\n<ul>\n";
  h += "<li><b>Runs.</b> For each scene × method: " + HtmlEscape(SettingOf(r, "warmup")) +
       " untimed warm-up run, then " + HtmlEscape(repeat) +
       " timed run(s) of each stage, wall clock (<code>std::chrono::steady_clock</code>). Tables show the "
       "<b>median [min–max]</b> of the per-run total; the charts use the median.";
  if (repeat == "1" || repeat == "2") {
    h += " <b class=\"caveat\">This run has only " + HtmlEscape(repeat) +
         " timed run(s): min and max say little about the spread, so treat small time differences as noise.</b>";
  }
  h += "</li>\n<li><b>Stages.</b> <i>render</i>: tracing and resolving the frame the method asks for (1x pixel "
       "centres, supersampled, or a scaled size); <i>post</i>: the post filter (FXAA) on the 8-bit frame; "
       "<i>resample</i>: rescaling a render-scale frame to the output size. The total is their sum per run.</li>\n"
       "<li><b>Shared frame.</b> Post filters reuse the 1x frame rendered once for <code>none</code>: their "
       "render time <i>is</i> none's render time (the same samples), so their time added over none is their "
       "post (and resample) time.</li>\n"
       "<li><b>Not counted.</b> Writing images, computing metrics, rendering the reference, building the BVH "
       "(shown per scene).</li>\n";
  h += "<li><b>Machine.</b> " + HtmlEscape(ContextOf(r, "cpu")) + ", " + HtmlEscape(ContextOf(r, "hardware_threads")) +
       " hardware threads (" + HtmlEscape(ContextOf(r, "threads")) + " used), " + HtmlEscape(ContextOf(r, "memory")) +
       ", host <code>" + HtmlEscape(ContextOf(r, "host")) + "</code>; " + HtmlEscape(ContextOf(r, "build_type")) +
       " build, " + HtmlEscape(ContextOf(r, "compiler")) + ", " + HtmlEscape(ContextOf(r, "float_flags")) +
       ". Other processes on the machine add noise.</li>\n";
  h += "<li><b>CPU time is not GPU cost.</b> These are the times of this implementation: an Embree CPU ray "
       "tracer and a CPU emulation of GPU texture filtering. On a GPU the balance differs (rasterisation "
       "instead of rays, hardware texture filtering), so a time ratio here does not predict a GPU frame time. "
       "The hardware-independent counters — rays/px (primary + shadow), texture lookups/px, shades/px, taps/px "
       "(post-filter fetches) — are the portable measure of work.</li>\n</ul>\n</section>\n";
}

// Where the run's time went (report.json's time_breakdown; the table `aalab run` prints at
// its end): wall and CPU seconds per stage, the stage's share of the wall time and the cores
// it kept busy on average (CPU ÷ wall). Nothing when the report has no breakdown.
void TimeBreakdownTable(std::string& h, const std::vector<StageTime>& stages) {
  if (stages.empty()) return;
  double total = 0;
  for (const auto& t : stages) {
    if (t.stage == "total") total = t.wall_ms;
  }
  h += "<table class=\"kv\" id=\"time-breakdown\"><caption>Where the run's time went</caption><thead><tr>"
       "<th scope=\"col\">stage</th><th scope=\"col\">wall s</th><th scope=\"col\">CPU s</th>"
       "<th scope=\"col\">share of wall</th><th scope=\"col\">cores busy</th></tr></thead><tbody>";
  for (const auto& t : stages) {
    h += "<tr><th scope=\"row\">" + HtmlEscape(t.stage) + "</th><td>" + FormatDouble("%.2f", t.wall_ms / 1e3) +
         "</td><td>" + FormatDouble("%.2f", t.cpu_ms / 1e3) + "</td><td>" +
         (total > 0 ? FormatDouble("%.1f%%", 100.0 * t.wall_ms / total) : std::string("—")) + "</td><td>" +
         (t.wall_ms > 0 ? FormatDouble("%.2f", t.cpu_ms / t.wall_ms) : std::string("—")) + "</td></tr>";
  }
  h += "</tbody></table>";
}

void ContextSection(std::string& h, const Report& r) {
  h += "<footer id=\"context\">\n<h2>Run context</h2>\n<div class=\"ctx\"><table class=\"kv\"><caption>Tool and "
       "machine</caption><tbody>";
  for (const auto& [k, v] : r.context) {
    h += "<tr><th scope=\"row\">" + HtmlEscape(k) + "</th><td>" + HtmlEscape(v) + "</td></tr>";
  }
  h += "</tbody></table><table class=\"kv\"><caption>Settings</caption><tbody>";
  for (const auto& [k, v] : r.settings) {
    h += "<tr><th scope=\"row\">" + HtmlEscape(k) + "</th><td>" + HtmlEscape(v) + "</td></tr>";
  }
  h += "</tbody></table>";
  TimeBreakdownTable(h, r.time_breakdown);
  h += "</div>\n<p>Schema version " + Int(r.schema_version) +
       ". Every number on this page comes from <a href=\"report.json\">report.json</a> (embedded below as "
       "data); metric definitions: <code>metrics/METRICS.md</code>, report format: "
       "<code>reports/SCHEMA.md</code> in the aalab source.</p>\n</footer>\n";
}

}  // namespace

std::string RenderHtmlReport(const Report& r) { return RenderHtmlReport(r, ReportToJson(r)); }

std::string RenderHtmlReport(const Report& r, const nlohmann::ordered_json& report_json) {
  std::string h;
  h.reserve(64 * 1024 + r.rows.size() * 2048);
  h += "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
       "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
       "<meta name=\"generator\" content=\"aalab " +
       Attr(ContextOf(r, "tool_version")) + "\">\n<title>aalab report — " + HtmlEscape(SettingOf(r, "suite")) + " " +
       HtmlEscape(SettingOf(r, "size")) + "</title>\n<style>\n";
  h += "\n";
  h += html::PageStyle();
  h += "</style>\n</head>\n<body>\n<a class=\"skip\" href=\"#main\">Skip to content</a>\n";
  Header(h, r);
  h += "<main id=\"main\">\n<section class=\"view\" id=\"view-suite\" data-view=\"suite\">\n<h2>Suite overview</h2>\n"
       "<p class=\"desc\">Each method's quality and time averaged over the " +
       Int(static_cast<long>(r.scenes.size())) +
       " scenes (arithmetic mean of the per-scene scores and of the per-scene median times, taken over the "
       "scenes where every method has a value of the chosen metric, so that every method is averaged over the "
       "same scenes; the scenes left out and why are listed with the chart). Per-scene details, tables and the "
       "gallery are in the scene tabs.</p>\n";
  h += "<h3>Verdict per scene</h3>\n<ul class=\"verdicts\">\n";
  for (const SceneVerdict& v : Verdicts(r)) {
    h += "<li" + std::string(v.disagree ? " class=\"disagree\"" : "") + "><b>" + HtmlEscape(v.scene) +
         "</b>: " + HtmlEscape(v.line) + "</li>\n";
  }
  h += "</ul>\n";
  QualityCostBlock(h, "suite", nullptr);
  h += html::GpuSummary(r);
  h += "</section>\n";
  for (size_t i = 0; i < r.scenes.size(); ++i) SceneSection(h, r, r.scenes[i], static_cast<int>(i));
  AppendSpeedSection(h, r);  // only for runs over the speed-sweep scenes
  Methodology(h, r);
  AppendStabilitySection(h, r);
  h += "</main>\n";
  ContextSection(h, r);
  h += "<div id=\"tooltip\" role=\"tooltip\" hidden></div>\n";
  h += "<script type=\"application/json\" id=\"aalab-data\">" + JsonForScriptTag(report_json.dump()) + "</script>\n";
  h += "<script type=\"application/json\" id=\"aalab-meta\">" + JsonForScriptTag(MetaJson(r).dump()) +
       "</script>\n<script>\n";
  h += html::PageScript();
  h += "</script>\n</body>\n</html>\n";
  return h;
}

}  // namespace aalab
