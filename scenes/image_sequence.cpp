// Captured sequences of image scenes: frame-number patterns and motion-vector conventions.
#include "scenes/image_sequence.h"

#include <cstdio>

#include "core/parallel.h"

namespace aalab {

namespace {

/// Finds the placeholder at `pos` ('%' already seen): `%d` or `%0Nd`; returns its length and
/// the zero-padding width, or 0 when it is not one.
size_t PlaceholderAt(const std::string& s, size_t pos, int* width) {
  size_t i = pos + 1;
  *width = 0;
  if (i < s.size() && s[i] == 'd') return 2;
  if (i + 2 < s.size() && s[i] == '0' && s[i + 1] >= '1' && s[i + 1] <= '9' && s[i + 2] == 'd') {
    *width = s[i + 1] - '0';
    return 4;
  }
  return 0;
}

}  // namespace

bool HasFramePattern(const std::string& path) {
  for (size_t i = 0; i < path.size(); ++i) {
    if (path[i] != '%') continue;
    if (i + 1 < path.size() && path[i + 1] == '%') {
      ++i;
      continue;
    }
    int w = 0;
    if (PlaceholderAt(path, i, &w) > 0) return true;
  }
  return false;
}

std::optional<std::string> ExpandFramePattern(const std::string& pattern, int number, std::string* why) {
  std::string out;
  int found = 0;
  for (size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%') {
      out += pattern[i];
      continue;
    }
    if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
      out += '%';
      ++i;
      continue;
    }
    int w = 0;
    const size_t len = PlaceholderAt(pattern, i, &w);
    if (len == 0) {
      *why = "'" + pattern + "' has a '%' that is not a frame number (%d or %0Nd, N = 1..9; %% for a percent sign)";
      return std::nullopt;
    }
    char buf[32];
    std::snprintf(buf, sizeof buf, "%0*d", w, number);
    out += buf;
    ++found;
    i += len - 1;
  }
  if (found != 1) {
    *why = "'" + pattern + "' has " + std::to_string(found) +
           " frame-number placeholders; a numbered pattern has exactly one (%d or %0Nd, e.g. frame_%04d.png)";
    return std::nullopt;
  }
  return out;
}

std::string MotionConvention::Describe() const {
  std::string s = units == Units::kPixels ? "pixels"
                  : units == Units::kUv   ? "UV (1 = the frame's size)"
                                          : "NDC (2 = the frame's size)";
  s += points_to_previous ? ", pointing to the previous position (previous − current)"
                          : ", velocity (current − previous)";
  s += y_up ? ", y up" : ", y down";
  if (includes_jitter) s += ", between jittered positions (the jitter change is taken out)";
  return s;
}

std::array<float, 2> MotionToPreviousPx(float mx, float my, int width, int height, const MotionConvention& c,
                                        Jitter jitter_prev, Jitter jitter_cur) {
  float dx = mx, dy = my;
  if (c.units == MotionConvention::Units::kUv) {
    dx *= static_cast<float>(width);
    dy *= static_cast<float>(height);
  } else if (c.units == MotionConvention::Units::kNdc) {
    dx *= 0.5f * static_cast<float>(width);
    dy *= 0.5f * static_cast<float>(height);
  }
  if (c.y_up) dy = -dy;
  if (!c.points_to_previous) {
    dx = -dx;
    dy = -dy;
  }
  if (c.includes_jitter) {
    // A surface at unjittered position u lands on the jittered raster at u − j, so a vector
    // between jittered positions is (u_prev − j_prev) − (u_cur − j_cur).
    dx += jitter_prev[0] - jitter_cur[0];
    dy += jitter_prev[1] - jitter_cur[1];
  }
  return {dx, dy};
}

std::vector<float> PreviousFromMotion(const ImageF& mv, const MotionConvention& c, Jitter jitter_prev,
                                      Jitter jitter_cur) {
  const int W = mv.Width(), H = mv.Height(), nc = mv.Channels();
  std::vector<float> out(2 * static_cast<size_t>(W) * static_cast<size_t>(H));
  ParallelFor(H, [&](int y) {
    for (int x = 0; x < W; ++x) {
      const size_t i = static_cast<size_t>(y) * static_cast<size_t>(W) + static_cast<size_t>(x);
      const float* p = &mv.Data()[i * static_cast<size_t>(nc)];
      const std::array<float, 2> d = MotionToPreviousPx(p[0], p[1], W, H, c, jitter_prev, jitter_cur);
      out[2 * i] = static_cast<float>(x) + 0.5f + d[0];
      out[2 * i + 1] = static_cast<float>(y) + 0.5f + d[1];
    }
  });
  return out;
}

}  // namespace aalab
