/// A fingerprint of a scene's content: everything the renderer reads (camera, display,
/// materials, textures, lights, every shape's geometry, the animation) and the scene's name,
/// hashed field by field in declaration order, floats by their bit patterns. Two scenes with
/// the same fingerprint render the same frames; editing any value of a scene file (or the
/// mesh it loads) changes it. The file's path and description are not part of it (moving a
/// file does not invalidate what was rendered from it). Used to key the reference cache
/// (harness/run/reference_cache.h).
#pragma once
#include <cstdint>

#include "scenes/scene.h"

namespace aalab {

/// FNV-1a 64 over the scene's content (see the header comment). Deterministic across runs and
/// machines of the same byte order.
uint64_t SceneContentHash(const Scene& scene);

}  // namespace aalab
