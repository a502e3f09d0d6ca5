// Toksvig / vMF roughness from a normal map's own variance per mip level.
//
// Sources: M. Toksvig, "Mipmapping Normal Maps", Journal of Graphics Tools 10(3), 2005 (the
// shortened mean normal measures the spread); A. Banerjee, I. Dhillon, J. Ghosh, S. Sra,
// "Clustering on the Unit Hypersphere using von Mises-Fisher Distributions", JMLR 6, 2005
// (κ ≈ (3r − r³)/(1 − r²)); D. Neubelt and M. Pettineo, "Crafting a Next-Gen Material Pipeline
// for The Order: 1886", SIGGRAPH 2013 course notes, listing 32 (roughness² += 1/(2κ)); Unity
// HDRP (SRP Core CommonMaterial.hlsl, TextureNormalVariance and NormalFiltering) uses the same
// relation as variance = 1/(4κ), α² += 2·variance. Filament exposes the same idea offline
// (its roughness-prefilter tool bakes the variance into the roughness mips).
// Where the mean is taken: the unit-normal chain (each level-0 texel normalised first, so an
// 8-bit texel's quantisation error adds no spread), sampled with the same trilinear /
// anisotropic footprint as the normal texture itself.
#include "scenes/toksvig.h"

#include <algorithm>
#include <cmath>

namespace aalab {

MipChain UnitNormalChain(const MipChain& normal_texture) {
  MipLevel l0 = ToFloatLevel(normal_texture.levels[0]);
  for (glm::vec4& t : l0.texels) {
    const glm::vec3 m = glm::vec3(t) * 2.0f - 1.0f;
    const float len = glm::length(m);
    t = len > 0.0f && std::isfinite(len) ? glm::vec4(m / len, 1.0f) : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  }
  return BuildMipChain(std::move(l0), normal_texture.name + " (unit normals)");
}

MipChain ToksvigAlpha2Chain(const MipChain& normal_texture) {
  MipChain c = UnitNormalChain(normal_texture);
  c.name = normal_texture.name + " (Toksvig alpha^2)";
  for (MipLevel& l : c.levels) {
    for (glm::vec4& t : l.texels) t = glm::vec4(ToksvigAlpha2(glm::length(glm::vec3(t))), 0.0f, 0.0f, 1.0f);
  }
  return c;
}

float ToksvigAlpha2(float r) {
  if (!(r < 1.0f)) return 0.0f;
  if (!(r > 0.0f)) return 1.0f;
  const double rd = r;
  const double kappa = (3.0 * rd - rd * rd * rd) / (1.0 - rd * rd);
  return static_cast<float>(std::min(1.0, 1.0 / (2.0 * kappa)));
}

const MipChain& ToksvigChains::Get(const Scene& sc, int image) const {
  std::call_once(once_, [&] {
    chains_.assign(sc.images.size(), nullptr);
    for (const Material& m : sc.materials) {
      if (!m.gltf || !m.gltf->normal_tex.Has()) continue;
      const auto i = static_cast<size_t>(m.gltf->normal_tex.image);
      if (!chains_[i]) chains_[i] = std::make_shared<const MipChain>(ToksvigAlpha2Chain(*sc.images[i]));
    }
  });
  return *chains_[static_cast<size_t>(image)];
}

}  // namespace aalab
