// Captures as renderers write them (docs/own-frames.md "Channels and layers"): the channel
// choice by hand (Blender/Cycles multilayer names, RGBA+Z, multi-part, ambiguous layers,
// explicit layer/channels), and end to end a Blender-style multilayer half-float EXR
// (ViewLayer.Combined.RGBA, ViewLayer.Depth.Z with +Inf background, ViewLayer.IndexOB.X)
// written by the test with OpenImageIO scores exactly like the same data in plain files; an
// RGBA frame with alpha 0 scores like the RGB frame (alpha is never multiplied); an
// ambiguous file is refused naming its channels and what to write.
#include <gtest/gtest.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "tests/cli/cli_util.h"
#include "tests/run/image_scene_settings.h"
#include "core/color.h"
#include "core/error.h"
#include "io/image_io.h"
#include "scenes/image_channels.h"
#include "harness/run/runner.h"

namespace aalab {
namespace {
namespace fs = std::filesystem;
using Names = std::vector<std::string>;

constexpr int kW = 32, kH = 20;

fs::path TempDir(const std::string& name) { return clitest::TempDir("image-ch-" + name); }

void WriteText(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

/// Writes `data` (w×h×names.size() values, interleaved) with these channel names.
void WriteExr(const fs::path& p, const Names& names, OIIO::TypeDesc type, const std::vector<float>& data) {
  OIIO::ImageSpec spec(kW, kH, static_cast<int>(names.size()), type);
  spec.channelnames = names;
  spec.alpha_channel = -1;
  auto out = OIIO::ImageOutput::create(p.string());
  ASSERT_TRUE(out);
  ASSERT_TRUE(out->open(p.string(), spec)) << out->geterror();
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, data.data())) << out->geterror();
  ASSERT_TRUE(out->close());
}

std::string Pick(const Names& have, ChannelRole role, const std::string& layer = "", const Names& channels = {}) {
  std::string why;
  const Names got = PickChannels(have, role, layer, channels, &why);
  if (got.empty()) return "FAIL: " + why;
  std::string s;
  for (size_t i = 0; i < got.size(); ++i) s += (i ? "," : "") + got[i];
  return s;
}

TEST(ImageChannels, ChoiceByName) {
  const Names rgbaz = {"R", "G", "B", "A", "Z"};
  EXPECT_EQ(Pick(rgbaz, ChannelRole::kColour), "R,G,B");
  EXPECT_EQ(Pick(rgbaz, ChannelRole::kDepth), "Z");
  EXPECT_EQ(Pick({"Y"}, ChannelRole::kColour), "Y");
  EXPECT_EQ(Pick({"Y", "A"}, ChannelRole::kColour), "Y");
  EXPECT_EQ(Pick({"Z"}, ChannelRole::kDepth), "Z");
  EXPECT_EQ(Pick({"R", "G"}, ChannelRole::kMotion), "R,G");
  // Blender/Cycles multilayer EXR: the Combined layer among other colour passes.
  const Names blender = {"ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B", "ViewLayer.Combined.A",
                         "ViewLayer.DiffCol.R",  "ViewLayer.DiffCol.G",  "ViewLayer.DiffCol.B",  "ViewLayer.Depth.Z",
                         "ViewLayer.IndexOB.X",  "ViewLayer.IndexMA.X",  "ViewLayer.Vector.X",   "ViewLayer.Vector.Y",
                         "ViewLayer.Vector.Z",   "ViewLayer.Vector.W"};
  EXPECT_EQ(Pick(blender, ChannelRole::kColour), "ViewLayer.Combined.R,ViewLayer.Combined.G,ViewLayer.Combined.B");
  EXPECT_EQ(Pick(blender, ChannelRole::kDepth), "ViewLayer.Depth.Z");
  EXPECT_EQ(Pick(blender, ChannelRole::kIds), "ViewLayer.IndexOB.X");
  EXPECT_EQ(Pick(blender, ChannelRole::kMotion), "ViewLayer.Vector.X,ViewLayer.Vector.Y");
  EXPECT_EQ(Pick(blender, ChannelRole::kColour, "ViewLayer.DiffCol"),
            "ViewLayer.DiffCol.R,ViewLayer.DiffCol.G,ViewLayer.DiffCol.B");
  EXPECT_EQ(Pick(blender, ChannelRole::kMotion, "", {"ViewLayer.Vector.Z", "ViewLayer.Vector.W"}),
            "ViewLayer.Vector.Z,ViewLayer.Vector.W");
  // A multi-part file as the reader lists it (PART.NAME).
  const Names parts = {"beauty.R", "beauty.G", "beauty.B", "depth.Z"};
  EXPECT_EQ(Pick(parts, ChannelRole::kColour), "beauty.R,beauty.G,beauty.B");
  EXPECT_EQ(Pick(parts, ChannelRole::kDepth), "depth.Z");
  // Ambiguous: two colour layers, neither named Combined.
  const Names two = {"diffuse.R", "diffuse.G", "diffuse.B", "specular.R", "specular.G", "specular.B"};
  const std::string amb = Pick(two, ChannelRole::kColour);
  EXPECT_NE(amb.find("FAIL"), std::string::npos);
  EXPECT_NE(amb.find("\"diffuse.R\""), std::string::npos) << amb;
  EXPECT_NE(amb.find("layers \"diffuse\", \"specular\""), std::string::npos) << amb;
  EXPECT_NE(amb.find("\"layer\""), std::string::npos) << amb;
  EXPECT_EQ(Pick(two, ChannelRole::kColour, "specular"), "specular.R,specular.G,specular.B");
  EXPECT_NE(Pick(two, ChannelRole::kColour, "", {"R", "G", "B"}).find("there is no channel \"R\""), std::string::npos);
  EXPECT_NE(Pick(two, ChannelRole::kColour, "", {"diffuse.R", "diffuse.G"}).find("colour takes 3 channels"),
            std::string::npos);
  EXPECT_NE(Pick(two, ChannelRole::kDepth).find("FAIL"), std::string::npos);
}

/// A bright rectangle [9.3, 22.6) x [5.5, 14.25) on a dark background: the reference is the
/// exact coverage-weighted display-linear value, the 1x frame its pixel-centre sample.
float Coverage(int x, int y) {
  const double x0 = 9.3, x1 = 22.6, y0 = 5.5, y1 = 14.25;
  const double cx = std::max(0.0, std::min<double>(x + 1, x1) - std::max<double>(x, x0));
  const double cy = std::max(0.0, std::min<double>(y + 1, y1) - std::max<double>(y, y0));
  return static_cast<float>(cx * cy);
}
constexpr float kIn[3] = {0.8f, 0.6f, 0.3f}, kOut[3] = {0.05f, 0.1f, 0.2f};

struct Capture {
  std::vector<float> frame_rgba;  // 8-bit values / 255 (alpha 0 outside the rectangle)
  std::vector<float> ref, depth, ids;
};

Capture MakeCapture() {
  Capture c;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      const float cov = Coverage(x, y);
      const bool centre = x + 0.5 >= 9.3 && x + 0.5 < 22.6 && y + 0.5 >= 5.5 && y + 0.5 < 14.25;
      for (int k = 0; k < 3; ++k) {
        const float lin = centre ? kIn[k] : kOut[k];
        c.frame_rgba.push_back(QuantizeUnorm8(SrgbEncode(lin)) / 255.0f);
        c.ref.push_back(cov * kIn[k] + (1.0f - cov) * kOut[k]);
      }
      c.frame_rgba.push_back(centre ? 1.0f : 0.0f);
      c.depth.push_back(centre ? 4.0f : std::numeric_limits<float>::infinity());
      c.ids.push_back(centre ? 7.0f : 0.0f);
    }
  }
  return c;
}

TEST(ImageChannels, BlenderMultilayerExrScoresLikePlainFiles) {
  const fs::path dir = TempDir("blender");
  const Capture c = MakeCapture();
  // Plain files: RGB frame, RGB half EXR reference, depth with 0 = no surface, ids as EXR.
  std::vector<float> rgb, zero_bg;
  for (size_t i = 0; i < c.depth.size(); ++i) {
    for (int k = 0; k < 3; ++k) rgb.push_back(c.frame_rgba[4 * i + static_cast<size_t>(k)]);
    zero_bg.push_back(std::isinf(c.depth[i]) ? 0.0f : c.depth[i]);
  }
  WriteImageF((dir / "frame-rgb.png").string(), ImageF(kW, kH, 3, ImageF::Storage(rgb.begin(), rgb.end())));
  WriteExr(dir / "ref.exr", {"R", "G", "B"}, OIIO::TypeDesc::HALF, c.ref);
  WriteExr(dir / "depth.exr", {"Z"}, OIIO::TypeDesc::HALF, zero_bg);
  WriteExr(dir / "ids.exr", {"R"}, OIIO::TypeDesc::FLOAT, c.ids);
  // As Blender writes them: an RGBA PNG (alpha 0 on the background: film transparent) and
  // one multilayer half-float EXR with Combined RGBA, Depth.Z (+Inf background), IndexOB.X.
  OIIO::ImageSpec ps(kW, kH, 4, OIIO::TypeDesc::UINT8);
  {
    auto out = OIIO::ImageOutput::create((dir / "frame-rgba.png").string());
    ASSERT_TRUE(out->open((dir / "frame-rgba.png").string(), ps));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, c.frame_rgba.data()));
    ASSERT_TRUE(out->close());
  }
  std::vector<float> layered;
  for (size_t i = 0; i < c.depth.size(); ++i) {
    for (int k = 0; k < 3; ++k) layered.push_back(c.ref[3 * i + static_cast<size_t>(k)]);
    layered.push_back(c.frame_rgba[4 * i + 3]);
    layered.push_back(c.depth[i]);
    layered.push_back(c.ids[i]);
  }
  WriteExr(dir / "capture.exr",
           {"ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B", "ViewLayer.Combined.A",
            "ViewLayer.Depth.Z", "ViewLayer.IndexOB.X"},
           OIIO::TypeDesc::HALF, layered);
  WriteText(dir / "plain.json", R"({"aalab_image_scene": 1, "views": [{"name": "v", "frame": "frame-rgb.png",
    "reference": "ref.exr", "depth": "depth.exr", "object_ids": "ids.exr"}]})");
  WriteText(dir / "blender.json", R"({"aalab_image_scene": 1, "views": [{"name": "v", "frame": "frame-rgba.png",
    "reference": "capture.exr", "depth": "capture.exr", "object_ids": "capture.exr"}]})");
  WriteText(dir / "explicit.json", R"({"aalab_image_scene": 1, "views": [{"name": "v", "frame": "frame-rgba.png",
    "reference": {"path": "capture.exr", "layer": "ViewLayer.Combined"},
    "depth": {"path": "capture.exr", "channels": ["ViewLayer.Depth.Z"]},
    "object_ids": {"path": "capture.exr", "layer": "ViewLayer.IndexOB"}}]})");
  const Report plain = RunSuite(testing_util::ImageSceneSettings(dir / "plain.json", dir / "out-plain"));
  for (const std::string m : {"blender", "explicit"}) {
    const Report r = RunSuite(testing_util::ImageSceneSettings(dir / (m + ".json"), dir / ("out-" + m)));
    ASSERT_EQ(r.rows.size(), plain.rows.size());
    EXPECT_EQ(r.scenes[0].edge_pixel_fraction, plain.scenes[0].edge_pixel_fraction) << m;
    EXPECT_GT(plain.scenes[0].edge_pixel_fraction, 0.0);
    EXPECT_NE(r.scenes[0].edge_mask_source.find("+Inf read as no surface"), std::string::npos)
        << r.scenes[0].edge_mask_source;
    for (size_t i = 0; i < r.rows.size(); ++i) {
      // Alpha is ignored: the RGBA frame is the RGB frame, bit for bit.
      EXPECT_EQ(r.rows[i].output_hash, plain.rows[i].output_hash) << m << " " << r.rows[i].spec;
      ASSERT_EQ(r.rows[i].metrics.size(), plain.rows[i].metrics.size());
      for (size_t k = 0; k < r.rows[i].metrics.size(); ++k) {
        EXPECT_EQ(r.rows[i].metrics[k].value, plain.rows[i].metrics[k].value)
            << m << " " << r.rows[i].spec << " " << r.rows[i].metrics[k].name;
      }
    }
  }
  fs::remove_all(dir);
}

TEST(ImageChannels, AmbiguousOrMissingChannelsAreRefusedNamingThem) {
  const fs::path dir = TempDir("refuse");
  const Capture c = MakeCapture();
  std::vector<float> rgb;
  for (size_t i = 0; i < c.depth.size(); ++i) {
    for (int k = 0; k < 3; ++k) rgb.push_back(c.frame_rgba[4 * i + static_cast<size_t>(k)]);
  }
  WriteImageF((dir / "frame.png").string(), ImageF(kW, kH, 3, ImageF::Storage(rgb.begin(), rgb.end())));
  std::vector<float> six;
  for (size_t i = 0; i < c.depth.size(); ++i) {
    for (int k = 0; k < 6; ++k) six.push_back(c.ref[3 * i + static_cast<size_t>(k % 3)]);
  }
  WriteExr(dir / "aovs.exr", {"diffuse.R", "diffuse.G", "diffuse.B", "specular.R", "specular.G", "specular.B"},
           OIIO::TypeDesc::HALF, six);
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {R"("reference": "aovs.exr")", {"/views/0/reference", "\"diffuse.R\"", "\"layer\""}},
      {R"("reference": {"path": "aovs.exr", "layer": "beauty"})", {"layer \"beauty\" has no colour channels"}},
      {R"("reference": {"path": "aovs.exr", "layer": "diffuse"}, "depth": "aovs.exr")",
       {"/views/0/depth", "which channels hold the depth", "\"specular.B\""}},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    WriteText(dir / "m.json",
              R"({"aalab_image_scene": 1, "views": [{"name": "v", "frame": "frame.png", )" + cases[i].first + "}]}");
    const fs::path out = dir / ("out" + std::to_string(i));
    try {
      RunSuite(testing_util::ImageSceneSettings(dir / "m.json", out));
      ADD_FAILURE() << "accepted case " << i;
    } catch (const UserError& e) {
      for (const auto& want : cases[i].second)
        EXPECT_NE(std::string(e.what()).find(want), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(out));
  }
  // Naming the layer makes the same file work.
  WriteText(dir / "m.json", R"({"aalab_image_scene": 1, "views": [{"name": "v", "frame": "frame.png",
    "reference": {"path": "aovs.exr", "layer": "diffuse"}}]})");
  EXPECT_NO_THROW(RunSuite(testing_util::ImageSceneSettings(dir / "m.json", dir / "ok")));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace aalab
