/// What an AA method is: how its frame is rendered, which post filter runs on the 8-bit
/// frame, and how the result is resampled to the output size. Pure data + pure functions:
/// methods do no I/O and read no clocks (the runner times the stages).
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "harness/core/image.h"
#include "harness/core/params.h"
#include "harness/core/render_spec.h"

namespace aalab {

/// Options that do not change a method's identity (debug views).
struct PostOptions {
  std::string debug_view;  ///< "" = normal output; otherwise a view the filter supports
};

/// Counters a post filter reports.
struct PostStats {
  uint64_t taps = 0;  ///< texture fetches (bilinear or exact), summed over all pixels
};

/// A post filter: 8-bit RGBA frame in, 8-bit RGBA frame out, same size.
using PostFilter = std::function<Image8(const Image8& in, const PostOptions& options, PostStats* stats)>;

/// How the rendered/post-filtered frame is brought back to the output size.
enum class Rescale { kNone, kBilinear, kBicubic };

/// A fully resolved method: everything the runner needs.
struct MethodPlan {
  std::string name;          ///< registry name ("fxaa311-p39")
  std::string spec;          ///< canonical spec: name plus overrides in definition order
  ParamValues params;        ///< every parameter, resolved
  RenderSpec render;
  PostFilter post;           ///< empty when the method has no post filter
  std::vector<std::string> debug_views;  ///< views `post` supports ("" excluded)
  Rescale rescale = Rescale::kNone;

  /// True when the method works on a finished 1x frame alone (usable by `aalab apply`).
  bool IsPostOnly() const {
    return post && render.IsPlain1x() && rescale == Rescale::kNone;
  }
};

/// One registry row: name, one-line help, parameter table and a factory.
struct MethodEntry {
  std::string name;
  std::string help;
  std::vector<ParamDef> params;
  std::function<MethodPlan(const ParamValues&)> make;
};

}  // namespace aalab
