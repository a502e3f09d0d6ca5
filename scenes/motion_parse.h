/// Parsing and validation of the scene file's motion fields (scenes/README.md "Animation").
#pragma once
#include "scenes/json_fields.h"
#include "scenes/scene.h"

namespace aalab {

/// Parses the top-level `animation` object: `frames` and the camera keys. Every key's frame
/// must lie inside the sequence [0, frames − 1] and increase strictly.
Animation ParseAnimation(const JsonField& f);

/// Parses an object's `motion` object against the sequence length `frames` (0: the scene
/// declares no animation, which is an error naming the field).
ObjectMotion ParseObjectMotion(const JsonField& f, int frames);

}  // namespace aalab
