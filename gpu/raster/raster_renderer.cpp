// The raster path's renderer (gpu/raster/raster_renderer.h): GL objects, the camera's
// matrix (the tracer's rays inverted), the three stages and their timer queries.
#include "gpu/raster/raster_renderer.h"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "gpu/raster/raster_shaders.h"

namespace aalab::raster {

namespace {

/// `src` with `#define AALAB_GLTF 1` after its #version line when `on`.
std::string WithGltf(const char* src, bool on) {
  std::string s = src;
  if (on) s.insert(s.find('\n') + 1, "#define AALAB_GLTF 1\n");
  return s;
}

using V3 = std::array<float, 3>;
V3 Sub(V3 a, V3 b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
float Dot(V3 a, V3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 Cross(V3 a, V3 b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
V3 Normalize(V3 a) {
  const float l = std::sqrt(Dot(a, a));
  return {a[0] / l, a[1] / l, a[2] / l};
}

/// The radical inverse of `index` in `base`, in double (core/render_spec.h RadicalInverse).
double RadicalInverse(int base, int index) {
  double r = 0.0, f = 1.0 / base;
  for (int i = index; i > 0; i /= base, f /= base) r += f * (i % base);
  return r;
}

void Check(const char* what) {
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR) {
    char b[64];
    std::snprintf(b, sizeof b, "GL error 0x%04x", e);
    throw std::runtime_error(std::string(what) + ": " + b);
  }
}

GLuint Compile(GLenum type, const char* src) {
  const GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096];
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    throw std::runtime_error(std::string("a raster shader does not compile: ") + log);
  }
  return s;
}

GLuint Link(std::initializer_list<std::pair<GLenum, const char*>> stages) {
  const GLuint p = glCreateProgram();
  std::vector<GLuint> shaders;
  for (const auto& [type, src] : stages) {
    shaders.push_back(Compile(type, src));
    glAttachShader(p, shaders.back());
  }
  glLinkProgram(p);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096];
    glGetProgramInfoLog(p, sizeof log, nullptr, log);
    throw std::runtime_error(std::string("a raster program does not link: ") + log);
  }
  for (GLuint s : shaders) glDeleteShader(s);
  return p;
}

/// A colour texture (multisampled when samples > 1) and its framebuffer, with an optional
/// depth renderbuffer of the same sample count.
struct Target {
  GLuint tex = 0, fbo = 0, depth = 0;
  int w = 0, h = 0, samples = 1;
  void Make(int width, int height, int n, GLenum format, bool with_depth) {
    w = width;
    h = height;
    samples = n;
    const GLenum target = n > 1 ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D;
    glCreateTextures(target, 1, &tex);
    if (n > 1) {
      glTextureStorage2DMultisample(tex, n, format, w, h, GL_TRUE);
      // A GL may give more samples than asked (llvmpipe: 4 for 2): keep what it gave.
      GLint got = n;
      glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_SAMPLES, &got);
      samples = got;
    } else {
      glTextureStorage2D(tex, 1, format, w, h);
      glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);
    if (with_depth) {
      glCreateRenderbuffers(1, &depth);
      glNamedRenderbufferStorageMultisample(depth, samples > 1 ? samples : 0, GL_DEPTH_COMPONENT32F, w, h);
      glNamedFramebufferRenderbuffer(fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    }
    if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      throw std::runtime_error("a raster framebuffer of " + std::to_string(w) + "x" + std::to_string(h) + " with " +
                               std::to_string(n) + " sample(s) is incomplete");
    }
    Check("allocating a raster target");
  }
  void Free() {
    if (fbo) glDeleteFramebuffers(1, &fbo);
    if (tex) glDeleteTextures(1, &tex);
    if (depth) glDeleteRenderbuffers(1, &depth);
    *this = Target{};
  }
};

}  // namespace

struct RasterRenderer::Gl {
  RasterScene scene;
  GLuint vao = 0, vbo = 0, materials = 0, occluders = 0, empty_vao = 0;
  bool gltf = false;  ///< the scene has glTF materials (AALAB_GLTF shaders, the buffers below)
  GLuint tri_info = 0, images = 0, texel_buf = 0, decode = 0;
  GLuint scene_prog = 0, id_prog = 0, resolve_ms_prog = 0, resolve_grid_prog = 0, encode_prog = 0, unpack_prog = 0;
  GLsizei vertices = 0;
  RasterMethod method;
  int w = 0, h = 0;
  GLenum format = GL_RGBA16F;
  ResolveKind resolve = ResolveKind::kShader;
  Target draw, resolved, encoded, ids;
  std::array<float, 16> view_proj{};

  void SceneUniforms() {
    const RasterScene& s = scene;
    glUseProgram(scene_prog);
    auto loc = [&](const char* n) { return glGetUniformLocation(scene_prog, n); };
    glUniformMatrix4fv(loc("u_view_proj"), 1, GL_FALSE, view_proj.data());
    glUniform3fv(loc("u_cam_pos"), 1, s.position.data());
    const V3 fwd = Normalize(Sub(s.look_at, s.position));
    glUniform3fv(loc("u_forward"), 1, fwd.data());
    glUniform1i(loc("u_ortho"), s.orthographic ? 1 : 0);
    glUniform1i(loc("u_lambert"), s.lambert ? 1 : 0);
    glUniform3fv(loc("u_ambient"), 1, s.ambient.data());
    glUniform1f(loc("u_exposure"), s.exposure);
    glUniform1i(loc("u_tonemap"), s.tonemap);
    const int n = static_cast<int>(std::min<size_t>(s.lights.size(), 16));
    glUniform1i(loc("u_lights"), n);
    for (int l = 0; l < n; ++l) {
      const RasterLight& li = s.lights[static_cast<size_t>(l)];
      const V3 L = {-li.direction[0], -li.direction[1], -li.direction[2]};
      const V3 cone = {li.range, li.cos_inner, li.cos_outer};
      auto at = [&](const char* name) {
        return glGetUniformLocation(scene_prog, (std::string(name) + "[" + std::to_string(l) + "]").c_str());
      };
      glUniform1i(at("u_light_type"), li.type);
      glUniform3fv(at("u_light_l"), 1, L.data());
      glUniform3fv(at("u_light_c"), 1, li.color.data());
      glUniform1f(at("u_light_i"), li.intensity);
      glUniform3fv(at("u_light_p"), 1, li.position.data());
      glUniform3fv(at("u_light_cone"), 1, cone.data());
      glUniform1i(at("u_light_shadow"), li.shadows ? 1 : 0);
    }
    glUniform1i(loc("u_shadows"), s.shadows ? 1 : 0);
    glUniform1i(loc("u_occluders"), static_cast<GLint>(s.triangles.size()));
    glUniform1i(loc("u_samples"), draw.samples);
    if (gltf) {
      const V3 right = Normalize(Cross(fwd, s.up));
      const V3 up = Cross(right, fwd);
      glUniform3fv(loc("u_right"), 1, right.data());
      glUniform3fv(loc("u_up"), 1, up.data());
      // As the tracer computes it (glm::radians' constant), for the footprint's offset rays.
      glUniform1f(loc("u_half_h"), s.orthographic ? s.height * 0.5f
                                                  : std::tan(s.fov_y_deg * 0.01745329251994329576923690768489f * 0.5f));
      glUniform2f(loc("u_fp_size"), static_cast<float>(draw.w), static_cast<float>(draw.h));
      glUniform1i(loc("u_gltf_flags"), (s.textures ? 1 : 0) | (s.normal_map ? 2 : 0) | (s.alpha_test ? 4 : 0));
    }
    glUseProgram(id_prog);
    glUniformMatrix4fv(glGetUniformLocation(id_prog, "u_view_proj"), 1, GL_FALSE, view_proj.data());
    glUniform1i(glGetUniformLocation(id_prog, "u_samples"), draw.samples);
  }

  /// glTF scenes (whose cameras sit among the geometry) draw with reversed float depth:
  /// glClipControl(GL_ZERO_TO_ONE), depth n / z, cleared to 0, GL_GREATER. The other scenes
  /// keep the standard mapping, so their frames are unchanged.
  bool ReversedZ() const { return gltf && !scene.orthographic; }

  /// The tracer's half height of the image plane (Tracer::Impl::half_h).
  float HalfH() const {
    return scene.orthographic ? scene.height * 0.5f : std::tan(scene.fov_y_deg * 3.14159265358979f / 180.0f * 0.5f);
  }

  /// The matrix that puts every world point where the tracer's camera ray through it
  /// starts: nx = 2x/W − 1, ny = 1 − 2y/H (scenes/tracer.cpp), with window y = image y
  /// (flipped, so row 0 of the framebuffer is the image's top row), plus TAA's jitter.
  void MakeViewProj() {
    const RasterScene& s = scene;
    const V3 fwd = Normalize(Sub(s.look_at, s.position));
    const V3 right = Normalize(Cross(fwd, s.up));
    const V3 up = Cross(right, fwd);
    const int tw = method.kind == RasterMethod::Kind::kSsaa ? w * method.grid : w;
    const int th = method.kind == RasterMethod::Kind::kSsaa ? h * method.grid : h;
    const float aspect = static_cast<float>(tw) / static_cast<float>(th);
    const float half_h = HalfH();
    float zmin = 1e30f, zmax = -1e30f;
    for (const auto& t : s.triangles) {
      for (const auto& c : t.corners) {
        const float z = Dot(fwd, Sub(c.position, s.position));
        zmin = std::min(zmin, z);
        zmax = std::max(zmax, z);
      }
    }
    // Rows of the 4 × 4 matrix (row-major here; GL gets it transposed to column-major).
    double m[4][4] = {};
    const double sx = 1.0 / (half_h * aspect), sy = -1.0 / half_h;
    const V3 p = s.position;
    const double rx = -Dot(right, p), uy = -Dot(up, p), fz = -Dot(fwd, p);
    if (s.orthographic) {
      const double n = zmin - 1.0 - 0.01 * std::fabs(zmin), f = zmax + 1.0 + 0.01 * std::fabs(zmax);
      for (int k = 0; k < 3; ++k) {
        m[0][k] = sx * right[k];
        m[1][k] = sy * up[k];
        m[2][k] = 2.0 / (f - n) * fwd[k];
      }
      m[0][3] = sx * rx;
      m[1][3] = sy * uy;
      m[2][3] = (2.0 * fz - (f + n)) / (f - n);
      m[3][3] = 1.0;
    } else {
      const double f = std::max(zmax, 1e-3f) * 1.01;
      const double n = std::max({zmin * 0.5, f * 1e-5, 1e-5});
      for (int k = 0; k < 3; ++k) {
        m[0][k] = sx * right[k];
        m[1][k] = sy * up[k];
        m[2][k] = (f + n) / (f - n) * fwd[k];
        m[3][k] = fwd[k];
      }
      m[0][3] = sx * rx;
      m[1][3] = sy * uy;
      m[2][3] = (f + n) / (f - n) * fz - 2.0 * f * n / (f - n);
      m[3][3] = fz;
      if (ReversedZ()) {
        // Reversed Z (depth = n / z, no far plane): float depth then resolves z to about
        // 2⁻²⁴·z everywhere, where the standard mapping near 1 resolves only z²/n·2⁻²⁴ (with
        // n = 10⁻⁵ and z = 10 that is 0.6 scene units: real-foliage's crossing leaves, 0.014
        // apart, came out in the wrong order).
        for (int k = 0; k < 3; ++k) m[2][k] = 0.0;
        m[2][3] = n;
      }
    }
    // TAA: the sample sits at the centre + (jx, jy) px; moving the geometry by −(jx, jy) px
    // puts it under the rasteriser's centre sample (clip x += −2jx/W · w, y likewise).
    const double ox = -2.0 * method.jx / tw, oy = -2.0 * method.jy / th;
    for (int k = 0; k < 4; ++k) {
      m[0][k] += ox * m[3][k];
      m[1][k] += oy * m[3][k];
    }
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) view_proj[static_cast<size_t>(c * 4 + r)] = static_cast<float>(m[r][c]);
    }
  }

  void Fullscreen(GLuint prog, const Target& dst) {
    glBindFramebuffer(GL_FRAMEBUFFER, dst.fbo);
    glViewport(0, 0, dst.w, dst.h);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(prog);
    glBindVertexArray(empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }

  void Draw(GLuint prog, const Target& t, bool ids) {
    glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
    glViewport(0, 0, t.w, t.h);
    glEnable(GL_DEPTH_TEST);
    glClipControl(GL_LOWER_LEFT, ReversedZ() ? GL_ZERO_TO_ONE : GL_NEGATIVE_ONE_TO_ONE);
    glDepthFunc(ReversedZ() ? GL_GREATER : GL_LESS);
    if (ids) {
      const GLuint zero[4] = {0, 0, 0, 0};
      glClearBufferuiv(GL_COLOR, 0, zero);
    } else {
      // The background through the display transform, as the tracer's miss.
      float bg[4] = {0, 0, 0, 1};
      for (int c = 0; c < 3; ++c) bg[c] = DisplayCpu(scene.background[static_cast<size_t>(c)]);
      glClearBufferfv(GL_COLOR, 0, bg);
    }
    const float far_depth = ReversedZ() ? 0.0f : 1.0f;
    glClearBufferfv(GL_DEPTH, 0, &far_depth);
    glUseProgram(prog);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, materials);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, occluders);  // SampleShapes borrows binding 1
    if (gltf) {
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, tri_info);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, images);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, texel_buf);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, decode);
      glProvokingVertex(GL_FIRST_VERTEX_CONVENTION);  // v_tw: the first corner's handedness
    }
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLES, 0, vertices);
  }

  /// core/color.h's display transform of one channel (for the clear colour).
  float DisplayCpu(float v) const {
    if (!(v > 0.0f)) v = 0.0f;
    v *= scene.exposure;
    if (scene.tonemap == 1) v = std::isinf(v) ? 1.0f : v / (1.0f + v);
    if (scene.tonemap == 2) {
      const float x = v * 0.6f;
      v = x > 1e15f ? 2.51f / 2.43f : (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
    }
    return std::clamp(v, 0.0f, 1.0f);
  }

  /// The glTF shading's buffers: per triangle its corners' uv and material (binding 2), the
  /// images' and levels' table (3), every level's RGBA8 texels (4), aalab's decode tables (5).
  void UploadGltf() {
    auto buffer = [](GLuint* b, const void* data, size_t bytes) {
      glCreateBuffers(1, b);
      glNamedBufferStorage(*b, static_cast<GLsizeiptr>(std::max<size_t>(bytes, 16)), data, 0);
    };
    std::vector<float> tri;
    for (const auto& t : scene.triangles) {
      float mat_bits = 0;
      std::memcpy(&mat_bits, &t.material, 4);
      const auto& c = t.corners;
      tri.insert(tri.end(), {c[0].uv[0], c[0].uv[1], c[1].uv[0], c[1].uv[1], c[2].uv[0], c[2].uv[1], mat_bits, 0});
    }
    tri.resize(std::max<size_t>(tri.size(), 8));
    buffer(&tri_info, tri.data(), tri.size() * 4);
    std::vector<int32_t> table;
    std::vector<uint32_t> texels;
    size_t levels = 0;
    for (const auto& im : scene.images) levels += im.levels.size();
    size_t entry = scene.images.size();
    for (const auto& im : scene.images) {
      table.insert(table.end(), {static_cast<int32_t>(entry), static_cast<int32_t>(im.levels.size()), im.format, 0});
      entry += im.levels.size();
    }
    for (const auto& im : scene.images) {
      for (const auto& l : im.levels) {
        table.insert(table.end(), {static_cast<int32_t>(texels.size()), l.width, l.height, 0});
        const size_t n = static_cast<size_t>(l.width) * static_cast<size_t>(l.height);
        const size_t at = texels.size();
        texels.resize(at + n);
        std::memcpy(texels.data() + at, l.rgba.data(), n * 4);  // little-endian: r in the low byte
      }
    }
    table.resize(std::max<size_t>(table.size(), 4));
    texels.resize(std::max<size_t>(texels.size(), 4));
    buffer(&images, table.data(), table.size() * 4);
    buffer(&texel_buf, texels.data(), texels.size() * 4);
    std::vector<float> dec(scene.srgb_table.begin(), scene.srgb_table.end());
    dec.insert(dec.end(), scene.unorm_table.begin(), scene.unorm_table.end());
    buffer(&decode, dec.data(), dec.size() * 4);
    (void)levels;
  }

  void StageDraw() { Draw(scene_prog, draw, false); }
  void StageResolve() {
    if (method.kind == RasterMethod::Kind::kMsaa) {
      if (resolve == ResolveKind::kBlit) {
        glBlitNamedFramebuffer(draw.fbo, resolved.fbo, 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
      } else {
        glBindTextureUnit(0, draw.tex);
        glUseProgram(resolve_ms_prog);
        glUniform1i(glGetUniformLocation(resolve_ms_prog, "u_samples"), draw.samples);
        Fullscreen(resolve_ms_prog, resolved);
      }
    } else if (method.kind == RasterMethod::Kind::kSsaa) {
      glBindTextureUnit(0, draw.tex);
      glUseProgram(resolve_grid_prog);
      glUniform1i(glGetUniformLocation(resolve_grid_prog, "u_grid"), method.grid);
      Fullscreen(resolve_grid_prog, resolved);
    }
  }
  bool HasResolve() const {
    return method.kind == RasterMethod::Kind::kMsaa || method.kind == RasterMethod::Kind::kSsaa;
  }
  void StageEncode() {
    glBindTextureUnit(0, HasResolve() ? resolved.tex : draw.tex);
    Fullscreen(encode_prog, encoded);
  }
};

bool ParseRasterMethod(const std::string& spec, RasterMethod* out, std::string* why) {
  RasterMethod m;
  m.name = spec;
  if (spec == "none") {
    m.kind = RasterMethod::Kind::kOne;
  } else if (spec == "aaa") {
    m.kind = RasterMethod::Kind::kOne;
    m.analytic = true;
  } else if (spec == "scale43") {
    m.kind = RasterMethod::Kind::kScale;
    m.scale = 4.0 / 3.0;  // scale43's default (methods/render_scale.cpp ScaleParams)
  } else if (spec == "msaa-2x" || spec == "msaa-4x" || spec == "msaa-8x" || spec == "msaa-16x") {
    m.kind = RasterMethod::Kind::kMsaa;
    m.samples = std::stoi(spec.substr(5));
  } else if (spec == "ssaa-2x2" || spec == "ssaa-4x4") {
    m.kind = RasterMethod::Kind::kSsaa;
    m.grid = spec[5] - '0';
  } else if (spec == "taa" || spec.rfind("taa@", 0) == 0) {
    m.kind = RasterMethod::Kind::kTaa;
    if (spec.size() > 4) {
      const std::string n = spec.substr(4);
      if (n.empty() || n.size() > 6 || n.find_first_not_of("0123456789") != std::string::npos) {
        *why = "'" + spec + "': taa@N takes a frame number N in 0..999999";
        return false;
      }
      m.taa_frame = std::stoi(n);
    }
    m.name = "taa";
    // taa's jitter (methods/taa.cpp, samples = 16): Halton(2,3) point (frame mod 16) + 1, − 0.5.
    const int index = m.taa_frame % 16 + 1;
    m.jx = static_cast<float>(RadicalInverse(2, index) - 0.5);
    m.jy = static_cast<float>(RadicalInverse(3, index) - 0.5);
  } else {
    *why = "unknown raster method '" + spec +
           "' (the raster path draws: none, aaa, msaa-2x, msaa-4x, msaa-8x, msaa-16x, ssaa-2x2, ssaa-4x4, scale43, "
           "taa, taa@N)";
    return false;
  }
  *out = m;
  return true;
}

std::string RasterMethodRefusal(const RasterMethod& method, const RasterScene& scene) {
  if (!method.analytic) return "";
  for (const auto& t : scene.triangles) {
    if (t.disk) {
      return "aaa computes an analytic disk's edge coverage from its distance; the raster path has no form of "
             "it (it draws disks with a hard edge): aaa is drawn only on scenes of triangles, where aalab renders "
             "it as none";
    }
  }
  return "";
}

void RasterFrameSize(const RasterMethod& method, int w, int h, int* fw, int* fh) {
  *fw = w;
  *fh = h;
  if (method.kind == RasterMethod::Kind::kScale) {
    // As harness/run renders a render-scale method: lround of the double product.
    *fw = std::max(1, static_cast<int>(std::lround(method.scale * w)));
    *fh = std::max(1, static_cast<int>(std::lround(method.scale * h)));
  }
}

RasterRenderer::RasterRenderer(const RasterScene& scene) : gl_(std::make_unique<Gl>()) {
  Gl& g = *gl_;
  g.scene = scene;
  g.gltf = scene.AnyGltf();
  // A scene with glTF materials compiles the glTF shading in (AALAB_GLTF); the others get
  // the shader they always had.
  const std::string vs = WithGltf(kSceneVertex, g.gltf), fs = WithGltf(kSceneFragment, g.gltf);
  g.scene_prog = Link({{GL_VERTEX_SHADER, vs.c_str()}, {GL_FRAGMENT_SHADER, fs.c_str()}});
  g.id_prog = Link({{GL_VERTEX_SHADER, kSceneVertex}, {GL_FRAGMENT_SHADER, kIdFragment}});
  g.resolve_ms_prog = Link({{GL_VERTEX_SHADER, kFullscreenVertex}, {GL_FRAGMENT_SHADER, kResolveMsaaFragment}});
  g.resolve_grid_prog = Link({{GL_VERTEX_SHADER, kFullscreenVertex}, {GL_FRAGMENT_SHADER, kResolveGridFragment}});
  g.encode_prog = Link({{GL_VERTEX_SHADER, kFullscreenVertex}, {GL_FRAGMENT_SHADER, kEncodeFragment}});
  g.unpack_prog = Link({{GL_COMPUTE_SHADER, kUnpackIdsCompute}});
  // Interleaved vertices: position (3 floats), normal (3 floats), shape and material (2 ints),
  // uv (2 floats).
  struct Vertex {
    float p[3], n[3];
    int32_t ids[2];
    float uv[2];
    float disk[4];  // centre, radius; radius −1: not a disk
    float tan[4];   // glTF tangent, handedness
  };
  std::vector<Vertex> v;
  v.reserve(scene.triangles.size() * 3);
  for (const auto& t : scene.triangles) {
    for (const auto& c : t.corners) {
      v.push_back({{c.position[0], c.position[1], c.position[2]},
                   {c.normal[0], c.normal[1], c.normal[2]},
                   {t.shape, t.material},
                   {c.uv[0], c.uv[1]},
                   {t.center[0], t.center[1], t.center[2], t.disk ? t.radius : -1.0f},
                   {c.tangent[0], c.tangent[1], c.tangent[2], c.tangent[3]}});
    }
  }
  g.vertices = static_cast<GLsizei>(v.size());
  glCreateBuffers(1, &g.vbo);
  glNamedBufferStorage(g.vbo, static_cast<GLsizeiptr>(std::max<size_t>(1, v.size()) * sizeof(Vertex)),
                       v.empty() ? nullptr : v.data(), 0);
  glCreateVertexArrays(1, &g.vao);
  glVertexArrayVertexBuffer(g.vao, 0, g.vbo, 0, sizeof(Vertex));
  glEnableVertexArrayAttrib(g.vao, 0);
  glEnableVertexArrayAttrib(g.vao, 1);
  glEnableVertexArrayAttrib(g.vao, 2);
  glEnableVertexArrayAttrib(g.vao, 3);
  glEnableVertexArrayAttrib(g.vao, 4);
  glEnableVertexArrayAttrib(g.vao, 5);
  glVertexArrayAttribFormat(g.vao, 0, 3, GL_FLOAT, GL_FALSE, offsetof(Vertex, p));
  glVertexArrayAttribFormat(g.vao, 1, 3, GL_FLOAT, GL_FALSE, offsetof(Vertex, n));
  glVertexArrayAttribIFormat(g.vao, 2, 2, GL_INT, offsetof(Vertex, ids));
  glVertexArrayAttribFormat(g.vao, 3, 2, GL_FLOAT, GL_FALSE, offsetof(Vertex, uv));
  glVertexArrayAttribFormat(g.vao, 4, 4, GL_FLOAT, GL_FALSE, offsetof(Vertex, disk));
  glVertexArrayAttribFormat(g.vao, 5, 4, GL_FLOAT, GL_FALSE, offsetof(Vertex, tan));
  for (GLuint a = 0; a < 6; ++a) glVertexArrayAttribBinding(g.vao, a, 0);
  glCreateVertexArrays(1, &g.empty_vao);
  // The shader's std430 Material: colour + lit, texture scale/cos/sin/duty, pattern + seed
  // (ints), color_a, color_b; the glTF part: base factor, (metallic, roughness, normal
  // scale, cutoff), flags (glTF, unlit, MASK, double-sided), 3 texture references; 11 × 16 bytes.
  struct GpuMaterial {
    float color[4], tex[4];
    int32_t kind[4];
    float a[4], b[4];
    float g_base[4], g_pbr[4];
    int32_t g_flags[4];
    int32_t g_tex[3][4];
  };
  std::vector<GpuMaterial> mats;
  for (const auto& m : scene.materials) {
    const RasterTexture& t = m.texture;
    int32_t seed = 0;
    std::memcpy(&seed, &t.seed, 4);
    mats.push_back({{m.color[0], m.color[1], m.color[2], m.lit ? 1.0f : 0.0f},
                    {t.scale, t.cos_angle, t.sin_angle, t.duty},
                    {t.pattern, seed, 0, 0},
                    {t.color_a[0], t.color_a[1], t.color_a[2], 0.0f},
                    {t.color_b[0], t.color_b[1], t.color_b[2], 0.0f},
                    {m.pbr.base_factor[0], m.pbr.base_factor[1], m.pbr.base_factor[2], m.pbr.base_factor[3]},
                    {m.pbr.metallic, m.pbr.roughness, m.pbr.normal_scale, m.pbr.alpha_cutoff},
                    {m.gltf ? 1 : 0, m.pbr.unlit ? 1 : 0, m.pbr.alpha_mode, m.pbr.double_sided ? 1 : 0},
                    {{m.pbr.base.image, m.pbr.base.wrap_s, m.pbr.base.wrap_t, 0},
                     {m.pbr.mr.image, m.pbr.mr.wrap_s, m.pbr.mr.wrap_t, 0},
                     {m.pbr.normal.image, m.pbr.normal.wrap_s, m.pbr.normal.wrap_t, 0}}});
  }
  if (mats.empty()) mats.push_back({});
  glCreateBuffers(1, &g.materials);
  glNamedBufferStorage(g.materials, static_cast<GLsizeiptr>(mats.size() * sizeof(GpuMaterial)), mats.data(), 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, g.materials);
  // Shadow rays' occluders: every triangle in draw order (gl_PrimitiveID), 3 vec4 each.
  std::vector<float> occ;
  for (const auto& t : scene.triangles) {
    if (t.disk) {
      const auto& n = t.corners[0].normal;
      occ.insert(occ.end(), {t.center[0], t.center[1], t.center[2], t.radius, n[0], n[1], n[2], 0, 0, 0, 0, 0});
    } else {
      for (const auto& c : t.corners) occ.insert(occ.end(), {c.position[0], c.position[1], c.position[2], -1.0f});
    }
  }
  if (occ.empty()) occ.assign(12, 0.0f);
  glCreateBuffers(1, &g.occluders);
  glNamedBufferStorage(g.occluders, static_cast<GLsizeiptr>(occ.size() * sizeof(float)), occ.data(), 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, g.occluders);
  if (g.gltf) g.UploadGltf();
  Check("uploading the raster scene");
}

RasterRenderer::~RasterRenderer() {
  Gl& g = *gl_;
  g.draw.Free();
  g.resolved.Free();
  g.encoded.Free();
  g.ids.Free();
  glDeleteBuffers(1, &g.vbo);
  glDeleteBuffers(1, &g.materials);
  glDeleteBuffers(1, &g.occluders);
  for (GLuint b : {g.tri_info, g.images, g.texel_buf, g.decode}) {
    if (b) glDeleteBuffers(1, &b);
  }
  glDeleteVertexArrays(1, &g.vao);
  glDeleteVertexArrays(1, &g.empty_vao);
  for (GLuint p : {g.scene_prog, g.id_prog, g.resolve_ms_prog, g.resolve_grid_prog, g.encode_prog, g.unpack_prog}) {
    glDeleteProgram(p);
  }
}

void RasterRenderer::Configure(const RasterMethod& method, int out_w, int out_h, TargetFormat format,
                               ResolveKind resolve) {
  Gl& g = *gl_;
  int w = 0, h = 0;  // the frame drawn: the output size, or a render-scale method's render size
  RasterFrameSize(method, out_w, out_h, &w, &h);
  g.draw.Free();
  g.resolved.Free();
  g.encoded.Free();
  g.ids.Free();
  g.method = method;
  g.w = w;
  g.h = h;
  g.format = format == TargetFormat::kRgba32f ? GL_RGBA32F : GL_RGBA16F;
  g.resolve = resolve;
  GLint max_samples = 0, max_size = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  const int n = method.kind == RasterMethod::Kind::kMsaa ? method.samples : 1;
  const int k = method.kind == RasterMethod::Kind::kSsaa ? method.grid : 1;
  if (n > max_samples) {
    throw CapabilityError(method.name + " needs " + std::to_string(n) + " samples; this GL allows " +
                          std::to_string(max_samples) + " (GL_MAX_SAMPLES)");
  }
  if (w * k > max_size || h * k > max_size) {
    throw CapabilityError(method.name + " at " + std::to_string(w) + "x" + std::to_string(h) + " needs a " +
                          std::to_string(w * k) + "x" + std::to_string(h * k) + " target; GL_MAX_TEXTURE_SIZE is " +
                          std::to_string(max_size));
  }
  g.draw.Make(w * k, h * k, n, g.format, true);
  if (g.HasResolve()) g.resolved.Make(w, h, 1, g.format, false);
  g.encoded.Make(w, h, 1, GL_RGBA8, false);
  g.MakeViewProj();
  g.SceneUniforms();
}

void RasterRenderer::RenderFrame() {
  Gl& g = *gl_;
  g.StageDraw();
  g.StageResolve();
  g.StageEncode();
  Check("rendering a raster frame");
}

FrameCounts PlanFrames(const TimingPlan& plan, double probe_ms) {
  if (!(plan.budget_ms > 0) || !(probe_ms > 0)) return {plan.warmup, plan.repeat};
  auto fit = [&](double budget, int lo, int hi) {
    const double n = std::floor(budget / probe_ms);
    return n >= hi ? hi : std::max(lo, static_cast<int>(n));
  };
  return {fit(plan.budget_ms * 0.5, std::min(1, plan.warmup), plan.warmup),
          fit(plan.budget_ms, std::min(plan.min_repeat, plan.repeat), plan.repeat)};
}

StageTimes CheckedStageTimes(const uint64_t ns[3], const bool available[3], bool has_resolve) {
  static const char* const kStage[3] = {"draw", "resolve", "encode"};
  for (int s = 0; s < 3; ++s) {
    const bool worked = s != 1 || has_resolve;
    if (!available[s]) {
      throw TimingError(std::string("the ") + kStage[s] + " stage's GL_TIME_ELAPSED query has no result", false);
    }
    if (worked && ns[s] == 0) {
      throw TimingError(
          std::string("the ") + kStage[s] + " stage's GL_TIME_ELAPSED query returned 0 ns for a stage that drew pixels",
          false);
    }
    if (ns[s] > 100000000000ull) {
      throw TimingError(std::string("the ") + kStage[s] + " stage's GL_TIME_ELAPSED query returned " +
                            std::to_string(ns[s]) + " ns (over 100 s: not a plausible time)",
                        false);
    }
  }
  return {ns[0] * 1e-6, has_resolve ? ns[1] * 1e-6 : 0.0, ns[2] * 1e-6};
}

namespace {

/// glGetGraphicsResetStatus and glGetError after reading a frame's queries: a TimingError
/// when the context was reset (lost) or an error was raised while timing.
void CheckTimingContext() {
  const GLenum reset = glGetGraphicsResetStatus();
  if (reset != GL_NO_ERROR) {
    const char* who = reset == GL_GUILTY_CONTEXT_RESET     ? "caused by this context"
                      : reset == GL_INNOCENT_CONTEXT_RESET ? "caused elsewhere"
                                                           : "of unknown cause";
    throw TimingError(std::string("the GL context was reset while timing (glGetGraphicsResetStatus: a reset ") + who +
                          "); no time measured after it is trusted",
                      true);
  }
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR) {
    char b[96];
    std::snprintf(b, sizeof b, "GL error 0x%04x while timing", e);
    throw TimingError(b, e == GL_CONTEXT_LOST);
  }
}

}  // namespace

TimedFrames RasterRenderer::TimeFrames(const TimingPlan& plan) {
  Gl& g = *gl_;
  const bool has_resolve = g.HasResolve();
  // A ring of kSlots frames' queries (3 each, one object per stage): frame i uses slot
  // i mod kSlots, whose previous frame's results are read and checked first, so at most
  // kSlots frames are in flight and no query object is reused before its result was read.
  constexpr int kSlots = 3;
  std::array<GLuint, 3 * kSlots> q{};
  glCreateQueries(GL_TIME_ELAPSED, static_cast<GLsizei>(q.size()), q.data());
  std::array<bool, kSlots> pending{};
  auto issue = [&](int slot) {
    const GLuint* s = &q[static_cast<size_t>(3 * slot)];
    glBeginQuery(GL_TIME_ELAPSED, s[0]);
    g.StageDraw();
    glEndQuery(GL_TIME_ELAPSED);
    glBeginQuery(GL_TIME_ELAPSED, s[1]);
    g.StageResolve();
    glEndQuery(GL_TIME_ELAPSED);
    glBeginQuery(GL_TIME_ELAPSED, s[2]);
    g.StageEncode();
    glEndQuery(GL_TIME_ELAPSED);
    glFlush();
    pending[static_cast<size_t>(slot)] = true;
  };
  // `check`: a warm-up frame's results are read (its queries are reused) and the context
  // checked, but not its values, which nothing reports.
  auto collect = [&](int slot, bool check) {
    const GLuint* s = &q[static_cast<size_t>(3 * slot)];
    uint64_t ns[3] = {0, 0, 0};
    bool available[3] = {false, false, false};
    for (int k = 0; k < 3; ++k) {
      GLuint64 v = 0;
      glGetQueryObjectui64v(s[k], GL_QUERY_RESULT, &v);  // waits for the result
      GLuint avail = GL_FALSE;
      glGetQueryObjectuiv(s[k], GL_QUERY_RESULT_AVAILABLE, &avail);
      ns[k] = k == plan.zero_stage ? 0 : v;
      available[k] = avail == GL_TRUE;
    }
    pending[static_cast<size_t>(slot)] = false;
    CheckTimingContext();  // a lost context reports results as available: check it first
    return check ? CheckedStageTimes(ns, available, has_resolve) : StageTimes{};
  };
  TimedFrames out;
  try {
    // One untimed frame first: llvmpipe (Mesa 22.3.6) returns the clock since boot, not the
    // elapsed time, for the draw query of the first frame drawn on a fresh context
    // (measured: 49 700 s for a 0.3 ms draw; later frames and targets are fine). The check
    // refuses such a value; this frame keeps it out of the probe and the warm-up.
    g.StageDraw();
    g.StageResolve();
    g.StageEncode();
    glFinish();
    FrameCounts counts{plan.warmup, plan.repeat};
    if (plan.budget_ms > 0) {
      issue(0);
      out.probe_ms = collect(0, true).Total();
      counts = PlanFrames(plan, out.probe_ms);
    }
    out.warmup = counts.warmup;
    const int frames = counts.warmup + counts.repeat;
    out.frames.reserve(static_cast<size_t>(counts.repeat));
    for (int i = 0; i < frames + kSlots; ++i) {
      const int slot = i % kSlots;
      const int done = i - kSlots;  // the frame whose results sit in this slot
      if (done >= 0 && pending[static_cast<size_t>(slot)]) {
        const StageTimes t = collect(slot, done >= counts.warmup);
        if (done >= counts.warmup) out.frames.push_back(t);
      }
      if (i < frames) issue(slot);
    }
  } catch (...) {
    glFinish();
    glDeleteQueries(static_cast<GLsizei>(q.size()), q.data());
    throw;
  }
  glDeleteQueries(static_cast<GLsizei>(q.size()), q.data());
  CheckTimingContext();
  return out;
}

std::vector<uint8_t> RasterRenderer::ReadRgb8() const {
  const Gl& g = *gl_;
  std::vector<uint8_t> rgba(static_cast<size_t>(g.w) * g.h * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, g.encoded.fbo);
  glReadPixels(0, 0, g.w, g.h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  Check("reading the raster frame");
  std::vector<uint8_t> rgb(static_cast<size_t>(g.w) * g.h * 3);
  for (size_t i = 0, n = static_cast<size_t>(g.w) * g.h; i < n; ++i) {
    for (int c = 0; c < 3; ++c) rgb[3 * i + static_cast<size_t>(c)] = rgba[4 * i + static_cast<size_t>(c)];
  }
  return rgb;
}

std::vector<int32_t> RasterRenderer::SampleShapes() {
  Gl& g = *gl_;
  if (g.method.kind != RasterMethod::Kind::kMsaa)
    throw std::runtime_error("SampleShapes needs an MSAA method configured");
  if (!g.ids.fbo) g.ids.Make(g.w, g.h, g.draw.samples, GL_R32UI, true);
  const int n = g.ids.samples;
  if (n != g.draw.samples) throw std::runtime_error("the ID target got another sample count than the colour target");
  g.Draw(g.id_prog, g.ids, true);
  GLuint buf = 0;
  const size_t count = static_cast<size_t>(g.w) * g.h * n;
  glCreateBuffers(1, &buf);
  glNamedBufferStorage(buf, static_cast<GLsizeiptr>(count * 4), nullptr, GL_DYNAMIC_STORAGE_BIT);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buf);
  glBindTextureUnit(0, g.ids.tex);
  glUseProgram(g.unpack_prog);
  glUniform1i(glGetUniformLocation(g.unpack_prog, "u_samples"), n);
  glUniform2i(glGetUniformLocation(g.unpack_prog, "u_size"), g.w, g.h);
  glDispatchCompute(static_cast<GLuint>((g.w + 7) / 8), static_cast<GLuint>((g.h + 7) / 8), 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<uint32_t> raw(count);
  glGetNamedBufferSubData(buf, 0, static_cast<GLsizeiptr>(count * 4), raw.data());
  glDeleteBuffers(1, &buf);
  Check("reading the per-sample shapes");
  std::vector<int32_t> out(count);
  for (size_t i = 0; i < count; ++i) out[i] = static_cast<int32_t>(raw[i]) - 1;
  return out;
}

std::vector<float> RasterRenderer::SamplePositions() const {
  const Gl& g = *gl_;
  glBindFramebuffer(GL_FRAMEBUFFER, g.draw.fbo);
  std::vector<float> pos(static_cast<size_t>(2 * g.draw.samples));
  for (int s = 0; s < g.draw.samples; ++s)
    glGetMultisamplefv(GL_SAMPLE_POSITION, static_cast<GLuint>(s), &pos[static_cast<size_t>(2 * s)]);
  Check("querying the sample positions");
  return pos;
}

int RasterRenderer::Samples() const { return gl_->draw.samples; }

int RasterRenderer::SubpixelBits() const {
  GLint b = 0;
  glGetIntegerv(GL_SUBPIXEL_BITS, &b);
  return b;
}

}  // namespace aalab::raster
