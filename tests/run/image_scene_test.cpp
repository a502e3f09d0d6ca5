// Image scenes (harness/run/image_scene.h): library scenes rendered small, written out as an
// image scene (1x frame PNG, reference EXR or 16-bit PNG, edge mask or object ids) and run
// again: post-filter outputs are bit-identical and every metric lies within a bound derived
// from how far the reference moved through its file; renderer-side methods are "not
// applicable" rows; bad manifests fail before any output; the edge detectors by hand.
#include "harness/run/image_scene.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "core/color.h"
#include "core/edge_mask.h"
#include "core/error.h"
#include "io/image_info.h"
#include "io/image_io.h"
#include "harness/run/runner.h"
#include "harness/run/sweep.h"
#include "reports/report_json.h"
#include "tests/temp_dir.h"

namespace aalab {
namespace {
namespace fs = std::filesystem;

constexpr int kW = 64, kH = 48;
const std::vector<std::string> kMethods = {"none", "fxaa1-p3", "fxaa311-p12", "fxaa-high", "ssaa-2x2"};

fs::path TempDir(const std::string& name) { return testenv::ScratchDir("image-scene-" + name); }

void WriteText(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

std::unique_ptr<PreparedScene> Render(const std::string& name) {
  auto scenes = LoadScenes({name});
  return PrepareScene(std::move(scenes[0]), kW, kH, 4, 1, 1);
}

/// Object ids as an engine writes them: the id (shape index + 1; 0 = background) of what the
/// 1x frame's pixel-centre sample sees, as 16-bit grey.
ImageF CentreIds(const PreparedScene& p) {
  std::vector<SamplePos> pos;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) pos.push_back({x + 0.5f, y + 0.5f});
  }
  std::vector<SampleResult> hits(pos.size());
  TraceCounters c;
  p.tracer->Trace(pos.data(), static_cast<int>(pos.size()), kW, kH, hits.data(), &c);
  ImageF ids(kW, kH, 1);
  for (size_t i = 0; i < hits.size(); ++i) ids.Data()[i] = static_cast<float>(hits[i].surface + 1) / 65535.0f;
  return ids;
}

ImageF Decoded(const ImageF& encoded) {
  ImageF out = encoded;
  for (float& v : out.Data()) v = SrgbDecode(v);
  return out;
}

float MaxAbsDiff(const ImageF& a, const ImageF& b) {
  float m = 0;
  for (size_t i = 0; i < a.Data().size(); ++i) m = std::max(m, std::fabs(a.Data()[i] - b.Data()[i]));
  return m;
}

RunSettings Settings(const std::vector<std::string>& scenes, const fs::path& out) {
  RunSettings s;
  s.scenes = scenes;
  s.methods = kMethods;
  s.width = kW;
  s.height = kH;
  s.ref_spp = 16;
  s.repeat = 1;
  s.quiet = true;
  s.out_dir = out.string();
  return s;
}

const ResultRow& Row(const Report& r, const std::string& scene, const std::string& spec) {
  for (const auto& row : r.rows) {
    if (row.scene == scene && row.spec == spec) return row;
  }
  throw InternalError("no row " + scene + " " + spec);
}

std::map<std::string, MetricResult> Metrics(const ResultRow& row) {
  std::map<std::string, MetricResult> m;
  for (const auto& v : row.metrics) m[v.name] = v;
  return m;
}

/// |Δ PSNR| (dB) when every reference value moves by at most eps: with e the per-channel
/// error, MSE = mean(e²) and |Δ MSE| = |mean(2eδ + δ²)| ≤ 2·eps·sqrt(MSE) + eps² (Cauchy–
/// Schwarz), so PSNR = −10·log10(MSE) moves by at most 10·log10(MSE / (MSE − Δ)).
double PsnrBound(double psnr_db, double eps) {
  const double mse = std::pow(10.0, -psnr_db / 10.0);
  const double d = 2.0 * eps * std::sqrt(mse) + eps * eps;
  return d >= mse ? 1e9 : 10.0 * std::log10(mse / (mse - d)) + 1e-9;
}

/// Checks every metric of an image-scene row against the directly rendered row. `eps`: the
/// largest change of a reference value through its file. `mask_metrics`: whether the edge
/// mask is the same (else the edge/interior metrics are skipped).
void ExpectWithinBounds(const ResultRow& direct, const ResultRow& image, double eps, bool mask_metrics) {
  const auto a = Metrics(direct), b = Metrics(image);
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [name, ma] : a) {
    const MetricResult& mb = b.at(name);
    const bool masked = name.rfind("edge_", 0) == 0 || name.rfind("interior_", 0) == 0;
    if (masked && !mask_metrics) continue;
    ASSERT_EQ(ma.value.has_value(), mb.value.has_value()) << image.spec << " " << name;
    if (!ma.value) continue;
    const double va = *ma.value, vb = *mb.value;
    double bound;
    if (name.size() > 3 && name.substr(name.size() - 3) == "_db") {
      bound = PsnrBound(va, eps);
    } else if (name == "mse") {
      bound = 2.0 * eps * std::sqrt(va) + eps * eps;
    } else if (name == "edge_rmse" || name.rfind("abs_err_", 0) == 0) {
      // RMS and order statistics of per-pixel errors move by at most the per-value change.
      bound = eps + 1e-7;
    } else if (name == "edge_error_removed") {
      // r = 1 − M/N with M = MSE_edge(method) = edge_rmse² and N = MSE_edge(none) = M/(1 − r),
      // both against the reference; each moves by at most dX = 2·eps·sqrt(X) + eps² (as "mse"
      // above), so M/N moves by at most (M + dM)/(N − dN) − M/N (the larger side).
      const double M = *a.at("edge_rmse").value * *a.at("edge_rmse").value;
      ASSERT_LT(va, 1.0) << image.spec;
      const double N = M / (1.0 - va);
      const double dM = 2.0 * eps * std::sqrt(M) + eps * eps, dN = 2.0 * eps * std::sqrt(N) + eps * eps;
      bound = dN < N ? (M + dM) / (N - dN) - M / N + 1e-12 : 1e9;
    } else if (name == "ssim") {
      // Per window and channel SSIM = L·Q, L = (2μxμy + C1)/(μx² + μy² + C1) in [0, 1],
      // Q = (2σxy + C2)/(σx² + σy² + C2) in [−1, 1]; y (the reference) moves by δ, |δ| ≤ eps.
      // μy moves by ≤ eps and |∂L/∂μy| ≤ 1/√C1 (at μy = 0, 2μx/(μx² + C1) peaks at μx = √C1;
      // a grid search over [0, 1]² finds no larger value). σxy moves by Cov(x, δ) ≤ σx·eps and
      // σy² by ≤ 2σy·eps + eps², so Q moves by ≤ 2σx·eps/D + |Q|·2σy·eps/D + O(eps²/C2), and
      // 2s/(s² + C2) ≤ 1/√C2: ≤ 2·eps/√C2. So |ΔSSIM| ≤ (1/√C1 + 2/√C2)·eps = 166.7·eps to
      // first order; for eps ≤ 1e-5 the second-order terms (eps²/C2, (eps/√C1)(2eps/√C2)) add
      // under 8 % of it: bound 1.1 × that. The mean over windows and channels obeys the same.
      EXPECT_LE(eps, 1e-5);
      const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
      bound = 1.1 * (1.0 / std::sqrt(c1) + 2.0 / std::sqrt(c2)) * eps + 1e-12;
    } else {
      // FLIP (flip_mean, flip_median_weighted, flip_max): no bound derived (a colour transform,
      // CSF filters and feature detectors between the values and the error); a sensitivity of
      // 100 per unit of reference change, ~50× the largest measured on these scenes (1.9).
      ASSERT_EQ(name.rfind("flip_", 0), 0u) << name << " needs a derived bound here";
      bound = 100.0 * eps + 1e-9;
    }
    EXPECT_LE(std::fabs(va - vb), bound) << image.scene << " " << image.spec << " " << name << ": " << va << " vs "
                                         << vb << " (eps " << eps << ")";
  }
}

TEST(ImageScene, RoundTripMatchesTheRenderedScenes) {
  const fs::path dir = TempDir("roundtrip");
  const auto circle = Render("circle");
  const auto wedges = Render("wedges");
  // circle: scene-linear EXR (display transform none: the display-linear resolve) + its mask;
  // wedges: 16-bit display-encoded PNG + its mask.
  WriteImage8((dir / "circle-frame.png").string(), circle->frame1x);
  WriteImageF((dir / "circle-ref.exr").string(), Decoded(circle->ref.image));
  WriteImage8((dir / "circle-mask.png").string(), ToUnorm8(circle->ref.edge_mask));
  WriteImage8((dir / "wedges-frame.png").string(), wedges->frame1x);
  WriteImage16((dir / "wedges-ref.png").string(), wedges->ref.image, 3);
  WriteImage8((dir / "wedges-mask.png").string(), ToUnorm8(wedges->ref.edge_mask));
  WriteText(dir / "frames.json", R"({"aalab_image_scene": 1, "views": [
    {"name": "circle", "frame": "circle-frame.png", "reference": "circle-ref.exr", "edge_mask": "circle-mask.png"},
    {"name": "wedges", "frame": "wedges-frame.png", "reference": "wedges-ref.png", "edge_mask": "wedges-mask.png"}]})");

  // How far the reference moved through its file.
  const std::vector<ImageView> views = LoadImageScene((dir / "frames.json").string());
  ASSERT_EQ(views.size(), 2u);
  const double eps_exr = MaxAbsDiff(views[0].reference, circle->ref.image);
  const double eps_16 = MaxAbsDiff(views[1].reference, wedges->ref.image);
  // sRGB decode then encode in float: a few ulps; 16 bits: half a step plus float rounding.
  EXPECT_LE(eps_exr, 1e-6);
  EXPECT_LE(eps_16, 0.5 / 65535.0 + 1e-6);
  EXPECT_EQ(views[0].frame, circle->frame1x);
  EXPECT_EQ(views[0].edge_mask, circle->ref.edge_mask);
  EXPECT_EQ(views[1].edge_mask, wedges->ref.edge_mask);

  const Report direct = RunSuite(Settings({"circle", "wedges"}, dir / "direct"));
  const Report image = RunSuite(Settings({(dir / "frames.json").string()}, dir / "image"));
  ASSERT_EQ(image.scenes.size(), 2u);
  for (const SceneResult& s : image.scenes) {
    EXPECT_EQ(s.kind, "image");
    EXPECT_EQ(s.width, kW);
    EXPECT_FALSE(s.ref_floor_psnr_db);
    EXPECT_NE(s.noise_floor_null_reason.find("unknown"), std::string::npos);
    EXPECT_EQ(s.edge_mask_source.rfind("given: the edge_mask image", 0), 0u) << s.edge_mask_source;
  }
  EXPECT_NE(image.scenes[0].reference_note.find("EXR, scene-linear"), std::string::npos);
  EXPECT_NE(image.scenes[1].reference_note.find("16-bit integer"), std::string::npos);
  EXPECT_EQ(image.scenes[0].crops, direct.scenes[0].crops);
  for (const std::string scene : {"circle", "wedges"}) {
    const double eps = scene == "circle" ? eps_exr : eps_16;
    for (const std::string& spec : kMethods) {
      const ResultRow& b = Row(image, scene, spec);
      if (spec == "ssaa-2x2") {
        EXPECT_NE(b.not_applicable.find("needs the renderer"), std::string::npos) << b.not_applicable;
        EXPECT_TRUE(b.images.empty());
        for (const auto& m : b.metrics) {
          EXPECT_FALSE(m.value) << m.name;
          EXPECT_EQ(m.null_reason.rfind("not applicable: ", 0), 0u) << m.null_reason;
        }
        continue;
      }
      const ResultRow& a = Row(direct, scene, spec);
      EXPECT_TRUE(b.not_applicable.empty());
      EXPECT_EQ(a.output_hash, b.output_hash) << scene << " " << spec;  // the filters saw the same frame
      ExpectWithinBounds(a, b, eps, true);
    }
  }
  // The report round-trips through JSON with the new fields, and the page names them.
  const Report back = ReadReportFile((dir / "image" / "report.json").string());
  EXPECT_EQ(back.scenes[0].kind, "image");
  EXPECT_EQ(back.scenes[0].edge_mask_source, image.scenes[0].edge_mask_source);
  EXPECT_EQ(Row(back, "circle", "ssaa-2x2").not_applicable, Row(image, "circle", "ssaa-2x2").not_applicable);
  std::ifstream html(dir / "image" / "index.html");
  const std::string page((std::istreambuf_iterator<char>(html)), std::istreambuf_iterator<char>());
  EXPECT_NE(page.find("not applicable"), std::string::npos);
  EXPECT_NE(page.find("given: the edge_mask image"), std::string::npos);
  fs::remove_all(dir);
}

TEST(ImageScene, ObjectIdsGiveAGeometricMask) {
  const fs::path dir = TempDir("ids");
  const auto circle = Render("circle");
  WriteImage8((dir / "frame.png").string(), circle->frame1x);
  WriteImageF((dir / "ref.exr").string(), Decoded(circle->ref.image));
  WriteImage16((dir / "ids.png").string(), CentreIds(*circle), 1);
  WriteText(dir / "m.json", R"({"aalab_image_scene": 1, "views": [
    {"name": "circle", "frame": "frame.png", "reference": "ref.exr", "object_ids": "ids.png"}]})");
  const std::vector<ImageView> views = LoadImageScene((dir / "m.json").string());
  EXPECT_EQ(views[0].edge_mask_source.rfind("geometry from object ids", 0), 0u) << views[0].edge_mask_source;
  // Where the centre ids of two 4-neighbours differ, the silhouette passes between the two
  // centres, so it crosses one of the two pixels: that pixel's reference samples see both
  // surfaces. Every raw id edge is thus within 1 px of a raw geometric edge, i.e. inside the
  // reference's dilated mask (unless all 16 samples of the crossed pixel missed the sliver).
  size_t id_px = 0, inside = 0;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      if (views[0].edge_mask_raw.At(x, y, 0) > 0.5f) {
        ++id_px;
        inside += circle->ref.edge_mask.At(x, y, 0) > 0.5f ? 1 : 0;
      }
    }
  }
  EXPECT_GT(id_px, 0u);
  EXPECT_EQ(inside, id_px);

  const Report direct = RunSuite(Settings({"circle"}, dir / "direct"));
  const Report image = RunSuite(Settings({(dir / "m.json").string()}, dir / "image"));
  const double eps = MaxAbsDiff(views[0].reference, circle->ref.image);
  for (const std::string spec : {"none", "fxaa311-p12"}) {
    ExpectWithinBounds(Row(direct, "circle", spec), Row(image, "circle", spec), eps, false);
  }
  fs::remove_all(dir);
}

TEST(ImageScene, EdgeDetectorsByHand) {
  // Ids: columns 0-2 are object 1, columns 3-5 object 2 → raw edges in columns 2 and 3; the
  // 1-px dilation adds columns 1 and 4.
  ImageF ids(6, 3, 1);
  for (int y = 0; y < 3; ++y) {
    for (int x = 3; x < 6; ++x) ids.At(x, y, 0) = 2.0f;
  }
  const ImageF raw = EdgesFromIds(ids), dil = DilateMask(raw);
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 6; ++x) {
      EXPECT_EQ(raw.At(x, y, 0), (x == 2 || x == 3) ? 1.0f : 0.0f) << x << "," << y;
      EXPECT_EQ(dil.At(x, y, 0), (x >= 1 && x <= 4) ? 1.0f : 0.0f) << x << "," << y;
    }
  }
  // Depth along a row: 10 → 10.5 (5 %, a slope) → 11 → 20 (82 %, an edge) → 20 → 0 (no surface).
  ImageF depth(6, 1, 1);
  const float d[6] = {10.0f, 10.5f, 11.0f, 20.0f, 20.0f, 0.0f};
  for (int x = 0; x < 6; ++x) depth.At(x, 0, 0) = d[x];
  const ImageF de = EdgesFromDepth(depth);
  const float want_depth[6] = {0, 0, 1, 1, 1, 1};
  for (int x = 0; x < 6; ++x) EXPECT_EQ(de.At(x, 0, 0), want_depth[x]) << x;
  // Just at the threshold is no edge: 10 → 11 is exactly 10 % of 10.
  ImageF two(2, 1, 1);
  two.At(0, 0, 0) = 10.0f;
  two.At(1, 0, 0) = 11.0f;
  EXPECT_EQ(EdgesFromDepth(two).At(0, 0, 0), 0.0f);
  // Gradients: a step of 0.05 is shading, one of 0.65 in the green channel an edge.
  ImageF img(3, 1, 3, 0.2f);
  img.At(1, 0, 1) = 0.25f;
  img.At(2, 0, 1) = 0.9f;
  const ImageF ge = EdgesFromGradient(img);
  EXPECT_EQ(ge.At(0, 0, 0), 0.0f);
  EXPECT_EQ(ge.At(1, 0, 0), 1.0f);
  EXPECT_EQ(ge.At(2, 0, 0), 1.0f);
  // A flat image has no edges at all (an image scene without edges: edge metrics go null).
  EXPECT_EQ(EdgesFromGradient(ImageF(5, 4, 3, 0.5f)), ImageF(5, 4, 1));
}

TEST(ImageScene, DepthMaskAndAViewWithoutEdges) {
  const fs::path dir = TempDir("depth");
  // 8x6, odd content: left half at depth 10, right half at 20 (a 100 % jump between columns
  // 3 and 4) → raw edges in columns 3 and 4, dilated to 2..5.
  Image8 frame(8, 6, 4, 255);
  ImageF depth(8, 6, 1, 10.0f);
  for (int y = 0; y < 6; ++y) {
    for (int x = 4; x < 8; ++x) {
      depth.At(x, y, 0) = 20.0f;
      frame.At(x, y, 0) = frame.At(x, y, 1) = frame.At(x, y, 2) = 40;
    }
  }
  WriteImage8((dir / "frame.png").string(), frame);
  WriteImage8((dir / "flat.png").string(), Image8(7, 5, 4, 90));
  WriteImageF((dir / "ref.exr").string(), Decoded(ToFloat(frame, 3)));
  WriteImageF((dir / "depth.exr").string(), depth);
  WriteText(dir / "m.json", R"({"aalab_image_scene": 1, "views": [
    {"name": "step", "frame": "frame.png", "reference": "ref.exr", "depth": "depth.exr"},
    {"name": "flat", "frame": "flat.png", "reference": "flat.png"}]})");
  const std::vector<ImageView> views = LoadImageScene((dir / "m.json").string());
  EXPECT_EQ(views[0].edge_mask_source.rfind("geometry from depth", 0), 0u) << views[0].edge_mask_source;
  for (int x = 0; x < 8; ++x) {
    EXPECT_EQ(views[0].edge_mask_raw.At(x, 2, 0), (x == 3 || x == 4) ? 1.0f : 0.0f) << x;
    EXPECT_EQ(views[0].edge_mask.At(x, 2, 0), (x >= 2 && x <= 5) ? 1.0f : 0.0f) << x;
  }
  // The flat view: an 8-bit display-encoded reference, no edges at all, so the edge metrics are
  // null (with the metric's reason) and the run still succeeds.
  const Report r = RunSuite(Settings({(dir / "m.json").string()}, dir / "out"));
  EXPECT_EQ(r.scenes[1].edge_pixel_fraction, 0.0);
  EXPECT_NE(r.scenes[1].reference_note.find("8-bit integer"), std::string::npos) << r.scenes[1].reference_note;
  const auto flat = Metrics(Row(r, "flat", "fxaa311-p12"));
  EXPECT_FALSE(flat.at("edge_psnr_db").value);
  EXPECT_FALSE(flat.at("edge_psnr_db").null_reason.empty());
  EXPECT_FALSE(flat.at("psnr_db").value);  // identical to its reference: infinite PSNR, null
  fs::remove_all(dir);
}

/// Writes a valid view's files into `dir` (frame 8x6, 8-bit; reference EXR; 16-bit frame and
/// others for the bad cases).
void WriteSmallViewFiles(const fs::path& dir) {
  Image8 frame(8, 6, 4, 255);
  for (int y = 0; y < 6; ++y) {
    for (int x = 4; x < 8; ++x) frame.At(x, y, 0) = frame.At(x, y, 1) = frame.At(x, y, 2) = 0;
  }
  WriteImage8((dir / "frame.png").string(), frame);
  WriteImage16((dir / "frame16.png").string(), ToFloat(frame, 3), 3);
  WriteImageF((dir / "ref.exr").string(), ToFloat(frame, 3));
  WriteImageF((dir / "small.exr").string(), ImageF(4, 3, 3));
  WriteImage16((dir / "ref16.png").string(), ToFloat(frame, 3), 3);
  Image8 grey(8, 6, 4, 128);
  WriteImage8((dir / "grey.png").string(), grey);
  WriteImage8((dir / "ids.png").string(), frame);
}

std::string ManifestError(const fs::path& dir, const std::string& json) {
  WriteText(dir / "m.json", json);
  const fs::path out = dir / "out";
  try {
    RunSuite(Settings({(dir / "m.json").string()}, out));
  } catch (const UserError& e) {
    EXPECT_FALSE(fs::exists(out)) << json;
    EXPECT_FALSE(fs::exists(out.string() + ".partial")) << json;
    return e.what();
  }
  ADD_FAILURE() << "accepted: " << json;
  return "";
}

TEST(ImageScene, BadManifestsFailWithOneClearMessageAndNoOutput) {
  const fs::path dir = TempDir("bad");
  WriteSmallViewFiles(dir);
  const std::string head = R"({"aalab_image_scene": 1, "views": [{"name": "v", )";
  // The valid form first: it runs.
  WriteText(dir / "ok.json", head + R"("frame": "frame.png", "reference": "ref.exr"}]})");
  RunSettings ok = Settings({(dir / "ok.json").string()}, dir / "ok-out");
  EXPECT_NO_THROW(RunSuite(ok));
  const struct {
    std::string json;
    std::vector<std::string> parts;
  } cases[] = {
      {head + R"("frame": "frame.png", "reference": "small.exr"}]})",
       {"/views/0/reference", "'small.exr' is 4x3 but the frame 'frame.png' is 8x6"}},
      {head + R"("frame": "nope.png", "reference": "ref.exr"}]})", {"/views/0/frame", "does not exist"}},
      {head + R"("frame": "frame16.png", "reference": "ref.exr"}]})",
       {"/views/0/frame", "16-bit integer", "must be 8-bit integer"}},
      {head + R"("frame": "frame.png", "reference": "ref.exr", "exposure": 2}]})",
       {"/views/0", "unknown field 'exposure'", "allowed:"}},
      {head + R"("frame": "frame.png", "reference": "ref16.png", "display": {"exposure": 2}}]})",
       {"/views/0/display", "only to a scene-linear .exr reference"}},
      {head + R"("frame": "frame.png", "reference": "ref.exr", "edge_mask": "grey.png"}]})",
       {"/views/0/edge_mask", "only grey 0 and 255"}},
      {head + R"("frame": "frame.png", "reference": "ref.exr", "edge_mask": "grey.png", "object_ids": "ids.png"}]})",
       {"either edge_mask or object_ids/depth"}},
      {head + R"("frame": "frame.png", "reference": "ref.exr", "depth": "ids.png"}]})",
       {"/views/0/depth", "cannot tell which channels hold the depth", "\"R\", \"G\", \"B\"", "\"channels\": [\"Z\"]"}},
      {head + R"("frame": "ref.exr", "reference": "ref.exr"}]})", {"/views/0/frame", "file type '.exr'"}},
      {R"({"views": [{"name": "v", "frame": "frame.png", "reference": "ref.exr"}]})",
       {"missing \"aalab_image_scene\": 1"}},
      {R"({"aalab_image_scene": 2, "views": []})", {"/aalab_image_scene"}},
      {R"({"aalab_image_scene": 1, "views": []})", {"/views", "no views"}},
      {head +
           R"("frame": "frame.png", "reference": "ref.exr"}, {"name": "v", "frame": "frame.png", "reference": "ref.exr"}]})",
       {"/views/1/name", "'v' is listed twice"}},
      {R"({"aalab_image_scene": 1, "views": [{"name": "V 1", "frame": "frame.png", "reference": "ref.exr"}]})",
       {"/views/0/name", "lowercase-kebab"}},
  };
  for (const auto& c : cases) {
    const std::string e = ManifestError(dir, c.json);
    EXPECT_EQ(e.rfind("image scene '", 0), 0u) << e;
    for (const auto& p : c.parts) EXPECT_NE(e.find(p), std::string::npos) << c.json << "\n" << e << "\nmissing: " << p;
  }
  fs::remove_all(dir);
}

TEST(ImageScene, SweepTunesAPostFilterAndSuggestsAPreset) {
  const fs::path dir = TempDir("sweep");
  const auto circle = Render("circle");
  WriteImage8((dir / "frame.png").string(), circle->frame1x);
  WriteImageF((dir / "ref.exr").string(), Decoded(circle->ref.image));
  WriteText(dir / "m.json", R"({"aalab_image_scene": 1, "views": [
    {"name": "circle", "frame": "frame.png", "reference": "ref.exr"}]})");
  SweepSettings s;
  s.scenes = {(dir / "m.json").string()};
  s.method = "fxaa311-p12";
  s.grid = {"edge_threshold=0.063,0.125,0.25"};
  s.repeat = 1;
  s.quiet = true;
  s.out_dir = (dir / "sweep").string();
  const SweepResult r = RunSweep(s);
  ASSERT_EQ(r.points.size(), 3u);
  EXPECT_EQ(r.reference_renders, 0);  // nothing rendered: the view brings its reference
  EXPECT_EQ(r.suggested_preset.rfind("fxaa311-p12:edge_threshold=", 0), 0u) << r.suggested_preset;
  EXPECT_NE(SweepSummaryText(r).find("suggested preset: " + r.suggested_preset), std::string::npos);
  // A renderer-side method cannot be swept on an image scene.
  s.method = "ssaa-jitter";
  s.grid = {"spp=2,4"};
  s.out_dir = (dir / "sweep2").string();
  try {
    RunSweep(s);
    ADD_FAILURE() << "ssaa swept on an image scene";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("needs the renderer"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "sweep2"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace aalab
