#include "harness/run/image_scene.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "harness/core/edge_mask.h"
#include "harness/core/error.h"
#include "harness/core/params.h"
#include "harness/io/image_info.h"
#include "harness/io/image_io.h"
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

std::string LowerExt(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

/// An image a view names, read and described.
struct ViewImage {
  std::string rel;   ///< as written in the manifest
  std::string path;  ///< resolved against the manifest's folder
  LoadedImage image;
  ImageFileInfo info;
};

/// Reads the image a field names; `exts` are the allowed extensions. Errors name the field.
ViewImage ReadViewImage(const JsonField& f, const fs::path& base, const std::vector<std::string>& exts) {
  ViewImage v;
  v.rel = f.String();
  if (v.rel.empty()) f.Fail("an empty path (give an image file relative to the manifest)");
  v.path = (base / v.rel).lexically_normal().string();
  const std::string ext = LowerExt(v.path);
  if (std::find(exts.begin(), exts.end(), ext) == exts.end()) {
    f.Fail("'" + v.rel + "' has file type '" + ext + "'; allowed here: " + JoinNames(exts));
  }
  try {
    v.image = ReadImage(v.path);
    v.info = ProbeImage(v.path);
  } catch (const UserError& e) {
    f.Fail(e.what());
  }
  return v;
}

void RequireSize(const JsonField& f, const ViewImage& img, int w, int h, const std::string& frame_rel) {
  if (img.info.width != w || img.info.height != h) {
    f.Fail("'" + img.rel + "' is " + std::to_string(img.info.width) + "x" + std::to_string(img.info.height) +
           " but the frame '" + frame_rel + "' is " + std::to_string(w) + "x" + std::to_string(h) +
           " (every image of a view must have the frame's size)");
  }
}

ImageF FirstChannels(const ImageF& img, int n) {
  ImageF out(img.Width(), img.Height(), n);
  for (size_t i = 0; i < img.PixelCount(); ++i) {
    for (int c = 0; c < n; ++c) out.Data()[i * n + c] = img.Data()[i * img.Channels() + c];
  }
  return out;
}

/// A float constant as people write it (0.1, not 0.10000000149011612).
std::string ShortNumber(float v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", static_cast<double>(v));
  return buf;
}

std::string DisplayText(const Display& d) {
  const char* tm = d.tonemap == Tonemap::kReinhard ? "reinhard" : d.tonemap == Tonemap::kAces ? "aces" : "none";
  return "exposure " + FormatNumber(d.exposure) + ", tonemap " + tm;
}

ImageView ParseView(const JsonField& v, const fs::path& base, const std::string& manifest) {
  v.RequireObject({"name", "description", "frame", "reference", "display", "depth", "object_ids", "edge_mask"});
  ImageView view;
  view.manifest = manifest;
  view.name = v.Child("name").String();
  if (view.name.empty()) v.Child("name").Fail("view names must not be empty");
  for (char c : view.name) {
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-')) {
      v.Child("name").Fail("view names are lowercase-kebab like scene names ([a-z0-9-]+), got '" + view.name + "'");
    }
  }
  view.description = v.StringOr("description", "");

  // The 1x frame: the back buffer, 8 bits per channel, display-encoded (sRGB).
  const JsonField ff = v.Child("frame");
  const ViewImage frame = ReadViewImage(ff, base, {".png", ".tif", ".tiff"});
  if (frame.info.is_float || frame.info.bits != 8) {
    ff.Fail("'" + frame.rel + "' stores " + frame.info.Describe() +
            " samples; the 1x frame must be 8-bit integer (the RGBA8 back buffer, sRGB-encoded)");
  }
  const int W = frame.info.width, H = frame.info.height;
  view.frame = Image8(W, H, 4, 255);
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      for (int c = 0; c < 3; ++c) view.frame.At(x, y, c) = QuantizeUnorm8(frame.image.pixels.At(x, y, c));
    }
  }

  // The reference: scene-linear EXR through the display transform, or display-encoded integers.
  const JsonField rf = v.Child("reference");
  const ViewImage ref = ReadViewImage(rf, base, {".exr", ".png", ".tif", ".tiff"});
  RequireSize(rf, ref, W, H, frame.rel);
  view.reference = ImageF(W, H, 3);
  if (ref.info.is_float) {
    if (LowerExt(ref.path) != ".exr") {
      rf.Fail("'" + ref.rel + "' stores float samples in a " + ref.info.format +
              " file; give a scene-linear reference as .exr, or a display-encoded one as 8/16-bit integers");
    }
    Display d;
    if (v.Has("display")) {
      const JsonField df = v.Child("display");
      df.RequireObject({"exposure", "tonemap"});
      d.exposure = static_cast<float>(df.NumberOr("exposure", 1.0, 0.0, 1e9, true));
      if (df.Has("tonemap")) d.tonemap = ParseTonemap(df.Child("tonemap").Choice({"none", "reinhard", "aces"}));
    }
    for (int y = 0; y < H; ++y) {
      for (int x = 0; x < W; ++x) {
        const float* p = ref.image.pixels.Pixel(x, y);
        const std::array<float, 3> lin = DisplayLinear(d, {p[0], p[1], p[2]});
        for (int c = 0; c < 3; ++c) view.reference.At(x, y, c) = SrgbEncode(lin[c]);
      }
    }
    view.reference_note = "'" + ref.rel + "': " + ref.info.Describe() +
                          " EXR, scene-linear, through the display transform (" + DisplayText(d) +
                          ", clamp to [0, 1]) and sRGB-encoded, kept as float";
  } else {
    if (v.Has("display")) {
      v.Child("display").Fail("a display transform applies only to a scene-linear .exr reference; '" + ref.rel +
                              "' is " + ref.info.Describe() + ", read as display-encoded (sRGB) values");
    }
    if (ref.info.bits != 8 && ref.info.bits != 16) {
      rf.Fail("'" + ref.rel + "' stores " + ref.info.Describe() +
              " samples; a display-encoded reference must be 8- or 16-bit integer (or give a scene-linear .exr)");
    }
    view.reference = FirstChannels(ref.image.pixels, 3);
    view.reference_note = "'" + ref.rel + "': " + ref.info.Describe() + " " + ref.info.format +
                          ", display-encoded (sRGB): value k read as k/" + (ref.info.bits == 8 ? "255" : "65535");
  }

  // The edge mask: given, from ids and/or depth, or from the reference's gradients.
  const bool has_mask = v.Has("edge_mask"), has_ids = v.Has("object_ids"), has_depth = v.Has("depth");
  if (has_mask && (has_ids || has_depth)) {
    v.Child("edge_mask").Fail("give either edge_mask or object_ids/depth, not both (the mask would be ambiguous)");
  }
  if (has_mask) {
    const JsonField mf = v.Child("edge_mask");
    const ViewImage m = ReadViewImage(mf, base, {".png", ".tif", ".tiff"});
    RequireSize(mf, m, W, H, frame.rel);
    if (m.info.is_float || m.info.bits != 8 || (m.info.channels != 1 && m.info.channels != 3)) {
      mf.Fail("'" + m.rel + "' is " + m.info.Describe() + " with " + std::to_string(m.info.channels) +
              " channel(s); an edge mask must be 8-bit integer grey (1 channel, or RGB with R = G = B), "
              "255 = edge, 0 = not");
    }
    view.edge_mask_raw = ImageF(W, H, 1);
    for (int y = 0; y < H; ++y) {
      for (int x = 0; x < W; ++x) {
        const float* px = m.image.pixels.Pixel(x, y);
        const uint8_t k = QuantizeUnorm8(px[0]);
        if ((k != 0 && k != 255) || px[1] != px[0] || px[2] != px[0]) {
          mf.Fail("'" + m.rel + "' has value (" + std::to_string(k) + ", " + std::to_string(QuantizeUnorm8(px[1])) +
                  ", " + std::to_string(QuantizeUnorm8(px[2])) + ") at pixel (" + std::to_string(x) + ", " +
                  std::to_string(y) + "); an edge mask holds only grey 0 and 255");
        }
        view.edge_mask_raw.At(x, y, 0) = k == 255 ? 1.0f : 0.0f;
      }
    }
    view.edge_mask = view.edge_mask_raw;
    view.edge_mask_source = "given: the edge_mask image '" + m.rel + "', used as is (no dilation)";
  } else if (has_ids || has_depth) {
    std::string how;
    if (has_ids) {
      const JsonField idf = v.Child("object_ids");
      const ViewImage ids = ReadViewImage(idf, base, {".png", ".tif", ".tiff", ".exr"});
      RequireSize(idf, ids, W, H, frame.rel);
      if (!ids.info.is_float && ids.info.bits != 8 && ids.info.bits != 16) {
        idf.Fail("'" + ids.rel + "' stores " + ids.info.Describe() +
                 " samples; object ids must be 8- or 16-bit integer PNG/TIFF, or a float EXR (integer ids up to 2^24)");
      }
      view.edge_mask_raw = EdgesFromIds(ids.image.pixels);
      how = "object ids ('" + ids.rel + "': a 4-neighbour has another id)";
    }
    if (has_depth) {
      const JsonField df = v.Child("depth");
      const ViewImage depth = ReadViewImage(df, base, {".exr", ".tif", ".tiff", ".png"});
      RequireSize(df, depth, W, H, frame.rel);
      if (depth.info.channels != 1) {
        df.Fail("'" + depth.rel + "' has " + std::to_string(depth.info.channels) +
                " channels; depth must be a single-channel image");
      }
      if (!depth.info.is_float && depth.info.bits != 16) {
        df.Fail("'" + depth.rel + "' stores " + depth.info.Describe() +
                " samples; depth must be float (EXR/TIFF) or 16-bit integer");
      }
      for (int y = 0; y < H; ++y) {
        for (int x = 0; x < W; ++x) {
          if (depth.image.pixels.At(x, y, 0) < 0.0f) {
            df.Fail("'" + depth.rel + "' has a negative depth at pixel (" + std::to_string(x) + ", " +
                    std::to_string(y) + "); depths are distances >= 0");
          }
        }
      }
      const ImageF d = EdgesFromDepth(FirstChannels(depth.image.pixels, 1));
      view.edge_mask_raw = has_ids ? UnionMask(view.edge_mask_raw, d) : d;
      how += std::string(has_ids ? " or " : "") + "depth ('" + depth.rel +
             "': a 4-neighbour's depth differs by more than " + ShortNumber(kDepthEdgeRelativeJump * 100.0f) +
             " % of the nearer one)";
    }
    view.edge_mask = DilateMask(view.edge_mask_raw);
    view.edge_mask_source = "geometry from " + how + "; dilated by 1 px";
  } else {
    view.edge_mask_raw = EdgesFromGradient(view.reference);
    view.edge_mask = DilateMask(view.edge_mask_raw);
    view.edge_mask_source = "reference gradients (no object ids or depth given): a 4-neighbour differs by more than " +
                            ShortNumber(kGradientEdgeThreshold) +
                            " in any sRGB-encoded channel; dilated by 1 px. Marks texture and shading detail too";
  }
  return view;
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
  if (!fs::is_regular_file(manifest_path)) throw UserError(origin + " does not exist or is not a file");
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

/// Reads view `index` of a manifest (every image), checking its name against the views before it.
ImageView LoadView(const Manifest& m, size_t index) {
  const JsonField views = JsonField(m.doc, "image scene '" + m.path + "'", "").Child("views");
  ImageView v = ParseView(views.At(index), fs::path(m.path).parent_path(), m.path);
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
      // Every view is read and validated now, before any work, but only its name is kept:
      // PrepareSource reads the images again, so a run holds one view's pixels at a time.
      const Manifest m = ReadManifest(n);
      for (size_t i = 0; i < m.views; ++i) {
        const ImageView full = LoadView(m, i);
        auto light = std::make_unique<ImageView>();
        light->name = full.name;
        light->manifest = full.manifest;
        light->index = i;
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

std::unique_ptr<PreparedScene> PrepareSource(SceneSource source, int width, int height, int grid, uint64_t seed,
                                             int repeat, bool exact_reference, StageClock* clock,
                                             const ReferenceCache* cache) {
  if (source.scene) {
    return PrepareScene(std::move(source.scene), width, height, grid, seed, repeat, exact_reference, clock, cache);
  }
  if (clock) clock->Enter("references");  // reading the view's images
  ImageView v = LoadView(ReadManifest(source.view->manifest), source.view->index);
  if (v.name != source.view->name) {
    throw UserError("image scene '" + v.manifest + "' changed during the run (view " + std::to_string(v.index) +
                    " was '" + source.view->name + "', now '" + v.name + "')");
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
  sr.noise_floor_null_reason =
      "unknown: a user's reference has no independent half-references to estimate its noise from";
  size_t edge_px = 0;
  for (float m : v.edge_mask.Data()) edge_px += m > 0.5f ? 1 : 0;
  sr.edge_pixel_fraction = static_cast<double>(edge_px) / (static_cast<double>(W) * H);
  p->ref.image = std::move(v.reference);
  p->ref.edge_mask = std::move(v.edge_mask);
  p->ref.edge_mask_raw = std::move(v.edge_mask_raw);
  p->frame1x = std::move(v.frame);
  // The frame comes from the user's renderer: its render time is not measured here.
  p->render1x.samples_ms.assign(static_cast<size_t>(repeat), 0.0);
  p->render1x.Summarize();
  p->none_f = ToFloat(p->frame1x, 3);
  p->flip_reference = flip::PrepareReference(p->ref.image, kFlipDefaultPpd);
  p->ssim_reference = PrepareSsimReference(p->ref.image);
  // The same crop choice as PrepareScene.
  const int crop_size = std::max(8, std::min(32, std::min(W, H) / 4));
  for (const auto& c : PickCrops(CropScore(p->none_f, p->ref.image, &p->ref.edge_mask), crop_size, 4)) {
    sr.crops.push_back({c.x, c.y, c.w, c.h});
  }
  return p;
}

bool RunsOnImageScenes(const MethodPlan& plan) { return plan.IsPostOnly() || plan.name == "none"; }

ResultRow NotApplicableRow(const PreparedScene& p, const MethodPlan& plan) {
  ResultRow row;
  row.scene = p.info.name;
  row.method = plan.name;
  row.spec = plan.spec;
  row.params = plan.params.Ordered();
  row.samples_per_pixel = plan.render.SamplesPerPixel();
  row.render_width = p.info.width;
  row.render_height = p.info.height;
  row.not_applicable = "needs the renderer (it renders its own frame";
  if (plan.render.SamplesPerPixel() > 1) {
    row.not_applicable += ", " + std::to_string(plan.render.SamplesPerPixel()) + " samples per pixel";
  }
  if (plan.render.scale != 1.0) row.not_applicable += ", at scale " + FormatNumber(plan.render.scale);
  row.not_applicable += "); image scene '" + p.info.source + "' has only the 1x frame";
  for (const MetricEntry& m : MetricRegistry()) {
    for (const std::string& name : m.outputs) {
      row.metrics.push_back({name, std::nullopt, "not applicable: " + row.not_applicable});
    }
  }
  return row;
}

}  // namespace aalab
