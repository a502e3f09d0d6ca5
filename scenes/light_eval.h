/// How much of a punctual light reaches a point: the one definition the tracer's lambert and
/// glTF shading share (docs/lighting.md "Punctual lights").
#pragma once
#include <algorithm>
#include <cmath>

#include "scenes/scene.h"

namespace aalab {

/// Direction from p towards the light (unit, *L) and the factor that scales its intensity
/// there (*falloff): 1 for a directional light; 1/d² for point and spot, times the
/// KHR_lights_punctual range window clamp(1 − (d/range)⁴, 0, 1) when range > 0, times the
/// spot's smooth cone (the specification's reference: s = clamp(cos·scale + offset, 0, 1)²,
/// scale = 1/max(0.001, cos inner − cos outer), offset = −cos outer · scale). False when p
/// sits on a point or spot light (d = 0). The point and directional cases perform exactly the
/// operations the tracer used before spot lights existed (same bits).
inline bool LightIncidence(const Light& light, glm::vec3 p, glm::vec3* L, float* falloff) {
  if (light.type == LightType::kDirectional) {
    *L = -light.direction;
    *falloff = 1.0f;
    return true;
  }
  glm::vec3 v = light.position - p;
  const float d2 = glm::dot(v, v);
  if (!(d2 > 0.0f)) return false;
  v /= std::sqrt(d2);
  float f = 1.0f / d2;
  if (light.range > 0.0f) {
    const float q = d2 / (light.range * light.range);  // (d/range)²
    f *= std::clamp(1.0f - q * q, 0.0f, 1.0f);
  }
  if (light.type == LightType::kSpot) {
    const float scale = 1.0f / std::max(0.001f, light.cos_inner - light.cos_outer);
    const float offset = -light.cos_outer * scale;
    const float cd = glm::dot(light.direction, -v);
    float s = std::clamp(cd * scale + offset, 0.0f, 1.0f);
    s *= s;
    f *= s;
  }
  *L = v;
  *falloff = f;
  return true;
}

}  // namespace aalab
