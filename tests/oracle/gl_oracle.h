// A test oracle: the original FXAA shaders (tests/oracle/seed_shaders.h) run on Mesa's
// software OpenGL (llvmpipe) through a surfaceless EGL context.
//
// How the shader is driven (so that it sees exactly the inputs aalab's port uses):
//   * the frame is an RGBA8 texture, LINEAR filtering, CLAMP_TO_EDGE, row y of the image at
//     t = (y + 0.5)/H (so the shader's +y, "S", is the image's next row, as in aalab);
//   * one point per pixel, its varying (uv / texCoord) set to the pixel centre as aalab
//     computes it, ((x + 0.5)/W, (y + 0.5)/H) rounded to float: a point's varying is its
//     vertex value, so no interpolation rounding enters;
//   * the output goes to an RGBA8 renderbuffer (GL's float-to-UNORM conversion) and is read
//     back with glReadPixels.
// llvmpipe settings, set in the environment before the driver loads: LIBGL_ALWAYS_SOFTWARE=1
// and GALLIUM_DRIVER=llvmpipe (software), GALLIVM_PERF=no_aos_sampling (RGBA8 filtered in
// float32 instead of with 8-bit weights), GALLIUM_OVERRIDE_CPU_CAPS=sse4.1 (no FMA: the
// filter's lerps round after the multiply, as aalab's -ffp-contract=off code does). A mode
// argument selects the default 8-bit path or FMA instead, for reporting what they change.
#pragma once
#include <string>

#include "core/image.h"

namespace aalab::oracle {

/// Which llvmpipe texture-filtering path runs the shader.
struct GlMode {
  bool float_sampling = true;  ///< GALLIVM_PERF=no_aos_sampling (false: default 8-bit weights)
  bool fma = false;            ///< let llvmpipe use the CPU's FMA (its default where present)
};

/// Starts the EGL context once per process with `mode` (later calls must pass the same mode).
/// Returns "" on success, else a message saying what is missing (packages, driver, error).
std::string StartGl(const GlMode& mode);

/// Runs seed 004's FXAA-interactive.fs with FXAA_QUALITY_PRESET `preset`, FXAA_GREEN_AS_LUMA
/// `green_luma`, on `frame` (RGBA8; alpha holds the luma unless green_luma) with the given
/// uniforms. Throws std::runtime_error (with the GL info log) on any failure.
Image8 RunFxaa311Shader(const Image8& frame, int preset, bool green_luma, float subpix, float edge_threshold,
                        float edge_threshold_min);

/// Runs seed 003's 12-iteration GLSL FXAA on `frame` (its thresholds are #defines in the text).
Image8 RunIter12Shader(const Image8& frame);

/// The GL_RENDERER string of the started context.
std::string GlRenderer();

}  // namespace aalab::oracle
