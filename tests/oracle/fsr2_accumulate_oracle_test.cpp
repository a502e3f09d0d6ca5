// FSR 2's accumulate pass (methods/fsr2.h, Fsr2Accumulate) against the ORIGINAL
// ffx_fsr2_accumulate_pass.glsl of FSR 2.2.1 on lavapipe (tests/oracle/fsr2_shader.h), on a
// 40×24 render for a 60×36 display (1.5×, neither a multiple of 8): structured inputs that
// reach the pass's branches — a prepared colour with edges on both axes and 1-px lines, depth
// clips of 0, partial and 1 (disocclusion), motion of several display pixels per region (one
// pushing the reprojection off screen: new samples; one below 0.1 px), a history whose
// temporal factor is negative where it moved, lock lifetimes set, expiring and dead, new locks,
// reactive and accumulation masks, a luma history — with the reset frame and without, each
// reprojection kernel (reference Lanczos and its table), HDR with display-resolution jittered
// motion, and sharpening on. Every output is compared value for value.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "methods/fsr2.h"
#include "tests/oracle/fsr2_oracle_fixture.h"
#include "tests/oracle/fsr2_shader.h"

namespace aalab {
namespace {

constexpr int kRw = 40, kRh = 24, kDw = 60, kDh = 36, kMipW = 10, kMipH = 6;

// The Lanczos 2 table as FSR2's API fills it (128 r16 snorm codes of lanczos2(2i/127)),
// worked out here from the kernel's formula.
std::vector<int16_t> LanczosCodes() {
  std::vector<int16_t> codes(128);
  for (int i = 0; i < 128; ++i) {
    const double x = 2.0 * i / 127.0, pi = 3.141592653589793;
    const double y = x < 1e-3 ? 1.0 : (std::sin(pi * x) / (pi * x)) * (std::sin(0.5 * pi * x) / (0.5 * pi * x));
    codes[static_cast<size_t>(i)] = static_cast<int16_t>(std::lround(y * 32767.0));
  }
  return codes;
}

// The texel values a LINEAR sampler reads from those codes: max(c/32767, −1).
Fsr2Plane LanczosPlane(const std::vector<int16_t>& codes) {
  Fsr2Plane p(static_cast<int>(codes.size()), 1, 1);
  for (size_t i = 0; i < codes.size(); ++i) p.v[i] = std::max(static_cast<float>(codes[i]) * (1.0f / 32767.0f), -1.0f);
  return p;
}

float U8(float v) { return std::round(std::clamp(v, 0.0f, 1.0f) * 255.0f) / 255.0f; }

struct Frame {
  Fsr2Constants k;
  Fsr2Plane masks, dilated_motion, motion, history, lock_status, prepared, mip, luma_history, new_locks;
  float exposure = 0.8f;
};

// Region of a display-UV position: 0 background, 1 a box moving 3.4 px left, 2 a disc that
// moved down-right by 5 px, 3 the right strip moving off screen.
int RegionAt(float u, float v) {
  if (u > 0.86f) return 3;
  if (u > 0.15f && u < 0.45f && v > 0.2f && v < 0.6f) return 1;
  const float du = u - 0.68f, dv = (v - 0.55f) * 0.6f;
  return du * du + dv * dv < 0.018f ? 2 : 0;
}

Frame MakeFrame(const Fsr2Options& o, int frame_index, uint32_t seed) {
  Frame f;
  Fsr2Constants& k = f.k;
  k.render_size[0] = k.max_render_size[0] = k.input_color_size[0] = kRw;
  k.render_size[1] = k.max_render_size[1] = k.input_color_size[1] = kRh;
  k.display_size[0] = kDw;
  k.display_size[1] = kDh;
  k.luma_mip_size[0] = kMipW;
  k.luma_mip_size[1] = kMipH;
  k.luma_mip_level = 1;
  k.frame_index = frame_index;
  k.jitter[0] = -0.28125f;
  k.jitter[1] = 0.3703704f;
  k.downscale_factor[0] = static_cast<float>(kRw) / kDw;
  k.downscale_factor[1] = static_cast<float>(kRh) / kDh;
  k.motion_vector_scale[0] = 1.0f / kDw;  // display-resolution motion in pixels
  k.motion_vector_scale[1] = 1.0f / kDh;
  k.motion_vector_jitter_cancellation[0] = 0.0071f;
  k.motion_vector_jitter_cancellation[1] = -0.0102f;
  k.pre_exposure = 1.25f;
  k.previous_pre_exposure = 1.1f;
  k.jitter_sequence_length = 18.0f;  // ceil(8·1.5²)
  Lcg r{seed};
  auto region_motion = [](int id, float* mx, float* my) {  // display pixels
    *mx = id == 1 ? -3.4f : id == 2 ? -5.2f : id == 3 ? 7.5f : 0.04f;
    *my = id == 1 ? 0.6f : id == 2 ? -4.9f : id == 3 ? -0.3f : -0.03f;
  };
  f.prepared = Fsr2Plane(kRw, kRh, 4);
  f.masks = Fsr2Plane(kRw, kRh, 2);
  f.dilated_motion = Fsr2Plane(kRw, kRh, 2);
  for (int y = 0; y < kRh; ++y) {
    for (int x = 0; x < kRw; ++x) {
      const float u = (x + 0.5f) / kRw, v = (y + 0.5f) / kRh;
      const int id = RegionAt(u, v);
      float rgb[3] = {0.2f + 0.3f * r.Next(), 0.25f + 0.05f * r.Next(), 0.3f};  // background, a little noise
      if (id == 1) rgb[0] = 1.4f, rgb[1] = 0.9f, rgb[2] = 0.2f;
      if (id == 2) rgb[0] = 0.05f, rgb[1] = 0.6f, rgb[2] = 2.5f;
      if (x == 31 || y == 4) rgb[0] = rgb[1] = rgb[2] = 1.0f;  // 1-px lines, both axes
      if ((x + y) % 11 == 0 && id == 0) rgb[0] = rgb[1] = rgb[2] = 0.0f;
      const float yy = (0.25f * rgb[0] + 0.5f * rgb[1]) + 0.25f * rgb[2];
      f.prepared.At(x, y, 0) = Fsr2Half(yy);
      f.prepared.At(x, y, 1) = Fsr2Half(0.5f * rgb[0] - 0.5f * rgb[2]);
      f.prepared.At(x, y, 2) = Fsr2Half((-0.25f * rgb[0] + 0.5f * rgb[1]) - 0.25f * rgb[2]);
      // Depth clip: 1 in a disoccluded band right of the box, partial around it, else 0.
      float clip = 0.0f;
      if (u >= 0.45f && u < 0.52f && v > 0.2f && v < 0.6f) clip = 1.0f;
      if (u >= 0.52f && u < 0.58f && v > 0.2f && v < 0.6f) clip = r.Next();
      f.prepared.At(x, y, 3) = Fsr2Half(clip);
      f.masks.At(x, y, 0) = (x > 2 && x < 12 && y > 14) ? U8(r.Next() * 0.8f) : 0.0f;  // reactive
      f.masks.At(x, y, 1) = (x > 20 && x < 30 && y > 16) ? U8(r.Next()) : 0.0f;        // accumulation mask
      float mx, my;
      region_motion(id, &mx, &my);
      f.dilated_motion.At(x, y, 0) = Fsr2Half(mx / kDw);
      f.dilated_motion.At(x, y, 1) = Fsr2Half(my / kDh);
    }
  }
  f.motion = Fsr2Plane(kDw, kDh, 2);
  f.history = Fsr2Plane(kDw, kDh, 4);
  f.lock_status = Fsr2Plane(kDw, kDh, 2);
  f.luma_history = Fsr2Plane(kDw, kDh, 4);
  f.new_locks = Fsr2Plane(kDw, kDh, 1);
  static const float kLifetimes[6] = {0.0f, 0.0f, 0.4f, 1.0f, 1.6f, 2.0f};
  for (int y = 0; y < kDh; ++y) {
    for (int x = 0; x < kDw; ++x) {
      const float u = (x + 0.5f) / kDw, v = (y + 0.5f) / kDh;
      const int id = RegionAt(u, v);
      float mx, my;
      region_motion(id, &mx, &my);
      f.motion.At(x, y, 0) = mx + 0.2f * (r.Next() - 0.5f);
      f.motion.At(x, y, 1) = my + 0.2f * (r.Next() - 0.5f);
      for (int c = 0; c < 3; ++c) f.history.At(x, y, c) = Fsr2Half((id == 1 ? 1.5f : 0.4f) * r.Next() + 0.05f * c);
      if (x == 40 || y == 9) f.history.At(x, y, 0) = f.history.At(x, y, 1) = f.history.At(x, y, 2) = Fsr2Half(1.2f);
      const float w = r.Next() * 0.9f;
      f.history.At(x, y, 3) = Fsr2Half(id == 0 ? w : -std::max(w, 1e-3f));  // negative: moved last frame
      f.lock_status.At(x, y, 0) = Fsr2Half(kLifetimes[(x * 7 + y * 3) % 6]);
      f.lock_status.At(x, y, 1) = Fsr2Half(((x + y) % 5 == 0) ? 0.0f : 0.5f + 0.6f * r.Next());
      for (int c = 0; c < 4; ++c) f.luma_history.At(x, y, c) = (x + 2 * y) % 7 == 0 ? 0.0f : U8(0.3f + 0.4f * r.Next());
      f.new_locks.At(x, y, 0) = (x % 9 == 4 || y == 20) ? 1.0f : 0.0f;
    }
  }
  f.mip = Fsr2Plane(kMipW, kMipH, 1);
  for (int y = 0; y < kMipH; ++y)
    for (int x = 0; x < kMipW; ++x) f.mip.At(x, y, 0) = Fsr2Half(-2.5f + 2.2f * r.Next() + (x == 6 ? 1.5f : 0.0f));
  (void)o;
  return f;
}

// How far apart two values are: half-float steps for 16-bit outputs, float ulps for floats
// (both finite, same sign here; anything else counts as far).
long Steps(float a, float b, bool half) {
  if (!std::isfinite(a) || !std::isfinite(b) || (a < 0) != (b < 0)) return 1L << 30;
  if (half)
    return std::labs(static_cast<long>(Fsr2HalfBits(a) & 0x7fffu) - static_cast<long>(Fsr2HalfBits(b) & 0x7fffu));
  int32_t ia, ib;
  std::memcpy(&ia, &a, 4);
  std::memcpy(&ib, &b, 4);
  return std::labs(static_cast<long>(ia & 0x7fffffff) - static_cast<long>(ib & 0x7fffffff));
}

struct Count {
  long total = 0, same = 0, max_steps = 0;
  float max_rel = 0.0f;  // the largest |a − b| / |b|
  bool half = true;      // 16-bit outputs (steps of a half), else floats (ulps)
  std::string examples;
  void Add(float a, float b, int x, int y, int c, const char* what) {
    ++total;
    if (std::memcmp(&a, &b, 4) != 0) {
      max_steps = std::max(max_steps, Steps(a, b, half));
      max_rel = std::max(max_rel, b != 0.0f ? std::fabs(a - b) / std::fabs(b) : 1.0f);
    }
    if (std::memcmp(&a, &b, 4) == 0) {
      ++same;
    } else if (examples.size() < 600) {
      std::ostringstream os;
      os.precision(9);
      os << " " << what << "(" << x << "," << y << ")." << c << " ours " << a << " shader " << b << ";";
      examples += os.str();
    }
  }
  void Add(const Fsr2Plane& a, const Fsr2Plane& b, const char* what) {
    for (size_t i = 0; i < a.v.size(); ++i) {
      const size_t px = i / static_cast<size_t>(a.c);
      Add(a.v[i], b.v[i], static_cast<int>(px % static_cast<size_t>(a.w)),
          static_cast<int>(px / static_cast<size_t>(a.w)), static_cast<int>(i % static_cast<size_t>(a.c)), what);
    }
  }
};

// Every output of the port against the shader's.
struct Comparison {
  Count color, factor, lock, luma, output, locks;
  Comparison(const Fsr2AccumulateOut& a, const Fsr2AccumulateOut& b, const Fsr2Plane& locks_a,
             const Fsr2Plane& locks_b) {
    output.half = false;
    for (int y = 0; y < kDh; ++y) {
      for (int x = 0; x < kDw; ++x) {
        for (int c = 0; c < 3; ++c)
          color.Add(a.internal_upscaled.At(x, y, c), b.internal_upscaled.At(x, y, c), x, y, c, "colour");
        factor.Add(a.internal_upscaled.At(x, y, 3), b.internal_upscaled.At(x, y, 3), x, y, 3, "factor");
      }
    }
    lock.Add(a.lock_status, b.lock_status, "lock");
    luma.Add(a.luma_history, b.luma_history, "luma");
    output.Add(a.output, b.output, "output");
    locks.Add(locks_a, locks_b, "new lock");
  }
  std::string Line() const {
    char buf[500];
    std::snprintf(buf, sizeof(buf),
                  "colour %ld/%ld (max %ld half steps), temporal factor %ld/%ld (%ld), lock status %ld/%ld (%ld), luma "
                  "history %ld/%ld, output %ld/%ld (max %ld ulps, %.2g relative), new locks %ld/%ld",
                  color.same, color.total, color.max_steps, factor.same, factor.total, factor.max_steps, lock.same,
                  lock.total, lock.max_steps, luma.same, luma.total, output.same, output.total, output.max_steps,
                  static_cast<double>(output.max_rel), locks.same, locks.total);
    return buf;
  }
  void ExpectAllSame(const std::string& name) const {
    for (const Count* c : {&color, &factor, &lock, &luma, &output, &locks})
      EXPECT_EQ(c->same, c->total) << name << c->examples;
  }
  // What the frames with a history show (docs/fsr2.md): the 8-bit outputs identical; at most
  // 1 in 200 of the 16-bit ones differ, each by at most 2 half-float steps; at least
  // `identical_percent` % of the output floats identical, the rest within `max_rel` (relative).
  void ExpectClose(const std::string& name, int identical_percent, float max_rel) const {
    EXPECT_EQ(luma.same, luma.total) << name << luma.examples;
    EXPECT_EQ(locks.same, locks.total) << name << locks.examples;
    for (const Count* c : {&color, &factor, &lock}) {
      EXPECT_LE((c->total - c->same) * 200, c->total) << name << c->examples;
      EXPECT_LE(c->max_steps, 2) << name << c->examples;
    }
    EXPECT_GE(output.same * 100, output.total * identical_percent) << name << output.examples;
    EXPECT_LE(output.max_rel, max_rel) << name << output.examples;
  }
};

struct Case {
  const char* name;
  Fsr2Options o;
  int frame_index;
};

TEST_F(Fsr2Oracle, AccumulateMatchesTheShader) {
  Fsr2Options lut;
  lut.reproject_lanczos_lut = true;
  Fsr2Options hdr;
  hdr.hdr_color_input = hdr.jittered_motion_vectors = true;
  hdr.low_res_motion_vectors = false;
  Fsr2Options sharpen;
  sharpen.apply_sharpening = true;
  const Case cases[] = {{"reference Lanczos", Fsr2Options{}, 5},
                        {"Lanczos table", lut, 5},
                        {"reset frame", Fsr2Options{}, 0},
                        {"hdr+display mv+jittered", hdr, 3},
                        {"sharpening on", sharpen, 7}};
  const std::vector<int16_t> codes = LanczosCodes();
  const Fsr2Plane lut_plane = LanczosPlane(codes);
  {
    const std::vector<float> read = oracle::ReadR16SnormTexels(codes);
    long same = 0;
    for (size_t i = 0; i < read.size(); ++i) same += read[i] == lut_plane.v[i];
    std::printf("Lanczos table: %ld of %zu texels read by lavapipe equal code·(1/32767)\n", same, read.size());
    EXPECT_EQ(same, static_cast<long>(read.size()));
  }
  uint32_t seed = 3;
  for (const Case& c : cases) {
    const Frame f = MakeFrame(c.o, c.frame_index, seed++);
    Fsr2AccumulateIn in;
    in.exposure = f.exposure;
    in.dilated_reactive_masks = &f.masks;
    in.dilated_motion = &f.dilated_motion;
    in.motion = &f.motion;
    in.history = &f.history;
    in.lock_status = &f.lock_status;
    in.prepared_color = &f.prepared;
    in.lanczos_lut = &lut_plane;
    in.luma_mip = &f.mip;
    in.luma_history = &f.luma_history;
    Fsr2Plane locks_theirs = f.new_locks;
    Fsr2AccumulateOut theirs;
    in.new_locks = &locks_theirs;
    oracle::RunFsr2AccumulateShader(f.k, c.o, in, codes, &theirs);
    // The port with the C library's exp2 / log2 / sin, then with lavapipe's.
    Fsr2Options lvp = c.o;
    lvp.half_toward_zero = true;
    Fsr2Plane locks_ours = f.new_locks;
    Fsr2AccumulateOut ours;
    in.new_locks = &locks_ours;
    Fsr2Accumulate(f.k, lvp, in, &ours);
    const Comparison libc(ours, theirs, locks_ours, locks_theirs);
    LavapipeMath math;
    lvp.math = &math;
    for (int pass = 0; pass < 8; ++pass) {
      locks_ours = f.new_locks;
      Fsr2Accumulate(f.k, lvp, in, &ours);
      if (!math.Fill()) break;
    }
    const Comparison same_math(ours, theirs, locks_ours, locks_theirs);
    long moving = 0, new_samples = 0, alive = 0, rectified = 0;
    for (int y = 0; y < kDh; ++y) {
      for (int x = 0; x < kDw; ++x) {
        const float fac = ours.internal_upscaled.At(x, y, 3);
        moving += fac < 0.0f;
        new_samples += fac == 1.0f;
        alive += ours.lock_status.At(x, y, 0) > 0.0f;
      }
    }
    (void)rectified;
    std::printf("Accumulate %-24s identical with lavapipe's exp2/log2/sin: %s\n", c.name, same_math.Line().c_str());
    std::printf(
        "Accumulate %-24s identical with the C library's:          %s (%ld of %ld arguments evaluate "
        "differently; %ld pixels moving, %ld new samples, %ld locks alive)\n",
        c.name, libc.Line().c_str(), math.Differing(), math.Known(), moving, new_samples, alive);
    if (c.frame_index == 0) {  // no history read: everything identical, whichever exp2 / log2 / sin
      same_math.ExpectAllSame(c.name);
      libc.ExpectAllSame(std::string(c.name) + " (C library)");
    } else {
      // With lavapipe's exp2 / log2 / sin: every 16-bit and 8-bit output identical.
      for (const Count* n : {&same_math.color, &same_math.factor, &same_math.lock, &same_math.luma, &same_math.locks})
        EXPECT_EQ(n->same, n->total) << c.name << n->examples;
      same_math.ExpectClose(c.name, 99, 0x1p-20f);
      libc.ExpectClose(std::string(c.name) + " (C library)", 80, 0x1p-10f);
    }
    // The fixture reaches the pass's branches.
    EXPECT_GT(moving, kDw * kDh / 5) << c.name;
    EXPECT_GT(alive, c.frame_index == 0 ? -1 : kDw * kDh / 5) << c.name;
    EXPECT_GT(new_samples, c.frame_index == 0 ? kDw * kDh / 2 : -1) << c.name;
  }
}

}  // namespace
}  // namespace aalab
