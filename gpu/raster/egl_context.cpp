// Headless OpenGL 4.5 core through EGL (gpu/raster/egl_context.h): no config
// (EGL_KHR_no_config_context) and no surface (EGL_KHR_surfaceless_context); the raster tool
// draws into framebuffer objects only.
#include "gpu/raster/egl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <cstdio>
#include <vector>

namespace aalab::raster {

namespace {

std::string Hex(EGLint e) {
  char b[16];
  std::snprintf(b, sizeof b, "0x%04x", static_cast<unsigned>(e));
  return b;
}

bool HasExt(const char* list, const char* name) {
  if (!list) return false;
  const std::string s = std::string(" ") + list + " ";
  return s.find(std::string(" ") + name + " ") != std::string::npos;
}

/// Initialises `dpy` and makes a 4.5 core context current on it; "" or why not.
std::string ContextOn(EGLDisplay dpy, const std::string& what, bool* reset_notification) {
  EGLint major = 0, minor = 0;
  if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, &major, &minor)) {
    return what + ": eglInitialize failed (EGL error " + Hex(eglGetError()) + ")";
  }
  const char* ext = eglQueryString(dpy, EGL_EXTENSIONS);
  if (!HasExt(ext, "EGL_KHR_surfaceless_context")) return what + ": no EGL_KHR_surfaceless_context";
  if (!eglBindAPI(EGL_OPENGL_API)) return what + ": eglBindAPI(EGL_OPENGL_API) failed (no desktop OpenGL)";
  // First with reset notification (EGL 1.5's EGL_LOSE_CONTEXT_ON_RESET, no robust buffer
  // access, which could cost shader time), so that glGetGraphicsResetStatus reports a lost
  // context while timing; then without, where the EGL or driver does not offer it.
  const EGLint with_reset[] = {EGL_CONTEXT_MAJOR_VERSION,
                               4,
                               EGL_CONTEXT_MINOR_VERSION,
                               5,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK,
                               EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                               EGL_CONTEXT_OPENGL_RESET_NOTIFICATION_STRATEGY,
                               EGL_LOSE_CONTEXT_ON_RESET,
                               EGL_NONE};
  const EGLint attrs[] = {
      EGL_CONTEXT_MAJOR_VERSION,           4,       EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK,
      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext ctx = EGL_NO_CONTEXT;
  if (major > 1 || (major == 1 && minor >= 5))
    ctx = eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, with_reset);
  *reset_notification = ctx != EGL_NO_CONTEXT;
  if (ctx == EGL_NO_CONTEXT) ctx = eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attrs);
  if (ctx == EGL_NO_CONTEXT) {
    return what + ": eglCreateContext(OpenGL 4.5 core, no config) failed (EGL error " + Hex(eglGetError()) + ")";
  }
  if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
    return what + ": eglMakeCurrent without a surface failed (EGL error " + Hex(eglGetError()) + ")";
  }
  return "";
}

std::string TryDevice(std::string* used, bool* reset) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  // EGL_EXT_device_base is EGL_EXT_device_enumeration plus EGL_EXT_device_query in one name:
  // GLVND's libEGL with the NVIDIA driver lists only the former (measured on the H100).
  const bool enumerate = HasExt(client, "EGL_EXT_device_enumeration") || HasExt(client, "EGL_EXT_device_base");
  if (!HasExt(client, "EGL_EXT_platform_device") || !enumerate) {
    return "device platform: EGL has no EGL_EXT_platform_device / EGL_EXT_device_enumeration (or EGL_EXT_device_base)";
  }
  auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  auto get_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!query_devices || !get_display) return "device platform: eglQueryDevicesEXT / eglGetPlatformDisplayEXT missing";
  EGLint n = 0;
  if (!query_devices(0, nullptr, &n) || n <= 0) return "device platform: no EGL devices";
  std::vector<EGLDeviceEXT> devices(static_cast<size_t>(n));
  query_devices(n, devices.data(), &n);
  std::string why;
  for (EGLint i = 0; i < n; ++i) {
    const std::string what = "device platform, device " + std::to_string(i);
    const std::string r =
        ContextOn(get_display(EGL_PLATFORM_DEVICE_EXT, devices[static_cast<size_t>(i)], nullptr), what, reset);
    if (r.empty()) {
      *used = "EGL_EXT_platform_device (device " + std::to_string(i) + " of " + std::to_string(n) + ")";
      return "";
    }
    why += (why.empty() ? "" : "; ") + r;
  }
  return why;
}

std::string TrySurfaceless(std::string* used, bool* reset) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!HasExt(client, "EGL_MESA_platform_surfaceless"))
    return "surfaceless platform: EGL has no EGL_MESA_platform_surfaceless";
  auto get_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get_display) return "surfaceless platform: eglGetPlatformDisplayEXT missing";
  const std::string r = ContextOn(get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
                                  "surfaceless platform", reset);
  if (r.empty()) *used = "EGL_MESA_platform_surfaceless";
  return r;
}

std::string Str(GLenum name) {
  const auto* s = reinterpret_cast<const char*>(glGetString(name));
  return s ? s : "";
}

}  // namespace

bool ParseEglPlatform(const std::string& name, EglPlatform* out) {
  if (name == "auto")
    *out = EglPlatform::kAuto;
  else if (name == "device")
    *out = EglPlatform::kDevice;
  else if (name == "surfaceless")
    *out = EglPlatform::kSurfaceless;
  else
    return false;
  return true;
}

std::string MakeHeadlessGlContext(EglPlatform platform, GlDeviceInfo* info) {
  std::string used, why;
  bool ok = false, reset = false;
  if (platform != EglPlatform::kSurfaceless) {
    why = TryDevice(&used, &reset);
    ok = why.empty();
  }
  if (!ok && platform != EglPlatform::kDevice) {
    const std::string r = TrySurfaceless(&used, &reset);
    ok = r.empty();
    why += (why.empty() ? "" : "; ") + r;
  }
  if (!ok) return why;
  info->renderer = Str(GL_RENDERER);
  info->vendor = Str(GL_VENDOR);
  info->version = Str(GL_VERSION);
  info->platform = used;
  GLint strategy = 0;
  glGetIntegerv(GL_RESET_NOTIFICATION_STRATEGY, &strategy);
  info->reset_notification = reset && strategy == GL_LOSE_CONTEXT_ON_RESET;
  return "";
}

}  // namespace aalab::raster
