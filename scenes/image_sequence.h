/// Captured sequences of image scenes (docs/own-frames.md "Sequences"): numbered file
/// patterns, per-frame jitter and the motion-vector conventions aalab accepts. Pure functions,
/// no file access: image_scene.cpp reads the files and hands the pixels here.
#pragma once
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"

namespace aalab {

/// Whether `path` holds a frame-number placeholder: `%d` or `%0Nd` (N = 1..9).
bool HasFramePattern(const std::string& path);

/// `pattern` with its one placeholder replaced by `number` (`%04d`, 7 → `0007`). Returns
/// std::nullopt and sets `*why` when the pattern has no placeholder, more than one, or another
/// `%` sequence (write `%%` for a literal percent sign).
std::optional<std::string> ExpandFramePattern(const std::string& pattern, int number, std::string* why);

/// How a file's two motion-vector channels are to be read (docs/own-frames.md lists which
/// engine writes which).
struct MotionConvention {
  enum class Units { kPixels, kUv, kNdc };
  Units units = Units::kPixels;  ///< pixels; UV (0..1 across the frame); NDC (-1..1: 2 across)
  /// true: the vector points from the pixel to where its surface was in the previous frame
  /// (previous − current); false: velocity, current − previous (Unity, Unreal).
  bool points_to_previous = true;
  bool y_up = false;  ///< the second channel grows upwards (UV/NDC of OpenGL-style engines)
  /// The vectors were taken between jittered positions (they include the jitter change).
  bool includes_jitter = false;
  std::string Describe() const;
};

/// Sub-pixel jitter of one frame: the sample position's offset from the pixel centre, in
/// pixels, x right, y down (rows), each in [-0.5, 0.5].
using Jitter = std::array<float, 2>;

/// TAA's `previous` input (methods/method.h TemporalInput) from a motion-vector image (its
/// first two channels are the vector): per pixel, x then y, the continuous position (centres
/// at +0.5) in the previous frame of this pixel's surface. With `includes_jitter`, the jitter
/// change between the frames (`jitter_prev`, `jitter_cur`) is taken out first.
std::vector<float> PreviousFromMotion(const ImageF& mv, const MotionConvention& c, Jitter jitter_prev,
                                      Jitter jitter_cur);

/// The motion in pixels (previous − current, y down) that PreviousFromMotion derives for
/// stored channels (mx, my) of a width × height frame; exposed for the tests.
std::array<float, 2> MotionToPreviousPx(float mx, float my, int width, int height, const MotionConvention& c,
                                        Jitter jitter_prev, Jitter jitter_cur);

}  // namespace aalab
