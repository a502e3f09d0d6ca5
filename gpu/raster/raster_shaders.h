/// The raster path's GLSL 4.50 sources (gpu/raster/raster_shaders.cpp).
#pragma once

namespace aalab::raster {

/// Forward pass: world position, normal and (shape, material) per vertex; view-projection
/// (with the raster path's y flip and TAA's jitter) as a uniform.
extern const char* const kSceneVertex;
/// Forward pass: the tracer's unlit / lambert shading (scenes/tracer_shade.cpp) and the
/// display transform (core/color.h DisplayLinear) per fragment; display-linear RGB out.
/// With `#define AALAB_GLTF 1` inserted after its #version line (and the vertex shader's),
/// also glTF materials (scenes/tracer_gltf.cpp ShadeGltf; storage buffers 2–5 hold the
/// triangles' uv and material, the image table, the texels and aalab's decode tables).
extern const char* const kSceneFragment;
/// Coverage pass: the shape index + 1 (0: background) into an R32UI target.
extern const char* const kIdFragment;
/// A full-screen triangle (no vertex buffer).
extern const char* const kFullscreenVertex;
/// MSAA resolve: box average of the `u_samples` samples of a sampler2DMS, in index order.
extern const char* const kResolveMsaaFragment;
/// SSAA resolve: box average of each u_grid × u_grid block, row by row.
extern const char* const kResolveGridFragment;
/// Encode: sRGB OETF (core/color.h SrgbEncode) and rounding to k/255.
extern const char* const kEncodeFragment;
/// Coverage read-back: every sample of an R32UI sampler2DMS into a buffer.
extern const char* const kUnpackIdsCompute;

}  // namespace aalab::raster
