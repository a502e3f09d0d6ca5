// FSR 2's sequence driver (methods/fsr2_sequence.h) against the ORIGINAL FSR 2.2.1 passes
// chained through the same driver: two Fsr2Contexts run the same five frames, one with the
// ported passes, one with the original GLSL passes on lavapipe (tests/oracle/fsr2_shader.h),
// each fed only its own resources (ping-pong lock status, upscaled colour, luma history,
// dilated motion; previous depth, new locks, the pyramid's mips, auto exposure and atomic
// counter). The frames: a small moving scene (a background panning 0.6 px/frame with a thin
// bright line, a striped box moving 1.3 px/frame, a disc moving diagonally, each at its own
// inverted depth, exact motion vectors), FSR 2's own jitter (Fsr2JitterOffset); the first
// dispatch resets. Two cases: 1.5× (40×24 → 60×36) with auto exposure and RCAS; 1× with
// exposure 1, no sharpening and a second reset at frame 3. The port runs with lavapipe's own
// exp2 / log2 / sin (LavapipeMath: rerun until it asks for no new argument) in the pyramid and
// accumulate, and lavapipe's rounding of 16-bit stores (toward zero); figures are printed and
// docs/fsr2.md lists them. Without the sources, glslang or lavapipe the test skips (fails
// under CI).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "methods/fsr2_sequence.h"
#include "methods/fsr2_tables.h"
#include "tests/oracle/fsr2_oracle_fixture.h"

namespace aalab {
namespace {

struct FrameData {
  Fsr2Plane color, depth, motion;
};

// The scene at frame t, sampled at render pixel centres shifted by FSR 2's jitter j (a sample of
// pixel i lies at unjittered i + 0.5 − j), in render pixels of a rw × rh render.
FrameData MakeFrame(int t, Fsr2Jitter j, int rw, int rh) {
  FrameData f{Fsr2Plane(rw, rh, 4), Fsr2Plane(rw, rh, 1), Fsr2Plane(rw, rh, 2)};
  const float s = static_cast<float>(rw) / 40.0f;  // scene units: a 40-wide render
  for (int y = 0; y < rh; ++y) {
    for (int x = 0; x < rw; ++x) {
      const float sx = (static_cast<float>(x) + 0.5f - j.x) / s, sy = (static_cast<float>(y) + 0.5f - j.y) / s;
      const float tf = static_cast<float>(t);
      // Background, panning: content u = sx + 0.6 t; far (device depth 0); motion +0.6 px.
      const float u = sx + 0.6f * tf;
      float r = 0.15f + 0.02f * u, g = 0.25f + 0.015f * sy, b = 0.4f;
      if (std::fabs(u - 31.0f) < 0.35f) r = g = b = 0.95f;  // a thin bright line: locks
      float d = 0.0f, mx = 0.6f * s, my = 0.0f;
      // A striped box moving right 1.3 px/frame (motion −1.3), device depth 0.25.
      const float bx = sx - (8.0f + 1.3f * tf);
      if (bx >= 0.0f && bx < 12.0f && sy >= 5.0f && sy < 15.0f) {
        const bool stripe = static_cast<int>(std::floor(bx * 1.5f)) % 2 == 0;
        r = stripe ? 0.8f : 0.1f;
        g = stripe ? 0.6f : 0.05f;
        b = 0.2f;
        d = 0.25f;
        mx = -1.3f * s;
        my = 0.0f;
      }
      // A disc moving (−0.9, +0.5) px/frame, nearer (0.5).
      const float cx = 28.0f - 0.9f * tf, cy = 13.0f + 0.5f * tf;
      if ((sx - cx) * (sx - cx) + (sy - cy) * (sy - cy) < 25.0f) {
        r = 0.9f;
        g = 0.85f;
        b = 0.7f * (0.5f + 0.05f * (sx - cx));
        d = 0.5f;
        mx = 0.9f * s;
        my = -0.5f * s;
      }
      f.color.At(x, y, 0) = r;
      f.color.At(x, y, 1) = g;
      f.color.At(x, y, 2) = std::max(0.0f, b);
      f.color.At(x, y, 3) = 1.0f;
      f.depth.At(x, y, 0) = d;
      f.motion.At(x, y, 0) = mx;
      f.motion.At(x, y, 1) = my;
    }
  }
  return f;
}

Fsr2Passes ShaderPasses() {
  Fsr2Passes p;
  p.pyramid = [](const Fsr2Constants& k, const Fsr2Options&, const Fsr2SpdDispatch& spd, const Fsr2Plane& color,
                 Fsr2PyramidState* st) { oracle::RunFsr2PyramidShader(k, spd, color, st); };
  p.reconstruct = oracle::RunFsr2ReconstructShader;
  p.depth_clip = oracle::RunFsr2DepthClipShader;
  p.lock = oracle::RunFsr2LockShader;
  p.accumulate = [](const Fsr2Constants& k, const Fsr2Options& o, const Fsr2AccumulateIn& in, Fsr2AccumulateOut* out) {
    const auto codes = Fsr2LanczosLutCodes();
    oracle::RunFsr2AccumulateShader(k, o, in, std::vector<int16_t>(codes.begin(), codes.end()), out);
  };
  p.rcas = [](const Fsr2Constants& k, const Fsr2Plane& up, float exposure, uint32_t con) {
    return oracle::RunFsr2RcasShader(k, up, exposure, con);
  };
  return p;
}

Fsr2Passes PortPasses(const LavapipeMath* math) {
  Fsr2Passes p = Fsr2PortedPasses();
  p.pyramid = [math](const Fsr2Constants& k, const Fsr2Options& o, const Fsr2SpdDispatch& spd, const Fsr2Plane& color,
                     Fsr2PyramidState* st) {
    Fsr2Transcendentals t;
    t.log2 = [math](float x) { return math->Log2(x); };
    t.exp2 = [math](float x) { return math->Exp2(x); };
    Fsr2LuminancePyramid(k, spd, color, st, o, t);
  };
  return p;
}

// Everything a frame leaves: the output floats, then every resource.
struct Snapshot {
  std::vector<float> output;
  std::vector<std::pair<std::string, std::vector<float>>> planes;
};

Snapshot Take(const Fsr2DispatchResult& r, const Fsr2Resources& res) {
  Snapshot s;
  s.output = r.output;
  const char* side[2] = {"_1", "_2"};
  for (int i = 0; i < 2; ++i) {
    s.planes.push_back({std::string("lock status") + side[i], res.lock_status[i].v});
    s.planes.push_back({std::string("upscaled colour") + side[i], res.internal_upscaled[i].v});
    s.planes.push_back({std::string("luma history") + side[i], res.luma_history[i].v});
    s.planes.push_back({std::string("dilated motion") + side[i], res.dilated_motion[i].v});
  }
  s.planes.push_back({"new locks", res.new_locks.v});
  std::vector<float> depth(res.prev_depth.size());
  std::memcpy(depth.data(), res.prev_depth.data(), depth.size() * 4);
  s.planes.push_back({"previous depth", depth});
  s.planes.push_back({"luma mip 4", res.pyramid.luma_mip.v});
  s.planes.push_back({"luma mip 5", res.pyramid.mip5.v});
  s.planes.push_back(
      {"auto exposure, counter",
       {res.pyramid.auto_exposure[0], res.pyramid.auto_exposure[1], static_cast<float>(res.pyramid.atomic_counter)}});
  return s;
}

struct Case {
  const char* name;
  int rw, rh, dw, dh;
  bool auto_exposure, sharpen;
  int reset_frame;  // a dispatch with reset (besides the context's first), −1: none
};

std::vector<Snapshot> RunChain(const Case& c, const Fsr2Passes& passes, const Fsr2Math* math) {
  Fsr2ContextParams cp;
  cp.max_render_size[0] = c.rw;
  cp.max_render_size[1] = c.rh;
  cp.display_size[0] = c.dw;
  cp.display_size[1] = c.dh;
  cp.inverted_depth = cp.infinite_depth = true;
  Fsr2Options o;
  o.inverted_depth = true;
  o.reproject_lanczos_lut = true;
  o.half_toward_zero = true;  // lavapipe's rounding of 16-bit stores (the shader side ignores it)
  o.math = math;              // the port's accumulate: lavapipe's exp2 / log2 / sin
  Fsr2Context ctx(cp, o, c.auto_exposure, passes);
  const int phases = Fsr2JitterPhaseCount(c.rw, c.dw);
  std::vector<Snapshot> out;
  for (int t = 0; t < 5; ++t) {
    const Fsr2Jitter j = Fsr2JitterOffset(t, phases);
    const FrameData f = MakeFrame(t, j, c.rw, c.rh);
    Fsr2DispatchInput in;
    in.color = &f.color;
    in.depth = &f.depth;
    in.motion = &f.motion;
    in.dispatch.jitter[0] = j.x;
    in.dispatch.jitter[1] = j.y;
    in.dispatch.motion_vector_scale[0] = in.dispatch.motion_vector_scale[1] = 1.0f;
    in.dispatch.render_size[0] = in.dispatch.input_color_size[0] = c.rw;
    in.dispatch.render_size[1] = in.dispatch.input_color_size[1] = c.rh;
    in.dispatch.frame_time_delta_ms = 16.6667f;
    in.dispatch.camera_near = 0.1f;
    in.dispatch.camera_far = 1e5f;
    in.dispatch.camera_fov_vertical = 1.0471976f;
    in.dispatch.reset = t == c.reset_frame;
    in.sharpen = c.sharpen;
    in.sharpness = 0.8f;
    const Fsr2DispatchResult r = ctx.Dispatch(in);
    out.push_back(Take(r, ctx.Resources()));
  }
  return out;
}

void CompareChain(const Case& c) {
  const std::vector<Snapshot> shader = RunChain(c, ShaderPasses(), nullptr);
  LavapipeMath math;
  std::vector<Snapshot> port;
  for (int pass = 0; pass < 10; ++pass) {
    port = RunChain(c, PortPasses(&math), &math);
    if (!math.Fill()) break;
  }
  long res_total = 0, res_same = 0, out_total = 0, out_same = 0;
  float out_max = 0.0f;
  std::string diffs;
  for (size_t t = 0; t < shader.size(); ++t) {
    const Snapshot &a = port[t], &b = shader[t];
    long ft = 0, fs = 0;
    for (size_t p = 0; p < a.planes.size(); ++p) {
      const auto& va = a.planes[p].second;
      const auto& vb = b.planes[p].second;
      ASSERT_EQ(va.size(), vb.size()) << a.planes[p].first;
      long differ = 0;
      for (size_t i = 0; i < va.size(); ++i) differ += std::memcmp(&va[i], &vb[i], 4) != 0;
      ft += static_cast<long>(va.size());
      fs += static_cast<long>(va.size()) - differ;
      if (differ && getenv("FSR2_CHAIN_DEBUG")) {
        for (size_t i = 0; i < va.size(); ++i)
          if (std::memcmp(&va[i], &vb[i], 4) != 0 && i < 8)
            std::printf("  %s[%zu] port %a shader %a\n", a.planes[p].first.c_str(), i, static_cast<double>(va[i]),
                        static_cast<double>(vb[i]));
      }
      if (differ) diffs += " f" + std::to_string(t) + " " + a.planes[p].first + ": " + std::to_string(differ);
    }
    long os = 0;
    for (size_t i = 0; i < a.output.size(); ++i) {
      os += std::memcmp(&a.output[i], &b.output[i], 4) == 0;
      out_max = std::max(out_max, std::fabs(a.output[i] - b.output[i]));
    }
    std::printf("%s frame %zu: resources %ld/%ld identical, output floats %ld/%zu\n", c.name, t, fs, ft, os,
                a.output.size());
    res_total += ft;
    res_same += fs;
    out_total += static_cast<long>(a.output.size());
    out_same += os;
  }
  // What the chain exercised (the port's last frame): locks alive, pixels whose history was
  // kept (|temporal factor| < 1), the exposure.
  long locked = 0, kept = 0;
  for (const auto& [name, v] : port.back().planes) {
    if (name.rfind("lock status", 0) == 0)
      for (size_t i = 0; i < v.size(); i += 2) locked += v[i] > 0.0f;
    if (name.rfind("upscaled colour", 0) == 0)
      for (size_t i = 3; i < v.size(); i += 4) kept += std::fabs(v[i]) < 1.0f && v[i] != 0.0f;
  }
  std::printf(
      "%s, last frame (both ping-pong sides): %ld lock lifetimes > 0, %ld pixels with a kept history, exposure %g\n",
      c.name, locked, kept, static_cast<double>(port.back().planes.back().second[0]));
  std::printf("%s, 5 frames: resources %ld/%ld identical, output floats %ld/%ld (max difference %.3g)%s%s\n", c.name,
              res_same, res_total, out_same, out_total, static_cast<double>(out_max), diffs.empty() ? "" : ";",
              diffs.c_str());
  // The same chain with the C library's exp2 / log2 / sin (what the rows run with): printed,
  // with a loose bound (their differences reach through the history into later frames).
  const std::vector<Snapshot> libm = RunChain(c, Fsr2PortedPasses(), nullptr);
  long lt = 0, ls = 0, lo = 0;
  float lmax = 0.0f;
  for (size_t t = 0; t < shader.size(); ++t) {
    for (size_t p = 0; p < libm[t].planes.size(); ++p) {
      const auto& va = libm[t].planes[p].second;
      const auto& vb = shader[t].planes[p].second;
      for (size_t i = 0; i < va.size(); ++i) ls += std::memcmp(&va[i], &vb[i], 4) == 0;
      lt += static_cast<long>(va.size());
    }
    for (size_t i = 0; i < libm[t].output.size(); ++i) {
      lo += std::memcmp(&libm[t].output[i], &shader[t].output[i], 4) == 0;
      lmax = std::max(lmax, std::fabs(libm[t].output[i] - shader[t].output[i]));
    }
  }
  std::printf(
      "%s, 5 frames, the C library's exp2/log2/sin: resources %ld/%ld identical, output floats %ld/%ld (max "
      "difference %.3g)\n",
      c.name, ls, lt, lo, out_total, static_cast<double>(lmax));
  EXPECT_LE(lmax, 0x1p-8f);
  // Measured figures in docs/fsr2.md; the limits leave room only for the known differences
  // (lock luma's pow ties, accumulate's few floats within a few ulps): 1 in 2000 values.
  EXPECT_LE((res_total - res_same) * 2000, res_total) << diffs;
  EXPECT_GE(out_same * 100, out_total * 99);
  EXPECT_LE(out_max, 0x1p-14f);
}

TEST_F(Fsr2Oracle, FiveFramesThroughTheDriverMatchTheChainedShaders) {
  CompareChain({"1.5x, auto exposure, RCAS", 40, 24, 60, 36, true, true, -1});
  CompareChain({"1x, exposure 1, no sharpening, reset at 3", 40, 24, 40, 24, false, false, 3});
}

}  // namespace
}  // namespace aalab
