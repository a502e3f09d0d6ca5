// The traps of a user's capture (docs/own-frames.md "Mismatch warnings", "What the header
// says"): a correct capture (pixel-centre frame against a coverage reference) gives no
// warning; a reference with another exposure, one holding linear values in a display-encoded
// file, and a frame through a Filmic-like curve are each warned about with the likely cause,
// in the run's report and page; image-scene runs show the views' size, not --size; a sweep
// whose points all tie suggests the point at the preset's defaults.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli/cli_util.h"
#include "tests/run/image_scene_settings.h"
#include "core/color.h"
#include "core/edge_mask.h"
#include "core/error.h"
#include "io/image_info.h"
#include "io/image_io.h"
#include "harness/run/capture_checks.h"
#include "harness/run/runner.h"
#include "harness/run/sweep.h"
#include "methods/registry.h"

namespace aalab {
namespace {
namespace fs = std::filesystem;

constexpr int kW = 48, kH = 32;

fs::path TempDir(const std::string& name) { return clitest::TempDir("capture-check-" + name); }

void WriteText(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

/// A disk of radius 9.3 px at (23.7, 15.2), colour kIn on kOut: exact-ish coverage by 16x16
/// sub-samples for the reference, the centre sample for the 1x frame (display-linear values).
constexpr float kIn[3] = {0.7f, 0.45f, 0.2f}, kOut[3] = {0.1f, 0.15f, 0.3f};
float Coverage(int x, int y, int n) {
  int in = 0;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double px = x + (i + 0.5) / n - 23.7, py = y + (j + 0.5) / n - 15.2;
      in += px * px + py * py < 9.3 * 9.3 ? 1 : 0;
    }
  }
  return static_cast<float>(in) / static_cast<float>(n * n);
}

/// Linear RGB with coverage sampled n×n per pixel (n = 1: the pixel centre).
ImageF Linear(int n) {
  ImageF img(kW, kH, 3);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      const float c = Coverage(x, y, n);
      for (int k = 0; k < 3; ++k) img.At(x, y, k) = c * kIn[k] + (1 - c) * kOut[k];
    }
  }
  return img;
}

ImageF Encoded(const ImageF& lin) {
  ImageF e = lin;
  for (float& v : e.Data()) v = SrgbEncode(std::clamp(v, 0.0f, 1.0f));
  return e;
}

/// The 1x frame as the 8-bit display values a renderer writes, as float.
ImageF Frame8(const ImageF& lin) {
  ImageF e = Encoded(lin);
  for (float& v : e.Data()) v = QuantizeUnorm8(v) / 255.0f;
  return e;
}

/// The edge mask: pixels whose 16×16 coverage is neither 0 nor 1, dilated by 1 px.
ImageF Mask() {
  ImageF m(kW, kH, 1);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = std::clamp(x + dx, 0, kW - 1), yy = std::clamp(y + dy, 0, kH - 1);
          const float c = Coverage(xx, yy, 16);
          if (c > 0 && c < 1) m.At(x, y, 0) = 1;
        }
      }
    }
  }
  return m;
}

TEST(CaptureChecks, ACorrectCaptureHasNoWarning) {
  const CaptureCheck c = CheckCapture(Frame8(Linear(1)), Encoded(Linear(16)), Mask());
  EXPECT_TRUE(c.warnings.empty()) << c.warnings.front();
  // Interior pixels differ only by the 8-bit rounding: at most half a level.
  for (double b : c.bias) EXPECT_LE(std::fabs(b), 0.5 / 255.0);
  EXPECT_LE(c.interior_rms, 0.5 / 255.0 + 1e-7);
  EXPECT_GT(c.edge_rms, 10.0 * c.interior_rms);
}

TEST(CaptureChecks, ExposureLinearValuesAndAViewTransformAreWarnedAbout) {
  const ImageF none = Frame8(Linear(1)), mask = Mask();
  // Exposure: the reference 1.5x brighter in linear light. The gain that fits is 1/1.5.
  ImageF bright = Linear(16);
  for (float& v : bright.Data()) v *= 1.5f;
  const CaptureCheck e = CheckCapture(none, Encoded(bright), mask);
  ASSERT_EQ(e.warnings.size(), 1u);
  EXPECT_NE(e.warnings[0].find("darker than the reference"), std::string::npos) << e.warnings[0];
  EXPECT_NE(e.warnings[0].find("exposure difference"), std::string::npos) << e.warnings[0];
  EXPECT_NEAR(e.best_gain, 1.0 / 1.5, 0.005);
  // A 16-bit PNG holding linear values: read as display-encoded, it is darker; encoding it
  // once is what the check finds.
  const CaptureCheck l = CheckCapture(none, Linear(16), mask);
  ASSERT_EQ(l.warnings.size(), 1u);
  EXPECT_NE(l.warnings[0].find("looks like linear values"), std::string::npos) << l.warnings[0];
  EXPECT_LE(l.rms_if_linear, 0.5 / 255.0 + 1e-6);
  // A Filmic-like view transform on the frame only (lower contrast, lifted blacks):
  // warned about, the view transform named among the causes.
  ImageF filmic = none;
  for (float& v : filmic.Data()) v = QuantizeUnorm8(0.25f + 0.55f * v) / 255.0f;  // lifted blacks, less contrast
  const CaptureCheck f = CheckCapture(filmic, Encoded(Linear(16)), mask);
  ASSERT_EQ(f.warnings.size(), 1u);
  EXPECT_NE(f.warnings[0].find("Filmic"), std::string::npos) << f.warnings[0];
}

std::string ReadAll(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

TEST(CaptureChecks, TheRunReportsAndShowsTheWarningAndTheViewsSize) {
  const fs::path dir = TempDir("run");
  Image8 frame(kW, kH, 4, 255);
  const ImageF f = Frame8(Linear(1));
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      for (int k = 0; k < 3; ++k) frame.At(x, y, k) = QuantizeUnorm8(f.At(x, y, k));
    }
  }
  WriteImage8((dir / "frame.png").string(), frame);
  WriteImageF((dir / "ref.exr").string(), Linear(16));               // display-linear: correct
  WriteImage16((dir / "ref-linear16.png").string(), Linear(16), 3);  // the trap: linear in a display file
  WriteText(dir / "good.json", R"({"aalab_image_scene": 1, "views": [{"name": "v", "frame": "frame.png",
    "reference": "ref.exr", "reference_info": {"renderer": "test", "samples_per_pixel": 256}}]})");
  WriteText(dir / "trap.json", R"({"aalab_image_scene": 1, "views": [{"name": "v", "frame": "frame.png",
    "reference": "ref-linear16.png"}]})");
  const Report good = RunSuite(testing_util::ImageSceneSettings(dir / "good.json", dir / "out-good"));
  EXPECT_TRUE(good.scenes[0].warnings.empty());
  EXPECT_EQ(good.scenes[0].ref_spp, 256);
  EXPECT_NE(good.scenes[0].reference_note.find("made by test, 256 samples per pixel"), std::string::npos);
  // The settings say what applied: the view's own size, not --size's default 960x540.
  for (const auto& [k, v] : good.settings) {
    if (k == "size") {
      EXPECT_EQ(v, std::to_string(kW) + "x" + std::to_string(kH) + " (the views' own size)");
    }
    if (k == "ref_spp") {
      EXPECT_EQ(v, "the user's own");
    }
  }
  const std::string good_page = ReadAll(dir / "out-good" / "index.html");
  EXPECT_EQ(good_page.find("960x540"), std::string::npos);
  EXPECT_EQ(good_page.find("class=\"mismatch\""), std::string::npos);
  const Report trap = RunSuite(testing_util::ImageSceneSettings(dir / "trap.json", dir / "out-trap"));
  ASSERT_EQ(trap.scenes[0].warnings.size(), 1u);
  EXPECT_NE(trap.scenes[0].warnings[0].find("looks like linear values"), std::string::npos);
  EXPECT_NE(ReadAll(dir / "out-trap" / "report.json").find("\"warnings\""), std::string::npos);
  EXPECT_NE(ReadAll(dir / "out-trap" / "index.html").find("class=\"mismatch\""), std::string::npos);
  fs::remove_all(dir);
}

TEST(CaptureChecks, SweepTiesGoToThePresetsDefaults) {
  // A flat frame two levels off its flat reference: FXAA changes nothing, so every point ties.
  const fs::path dir = TempDir("ties");
  WriteImage8((dir / "flat.png").string(), Image8(kW, kH, 4, 128));
  WriteImage8((dir / "ref.png").string(), Image8(kW, kH, 4, 130));
  WriteText(dir / "m.json", R"({"aalab_image_scene": 1, "views": [{"name": "flat", "frame": "flat.png",
    "reference": "ref.png"}]})");
  std::string def_threshold, def_subpix;
  const MethodPlan plan = MakeMethod("fxaa311-p12");
  for (const auto& [k, v] : plan.params.Ordered()) {
    if (k == "edge_threshold") def_threshold = v;
    if (k == "subpix") def_subpix = v;
  }
  SweepSettings s;
  s.scenes = {(dir / "m.json").string()};
  s.method = "fxaa311-p12";
  s.objectives = {"psnr_db"};  // a flat view has no edges
  // The defaults are in the middle and last of the grids, never first in grid order.
  s.grid = {"edge_threshold=0.063," + def_threshold + ",0.333", "subpix=0.25,0.5," + def_subpix};
  s.repeat = 1;
  s.quiet = true;
  s.out_dir = (dir / "sweep").string();
  const SweepResult r = RunSweep(s);
  ASSERT_EQ(r.points.size(), 9u);
  const SweepPoint& best = r.points.at(r.best.at(r.objectives.front()));
  for (const auto& [k, v] : best.overrides) EXPECT_EQ(v, k == "subpix" ? def_subpix : def_threshold) << k;
  EXPECT_EQ(r.best_ties.at(r.objectives.front()), 8);
  EXPECT_NE(SweepSummaryText(r).find("closest to the defaults"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace aalab

namespace aalab {
namespace {

TEST(CaptureChecks, SubsampledIdsAndDepthFindASubPixelWire) {
  // A 6x4 frame; ids and depth at 4x (24x16): background id 0 at depth 10, a vertical wire
  // one sub-sample wide (sub-column 9, inside pixel column 2, off its centre sub-samples 1-2)
  // with id 5 at depth 3, and a boundary exactly on the pixel border x = 4 (id 7 right of it).
  constexpr int n = 4, w = 6, h = 4;
  ImageF ids(w * n, h * n, 1), depth(w * n, h * n, 1, 10.0f);
  for (int y = 0; y < h * n; ++y) {
    ids.At(9, y, 0) = 5;
    depth.At(9, y, 0) = 3;
    for (int x = 4 * n; x < w * n; ++x) ids.At(x, y, 0) = 7;
  }
  const ImageF blocks = EdgesFromIdBlocks(ids, n), dblocks = EdgesFromDepthBlocks(depth, n);
  // The pixel-centre ids (sub-sample (2, 2) of each pixel, the sample nearest the centre) miss
  // the wire; only the id boundary on the pixel border shows there.
  ImageF centre(w, h, 1);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) centre.At(x, y, 0) = ids.At(x * n + 2, y * n + 2, 0);
  }
  const ImageF centre_mask = EdgesFromIds(centre);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      EXPECT_EQ(blocks.At(x, y, 0), x == 2 ? 1.0f : 0.0f) << x << "," << y;  // the wire's pixel only
      EXPECT_EQ(dblocks.At(x, y, 0), x == 2 ? 1.0f : 0.0f) << x << "," << y;
      EXPECT_EQ(centre_mask.At(x, y, 0), x == 3 || x == 4 ? 1.0f : 0.0f) << x << "," << y;
    }
  }
}

}  // namespace
}  // namespace aalab
