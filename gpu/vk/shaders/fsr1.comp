// aalab's wrapper around AMD's ffx_a.h + ffx_fsr1.h (../shared/third_party/fidelityfx-fsr1,
// included at compile time by scripts/vk_shaders.sh, never copied here), shaped as the
// sample's FSR_Pass.glsl calls them in its fp32 build (A_GPU, A_GLSL, FSR_EASU_F or
// FSR_RCAS_F, 64-thread workgroups over 16x16 tiles through ARmp8x8), as
// tests/oracle/fsr1_shader.cpp runs them on llvmpipe. Compile with -DAALAB_EASU=1 (EASU) or
// -DAALAB_EASU=0 (RCAS). Differences from the sample, each the oracle's too:
// - the constants arrive as push constants (the sample: a uniform block), FsrEasuCon /
//   FsrRcasCon computed on the host as aalab's port computes them;
// - FsrRcasLoadF clamps its position to the texture (the sample reads outside on the border,
//   undefined without robust access: docs/fsr1.md);
// - a store outside the output (frames not a multiple of 16) is skipped, not left to the
//   driver (Vulkan leaves such a store undefined without robustness).
#version 450
#extension GL_GOOGLE_include_directive : require
#define A_GPU 1
#define A_GLSL 1
#include "ffx_a.h"
layout(binding = 0) uniform sampler2D InputTexture;
layout(rgba8, binding = 1) uniform writeonly image2D OutputTexture;
layout(push_constant) uniform Constants {
  uvec4 Const0;
  uvec4 Const1;
  uvec4 Const2;
  uvec4 Const3;
};
#if AALAB_EASU
#define FSR_EASU_F 1
AF4 FsrEasuRF(AF2 p) { return textureGather(InputTexture, p, 0); }
AF4 FsrEasuGF(AF2 p) { return textureGather(InputTexture, p, 1); }
AF4 FsrEasuBF(AF2 p) { return textureGather(InputTexture, p, 2); }
#else
#define FSR_RCAS_F 1
AF4 FsrRcasLoadF(ASU2 p) { return texelFetch(InputTexture, clamp(p, ASU2(0), textureSize(InputTexture, 0) - ASU2(1)), 0); }
void FsrRcasInputF(inout AF1 r, inout AF1 g, inout AF1 b) {}
#endif
#include "ffx_fsr1.h"
void CurrFilter(AU2 pos) {
  if (any(greaterThanEqual(ASU2(pos), imageSize(OutputTexture)))) return;
  AF3 c;
#if AALAB_EASU
  FsrEasuF(c, pos, Const0, Const1, Const2, Const3);
#else
  FsrRcasF(c.r, c.g, c.b, pos, Const0);
#endif
  imageStore(OutputTexture, ASU2(pos), AF4(c, 1));
}
layout(local_size_x = 64) in;
void main() {
  AU2 gxy = ARmp8x8(gl_LocalInvocationID.x) + AU2(gl_WorkGroupID.x << 4u, gl_WorkGroupID.y << 4u);
  CurrFilter(gxy);
  gxy.x += 8u;
  CurrFilter(gxy);
  gxy.y += 8u;
  CurrFilter(gxy);
  gxy.x -= 8u;
  CurrFilter(gxy);
}
