// Captured sequences and supplied outputs of image scenes (docs/own-frames.md "Sequences",
// "Your own AA as rows"): numbered patterns and motion-vector conventions by hand; a
// synthetic capture (a texture moving by a known (1, 1) px per frame) written by the test and
// run through RunSuite: supplied rows score exactly like aalab's row of the same frames,
// aalab's TAA on the captured frames with correct motion vectors reproduces the moving
// texture exactly (and every accepted convention of the same motion gives the same bits),
// reversed vectors do not; bad sequence manifests fail with one message and no output.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "tests/cli/cli_util.h"
#include "core/error.h"
#include "io/image_io.h"
#include "harness/run/image_scene.h"
#include "harness/run/pipeline.h"
#include "scenes/image_sequence.h"
#include "harness/run/runner.h"

namespace aalab {
namespace {
namespace fs = std::filesystem;

constexpr int kW = 40, kH = 24, kFrames = 6;

fs::path TempDir(const std::string& name) { return clitest::TempDir("image-seq-" + name); }

void WriteText(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

/// A texture with detail at every pixel (no two neighbours alike), as 8-bit values.
uint8_t Texture(int x, int y, int c) {
  const unsigned h = (static_cast<unsigned>(x) * 73856093u) ^ (static_cast<unsigned>(y) * 19349663u) ^
                     (static_cast<unsigned>(c) * 83492791u);
  return static_cast<uint8_t>(40 + (h % 177));
}

/// Frame t: the texture moved by (t, t) pixels (right and down).
Image8 MovingFrame(int t) {
  Image8 f(kW, kH, 4, 255);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      for (int c = 0; c < 3; ++c) f.At(x, y, c) = Texture(x - t, y - t, c);
    }
  }
  return f;
}

/// Motion vectors of the moving texture: every pixel stores (mx, my).
ImageF ConstantMotion(float mx, float my, int channels) {
  ImageF mv(kW, kH, channels);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      mv.At(x, y, 0) = mx;
      mv.At(x, y, 1) = my;
    }
  }
  return mv;
}

/// Writes the capture: frames f_000k.png, references (the frames themselves), a supplied
/// output that is a copy of the frames, and motion vectors mv_<tag>_k.exr storing (mx, my).
void WriteCapture(const fs::path& dir) {
  for (int t = 0; t < kFrames; ++t) {
    char name[64];
    std::snprintf(name, sizeof name, "f_%04d.png", t + 1);
    WriteImage8((dir / name).string(), MovingFrame(t));
    std::snprintf(name, sizeof name, "copy_%d.png", t + 1);
    WriteImage8((dir / name).string(), MovingFrame(t));
  }
}

void WriteMotion(const fs::path& dir, const std::string& tag, float mx, float my, int channels) {
  for (int t = 0; t < kFrames; ++t) {
    WriteImageF((dir / ("mv_" + tag + "_" + std::to_string(t + 1) + ".exr")).string(),
                ConstantMotion(mx, my, channels));
  }
}

std::string Manifest(const std::string& motion) {
  std::string jitter = "[";
  for (int t = 0; t < kFrames; ++t) jitter += std::string(t ? "," : "") + "[0, 0]";
  jitter += "]";
  return R"({"aalab_image_scene": 1, "views": [{"name": "moving", "sequence": {"frames": 6, "first": 1},
    "frame": "f_%04d.png", "reference": "f_%04d.png", "frame_ms": 4.5,
    "outputs": [{"name": "engine-copy", "frame": "copy_%d.png", "ms": 5.25}])" +
         (motion.empty() ? std::string() : ", \"jitter\": " + jitter + ", \"motion_vectors\": " + motion) + "}]}";
}

RunSettings Settings(const fs::path& manifest, const fs::path& out, const std::vector<std::string>& methods) {
  RunSettings s;
  s.scenes = {manifest.string()};
  s.methods = methods;
  s.repeat = 1;
  s.quiet = true;
  s.out_dir = out.string();
  return s;
}

const ResultRow& Row(const Report& r, const std::string& spec) {
  for (const auto& row : r.rows) {
    if (row.spec == spec) return row;
  }
  throw InternalError("no row " + spec);
}

std::map<std::string, std::optional<double>> Metrics(const ResultRow& row) {
  std::map<std::string, std::optional<double>> m;
  for (const auto& v : row.metrics) m[v.name] = v.value;
  return m;
}

TEST(ImageSequence, FramePatterns) {
  std::string why;
  EXPECT_EQ(ExpandFramePattern("f_%04d.png", 7, &why).value(), "f_0007.png");
  EXPECT_EQ(ExpandFramePattern("a/%d.exr", 12, &why).value(), "a/12.exr");
  EXPECT_EQ(ExpandFramePattern("100%%_%02d.png", 3, &why).value(), "100%_03.png");
  EXPECT_FALSE(ExpandFramePattern("f_%04d_%04d.png", 1, &why));
  EXPECT_NE(why.find("2 frame-number placeholders"), std::string::npos) << why;
  EXPECT_FALSE(ExpandFramePattern("f.png", 1, &why));
  EXPECT_FALSE(ExpandFramePattern("f_%s.png", 1, &why));
  EXPECT_TRUE(HasFramePattern("x_%d.png"));
  EXPECT_FALSE(HasFramePattern("x_100%%.png"));
}

TEST(ImageSequence, MotionConventionsByHand) {
  // A surface that moved 3 px right and 2 px down from frame t−1 to t, at 40x24: the vector
  // to the previous position is (−3, −2) px (y down).
  const Jitter zero{0.0f, 0.0f};
  MotionConvention px;  // pixels, to_previous, y down
  auto expect = [&](float mx, float my, const MotionConvention& c) {
    const auto d = MotionToPreviousPx(mx, my, kW, kH, c, zero, zero);
    EXPECT_FLOAT_EQ(d[0], -3.0f) << c.Describe();
    EXPECT_FLOAT_EQ(d[1], -2.0f) << c.Describe();
  };
  expect(-3.0f, -2.0f, px);
  MotionConvention vel_px = px;  // velocity (current − previous): (3, 2)
  vel_px.points_to_previous = false;
  expect(3.0f, 2.0f, vel_px);
  MotionConvention unity;  // UV, velocity, y up: (3/40, −2/24)
  unity.units = MotionConvention::Units::kUv;
  unity.points_to_previous = false;
  unity.y_up = true;
  expect(3.0f / 40.0f, -2.0f / 24.0f, unity);
  MotionConvention ndc = unity;  // NDC spans 2: (6/40, −4/24)
  ndc.units = MotionConvention::Units::kNdc;
  expect(6.0f / 40.0f, -4.0f / 24.0f, ndc);
  // Between jittered positions: frame t−1 sampled at +(0.25, −0.25) px, frame t at
  // (−0.125, 0.375): the surface lands at u − j, so the stored vector is
  // (−3 − 0.25 − 0.125, −2 + 0.25 + 0.375) and taking the jitter change out gives (−3, −2).
  MotionConvention jit = px;
  jit.includes_jitter = true;
  const auto d = MotionToPreviousPx(-3.375f, -1.375f, kW, kH, jit, {0.25f, -0.25f}, {-0.125f, 0.375f});
  EXPECT_FLOAT_EQ(d[0], -3.0f);
  EXPECT_FLOAT_EQ(d[1], -2.0f);
  // The previous position of pixel (x, y)'s centre.
  const std::vector<float> prev = PreviousFromMotion(ConstantMotion(-3.0f, -2.0f, 2), px, zero, zero);
  EXPECT_FLOAT_EQ(prev[2 * (5 * kW + 7)], 7.5f - 3.0f);
  EXPECT_FLOAT_EQ(prev[2 * (5 * kW + 7) + 1], 5.5f - 2.0f);
}

TEST(ImageSequence, SuppliedRowsScoreLikeTheSameFrames) {
  const fs::path dir = TempDir("supplied");
  WriteCapture(dir);
  WriteText(dir / "m.json", Manifest(""));
  const Report r = RunSuite(Settings(dir / "m.json", dir / "out", {"none", "fxaa-high", "ssaa-2x2"}));
  const ResultRow& none = Row(r, "none");
  const ResultRow& copy = Row(r, "engine-copy");
  // The supplied frames are the 1x frames: the same bits, so every metric (pooled over the 6
  // frames, temporal ones included) and every per-frame series is the same.
  EXPECT_EQ(copy.output_hash, none.output_hash);
  EXPECT_EQ(Metrics(copy), Metrics(none));
  EXPECT_EQ(copy.frame_series, none.frame_series);
  EXPECT_EQ(copy.frame_images.size(), static_cast<size_t>(kFrames));
  EXPECT_NE(copy.supplied.find("not run by aalab"), std::string::npos) << copy.supplied;
  EXPECT_TRUE(none.supplied.empty());
  // The given times: none's frame_ms, the output's ms (render = total, no post).
  EXPECT_DOUBLE_EQ(none.render.median_ms, 4.5);
  EXPECT_DOUBLE_EQ(copy.total.median_ms, 5.25);
  EXPECT_DOUBLE_EQ(copy.post.median_ms, 0.0);
  // The reference is the frame itself: none is exact on every frame, so its temporal error is 0.
  EXPECT_LT(Metrics(none).at("temporal_rmse").value(), 1e-6);  // float rounding of k/255 only
  EXPECT_EQ(r.scenes.at(0).frames, kFrames);
  EXPECT_EQ(r.scenes.at(0).frame_images.size(), static_cast<size_t>(kFrames));
  EXPECT_TRUE(r.scenes.at(0).frame_ms_given);
  EXPECT_FALSE(Row(r, "ssaa-2x2").not_applicable.empty());
  // TAA without motion vectors has nothing to reproject with: not applicable.
  const Report r2 = RunSuite(Settings(dir / "m.json", dir / "out2", {"none", "taa"}));
  EXPECT_FALSE(Row(r2, "taa").not_applicable.empty());
  fs::remove_all(dir);
}

TEST(ImageSequence, TaaOnACapturedSequenceFollowsTheMotionVectors) {
  const fs::path dir = TempDir("taa");
  WriteCapture(dir);
  // The texture moves (+1, +1) px per frame: to the previous position (−1, −1) px; as Unity
  // writes it (UV velocity, y up): (1/40, −1/24); as NDC velocity y up: (2/40, −2/24).
  WriteMotion(dir, "px", -1.0f, -1.0f, 2);
  WriteMotion(dir, "uv", 1.0f / kW, -1.0f / kH, 3);
  WriteMotion(dir, "ndc", 2.0f / kW, -2.0f / kH, 2);
  WriteMotion(dir, "wrong", 1.0f, 1.0f, 2);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"px", R"({"path": "mv_px_%d.exr", "direction": "to_previous"})"},
      {"uv", R"({"path": "mv_uv_%d.exr", "units": "uv", "direction": "velocity", "y": "up"})"},
      {"ndc", R"({"path": "mv_ndc_%d.exr", "units": "ndc", "direction": "velocity", "y": "up"})"},
      {"wrong", R"({"path": "mv_wrong_%d.exr", "direction": "to_previous"})"}};
  std::map<std::string, std::string> taa_hash, prod_hash;
  std::string none_hash;
  for (const auto& [tag, mv] : cases) {
    WriteText(dir / ("m_" + tag + ".json"), Manifest(mv));
    // clip=none: the variance clip would move a texel that is more than 1 sigma off its
    // 3x3 neighbourhood's mean (common in this noise-like texture) even when the history is right.
    // The production TAA on the same captured frames (no depth given: no dilation, the
    // motion-vector disocclusion test; Catmull-Rom at texel centres is the texel itself).
    const Report r = RunSuite(
        Settings(dir / ("m_" + tag + ".json"), dir / ("out_" + tag), {"none", "taa:clip=none", "taa-prod:clip=none"}));
    const ResultRow& taa = Row(r, "taa:clip=none");
    ASSERT_TRUE(taa.not_applicable.empty()) << taa.not_applicable;
    taa_hash[tag] = taa.output_hash;
    const ResultRow& prod = Row(r, "taa-prod:clip=none");
    ASSERT_TRUE(prod.not_applicable.empty()) << prod.not_applicable;
    prod_hash[tag] = prod.output_hash;
    none_hash = Row(r, "none").output_hash;
    EXPECT_FALSE(r.scenes.at(0).motion_note.empty());
  }
  // Exact integer motion: the history of every pixel is fetched at a texel centre and equals
  // the current value (h + alpha (c - h) = c), so TAA's last output is the last frame itself, bit for bit.
  EXPECT_EQ(taa_hash.at("px"), none_hash);
  EXPECT_EQ(taa_hash.at("uv"), none_hash);
  EXPECT_EQ(taa_hash.at("ndc"), none_hash);
  // Reversed vectors fetch the wrong history: the output differs.
  EXPECT_NE(taa_hash.at("wrong"), none_hash);
  for (const char* tag : {"px", "uv", "ndc"}) EXPECT_EQ(prod_hash.at(tag), none_hash) << tag;
  EXPECT_NE(prod_hash.at("wrong"), none_hash);
  if (!HasFailure()) fs::remove_all(dir);
}

// Through the manifest, with a different, asymmetric jitter in every frame and vectors taken
// between jittered positions ("includes_jitter": true): frame k's own jitter reaches TAA, and
// its previous positions come from the stored vector minus the jitter change from frame k−1
// to k (a zero-jitter capture cannot tell j(k) from j(k−1), nor either sign). The texture
// moves (+1, +1) px a frame, so the true vector to the previous frame is (−1, −1) and the
// stored one (−1, −1) − j(k−1) + j(k) (image_sequence.h, worked by hand in
// MotionConventionsByHand). Every value is a multiple of 1/8: exact in float.
TEST(ImageSequence, PerFrameJitterThroughTheManifestReachesTaaAndLeavesTheVectors) {
  const fs::path dir = TempDir("jitter");
  WriteCapture(dir);
  const float jit[kFrames][2] = {{0.25f, -0.125f}, {-0.375f, 0.25f}, {0.125f, 0.375f},
                                 {-0.25f, -0.5f},  {0.5f, 0.125f},   {0.0f, -0.25f}};
  std::string jitter = "[";
  for (int t = 0; t < kFrames; ++t) {
    jitter += std::string(t ? "," : "") + "[" + std::to_string(jit[t][0]) + ", " + std::to_string(jit[t][1]) + "]";
    if (t == 0) continue;
    WriteImageF((dir / ("mvj_" + std::to_string(t + 1) + ".exr")).string(),
                ConstantMotion(-1.0f - jit[t - 1][0] + jit[t][0], -1.0f - jit[t - 1][1] + jit[t][1], 2));
  }
  jitter += "]";
  WriteImageF((dir / "mvj_1.exr").string(), ConstantMotion(0.0f, 0.0f, 2));  // frame 0: not read
  WriteText(dir / "m.json",
            R"({"aalab_image_scene": 1, "views": [{"name": "jittered", "sequence": {"frames": 6, "first": 1},
    "frame": "f_%04d.png", "reference": "f_%04d.png", "jitter": )" +
                jitter + R"(, "motion_vectors": {"path": "mvj_%d.exr", "direction": "to_previous",
    "includes_jitter": true}}]})");
  auto sources = LoadSceneSources({(dir / "m.json").string()});
  ASSERT_EQ(sources.size(), 1u);
  for (int k = 0; k < kFrames; ++k) {
    const auto p = PrepareSource(sources[0], kW, kH, 1, 1, 1, false, nullptr, nullptr, k, 67.0);
    EXPECT_TRUE(p->captured_motion);
    EXPECT_EQ(p->captured_jitter.x, jit[k][0]) << "frame " << k;
    EXPECT_EQ(p->captured_jitter.y, jit[k][1]) << "frame " << k;
    if (k == 0) continue;
    ASSERT_EQ(p->captured_previous.size(), static_cast<size_t>(2 * kW * kH));
    for (const auto& [x, y] : {std::pair{7, 5}, std::pair{0, 23}, std::pair{39, 0}}) {
      EXPECT_EQ(p->captured_previous[2 * (y * kW + x)], x + 0.5f - 1.0f) << "frame " << k << " x " << x;
      EXPECT_EQ(p->captured_previous[2 * (y * kW + x) + 1], y + 0.5f - 1.0f) << "frame " << k << " y " << y;
    }
  }
  if (!HasFailure()) fs::remove_all(dir);
}

TEST(ImageSequence, BadSequenceManifestsFailWithOneMessageAndNoOutput) {
  const fs::path dir = TempDir("bad");
  WriteCapture(dir);
  const std::string head = R"({"aalab_image_scene": 1, "views": [{"name": "v", )";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"("sequence": {"frames": 6}, "frame": "f_%04d_%04d.png", "reference": "f_0001.png"}]})",
       "frame-number placeholders"},
      {R"("sequence": {"frames": 6, "first": 1}, "frame": ["f_0001.png", "f_0002.png"], "reference": "f_%04d.png"}]})",
       "lists 2 file(s) but the view has 6 frame(s)"},
      {R"("sequence": {"frames": 7, "first": 1}, "frame": "f_%04d.png", "reference": "f_%04d.png"}]})", "f_0007.png"},
      {R"("frame": "f_0001.png", "reference": "f_0001.png", "outputs": [{"name": "fxaa-high", "frame": "f_0001.png"}]}]})",
       "name of one of aalab's methods"},
      {R"("frame": "f_0001.png", "reference": "f_0001.png", "outputs": [{"name": "Engine TAA", "frame": "f_0001.png"}]}]})",
       "lowercase-kebab"},
      {R"("sequence": {"frames": 6, "first": 1}, "frame": "f_%04d.png", "reference": "f_%04d.png",
          "motion_vectors": {"path": "mv_%d.exr", "direction": "to_previous"}}]})",
       "motion vectors and jitter go together"},
      {R"("sequence": {"frames": 6, "first": 1}, "frame": "f_%04d.png", "reference": "f_%04d.png",
          "jitter": [[0, 0]], "motion_vectors": {"path": "mv_%d.exr", "direction": "to_previous"}}]})",
       "one [dx, dy] per frame"},
      {R"("sequence": {"frames": 6, "first": 1}, "frame": "f_%04d.png", "reference": "f_%04d.png",
          "jitter": [[0,0],[0,0],[0,0],[0,0],[0,0],[0,0]], "motion_vectors": {"path": "mv_%d.exr"}}]})",
       "missing \"direction\""},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    WriteText(dir / "m.json", head + cases[i].first);
    const fs::path out = dir / ("out" + std::to_string(i));
    try {
      RunSuite(Settings(dir / "m.json", out, {"none"}));
      ADD_FAILURE() << "accepted case " << i;
    } catch (const UserError& e) {
      EXPECT_NE(std::string(e.what()).find(cases[i].second), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("m.json"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(out));
    EXPECT_FALSE(fs::exists(out.string() + ".partial"));
  }
  // --frames beyond the sequence.
  WriteText(dir / "m.json",
            head + R"("sequence": {"frames": 6, "first": 1}, "frame": "f_%04d.png", "reference": "f_%04d.png"}]})");
  RunSettings s = Settings(dir / "m.json", dir / "outf", {"none"});
  s.frames = 7;
  EXPECT_THROW(RunSuite(s), UserError);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace aalab
