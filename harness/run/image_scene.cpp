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
#include "harness/run/image_sequence.h"
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
/// More supplied outputs than this in one view is refused.
constexpr size_t kMaxOutputs = 64;

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

/// Reads the image a field names for one frame (`rel`: the field's path for that frame);
/// `exts` are the allowed extensions. Errors name the field.
ViewImage ReadViewImage(const JsonField& f, const std::string& rel, const fs::path& base,
                        const std::vector<std::string>& exts) {
  ViewImage v;
  v.rel = rel;
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

/// A view's sequence: how many frames, and the number frame 0 has in numbered patterns.
struct ViewSequence {
  bool declared = false;  ///< the view has "sequence"
  int frames = 1;
  int first = 0;
};

ViewSequence ParseSequence(const JsonField& v) {
  ViewSequence s;
  if (!v.Has("sequence")) return s;
  const JsonField sf = v.Child("sequence");
  sf.RequireObject({"frames", "first"});
  s.declared = true;
  s.frames = sf.Child("frames").Integer(1, kMaxFrames);
  s.first = sf.Has("first") ? sf.Child("first").Integer(0, 1000000000) : 0;
  return s;
}

/// The file a path field names for frame k: an array of one path per frame, a numbered
/// pattern (sequence views only), or one path used for every frame.
std::string FramePath(const JsonField& f, const ViewSequence& seq, int k) {
  if (f.Value().is_array()) {
    const size_t n = f.ArraySize();
    if (n != static_cast<size_t>(seq.frames)) {
      f.Fail("lists " + std::to_string(n) + " file(s) but the view has " + std::to_string(seq.frames) +
             " frame(s) (" + (seq.declared ? "\"sequence\": {\"frames\": " + std::to_string(seq.frames) + "}"
                                           : std::string("no \"sequence\": a still view takes one path")) +
             "); give one file per frame, or a numbered pattern such as frame_%04d.png");
    }
    return f.At(static_cast<size_t>(k)).String();
  }
  const std::string text = f.String();
  if (!seq.declared || !HasFramePattern(text)) return text;
  std::string why;
  const auto path = ExpandFramePattern(text, seq.first + k, &why);
  if (!path) f.Fail(why);
  return *path;
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

/// An 8-bit display frame (the 1x frame or a supplied output) as RGBA8, alpha 255.
Image8 ReadDisplayFrame(const JsonField& f, const std::string& rel, const fs::path& base, int w, int h,
                        const std::string& frame_rel, const std::string& what) {
  const ViewImage img = ReadViewImage(f, rel, base, {".png", ".tif", ".tiff"});
  if (img.info.is_float || img.info.bits != 8) {
    f.Fail("'" + img.rel + "' stores " + img.info.Describe() + " samples; " + what +
           " must be 8-bit integer (the RGBA8 back buffer, sRGB-encoded)");
  }
  if (w > 0) RequireSize(f, img, w, h, frame_rel);
  const int W = img.info.width, H = img.info.height;
  Image8 out(W, H, 4, 255);
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      for (int c = 0; c < 3; ++c) out.At(x, y, c) = QuantizeUnorm8(img.image.pixels.At(x, y, c));
    }
  }
  return out;
}

/// The reference: scene-linear EXR through the display transform, or display-encoded integers.
void ReadReference(const JsonField& v, const std::string& rel, const fs::path& base, const std::string& frame_rel,
                   ImageView* view) {
  const int W = view->frame.Width(), H = view->frame.Height();
  const JsonField rf = v.Child("reference");
  const ViewImage ref = ReadViewImage(rf, rel, base, {".exr", ".png", ".tif", ".tiff"});
  RequireSize(rf, ref, W, H, frame_rel);
  view->reference = ImageF(W, H, 3);
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
        for (int c = 0; c < 3; ++c) view->reference.At(x, y, c) = SrgbEncode(lin[c]);
      }
    }
    view->reference_note = "'" + ref.rel + "': " + ref.info.Describe() +
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
    view->reference = FirstChannels(ref.image.pixels, 3);
    view->reference_note = "'" + ref.rel + "': " + ref.info.Describe() + " " + ref.info.format +
                           ", display-encoded (sRGB): value k read as k/" + (ref.info.bits == 8 ? "255" : "65535");
  }
}

/// The edge mask: given, from ids and/or depth, or from the reference's gradients.
void ReadEdgeMask(const JsonField& v, const ViewSequence& seq, int k, const fs::path& base,
                  const std::string& frame_rel, ImageView* view) {
  const int W = view->frame.Width(), H = view->frame.Height();
  const bool has_mask = v.Has("edge_mask"), has_ids = v.Has("object_ids"), has_depth = v.Has("depth");
  if (has_mask && (has_ids || has_depth)) {
    v.Child("edge_mask").Fail("give either edge_mask or object_ids/depth, not both (the mask would be ambiguous)");
  }
  if (has_mask) {
    const JsonField mf = v.Child("edge_mask");
    const ViewImage m = ReadViewImage(mf, FramePath(mf, seq, k), base, {".png", ".tif", ".tiff"});
    RequireSize(mf, m, W, H, frame_rel);
    if (m.info.is_float || m.info.bits != 8 || (m.info.channels != 1 && m.info.channels != 3)) {
      mf.Fail("'" + m.rel + "' is " + m.info.Describe() + " with " + std::to_string(m.info.channels) +
              " channel(s); an edge mask must be 8-bit integer grey (1 channel, or RGB with R = G = B), "
              "255 = edge, 0 = not");
    }
    view->edge_mask_raw = ImageF(W, H, 1);
    for (int y = 0; y < H; ++y) {
      for (int x = 0; x < W; ++x) {
        const float* px = m.image.pixels.Pixel(x, y);
        const uint8_t q = QuantizeUnorm8(px[0]);
        if ((q != 0 && q != 255) || px[1] != px[0] || px[2] != px[0]) {
          mf.Fail("'" + m.rel + "' has value (" + std::to_string(q) + ", " + std::to_string(QuantizeUnorm8(px[1])) +
                  ", " + std::to_string(QuantizeUnorm8(px[2])) + ") at pixel (" + std::to_string(x) + ", " +
                  std::to_string(y) + "); an edge mask holds only grey 0 and 255");
        }
        view->edge_mask_raw.At(x, y, 0) = q == 255 ? 1.0f : 0.0f;
      }
    }
    view->edge_mask = view->edge_mask_raw;
    view->edge_mask_source = "given: the edge_mask image '" + m.rel + "', used as is (no dilation)";
    return;
  }
  if (!has_ids && !has_depth) {
    view->edge_mask_raw = EdgesFromGradient(view->reference);
    view->edge_mask = DilateMask(view->edge_mask_raw);
    view->edge_mask_source = "reference gradients (no object ids or depth given): a 4-neighbour differs by more than " +
                             ShortNumber(kGradientEdgeThreshold) +
                             " in any sRGB-encoded channel; dilated by 1 px. Marks texture and shading detail too";
    return;
  }
  std::string how;
  if (has_ids) {
    const JsonField idf = v.Child("object_ids");
    const ViewImage ids = ReadViewImage(idf, FramePath(idf, seq, k), base, {".png", ".tif", ".tiff", ".exr"});
    RequireSize(idf, ids, W, H, frame_rel);
    if (!ids.info.is_float && ids.info.bits != 8 && ids.info.bits != 16) {
      idf.Fail("'" + ids.rel + "' stores " + ids.info.Describe() +
               " samples; object ids must be 8- or 16-bit integer PNG/TIFF, or a float EXR (integer ids up to 2^24)");
    }
    view->edge_mask_raw = EdgesFromIds(ids.image.pixels);
    how = "object ids ('" + ids.rel + "': a 4-neighbour has another id)";
  }
  if (has_depth) {
    const JsonField df = v.Child("depth");
    const ViewImage depth = ReadViewImage(df, FramePath(df, seq, k), base, {".exr", ".tif", ".tiff", ".png"});
    RequireSize(df, depth, W, H, frame_rel);
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
    view->edge_mask_raw = has_ids ? UnionMask(view->edge_mask_raw, d) : d;
    how += std::string(has_ids ? " or " : "") + "depth ('" + depth.rel +
           "': a 4-neighbour's depth differs by more than " + ShortNumber(kDepthEdgeRelativeJump * 100.0f) +
           " % of the nearer one)";
  }
  view->edge_mask = DilateMask(view->edge_mask_raw);
  view->edge_mask_source = "geometry from " + how + "; dilated by 1 px";
}

/// A name a supplied output may take: kebab, not `none`, not a method aalab registers.
void CheckOutputName(const JsonField& f, const std::string& name) {
  if (name.empty()) f.Fail("an output's name must not be empty");
  for (char c : name) {
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-')) {
      f.Fail("output names are lowercase-kebab ([a-z0-9-]+, e.g. engine-taa), got '" + name + "'");
    }
  }
  const std::vector<std::string> taken = MethodNames();
  if (name == "none" || std::find(taken.begin(), taken.end(), name) != taken.end()) {
    f.Fail("'" + name + "' is the name of one of aalab's methods; give your output another name (e.g. engine-" + name +
           ")");
  }
}

/// The view's supplied outputs (frames anti-aliased by the user's pipeline) for frame k.
void ReadOutputs(const JsonField& v, const ViewSequence& seq, int k, const fs::path& base, const std::string& frame_rel,
                 ImageView* view) {
  if (!v.Has("outputs")) return;
  const JsonField of = v.Child("outputs");
  const size_t n = of.ArraySize();
  if (n > kMaxOutputs) of.Fail(std::to_string(n) + " outputs; at most " + std::to_string(kMaxOutputs) + " per view");
  for (size_t i = 0; i < n; ++i) {
    const JsonField o = of.At(i);
    o.RequireObject({"name", "frame", "ms"});
    SuppliedFrame s;
    s.name = o.Child("name").String();
    CheckOutputName(o.Child("name"), s.name);
    for (const auto& other : view->outputs) {
      if (other.name == s.name) o.Child("name").Fail("output '" + s.name + "' is listed twice in this view");
    }
    const JsonField ff = o.Child("frame");
    s.file = FramePath(ff, seq, k);
    s.frame = ReadDisplayFrame(ff, s.file, base, view->frame.Width(), view->frame.Height(), frame_rel,
                               "a supplied output (what your AA pass wrote)");
    if (o.Has("ms")) s.ms = o.Child("ms").Number(0.0, 1e7);
    view->outputs.push_back(std::move(s));
  }
}

/// Jitter and motion vectors of frame k (a sequence view whose TAA input they describe).
void ReadMotion(const JsonField& v, const ViewSequence& seq, int k, const fs::path& base, const std::string& frame_rel,
                ImageView* view) {
  const bool has_mv = v.Has("motion_vectors"), has_jitter = v.Has("jitter");
  if (!has_mv && !has_jitter) return;
  if (has_mv != has_jitter) {
    v.Child(has_mv ? "motion_vectors" : "jitter")
        .Fail("motion vectors and jitter go together (aalab's TAA runs on a captured sequence only with both): "
              "give \"jitter\": [[dx, dy], ...] (one per frame, pixels) and \"motion_vectors\"");
  }
  if (!seq.declared || seq.frames < 2) {
    v.Child("motion_vectors").Fail("motion vectors need a sequence: give \"sequence\": {\"frames\": N} with N >= 2");
  }
  const JsonField jf = v.Child("jitter");
  if (jf.ArraySize() != static_cast<size_t>(seq.frames)) {
    jf.Fail("has " + std::to_string(jf.ArraySize()) + " entries; give one [dx, dy] per frame (" +
            std::to_string(seq.frames) + ")");
  }
  auto jitter_at = [&](int t) {
    const glm::vec2 j = jf.At(static_cast<size_t>(t)).Vec2(-0.5, 0.5);
    return Jitter{j.x, j.y};
  };
  view->jitter = jitter_at(k);
  view->has_motion = true;
  const JsonField mf = v.Child("motion_vectors");
  mf.RequireObject({"path", "units", "direction", "y", "includes_jitter"});
  MotionConvention c;
  const std::string units = mf.Has("units") ? mf.Child("units").Choice({"pixels", "uv", "ndc"}) : "pixels";
  c.units = units == "uv" ? MotionConvention::Units::kUv
            : units == "ndc" ? MotionConvention::Units::kNdc
                             : MotionConvention::Units::kPixels;
  if (!mf.Has("direction")) {
    mf.Fail("missing \"direction\": \"to_previous\" (the vector points to where the surface was: previous − "
            "current) or \"velocity\" (current − previous, as Unity and Unreal write it)");
  }
  c.points_to_previous = mf.Child("direction").Choice({"to_previous", "velocity"}) == "to_previous";
  c.y_up = (mf.Has("y") ? mf.Child("y").Choice({"down", "up"}) : "down") == "up";
  c.includes_jitter = mf.BoolOr("includes_jitter", false);
  view->motion_note = c.Describe();
  if (k == 0) return;  // frame 0 has no history
  const JsonField pf = mf.Child("path");
  const ViewImage m = ReadViewImage(pf, FramePath(pf, seq, k), base, {".exr"});
  RequireSize(pf, m, view->frame.Width(), view->frame.Height(), frame_rel);
  if (!m.info.is_float || m.info.channels < 2) {
    pf.Fail("'" + m.rel + "' is " + m.info.Describe() + " with " + std::to_string(m.info.channels) +
            " channel(s); motion vectors are a float EXR whose first two channels are x and y");
  }
  // Two-channel files come back as grey + alpha (channels 0 and 3); wider ones as R, G.
  ImageF mv(m.info.width, m.info.height, 2);
  const int second = m.info.channels == 2 ? 3 : 1;
  for (int y = 0; y < mv.Height(); ++y) {
    for (int x = 0; x < mv.Width(); ++x) {
      mv.At(x, y, 0) = m.image.pixels.At(x, y, 0);
      mv.At(x, y, 1) = m.image.pixels.At(x, y, second);
    }
  }
  view->previous = PreviousFromMotion(mv, c, jitter_at(k - 1), view->jitter);
}

/// Reads frame k of a view: the frame, reference, edge mask, supplied outputs and motion.
ImageView ParseView(const JsonField& v, const fs::path& base, const std::string& manifest, int k) {
  v.RequireObject({"name", "description", "frame", "reference", "display", "depth", "object_ids", "edge_mask",
                   "sequence", "frame_ms", "outputs", "motion_vectors", "jitter"});
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
  const ViewSequence seq = ParseSequence(v);
  view.frames = seq.frames;
  view.frame_index = k;
  if (v.Has("frame_ms")) view.frame_ms = v.Child("frame_ms").Number(0.0, 1e7);
  const JsonField ff = v.Child("frame");
  const std::string frame_rel = FramePath(ff, seq, k);
  view.frame = ReadDisplayFrame(ff, frame_rel, base, 0, 0, frame_rel, "the 1x frame");
  const JsonField rf = v.Child("reference");
  ReadReference(v, FramePath(rf, seq, k), base, frame_rel, &view);
  ReadEdgeMask(v, seq, k, base, frame_rel, &view);
  ReadOutputs(v, seq, k, base, frame_rel, &view);
  ReadMotion(v, seq, k, base, frame_rel, &view);
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
                                             const ReferenceCache* cache, int frame) {
  if (source.scene) {
    return PrepareScene(std::move(source.scene), width, height, grid, seed, repeat, exact_reference, clock, cache);
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
  sr.motion_note = v.motion_note;
  p->none_f = ToFloat(p->frame1x, 3);
  p->flip_reference = flip::PrepareReference(p->ref.image, kFlipDefaultPpd);
  // The same crop choice as PrepareScene.
  const int crop_size = std::max(8, std::min(32, std::min(W, H) / 4));
  for (const auto& c : PickCrops(CropScore(p->none_f, p->ref.image, &p->ref.edge_mask), crop_size, 4)) {
    sr.crops.push_back({c.x, c.y, c.w, c.h});
  }
  return p;
}

bool RunsOnImageScenes(const MethodPlan& plan, bool has_motion) {
  if (plan.IsPostOnly() || plan.name == "none") return true;
  // TAA: a jittered one-sample 1x render plus a temporal step, all of which a captured
  // sequence with motion vectors and jitter supplies.
  return has_motion && plan.make_state && plan.render.jitter.samples > 0 && plan.render.scale == 1.0 &&
         plan.rescale == Rescale::kNone;
}

MethodOutput SuppliedOutputRow(const PreparedScene& p, const std::string& name, int repeat, StageClock* clock) {
  MethodOutput out;
  ResultRow& row = out.row;
  row.scene = p.info.name;
  row.method = name;
  row.spec = name;
  row.render_width = p.info.width;
  row.render_height = p.info.height;
  const auto it = std::find_if(p.supplied.begin(), p.supplied.end(), [&](const SuppliedFrame& s) { return s.name == name; });
  if (it == p.supplied.end()) {
    row.not_applicable = "no '" + name + "' frames were supplied for this scene (outputs are given per view in an "
                         "image scene's manifest)";
    for (const MetricEntry& m : MetricRegistry()) {
      for (const std::string& metric : m.outputs) {
        row.metrics.push_back({metric, std::nullopt, "not applicable: " + row.not_applicable});
      }
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
