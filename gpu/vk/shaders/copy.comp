// aalab_vk's floor (docs/gpu.md "Original shaders through Vulkan"): every texel of the RGBA8
// frame read once through the texture path (texelFetch, no filtering) and written once to an
// RGBA8 storage image, in 16x16 workgroups: the least a post filter that reads its frame and
// writes a frame can cost. aalab's own code (not a third-party shader).
#version 450
layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = 0) uniform sampler2D InputTexture;
layout(rgba8, binding = 1) uniform writeonly image2D OutputTexture;
void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(OutputTexture)))) return;
  imageStore(OutputTexture, p, texelFetch(InputTexture, p, 0));
}
