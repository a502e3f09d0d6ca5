# The CPU method sources, relative to methods/: one list for aalab::methods (methods/CMakeLists.txt)
# and for the stand-alone GPU tool's copy of the CPU methods (gpu/CMakeLists.txt).
set(AALAB_METHOD_SOURCES
  registry.cpp
  supersample.cpp
  msaa.cpp
  fxaa1.cpp
  fxaa1_fast.cpp
  fxaa311.cpp
  fxaa311_fast.cpp
  smaa.cpp
  smaa_fast.cpp
  smaa_textures.cpp
  cmaa2.cpp
  rescale.cpp
  render_scale.cpp
  fsr1.cpp
  fsr2_common.cpp
  fsr2_reconstruct.cpp
  fsr2_lock.cpp
  fsr2_depth_clip.cpp
  fsr2_rcas.cpp
  aaa.cpp
  taa.cpp
  taa_production.cpp
  taau.cpp
  specular_aa.cpp
)
