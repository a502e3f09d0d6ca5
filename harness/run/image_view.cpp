// Reading one view of an image scene: every field, for one frame (image_view.h).
#include "harness/run/image_view.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/color.h"
#include "core/edge_mask.h"
#include "core/error.h"
#include "core/params.h"
#include "io/image_info.h"
#include "io/image_io.h"
#include "io/safe_path.h"
#include "scenes/image_channels.h"
#include "scenes/image_sequence.h"
#include "methods/registry.h"
#include "scenes/motion.h"

namespace aalab {
namespace fs = std::filesystem;

std::string LowerExt(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

namespace {

/// More supplied outputs than this in one view is refused.
constexpr size_t kMaxOutputs = 64;

/// A path field of a view: a path, numbered pattern or list, or an object
/// {"path": ..., "layer": "...", "channels": [...]} naming which channels to read.
struct FieldRef {
  JsonField field;  ///< the field itself (errors name it)
  JsonField path;   ///< its path part
  std::string layer;
  std::vector<std::string> channels;
};

FieldRef ParseFieldRef(const JsonField& f) {
  if (!f.Value().is_object()) return FieldRef{f, f, "", {}};
  f.RequireObject({"path", "layer", "channels"});
  FieldRef r{f, f.Child("path"), "", {}};
  r.layer = f.StringOr("layer", "");
  if (f.Has("channels")) {
    const JsonField cf = f.Child("channels");
    for (size_t i = 0; i < cf.ArraySize(); ++i) r.channels.push_back(cf.At(i).String());
    if (r.channels.empty()) cf.Fail("an empty channel list (name the channels to read, e.g. [\"R\", \"G\", \"B\"])");
  }
  if (!r.layer.empty() && !r.channels.empty()) f.Fail("give \"layer\" or \"channels\", not both");
  return r;
}

/// An image a view names, read and described.
struct ViewImage {
  std::string rel;                 ///< as written in the manifest
  std::string path;                ///< resolved against the manifest's folder
  ImageF pixels;                   ///< the channels read (colour: always 3)
  std::vector<std::string> names;  ///< which channels were read
  ImageFileInfo info;
};

/// Reads the image a field names for one frame (`rel`: the field's path for that frame):
/// the channels `role` needs, chosen by name (image_channels.h). `exts` are the allowed
/// extensions; `allow_inf` keeps ±Inf (depth). Errors name the field.
ViewImage ReadViewImage(const FieldRef& f, const std::string& rel, const fs::path& base,
                        const std::vector<std::string>& exts, ChannelRole role = ChannelRole::kColour,
                        bool allow_inf = false) {
  ViewImage v;
  v.rel = rel;
  if (v.rel.empty()) f.field.Fail("an empty path (give an image file relative to the manifest)");
  try {  // the one rule for paths read from a file (io/safe_path.h)
    v.path = ResolveInside(base.empty() ? fs::path(".") : base, v.rel, "the path").string();
  } catch (const UserError& e) {
    f.field.Fail(e.what());
  }
  const std::string ext = LowerExt(v.path);
  if (std::find(exts.begin(), exts.end(), ext) == exts.end()) {
    f.field.Fail("'" + v.rel + "' has file type '" + ext + "'; allowed here: " + JoinNames(exts));
  }
  std::vector<std::string> have;
  try {
    have = ListImageChannels(v.path);
  } catch (const UserError& e) {
    f.field.Fail(e.what());
  }
  std::string why;
  v.names = PickChannels(have, role, f.layer, f.channels, &why);
  if (v.names.empty()) f.field.Fail("'" + v.rel + "': " + why);
  try {
    v.pixels = ReadImageChannels(v.path, v.names, kMaxImagePixels, allow_inf);
    v.info = ProbeImage(v.path);
  } catch (const UserError& e) {
    f.field.Fail(e.what());
  }
  if (role == ChannelRole::kColour && v.pixels.Channels() == 1) {  // grey: R = G = B
    ImageF rgb(v.pixels.Width(), v.pixels.Height(), 3);
    for (size_t i = 0; i < v.pixels.PixelCount(); ++i) {
      for (int c = 0; c < 3; ++c) rgb.Data()[3 * i + static_cast<size_t>(c)] = v.pixels.Data()[i];
    }
    v.pixels = std::move(rgb);
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
      f.Fail("lists " + std::to_string(n) + " file(s) but the view has " + std::to_string(seq.frames) + " frame(s) (" +
             (seq.declared ? "\"sequence\": {\"frames\": " + std::to_string(seq.frames) + "}"
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

/// Ids and depth may come at n times the frame's width and height (sub-samples, 2 <= n <= 32):
/// returns n (1 at the frame's size); anything else fails naming both sizes.
int SubsampleFactor(const JsonField& f, const ViewImage& img, int w, int h, const std::string& frame_rel) {
  const int iw = img.pixels.Width(), ih = img.pixels.Height();
  if (iw == w && ih == h) return 1;
  const int n = iw / w;
  if (n >= 2 && n <= 32 && iw == n * w && ih == n * h) return n;
  f.Fail("'" + img.rel + "' is " + std::to_string(iw) + "x" + std::to_string(ih) + " but the frame '" + frame_rel +
         "' is " + std::to_string(w) + "x" + std::to_string(h) +
         " (give ids and depth at the frame's size, or at n times it, 2 <= n <= 32, for sub-sample edges: e.g. " +
         std::to_string(8 * w) + "x" + std::to_string(8 * h) + ")");
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
Image8 ReadDisplayFrame(const FieldRef& f, const std::string& rel, const fs::path& base, int w, int h,
                        const std::string& frame_rel, const std::string& what) {
  const ViewImage img = ReadViewImage(f, rel, base, {".png", ".tif", ".tiff"});
  if (img.info.is_float || img.info.bits != 8) {
    f.field.Fail("'" + img.rel + "' stores " + img.info.Describe() + " samples; " + what +
                 " must be 8-bit integer (the RGBA8 back buffer, sRGB-encoded)");
  }
  if (w > 0) RequireSize(f.field, img, w, h, frame_rel);
  const int W = img.info.width, H = img.info.height;
  Image8 out(W, H, 4, 255);
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      for (int c = 0; c < 3; ++c) out.At(x, y, c) = QuantizeUnorm8(img.pixels.At(x, y, c));
    }
  }
  return out;
}

/// The reference: scene-linear EXR through the display transform, or display-encoded integers.
void ReadReference(const JsonField& v, const std::string& rel, const fs::path& base, const std::string& frame_rel,
                   ImageView* view) {
  const int W = view->frame.Width(), H = view->frame.Height();
  const JsonField rf = v.Child("reference");
  const ViewImage ref = ReadViewImage(ParseFieldRef(rf), rel, base, {".exr", ".png", ".tif", ".tiff"});
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
        const float* p = ref.pixels.Pixel(x, y);
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
    view->reference = FirstChannels(ref.pixels, 3);
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
    const FieldRef mr = ParseFieldRef(mf);
    const ViewImage m = ReadViewImage(mr, FramePath(mr.path, seq, k), base, {".png", ".tif", ".tiff"});
    RequireSize(mf, m, W, H, frame_rel);
    if (m.info.is_float || m.info.bits != 8 || (m.info.channels != 1 && m.info.channels != 3)) {
      mf.Fail("'" + m.rel + "' is " + m.info.Describe() + " with " + std::to_string(m.info.channels) +
              " channel(s); an edge mask must be 8-bit integer grey (1 channel, or RGB with R = G = B), "
              "255 = edge, 0 = not");
    }
    view->edge_mask_raw = ImageF(W, H, 1);
    for (int y = 0; y < H; ++y) {
      for (int x = 0; x < W; ++x) {
        const float* px = m.pixels.Pixel(x, y);
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
    const FieldRef ir = ParseFieldRef(idf);
    const ViewImage ids =
        ReadViewImage(ir, FramePath(ir.path, seq, k), base, {".png", ".tif", ".tiff", ".exr"}, ChannelRole::kIds);
    const int n = SubsampleFactor(idf, ids, W, H, frame_rel);
    if (!ids.info.is_float && ids.info.bits != 8 && ids.info.bits != 16) {
      idf.Fail("'" + ids.rel + "' stores " + ids.info.Describe() +
               " samples; object ids must be 8- or 16-bit integer PNG/TIFF, or a float EXR (integer ids up to 2^24)");
    }
    view->edge_mask_raw = n > 1 ? EdgesFromIdBlocks(ids.pixels, n) : EdgesFromIds(ids.pixels);
    how = n > 1 ? "object ids at " + std::to_string(n) + "x ('" + ids.rel + "': the " + std::to_string(n) + "x" +
                      std::to_string(n) + " sub-samples of a pixel have more than one id)"
                : "object ids ('" + ids.rel + "': a 4-neighbour has another id)";
  }
  if (has_depth) {
    const JsonField df = v.Child("depth");
    const FieldRef dr = ParseFieldRef(df);
    // +Inf (a background that overflowed, e.g. a half-float depth) means "no surface": 0.
    ViewImage depth = ReadViewImage(dr, FramePath(dr.path, seq, k), base, {".exr", ".tif", ".tiff", ".png"},
                                    ChannelRole::kDepth, true);
    size_t infinite = 0;
    for (float& z : depth.pixels.Data()) {
      if (std::isinf(z) && z > 0.0f) {
        z = 0.0f;
        ++infinite;
      }
    }
    const int dn = SubsampleFactor(df, depth, W, H, frame_rel);
    if (!depth.info.is_float && depth.info.bits != 16) {
      df.Fail("'" + depth.rel + "' stores " + depth.info.Describe() +
              " samples; depth must be float (EXR/TIFF) or 16-bit integer");
    }
    for (int y = 0; y < H; ++y) {
      for (int x = 0; x < W; ++x) {
        if (depth.pixels.At(x, y, 0) < 0.0f) {
          df.Fail("'" + depth.rel + "' has a negative depth at pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                  "); depths are distances >= 0");
        }
      }
    }
    const ImageF d = dn > 1 ? EdgesFromDepthBlocks(depth.pixels, dn) : EdgesFromDepth(FirstChannels(depth.pixels, 1));
    view->edge_mask_raw = has_ids ? UnionMask(view->edge_mask_raw, d) : d;
    how += std::string(has_ids ? " or " : "") + "depth" + (dn > 1 ? " at " + std::to_string(dn) + "x" : std::string()) +
           " ('" + depth.rel +
           (dn > 1 ? "': within a pixel's sub-samples the depth varies by more than "
                   : "': a 4-neighbour's depth differs by more than ") +
           ShortNumber(kDepthEdgeRelativeJump * 100.0f) + " % of the nearer one" +
           (infinite ? "; " + std::to_string(infinite) + " px of +Inf read as no surface" : std::string()) + ")";
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
  // Its images are written as images/<scene>/<name>.png beside the reference's: aalab's own
  // file names are not for user rows (io/safe_path.h).
  for (const auto& reserved : ReservedOutputNames()) {
    if (name == reserved) {
      f.Fail("'" + name + "' is reserved for aalab's own files in the run folder (images/<scene>/" + name +
             ".png); give your output another name (e.g. engine-" + name + ")");
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
    const FieldRef ff = ParseFieldRef(o.Child("frame"));
    s.file = FramePath(ff.path, seq, k);
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
        .Fail(
            "motion vectors and jitter go together (aalab's TAA runs on a captured sequence only with both): "
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
  mf.RequireObject({"path", "layer", "channels", "units", "direction", "y", "includes_jitter"});
  MotionConvention c;
  const std::string units = mf.Has("units") ? mf.Child("units").Choice({"pixels", "uv", "ndc"}) : "pixels";
  c.units = units == "uv"    ? MotionConvention::Units::kUv
            : units == "ndc" ? MotionConvention::Units::kNdc
                             : MotionConvention::Units::kPixels;
  if (!mf.Has("direction")) {
    mf.Fail(
        "missing \"direction\": \"to_previous\" (the vector points to where the surface was: previous − "
        "current) or \"velocity\" (current − previous, as Unity and Unreal write it)");
  }
  c.points_to_previous = mf.Child("direction").Choice({"to_previous", "velocity"}) == "to_previous";
  c.y_up = (mf.Has("y") ? mf.Child("y").Choice({"down", "up"}) : "down") == "up";
  c.includes_jitter = mf.BoolOr("includes_jitter", false);
  view->motion_note = c.Describe();
  if (k == 0) return;  // frame 0 has no history
  const JsonField pf = mf.Child("path");
  FieldRef mr{mf, pf, mf.StringOr("layer", ""), {}};
  if (mf.Has("channels")) {
    const JsonField cf = mf.Child("channels");
    for (size_t i = 0; i < cf.ArraySize(); ++i) mr.channels.push_back(cf.At(i).String());
  }
  const ViewImage m = ReadViewImage(mr, FramePath(pf, seq, k), base, {".exr"}, ChannelRole::kMotion);
  RequireSize(pf, m, view->frame.Width(), view->frame.Height(), frame_rel);
  if (!m.info.is_float) {
    pf.Fail("'" + m.rel + "' is " + m.info.Describe() + "; motion vectors are a float (half or float) EXR");
  }
  view->motion_note += "; channels " + JoinNames(m.names);
  view->previous = PreviousFromMotion(m.pixels, c, jitter_at(k - 1), view->jitter);
}

}  // namespace

/// Reads frame k of a view: the frame, reference, edge mask, supplied outputs and motion.
ImageView ParseView(const JsonField& v, const fs::path& base, const std::string& manifest, int k) {
  v.RequireObject({"name", "description", "frame", "reference", "display", "depth", "object_ids", "edge_mask",
                   "sequence", "frame_ms", "outputs", "motion_vectors", "jitter", "reference_info"});
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
  const FieldRef ff = ParseFieldRef(v.Child("frame"));
  const std::string frame_rel = FramePath(ff.path, seq, k);
  view.frame = ReadDisplayFrame(ff, frame_rel, base, 0, 0, frame_rel, "the 1x frame");
  ReadReference(v, FramePath(ParseFieldRef(v.Child("reference")).path, seq, k), base, frame_rel, &view);
  ReadEdgeMask(v, seq, k, base, frame_rel, &view);
  view.width = view.frame.Width();
  view.height = view.frame.Height();
  if (v.Has("reference_info")) {
    const JsonField ri = v.Child("reference_info");
    ri.RequireObject({"renderer", "samples_per_pixel"});
    view.reference_origin = ri.StringOr("renderer", "");
    if (ri.Has("samples_per_pixel")) view.reference_spp = ri.Child("samples_per_pixel").Integer(1, 1 << 30);
  }
  ReadOutputs(v, seq, k, base, frame_rel, &view);
  ReadMotion(v, seq, k, base, frame_rel, &view);
  return view;
}

}  // namespace aalab
