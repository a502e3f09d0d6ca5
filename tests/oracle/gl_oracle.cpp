#include "tests/oracle/gl_oracle.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <cstdlib>
#include <map>
#include <stdexcept>
#include <vector>

#include "tests/oracle/seed_shaders.h"

namespace aalab::oracle {

namespace {

constexpr const char* kPackages = "Debian packages libegl1, libegl-mesa0, libgl1-mesa-dri, libopengl0";

struct GlState {
  bool started = false;
  std::string error;
  GlMode mode;
  std::string renderer;
  std::map<std::string, GLuint> programs;
};
GlState& State() {
  static GlState s;
  return s;
}

std::string Hex(long v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "0x%lx", v);
  return buf;
}

std::string StartOnce(const GlMode& mode) {
  setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1);
  setenv("GALLIUM_DRIVER", "llvmpipe", 1);
  if (mode.float_sampling) {
    setenv("GALLIVM_PERF", "no_aos_sampling", 1);
  } else {
    unsetenv("GALLIVM_PERF");
  }
  if (mode.fma) {
    unsetenv("GALLIUM_OVERRIDE_CPU_CAPS");
  } else {
    setenv("GALLIUM_OVERRIDE_CPU_CAPS", "sse4.1", 1);
  }
  const char* exts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!exts || std::string(exts).find("EGL_MESA_platform_surfaceless") == std::string::npos) {
    return "EGL has no EGL_MESA_platform_surfaceless (client extensions: " + std::string(exts ? exts : "none") +
           "); needs Mesa's EGL: " + kPackages;
  }
  auto get_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get_display) return std::string("eglGetPlatformDisplayEXT is missing; needs ") + kPackages;
  EGLDisplay dpy = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  EGLint major = 0, minor = 0;
  if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, &major, &minor)) {
    return "eglInitialize failed on the surfaceless platform (EGL error " + Hex(eglGetError()) +
           "); needs Mesa's EGL and llvmpipe: " + kPackages;
  }
  if (!eglBindAPI(EGL_OPENGL_API)) return "eglBindAPI(EGL_OPENGL_API) failed: no desktop OpenGL";
  const EGLint attrs[] = {
      EGL_CONTEXT_MAJOR_VERSION,           4,       EGL_CONTEXT_MINOR_VERSION, 3, EGL_CONTEXT_OPENGL_PROFILE_MASK,
      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext ctx = eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attrs);
  if (ctx == EGL_NO_CONTEXT) {
    return "eglCreateContext(OpenGL 4.3 core, no config) failed (EGL error " + Hex(eglGetError()) +
           "); needs EGL_KHR_no_config_context and llvmpipe: " + kPackages;
  }
  if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
    return "eglMakeCurrent without a surface failed (EGL error " + Hex(eglGetError()) + ")";
  }
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  State().renderer = renderer ? renderer : "";
  if (State().renderer.find("llvmpipe") == std::string::npos) {
    return "the OpenGL renderer is '" + State().renderer + "', not Mesa's llvmpipe; needs " + kPackages;
  }
  return "";
}

GLuint CompileShader(GLenum type, const std::string& src, const std::string& what) {
  GLuint s = glCreateShader(type);
  const char* p = src.c_str();
  glShaderSource(s, 1, &p, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    std::vector<char> log(16384);
    glGetShaderInfoLog(s, static_cast<GLsizei>(log.size()), nullptr, log.data());
    throw std::runtime_error("compiling " + what + " failed: " + log.data());
  }
  return s;
}

GLuint Program(const std::string& key, const std::string& vs, const std::string& fs) {
  auto it = State().programs.find(key);
  if (it != State().programs.end()) return it->second;
  GLuint p = glCreateProgram();
  glAttachShader(p, CompileShader(GL_VERTEX_SHADER, vs, key + " (vertex)"));
  glAttachShader(p, CompileShader(GL_FRAGMENT_SHADER, fs, key));
  glBindAttribLocation(p, 0, "a_pix");
  glBindAttribLocation(p, 1, "a_pos");
  glLinkProgram(p);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    std::vector<char> log(16384);
    glGetProgramInfoLog(p, static_cast<GLsizei>(log.size()), nullptr, log.data());
    throw std::runtime_error("linking " + key + " failed: " + log.data());
  }
  State().programs[key] = p;
  return p;
}

// Draws one point per pixel with `prog` (texture unit 0 bound to `frame`), returns RGBA8.
Image8 Draw(GLuint prog, const Image8& frame) {
  const int w = frame.Width(), h = frame.Height();
  GLuint tex = 0, fbo = 0, rb = 0, vao = 0, vbo[2] = {0, 0};
  glGenTextures(1, &tex);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, tex);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, frame.Data().data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glGenFramebuffers(1, &fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glGenRenderbuffers(1, &rb);
  glBindRenderbuffer(GL_RENDERBUFFER, rb);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw std::runtime_error("RGBA8 framebuffer incomplete");
  }
  glViewport(0, 0, w, h);
  // Clip-space point positions at pixel centres, and the exact pixel-centre texcoords.
  std::vector<float> pix, pos;
  pix.reserve(static_cast<size_t>(w) * h * 2);
  pos.reserve(static_cast<size_t>(w) * h * 2);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      pix.push_back((static_cast<float>(x) + 0.5f) / static_cast<float>(w) * 2.0f - 1.0f);
      pix.push_back((static_cast<float>(y) + 0.5f) / static_cast<float>(h) * 2.0f - 1.0f);
      pos.push_back((static_cast<float>(x) + 0.5f) / static_cast<float>(w));
      pos.push_back((static_cast<float>(y) + 0.5f) / static_cast<float>(h));
    }
  }
  glGenVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glGenBuffers(2, vbo);
  glBindBuffer(GL_ARRAY_BUFFER, vbo[0]);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(pix.size() * 4), pix.data(), GL_STATIC_DRAW);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glEnableVertexAttribArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, vbo[1]);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(pos.size() * 4), pos.data(), GL_STATIC_DRAW);
  glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glEnableVertexAttribArray(1);
  glUseProgram(prog);
  glDrawArrays(GL_POINTS, 0, w * h);
  Image8 out(w, h, 4);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, out.Data().data());
  const GLenum err = glGetError();
  glDeleteBuffers(2, vbo);
  glDeleteVertexArrays(1, &vao);
  glDeleteRenderbuffers(1, &rb);
  glDeleteFramebuffers(1, &fbo);
  glDeleteTextures(1, &tex);
  if (err != GL_NO_ERROR) throw std::runtime_error("OpenGL error " + Hex(err) + " while running the shader");
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) out.Pixel(x, y)[3] = 255;  // aalab's frames are opaque
  }
  return out;
}

void Require() {
  if (!State().started || !State().error.empty()) {
    throw std::runtime_error("OpenGL oracle not started: " + State().error);
  }
}

}  // namespace

std::string StartGl(const GlMode& mode) {
  GlState& s = State();
  if (!s.started) {
    s.mode = mode;
    s.error = StartOnce(mode);
    s.started = true;
  } else if (s.mode.float_sampling != mode.float_sampling || s.mode.fma != mode.fma) {
    return "the OpenGL oracle was already started in another llvmpipe mode in this process";
  }
  return s.error;
}

std::string GlRenderer() { return State().renderer; }

Image8 RunFxaa311Shader(const Image8& frame, int preset, bool green_luma, float subpix, float edge_threshold,
                        float edge_threshold_min) {
  Require();
  // GLSL ES 1.00, as the article's WebGL 1 page compiles it, with the defines its JS prepends.
  const std::string defs = "#define FXAA_QUALITY_PRESET " + std::to_string(preset) + "\n#define FXAA_GREEN_AS_LUMA " +
                           (green_luma ? "1" : "0") + "\n#define FXAA_ENABLE 1\n#define FXAA_LUMA 0\n";
  const std::string vs =
      "#version 100\nattribute vec2 a_pix;\nattribute vec2 a_pos;\nvarying vec2 uv;\n"
      "void main() { uv = a_pos; gl_Position = vec4(a_pix, 0.0, 1.0); gl_PointSize = 1.0; }\n";
  const std::string fs = "#version 100\n" + defs + Fxaa311InteractiveShader();
  const GLuint prog =
      Program("FXAA-interactive.fs preset " + std::to_string(preset) + (green_luma ? " green" : ""), vs, fs);
  glUseProgram(prog);
  glUniform1i(glGetUniformLocation(prog, "texture"), 0);
  glUniform2f(glGetUniformLocation(prog, "RcpFrame"), 1.0f / static_cast<float>(frame.Width()),
              1.0f / static_cast<float>(frame.Height()));
  glUniform1f(glGetUniformLocation(prog, "u_fxaaQualitySubpix"), subpix);
  glUniform1f(glGetUniformLocation(prog, "u_fxaaQualityEdgeThreshold"), edge_threshold);
  glUniform1f(glGetUniformLocation(prog, "u_fxaaQualityEdgeThresholdMin"), edge_threshold_min);
  return Draw(prog, frame);
}

Image8 RunIter12Shader(const Image8& frame) {
  Require();
  const std::string vs =
      "#version 430 core\nin vec2 a_pix;\nin vec2 a_pos;\nout vec2 texCoord;\n"
      "void main() { texCoord = a_pos; gl_Position = vec4(a_pix, 0.0, 1.0); }\n";
  // The one edit to the seed's text: GLSL 4.30 (section 4.3.3) requires a const's
  // initializer to be a constant expression, so Mesa rejects "const vec2 inverseScreenSize =
  // 1/viewportSize;". A macro with the same expression keeps every use's value the same.
  std::string fs = Iter12Shader();
  const std::string bad = "const vec2 inverseScreenSize = 1/viewportSize;";
  const size_t at = fs.find(bad);
  if (at == std::string::npos) throw std::runtime_error("seed 003's shader no longer has the line '" + bad + "'");
  fs.replace(at, bad.size(), "#define inverseScreenSize (1/viewportSize)");
  const GLuint prog = Program("seed 003 FXAA (12 iterations)", vs, fs);
  glUseProgram(prog);
  glUniform1i(glGetUniformLocation(prog, "ldrTexture"), 0);
  glUniform2f(glGetUniformLocation(prog, "viewportSize"), static_cast<float>(frame.Width()),
              static_cast<float>(frame.Height()));
  return Draw(prog, frame);
}

}  // namespace aalab::oracle
