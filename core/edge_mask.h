/// Edge masks: the 1-px dilation the reference's geometric mask uses, and the masks an image
/// scene builds from the buffers a user brings (object ids, depth, or the reference alone).
/// A mask is a 1-channel float image, 1 on edge pixels and 0 elsewhere.
#pragma once
#include "core/image.h"

namespace aalab {

/// Relative depth jump that makes an edge: neighbours a and b (both > 0) with
/// |a − b| > kDepthEdgeRelativeJump · min(a, b). 0.1 = the farther surface lies more than 10 %
/// behind the nearer one. A plane seen at a grazing angle changes depth by less than this
/// between adjacent pixels unless it is nearly edge-on.
inline constexpr float kDepthEdgeRelativeJump = 0.1f;

/// Contrast that makes an edge in the reference-gradient fallback: neighbours whose
/// sRGB-encoded values differ by more than this in any RGB channel (in [0, 1]). 0.1 is below
/// FXAA 3.11's default relative threshold (0.166) so every edge FXAA would treat is marked.
inline constexpr float kGradientEdgeThreshold = 0.1f;

/// Dilates a mask by 1 px: a pixel is 1 when any pixel of its 3×3 neighbourhood (clamped at
/// the border) is > 0.5. The reference's edge mask (scenes/render.cpp) goes through this.
ImageF DilateMask(const ImageF& raw);

/// Raw (undilated) mask from an object-id image (any channel count): a pixel is an edge when
/// one of its 4 neighbours (left, right, up, down; none outside the image) has a different
/// value in any channel.
ImageF EdgesFromIds(const ImageF& ids);

/// Raw mask from a depth image (channel 0; values ≥ 0): a pixel is an edge when one of its 4
/// neighbours differs by more than `relative_jump` × the smaller of the two depths (a jump
/// from 0 to anything positive counts: 0 marks "no surface" in many engines).
ImageF EdgesFromDepth(const ImageF& depth, float relative_jump = kDepthEdgeRelativeJump);

/// Raw mask from an image's local contrast (the first 3 channels): a pixel is an edge when
/// one of its 4 neighbours differs by more than `threshold` in any of them. Marks texture
/// and shading detail as well as geometric edges.
ImageF EdgesFromGradient(const ImageF& image, float threshold = kGradientEdgeThreshold);

/// Raw mask at 1/n of the resolution of object ids given at n× the frame's width and height
/// (n ≥ 2): a pixel is an edge when the n×n sub-samples of its square do not all have the same
/// value (any channel), the rule of the rendered scenes' mask (more than one surface under the
/// pixel). Sub-pixel wires and silhouettes between pixel centres are found; a boundary that
/// lies exactly on a pixel border is not (no pixel is partly covered).
ImageF EdgesFromIdBlocks(const ImageF& ids, int n);

/// The same for depth at n× (channel 0): an edge when, within a pixel's n×n sub-samples, the
/// largest depth exceeds the smallest by more than `relative_jump` × the smallest (or the
/// smallest is 0, "no surface", and the largest is not).
ImageF EdgesFromDepthBlocks(const ImageF& depth, int n, float relative_jump = kDepthEdgeRelativeJump);

/// Pixel-wise maximum of two masks of the same size.
ImageF UnionMask(const ImageF& a, const ImageF& b);

}  // namespace aalab
