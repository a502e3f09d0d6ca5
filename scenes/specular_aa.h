/// Geometric specular AA's roughness widening (methods/specular_aa.cpp cites the paper).
#pragma once
#include <algorithm>

#include <glm/glm.hpp>

namespace aalab {

/// α'² = min(1, α² + min(σ²·(|dN/dx|² + |dN/dy|²), κ)) (Tokuyoshi & Kaplanyan 2021, listing 5).
inline float FilteredAlpha2(float alpha2, glm::vec3 dndx, glm::vec3 dndy, float sigma2, float kappa) {
  const float kernel = sigma2 * (glm::dot(dndx, dndx) + glm::dot(dndy, dndy));
  return std::min(1.0f, alpha2 + std::min(kernel, kappa));
}

}  // namespace aalab
