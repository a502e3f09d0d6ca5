/// Normal-map variance as roughness (Toksvig 2005; the von Mises-Fisher form of Neubelt &
/// Pettineo 2013, which Unity HDRP's TextureNormalVariance uses): the filtered mean of a normal
/// map's unit normals is shorter than 1 where its texels disagree, and that length r gives the
/// extra GGX α² of the lobe the pixel really sees. methods/specular_aa.cpp pairs it with
/// geometric specular AA (`gsaa`).
#pragma once
#include <memory>
#include <mutex>
#include <vector>

#include "scenes/scene.h"
#include "scenes/texture_image.h"

namespace aalab {

/// The unit-normal mip chain of a normal texture: level 0 holds normalize(2t − 1) of each texel
/// (xyz; w = 1; a zero vector stays zero), every further level the 2 × 2 box mean of the one
/// above (BuildMipChain). Sampled with a pixel's footprint it returns the mean unit normal over
/// that footprint; its length is r. Pure.
MipChain UnitNormalChain(const MipChain& normal_texture);

/// The Toksvig α² of every texel of every level of the unit-normal chain, in the texel's x
/// (y = z = 0, w = 1): level 0 is 0 everywhere (unit texels), level k holds the spread of the
/// 2^k × 2^k block it averages. Sampled trilinearly with a pixel's footprint it interpolates
/// α² between texels and levels (as a roughness mip chain baked offline does), so a magnified
/// normal map (λ ≤ 0) adds nothing: bilinear interpolation between two level-0 texels is a
/// smooth surface, not sub-texel spread. Pure.
MipChain ToksvigAlpha2Chain(const MipChain& normal_texture);

/// The α² a mean unit-normal length r adds: the vMF concentration κ = (3r − r³)/(1 − r²)
/// (Banerjee et al. 2005's estimate) and α² = 1/(2κ) (Neubelt & Pettineo 2013, listing 32;
/// HDRP: variance 1/(4κ), α² += 2·variance). 0 for r ≥ 1 (no spread), 1 for r ≤ 0.
float ToksvigAlpha2(float r);

/// The Toksvig α² chains (ToksvigAlpha2Chain) of every image a scene uses as a glTF
/// normalTexture, built once on first use (thread-safe; lock-free afterwards) and only when
/// specular AA asks for them.
class ToksvigChains {
 public:
  /// The chain of Scene::images[image] (built for all normal textures at the first call).
  const MipChain& Get(const Scene& sc, int image) const;

 private:
  mutable std::once_flag once_;
  mutable std::vector<std::shared_ptr<const MipChain>> chains_;
};

}  // namespace aalab
