/// Resampling a finished 8-bit frame to the output size (render scale), as a GPU's final
/// blit does: bilinear (one tap) or B-spline bicubic built from four bilinear taps.
#pragma once

#include "core/image.h"
#include "methods/method.h"

namespace aalab {

/// Cubic B-spline weights for the four texels i-1, i, i+1, i+2 around a sample whose
/// fractional position past texel i's centre is t in [0, 1), and their folding into two
/// bilinear taps per axis:
///   w0 = (1-t)^3/6, w1 = (3t^3 - 6t^2 + 4)/6, w2 = (-3t^3 + 3t^2 + 3t + 1)/6, w3 = t^3/6,
///   g0 = w0 + w1, g1 = w2 + w3 (the taps' weights), h0 = w1/g0, h1 = w3/g1: the first tap
///   sits h0 of the way from texel i-1 to texel i, the second h1 of the way from i+1 to i+2
///   (a bilinear tap there returns (w0·T[i-1] + w1·T[i])/g0, resp. (w2·T[i+1] + w3·T[i+2])/g1).
struct BsplineTaps {
  float w[4];
  float g0, g1, h0, h1;
};
/// The weights above for one axis, in float32.
BsplineTaps BsplineCubicTaps(float t);

/// Resamples `in` (RGBA8) to out_w × out_h. Output pixel (X, Y) samples the input at its
/// centre mapped to normalised coordinates s = (X + 0.5)/out_w, t = (Y + 0.5)/out_h (float),
/// i.e. at input pixel coordinates (s·W, t·H):
///   kBilinear  one BilinearSampler::SampleNormalized tap (at scale 2 exactly a 2×2 box);
///   kBicubic   the B-spline above, 4 bilinear taps (16 texels, clamp-to-edge), weights
///              g0y·(g0x·T00 + g1x·T10) + g1y·(g0x·T01 + g1x·T11);
///   kNone      requires out size == in size and returns the frame unchanged.
/// rgb is rounded to 8 bits (UNORM store), alpha is 255. Deterministic at any thread count.
/// When `stats` is not null, adds the bilinear taps taken to stats->taps.
/// This is the production path (per-axis tap tables); same bits and taps as
/// RescaleFrameReference. `sampler` (PostOptions::sampler): the fetches' arithmetic; with
/// kGpuTexture this runs RescaleFrameReference (the fast path is the default arithmetic's).
Image8 RescaleFrame(const Image8& in, int out_w, int out_h, Rescale kind, PostStats* stats,
                    SamplerArithmetic sampler = SamplerArithmetic::kGl);

/// The simple implementation of RescaleFrame (every tap through BilinearSampler), kept as the
/// reference the production path is tested against, bit for bit.
Image8 RescaleFrameReference(const Image8& in, int out_w, int out_h, Rescale kind, PostStats* stats,
                             SamplerArithmetic sampler = SamplerArithmetic::kGl);

}  // namespace aalab
