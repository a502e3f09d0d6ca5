# The core sources, relative to core/, all but the parallel loops: one list for
# aalab::core (harness/CMakeLists.txt adds parallel.cpp, on TBB) and for the stand-alone GPU
# tool's copy of the core (gpu/CMakeLists.txt adds gpu/parallel_threads.cpp, on std::thread).
# The same pattern as methods/sources.cmake.
set(AALAB_CORE_SOURCES
  error.cpp
  image.cpp
  color.cpp
  sampler.cpp
  params.cpp
  render_spec.cpp
  edge_mask.cpp
  cleanup.cpp
  input_files.cpp
  raster_geometry.cpp
  format.cpp
  memory_policy.cpp
)
