#include "harness/run/image_scene.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/edge_mask.h"
#include "core/error.h"
#include "core/input_files.h"
#include "core/params.h"
#include "io/image_info.h"
#include "io/image_io.h"
#include "harness/run/capture_checks.h"
#include "harness/run/image_view.h"
#include "methods/registry.h"
#include "scenes/motion.h"
#include "metrics/crops.h"
#include "metrics/metric.h"
#include "scenes/json_fields.h"

namespace aalab {
namespace fs = std::filesystem;

namespace {

/// The manifest version this build reads.
constexpr int kImageSceneVersion = 1;
/// More views than this in one manifest is refused (each holds several full-size images).
constexpr size_t kMaxViews = 1000;

std::string ReadText(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return "";
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

}  // namespace

bool IsImageSceneManifest(const std::string& path) {
  if (LowerExt(path) != ".json" || !fs::is_regular_file(path)) return false;
  const nlohmann::json doc = nlohmann::json::parse(ReadText(path), nullptr, false);
  return doc.is_object() && (doc.contains("aalab_image_scene") || doc.contains("views"));
}

namespace {

/// A manifest's top level, validated; views are read one at a time (LoadView).
struct Manifest {
  std::string path;
  nlohmann::json doc;
  size_t views = 0;
  std::string description;
};

Manifest ReadManifest(const std::string& manifest_path) {
  Manifest m;
  m.path = manifest_path;
  const std::string origin = "image scene '" + manifest_path + "'";
  if (const std::string what = WhatIsAt(manifest_path); !what.empty()) {
    throw UserError(origin + " " + what + " (a JSON manifest file is expected)");
  }
  try {
    m.doc = nlohmann::json::parse(ReadText(manifest_path));
  } catch (const nlohmann::json::exception& e) {
    throw UserError(origin + ": not valid JSON: " + e.what());
  }
  const JsonField root(m.doc, origin, "");
  root.RequireObject({"aalab_image_scene", "description", "views"});
  if (!root.Has("aalab_image_scene")) {
    root.Fail("missing \"aalab_image_scene\": 1 (the manifest format version this build reads)");
  }
  root.Child("aalab_image_scene").Integer(kImageSceneVersion, kImageSceneVersion);
  const JsonField views = root.Child("views");
  m.views = views.ArraySize();
  if (m.views == 0) views.Fail("no views (give at least one)");
  if (m.views > kMaxViews) {
    views.Fail(std::to_string(m.views) + " views; at most " + std::to_string(kMaxViews) + " per manifest");
  }
  m.description = root.StringOr("description", "");
  return m;
}

/// Reads frame k of view `index` of a manifest (every image), checking its name against the
/// views before it.
ImageView LoadView(const Manifest& m, size_t index, int k = 0) {
  const JsonField views = JsonField(m.doc, "image scene '" + m.path + "'", "").Child("views");
  ImageView v = ParseView(views.At(index), fs::path(m.path).parent_path(), m.path, k);
  for (size_t i = 0; i < index; ++i) {
    const nlohmann::json& other = m.doc.at("views").at(i);
    if (other.is_object() && other.contains("name") && other.at("name") == v.name) {
      views.At(index).Child("name").Fail("view '" + v.name + "' is listed twice");
    }
  }
  if (v.description.empty()) v.description = m.description.empty() ? "a view of " + m.path : m.description;
  v.index = index;
  return v;
}

}  // namespace

std::vector<ImageView> LoadImageScene(const std::string& manifest_path) {
  const Manifest m = ReadManifest(manifest_path);
  std::vector<ImageView> out;
  for (size_t i = 0; i < m.views; ++i) out.push_back(LoadView(m, i));
  return out;
}

const std::string& SceneSource::Name() const { return scene ? scene->name : view->name; }

std::vector<SceneSource> LoadSceneSources(const std::vector<std::string>& names) {
  if (names.empty()) throw UserError("no scenes to run");
  std::vector<SceneSource> out;
  for (const auto& n : names) {
    std::vector<SceneSource> added;
    if (IsImageSceneManifest(n)) {
      // Every frame of every view is read and validated now, before any work, but only what
      // the run plans with is kept: PrepareSource reads the images again, so a run holds one
      // frame's pixels at a time.
      const Manifest m = ReadManifest(n);
      for (size_t i = 0; i < m.views; ++i) {
        const ImageView full = LoadView(m, i);
        for (int k = 1; k < full.frames; ++k) LoadView(m, i, k);
        auto light = std::make_unique<ImageView>();
        light->name = full.name;
        light->manifest = full.manifest;
        light->index = i;
        light->frames = full.frames;
        light->has_motion = full.has_motion;
        light->width = full.width;
        light->height = full.height;
        for (const auto& o : full.outputs) light->outputs.push_back({o.name, o.file, Image8(), o.ms});
        added.push_back({nullptr, std::move(light)});
      }
    } else {
      for (auto& s : LoadScenes({n})) added.push_back({std::move(s), nullptr});
    }
    for (auto& a : added) {
      for (const auto& o : out) {
        if (o.Name() == a.Name()) throw UserError("scene '" + a.Name() + "' (from '" + n + "') is listed twice");
      }
      out.push_back(std::move(a));
    }
  }
  return out;
}

std::vector<std::string> SuppliedOutputNames(const std::vector<SceneSource>& sources) {
  std::vector<std::string> names;
  for (const auto& src : sources) {
    if (!src.view) continue;
    for (const auto& o : src.view->outputs) {
      if (std::find(names.begin(), names.end(), o.name) == names.end()) names.push_back(o.name);
    }
  }
  return names;
}

bool CheckReferenceKind(const std::string& kind, const std::vector<SceneSource>& sources) {
  std::vector<const Scene*> scenes;
  for (const auto& src : sources) {
    if (src.scene) scenes.push_back(src.scene.get());
  }
  const bool exact = CheckReferenceKind(kind, scenes);  // validates `kind` and the rendered scenes
  for (const auto& src : sources) {
    if (exact && src.view) {
      throw UserError("scene '" + src.Name() + "' cannot have --reference exact: it is a view of image scene '" +
                      src.view->manifest + "', whose reference is the file the manifest names");
    }
  }
  return exact;
}

std::unique_ptr<PreparedScene> PrepareSource(SceneSource& source, int width, int height, int grid, uint64_t seed,
                                             int repeat, bool exact_reference, StageClock* clock,
                                             const ReferenceCache* cache, int frame, double flip_ppd) {
  if (source.scene) {
    return PrepareScene(std::move(source.scene), width, height, grid, seed, repeat, exact_reference, clock, cache,
                        flip_ppd);
  }
  if (clock) clock->Enter("references");  // reading the view's images
  AALAB_CHECK(frame >= 0 && frame < source.view->frames, "a view's frame index lies in its sequence");
  ImageView v = LoadView(ReadManifest(source.view->manifest), source.view->index, frame);
  if (v.name != source.view->name || v.frames != source.view->frames) {
    throw UserError("image scene '" + v.manifest + "' changed during the run (view " + std::to_string(v.index) +
                    " was '" + source.view->name + "' with " + std::to_string(source.view->frames) +
                    " frame(s), now '" + v.name + "' with " + std::to_string(v.frames) + ")");
  }
  const int W = v.frame.Width(), H = v.frame.Height();
  auto p = std::make_unique<PreparedScene>();
  SceneResult& sr = p->info;
  sr.name = v.name;
  sr.description = v.description;
  sr.source = v.manifest;
  sr.width = W;
  sr.height = H;
  sr.kind = "image";
  sr.edge_mask_source = v.edge_mask_source;
  sr.reference_note = v.reference_note;
  sr.ref_spp = v.reference_spp;  // 0: unknown
  if (!v.reference_origin.empty() || v.reference_spp > 0) {
    sr.reference_note += "; made by " +
                         (v.reference_origin.empty() ? std::string("(renderer not given)") : v.reference_origin) +
                         (v.reference_spp > 0 ? ", " + std::to_string(v.reference_spp) + " samples per pixel" : "") +
                         " (the manifest's reference_info)";
  }
  sr.noise_floor_null_reason =
      "unknown: a user's reference has no independent half-references to estimate its noise from";
  size_t edge_px = 0;
  for (float m : v.edge_mask.Data()) edge_px += m > 0.5f ? 1 : 0;
  sr.edge_pixel_fraction = static_cast<double>(edge_px) / (static_cast<double>(W) * H);
  p->ref.image = std::move(v.reference);
  p->ref.edge_mask = std::move(v.edge_mask);
  p->ref.edge_mask_raw = std::move(v.edge_mask_raw);
  p->frame1x = std::move(v.frame);
  // The frame comes from the user's renderer: its render time is not measured here; the
  // manifest's frame_ms when given, else 0.
  p->render1x.samples_ms.assign(static_cast<size_t>(repeat), v.frame_ms.value_or(0.0));
  p->render1x.Summarize();
  sr.frame_ms_given = v.frame_ms.has_value();
  p->supplied = std::move(v.outputs);
  p->captured_motion = v.has_motion;
  p->captured_previous = std::move(v.previous);
  p->captured_jitter = {v.jitter[0], v.jitter[1]};
  sr.motion_note = v.motion_note;
  p->none_f = ToFloat(p->frame1x, 3);
  p->flip_ppd = flip_ppd;
  p->flip_reference = flip::PrepareReference(p->ref.image, flip_ppd);
  // What AA cannot explain: a bias or interior error between the frame and its reference.
  for (const auto& w : CheckCapture(p->none_f, p->ref.image, p->ref.edge_mask).warnings) {
    sr.warnings.push_back(v.frames > 1 ? "frame " + std::to_string(frame) + ": " + w : w);
  }
  p->ssim_reference = PrepareSsimReference(p->ref.image);
  // The same crop choice as PrepareScene.
  const int crop_size = std::max(8, std::min(32, std::min(W, H) / 4));
  for (const auto& c : PickCrops(CropScore(p->none_f, p->ref.image, &p->ref.edge_mask), crop_size, 4)) {
    sr.crops.push_back({c.x, c.y, c.w, c.h});
  }
  return p;
}

MethodOutput SuppliedOutputRow(const PreparedScene& p, const std::string& name, int repeat, StageClock* clock) {
  MethodOutput out;
  ResultRow& row = out.row;
  row.scene = p.info.name;
  row.method = name;
  row.spec = name;
  row.render_width = p.info.width;
  row.render_height = p.info.height;
  const auto it =
      std::find_if(p.supplied.begin(), p.supplied.end(), [&](const SuppliedFrame& s) { return s.name == name; });
  if (it == p.supplied.end()) {
    row.not_applicable = "no '" + name +
                         "' frames were supplied for this scene (outputs are given per view in an "
                         "image scene's manifest)";
    for (const std::string& metric : ImageMetricKeys()) {
      row.metrics.push_back({metric, std::nullopt, "not applicable: " + row.not_applicable});
    }
    return out;
  }
  row.supplied = "supplied: frames anti-aliased by the user's own pipeline, named in image scene '" + p.info.source +
                 "' (this frame: '" + it->file + "'); scored like aalab's outputs, not run by aalab";
  // The user's measured time per frame (the whole frame with that AA), when given: it stands
  // for render + AA, so it goes into `render` and `total` (post and resample 0).
  if (it->ms) {
    Timing t;
    t.samples_ms.assign(static_cast<size_t>(repeat), *it->ms);
    t.Summarize();
    row.render = t;
    row.total = t;
    Timing zero;
    zero.samples_ms.assign(static_cast<size_t>(repeat), 0.0);
    zero.Summarize();
    row.post = zero;
    row.resample = zero;
  }
  ScoreOutput(p, it->frame, &out, clock);
  return out;
}

}  // namespace aalab
