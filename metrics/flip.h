/// LDR-FLIP (Andersson et al., "FLIP: A Difference Evaluator for Alternating Images",
/// Proc. ACM CGIT 3(2), HPG 2020): a per-pixel perceptual error in [0, 1] between an
/// sRGB-encoded reference and test image. Definition, constants, deviations from NVIDIA's
/// reference code and precision: the block at the top of metrics/flip.cpp and METRICS.md.
#pragma once
#include <array>
#include <memory>
#include <span>
#include <vector>

#include "core/image.h"
#include "metrics/metric.h"

namespace aalab {

/// Default observer: 67 pixels per degree of visual angle (≈ a 0.7 m wide 4K monitor seen
/// from 0.7 m; NVIDIA's tool computes that case as 67.0206, see METRICS.md).
inline constexpr double kFlipDefaultPpd = 67.0;

/// Per-pixel LDR-FLIP error map (1 channel, float, values in [0, 1]) of `test` against
/// `reference`: same-size RGB images (channels 0..2 used), sRGB-encoded values; each value
/// is clamped to [0, 1] first (NaN → 0). `ppd` is pixels per degree, finite and > 0.
/// Computed in float32 (metrics/flip_fast.cpp, as NVIDIA's tools compute); bit-identical at
/// any thread count.
/// Throws UserError on a shape mismatch, fewer than 3 channels or a bad `ppd`.
ImageF FlipErrorMap(const ImageF& reference, const ImageF& test, double ppd = kFlipDefaultPpd);

/// Pooled statistics of a FLIP map.
struct FlipPooled {
  double mean = 0.0;             ///< arithmetic mean (double sum in the given order)
  double weighted_median = 0.0;  ///< value-weighted median, see PoolFlip
  double max = 0.0;              ///< largest value
};

/// Pools per-pixel FLIP values (non-empty; the order is the row-major pixel order).
/// weighted_median: sort ascending e(1) <= ... <= e(N); it is the first e(k) with
/// e(1) + ... + e(k) > 0.5 · (e(1) + ... + e(N)) (sums in double, in sorted order), i.e. the
/// median of the distribution in which each pixel weighs its own error: the "Weighted
/// median" of NVIDIA's FLIP tool v1.4 (`pooling::getPercentile(0.5, weighted = true)`);
/// 0 when every value is 0. The same values at any thread count: the mean's sum is one serial
/// pass in the given order (run beside the sort), the sort's loops are parallel.
FlipPooled PoolFlip(std::span<const double> values);
/// PoolFlip of a std::vector (also of a braced list of values).
inline FlipPooled PoolFlip(const std::vector<double>& values) { return PoolFlip(std::span<const double>(values)); }

/// Building blocks of LDR-FLIP, exposed for tests and cross-checks. Colours are triples of
/// double; "Lab" is CIELAB with the D65 white of NVIDIA's code.
namespace flip {

/// A colour triple (RGB, XYZ, YCxCz or Lab, as the function says).
using Color = std::array<double, 3>;

inline constexpr double kQc = 0.7;   ///< exponent on the HyAB distance
inline constexpr double kPc = 0.4;   ///< breakpoint of the colour remap, fraction of cmax
inline constexpr double kPt = 0.95;  ///< remapped value at the breakpoint
inline constexpr double kW = 0.082;  ///< feature filter peak-to-trough width, degrees
inline constexpr double kQf = 0.5;   ///< exponent on the feature difference
/// D65 reference white (X, Y, Z) as in NVIDIA's code; equals the row sums of the RGB→XYZ
/// matrix to ~1e-10, so linear white maps to Lab (100, 0, 0).
inline constexpr Color kWhite = {0.950428545, 1.0, 1.088900371};

/// Spatial CSF parameters (a1, b1, a2, b2) of one opponent channel: the filter is
/// a1·sqrt(π/b1)·exp(−π²r²/b1) + a2·sqrt(π/b2)·exp(−π²r²/b2), r in degrees.
struct CsfParams {
  double a1, b1, a2, b2;
};
inline constexpr CsfParams kCsfY = {1.0, 0.0047, 0.0, 1e-5};    ///< achromatic (Y)
inline constexpr CsfParams kCsfCx = {1.0, 0.0053, 0.0, 1e-5};   ///< red-green (Cx)
inline constexpr CsfParams kCsfCz = {34.1, 0.04, 13.5, 0.025};  ///< blue-yellow (Cz)

/// sRGB decode of one encoded value, clamped to [0, 1] first (NaN → 0).
double SrgbToLinear(double encoded);
/// Linear sRGB → CIE XYZ (D65), the rational matrix of NVIDIA's code.
Color LinearRgbToXyz(const Color& rgb);
/// CIE XYZ → linear sRGB, the exact double inverse of LinearRgbToXyz.
Color XyzToLinearRgb(const Color& xyz);
/// XYZ → YCxCz (Y = 116·Y/Yn − 16, Cx = 500·(X/Xn − Y/Yn), Cz = 200·(Y/Yn − Z/Zn)).
Color XyzToYCxCz(const Color& xyz);
/// YCxCz → XYZ (inverse of XyzToYCxCz).
Color YCxCzToXyz(const Color& ycxcz);
/// XYZ → CIELAB (CIE 1976, cube root with the linear segment below (6/29)³).
Color XyzToLab(const Color& xyz);
/// Hunt adjustment: (L, a, b) → (L, 0.01·L·a, 0.01·L·b).
Color HuntAdjust(const Color& lab);
/// HyAB distance: |ΔL| + sqrt(Δa² + Δb²).
double HyAB(const Color& p, const Color& q);
/// cmax = HyAB(Hunt(Lab(green)), Hunt(Lab(blue)))^qc for linear green (0,1,0) and blue
/// (0,0,1): ≈ 41.2761.
double Cmax();
/// The colour-error remap of a HyAB distance already raised to qc: values below pc·cmax
/// map linearly to [0, pt), the rest linearly from pt at pc·cmax to 1 at cmax.
double RemapColorError(double hyab_pow_qc);

/// CSF filter radius in pixels: ceil(3·sqrt(max b / (2π²))·ppd) over all six b (max b =
/// 0.04): 10 at 67 ppd. The same radius serves all three channels.
int SpatialFilterRadius(double ppd);
/// Feature filter radius in pixels: ceil(3·σ) with σ = 0.5·w·ppd: 9 at 67 ppd.
int FeatureFilterRadius(double ppd);

/// 1-D CSF kernels (length 2·radius + 1, tap i at offset i − radius pixels). `y` and `cx`
/// sum to 1; `cz1`, `cz2` are the square roots of the two Gaussians of the Cz filter,
/// scaled so that the 2-D kernel cz1(x)·cz1(y) + cz2(x)·cz2(y) sums to 1.
struct SpatialKernels {
  int radius = 0;
  std::vector<double> y, cx, cz1, cz2;
};
/// The CSF kernels for `ppd` (finite, > 0; UserError otherwise).
SpatialKernels MakeSpatialKernels(double ppd);

/// 1-D feature kernels (length 2·radius + 1): `g` the Gaussian (sum 1), `dg` its first
/// derivative −x·g (positive taps sum to 1, negative to −1), `ddg` its second derivative
/// (x²/σ² − 1)·g (positive taps sum to 1, negative to −1).
struct FeatureKernels {
  int radius = 0;
  double sigma = 0.0;  ///< 0.5·w·ppd, in pixels
  std::vector<double> g, dg, ddg;
};
/// The feature kernels for `ppd` (finite, > 0; UserError otherwise).
FeatureKernels MakeFeatureKernels(double ppd);

/// Colour pipeline alone: ΔEc per pixel (row-major), in [0, 1]. Same checks and input
/// handling as FlipErrorMap (UserError on bad shapes or ppd).
std::vector<double> ColorErrorValues(const ImageF& reference, const ImageF& test, double ppd);
/// Feature pipeline alone: ΔEf per pixel (row-major), in [0, 1].
std::vector<double> FeatureErrorValues(const ImageF& reference, const ImageF& test, double ppd);
/// Full LDR-FLIP per pixel (row-major): ΔEc^(1 − ΔEf), the production path (float32,
/// separable filters streamed through row rings, vectorised; metrics/flip_fast.cpp): equals
/// ErrorValues(*PrepareReference(reference, ppd), test) bit for bit. Against the double
/// path (ErrorValuesUncached): mean within ~1e-7, pixels within ~1e-5 (up to 2e-4 where
/// ΔEc ≈ 0 and ΔEf > 0); METRICS.md gives the measurements, also against NVIDIA's tool.
FlipValues ErrorValues(const ImageF& reference, const ImageF& test, double ppd);
/// The reference's half of LDR-FLIP (its filtered Hunt-adjusted Lab colours and feature
/// magnitudes, float32: 20 bytes a pixel), which depends on the reference and ppd alone: a
/// run scores every method against one reference, so the runner prepares it once per scene
/// (explicit, no cache).
struct ReferenceSide;
/// Prepares the reference side (same checks as FlipErrorMap).
std::shared_ptr<const ReferenceSide> PrepareReference(const ImageF& reference, double ppd);
/// ErrorValues against a prepared reference: the same values as ErrorValues(reference,
/// test, ppd), bit for bit. UserError when `test`'s size differs from the reference's or it
/// has fewer than 3 channels.
FlipValues ErrorValues(const ReferenceSide& reference, const ImageF& test);
/// The double-precision implementation of the definition (flip.cpp; the outside-oracle
/// cross-checks run on it at 1e-12); the tests bound the production path against it.
std::vector<double> ErrorValuesUncached(const ImageF& reference, const ImageF& test, double ppd);

}  // namespace flip
}  // namespace aalab
