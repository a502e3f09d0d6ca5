/// The exact reference for flat scenes (`--reference exact`): each pixel's covered area in
/// closed form, in double, with occlusion resolved exactly in depth order. Noise-free: its
/// noise floor is infinite.
///
/// A scene qualifies when (ExactReferenceRefusal returns ""):
///  - effects: exactly `unlit` (no lambert, shadows, specular, textures, alpha_test), so every
///    shape has one constant colour;
///  - camera: orthographic;
///  - objects: disks whose normal is parallel to the view direction (they image as disks),
///    spheres (they image as disks), capsules of any orientation (an orthographic view of a
///    sphere-swept segment is a 2-D stadium), triangles / quads / polygons / boxes / meshes
///    (every triangle images as a triangle); no cylinders (their outline has elliptic caps);
///  - nothing straddles the camera plane (depth along the view ≥ 0 everywhere);
///  - curved shapes (disks, spheres, capsules) do not overlap one another in the image;
///  - any two shapes that overlap in the image lie in disjoint depth ranges (so one of them is
///    in front over the whole overlap);
///  - at most kMaxExactPrimitives shapes after splitting meshes into triangles.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "scenes/render.h"
#include "scenes/scene.h"

namespace aalab {

/// Most shapes (triangles counted one by one) the exact reference accepts (its overlap check
/// is pairwise).
inline constexpr int kMaxExactPrimitives = 4000;

/// "" when the scene qualifies for the exact reference; otherwise one sentence naming the
/// disqualifying field (e.g. "/camera/type is 'perspective' ...") and what is allowed.
std::string ExactReferenceRefusal(const Scene& scene);

/// Renders the exact reference of a width × height frame: coverage of every visible shape
/// per pixel, colour = Σ coverage × display(colour) (the display transform is applied per
/// shape colour, which equals the sampled reference's per-sample transform because each
/// shape's colour is constant), sRGB-encoded float. half_a = half_b = image (zero noise), edge
/// masks from the pixels where more than one surface (or the background) has non-zero
/// coverage, dilated by 1 px like the sampled reference's; grid = 0. Throws UserError with
/// the refusal when the scene does not qualify. Deterministic at any thread count.
Reference RenderExactReference(const Scene& scene, int width, int height);

/// An isolated flat disk (or sphere) for the area-bias metric: its window [x0, x1) × [y0, y1)
/// holds the whole disk plus 2 px, no other curved shape and nothing in front of it, and
/// every window pixel farther than r + 1.5 px from the centre has one colour in `ref`.
struct DiskProbe {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  double radius_px = 0, area_px = 0;
  std::array<float, 3> inside{}, outside{};  ///< display-linear colours
};

/// The isolated disks of a qualifying scene (none when it does not qualify), checked against
/// the reference image `ref` (sRGB-encoded) of the same size.
std::vector<DiskProbe> DiskProbes(const Scene& scene, int width, int height, const ImageF& ref);

/// The exact visible area (in pixel² units) of every shape over the whole frame, and of the
/// background as the last entry: what the image's coverages sum to. For tests and self-checks.
std::vector<double> ExactVisibleAreas(const Scene& scene, int width, int height);

}  // namespace aalab
