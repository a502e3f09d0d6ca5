// PrepareScene (harness/run/pipeline.h) prepares the reference's metric sides, the coverage
// probes and the crops as four jobs side by side: at 1, 2 and 3 threads the prepared scene
// equals the parts computed one after another by their own functions (ToFloat, CropScore +
// PickCrops, DiskProbes) and scores an output with the same bits (the FLIP and SSIM sides).
#include <gtest/gtest.h>

#include <algorithm>

#include "core/color.h"
#include "core/parallel.h"
#include "harness/run/pipeline.h"
#include "metrics/crops.h"
#include "scenes/exact_reference.h"
#include "scenes/library.h"

namespace aalab {
namespace {

constexpr int kW = 96, kH = 54;  // W ≠ H, both > 11 (SSIM's window)

// An output that differs from the 1x frame and the reference everywhere near edges: the 1x
// frame with every third byte darkened, so FLIP and SSIM both see a non-trivial difference.
Image8 SomeOutput(const Image8& frame) {
  Image8 out = frame;
  for (size_t i = 0; i < out.Data().size(); i += 3) out.Data()[i] = static_cast<uint8_t>(out.Data()[i] / 2);
  return out;
}

TEST(PrepareScene, SideBySideJobsEqualThePartsComputedOneAfterAnother) {
  int probes = 0;
  for (const char* name : {"hdr-edges", "wedges"}) {
    SetThreadCount(1);
    const auto serial = PrepareScene(std::make_unique<Scene>(LoadScene(name)), kW, kH, 2, 1, 1);
    // The parts, each by its own function, one after another.
    const ImageF none_f = ToFloat(serial->frame1x, 3);
    const int crop_size = std::max(8, std::min(32, std::min(kW, kH) / 4));
    const auto crops = PickCrops(CropScore(none_f, serial->ref.image, &serial->ref.edge_mask), crop_size, 4);
    const auto disks = DiskProbes(*serial->scene, kW, kH, serial->ref.image);
    probes += static_cast<int>(disks.size());
    const Image8 output = SomeOutput(serial->frame1x);
    for (int threads : {1, 2, 3}) {
      SetThreadCount(threads);
      const auto p = PrepareScene(std::make_unique<Scene>(LoadScene(name)), kW, kH, 2, 1, 1);
      const std::string where = std::string(name) + ", " + std::to_string(threads) + " threads";
      EXPECT_TRUE(p->frame1x == serial->frame1x) << where;
      EXPECT_TRUE(p->none_f == none_f) << where;
      ASSERT_EQ(p->info.crops.size(), crops.size()) << where;
      for (size_t i = 0; i < crops.size(); ++i) {
        EXPECT_EQ(p->info.crops[i][0], crops[i].x) << where;
        EXPECT_EQ(p->info.crops[i][1], crops[i].y) << where;
        EXPECT_EQ(p->info.crops[i][2], crops[i].w) << where;
        EXPECT_EQ(p->info.crops[i][3], crops[i].h) << where;
      }
      ASSERT_EQ(p->coverage_probes.size(), disks.size()) << where;
      for (size_t i = 0; i < disks.size(); ++i) {
        const CoverageProbe& c = p->coverage_probes[i];
        EXPECT_EQ(c.x0, disks[i].x0) << where;
        EXPECT_EQ(c.y1, disks[i].y1) << where;
        EXPECT_EQ(c.radius_px, disks[i].radius_px) << where;
        EXPECT_EQ(c.area_px, disks[i].area_px) << where;
        for (int k = 0; k < 3; ++k) {
          EXPECT_EQ(c.inside[k], disks[i].inside[static_cast<size_t>(k)]) << where;
          EXPECT_EQ(c.outside[k], disks[i].outside[static_cast<size_t>(k)]) << where;
        }
      }
      // The FLIP and SSIM sides: the same output scores with the same bits.
      const auto want = ScoreFrame(*serial, output);
      const auto got = ScoreFrame(*p, output);
      EXPECT_EQ(got.flip_grey, want.flip_grey) << where;
      ASSERT_EQ(got.metrics.size(), want.metrics.size()) << where;
      int valued = 0;
      for (size_t i = 0; i < want.metrics.size(); ++i) {
        EXPECT_EQ(got.metrics[i].name, want.metrics[i].name) << where;
        ASSERT_EQ(got.metrics[i].value.has_value(), want.metrics[i].value.has_value()) << where;
        if (want.metrics[i].value) {
          EXPECT_EQ(*got.metrics[i].value, *want.metrics[i].value) << where << " " << want.metrics[i].name;
          ++valued;
        }
      }
      EXPECT_GT(valued, 5) << where;
    }
  }
  SetThreadCount(0);
  EXPECT_GT(probes, 0) << "no coverage probe: the DiskProbes job was not exercised";
}

}  // namespace
}  // namespace aalab
