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

/// The exact visible area (in pixel² units) of every shape over the whole frame, and of the
/// background as the last entry: what the image's coverages sum to. For tests and self-checks.
std::vector<double> ExactVisibleAreas(const Scene& scene, int width, int height);

}  // namespace aalab
