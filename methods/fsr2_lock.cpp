// FSR 2.2.1's lock pass (ffx_fsr2_lock_pass.glsl, ComputeLock of ffx_fsr2_lock.h), fp32 path:
// thin-feature detection on the lock luma and the previous-depth reset. Conventions:
// methods/fsr2_common.cpp's doc block; figures: docs/fsr2.md.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "methods/fsr2.h"
#include "methods/fsr2_internal.h"

namespace aalab {

using namespace fsr2_detail;  // NOLINT(google-build-using-namespace): the passes' shared helpers

namespace {

// ComputeThinFeatureConfidence.
bool ThinFeature(const Fsr2Constants& k, const Fsr2Plane& luma, I2 pos) {
  const float nucleus = luma.Fetch(pos.x, pos.y, 0);
  float dmin = 3.402823466e+38f, dmax = 0.0f;
  uint32_t mask = 1u << 4;
  int idx = 0;
  for (int y = -1; y <= 1; ++y) {
    for (int x = -1; x <= 1; ++x, ++idx) {
      if (x == 0 && y == 0) continue;
      const I2 p = ClampLoad(pos, {x, y}, k.render_size);
      const float s = luma.Fetch(p.x, p.y, 0);
      const float difference = std::max(s, nucleus) / std::min(s, nucleus);
      if (difference > 0.0f && difference < 1.05f) {
        mask |= 1u << idx;
      } else {
        dmin = std::min(dmin, s);
        dmax = std::max(dmax, s);
      }
    }
  }
  if (!(nucleus > dmax || nucleus < dmin)) return false;
  static constexpr uint32_t kCorners[4] = {0x1Bu, 0x36u, 0xD8u,
                                           0x1B0u};  // bits {0,1,3,4} {1,2,4,5} {3,4,6,7} {4,5,7,8}
  for (uint32_t c : kCorners) {
    if ((mask & c) == c) return false;
  }
  return true;
}

}  // namespace

void Fsr2ComputeLock(const Fsr2Constants& k, const Fsr2Options& o, const Fsr2Plane& lock_luma, Fsr2Plane* new_locks,
                     std::vector<uint32_t>* prev_depth) {
  const int rw = k.render_size[0], rh = k.render_size[1];
  for (int y = 0; y < RoundUp8(rh); ++y) {
    for (int x = 0; x < RoundUp8(rw); ++x) {
      if (ThinFeature(k, lock_luma, {x, y})) {
        const I2 hr = HrPosFromLrPos(k, {x, y});
        if (hr.x >= 0 && hr.y >= 0 && hr.x < new_locks->w && hr.y < new_locks->h) new_locks->At(hr.x, hr.y, 0) = 1.0f;
      }
      if (x < rw && y < rh) {  // ClearResourcesForNextFrame
        (*prev_depth)[static_cast<size_t>(y) * static_cast<size_t>(rw) + static_cast<size_t>(x)] =
            o.inverted_depth ? 0u : Bits(1.0f);
      }
    }
  }
}

}  // namespace aalab
