/// The raster path's view of a scene (docs/gpu.md "The raster path"): the triangles, camera
/// and shading inputs that the stand-alone raster tool (gpu/raster/) needs to draw what the
/// tracer traces, as the plain data of core/raster_geometry.h.
#pragma once
#include <string>

#include "core/raster_geometry.h"
#include "scenes/scene.h"

namespace aalab {

/// Why the raster path cannot draw `scene` yet ("" when it can): it draws still scenes of
/// triangles (quads, boxes, planes, meshes) and disks (as impostors: their bounding square,
/// the disk kept by the fragment shader) with unlit or lambert materials (solid colours or
/// the procedural textures checker, stripes, noise) under directional, point and spot
/// lights, with shadows (rays against every triangle and disk), and any display transform;
/// and scenes whose materials are all glTF ones (metallic-roughness with base colour,
/// metallic-roughness and normal textures at TEXCOORD_0 with the default sampler, OPAQUE or
/// MASK, single- or double-sided; their images as aalab's 8-bit mip chains).
/// Refused: the analytic shapes sphere, capsule and cylinder; without glTF materials the
/// effects specular, alpha_test and normal_map; alpha_blend; glTF BLEND, emissive,
/// occlusion, TEXCOORD_1, KHR_texture_transform, other samplers, non-8-bit textures,
/// normal maps without tangents; environments, animation.
std::string RasterUnsupported(const Scene& scene);

/// The scene as raster data, the Scene's floats unchanged. Throws UserError with
/// RasterUnsupported's reason when the raster path cannot draw it.
RasterScene RasterSceneOf(const Scene& scene);

}  // namespace aalab
