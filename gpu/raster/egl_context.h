/// A headless OpenGL 4.5 core context through EGL, with no display and no window system:
/// EGL_EXT_platform_device (the NVIDIA driver; Mesa lists its devices there too) or Mesa's
/// EGL_MESA_platform_surfaceless (llvmpipe). docs/gpu.md "The raster path".
#pragma once
#include <string>

namespace aalab::raster {

/// Which EGL platform to try: auto = device first, then surfaceless.
enum class EglPlatform { kAuto, kDevice, kSurfaceless };

/// What the context runs on (GL_RENDERER, GL_VENDOR, GL_VERSION and the EGL platform used),
/// and whether it reports a lost context (GL_RESET_NOTIFICATION_STRATEGY is
/// GL_LOSE_CONTEXT_ON_RESET, so glGetGraphicsResetStatus tells a reset while timing).
struct GlDeviceInfo {
  std::string renderer, vendor, version, platform;
  bool reset_notification = false;
};

/// Creates the context and makes it current on this thread (one per process; it lives until
/// exit). Returns "" on success and fills *info, else why no context could be made (every
/// platform tried, with its EGL error).
std::string MakeHeadlessGlContext(EglPlatform platform, GlDeviceInfo* info);

/// "auto", "device" or "surfaceless" → the platform; false for anything else.
bool ParseEglPlatform(const std::string& name, EglPlatform* out);

}  // namespace aalab::raster
