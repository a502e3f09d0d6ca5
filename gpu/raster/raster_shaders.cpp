// The raster path's GLSL (gpu/raster/raster_shaders.h). Arithmetic follows the CPU code's
// order; `precise` keeps the compiler from fusing multiply-adds the CPU build does not fuse
// (-ffp-contract=off).
#include "gpu/raster/raster_shaders.h"

#include <string>

namespace aalab::raster {

// A disk impostor's coverage (shared by the colour and ID passes): the interpolated world
// position on the bounding square (the disk's plane) within the radius, the tracer's
// |p − c|² ≤ r². 1 sample: the fragment's centre, discarded outside. MSAA: the test at each
// sample's position (interpolateAtSample) into gl_SampleMask, the shader still run once per
// pixel (no sample-rate shading).
namespace {

const char* const kDiskCoverage = R"(
flat in vec4 v_disk;  // centre, radius (< 0: not a disk)
uniform int u_samples;
bool InDisk(vec3 p) {
  precise vec3 d = p - v_disk.xyz;
  precise float d2 = dot(d, d);
  precise float r2 = v_disk.w * v_disk.w;
  return d2 <= r2;
}
// gl_SampleMask is written on every path (a path that leaves it unwritten leaves it
// undefined, GLSL 4.50 §7.1.2); the GL ANDs it with the raster coverage.
void DiskCoverage() {
  gl_SampleMask[0] = -1;
  if (v_disk.w < 0.0) return;
  if (u_samples <= 1) {
    if (!InDisk(v_pos)) discard;
    return;
  }
  int mask = 0;
  for (int s = 0; s < u_samples; ++s) {
    if (InDisk(interpolateAtSample(v_pos, s))) mask |= 1 << s;
  }
  if (mask == 0) discard;
  gl_SampleMask[0] = mask;
}
)";

}  // namespace

const char* const kSceneVertex = R"(#version 450 core
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_nrm;
layout(location = 2) in ivec2 a_ids;
layout(location = 3) in vec2 a_uv;
layout(location = 4) in vec4 a_disk;
uniform mat4 u_view_proj;
out vec3 v_pos;
out vec3 v_nrm;
out vec2 v_uv;
flat out ivec2 v_ids;
flat out vec4 v_disk;
void main() {
  v_pos = a_pos;
  v_disk = a_disk;
  v_nrm = a_nrm;
  v_uv = a_uv;
  v_ids = a_ids;
  gl_Position = u_view_proj * vec4(a_pos, 1.0);
}
)";

static const std::string kSceneFragmentText = std::string(R"(#version 450 core
in vec3 v_pos;
in vec3 v_nrm;
in vec2 v_uv;
flat in ivec2 v_ids;
layout(location = 0) out vec4 o_color;
struct Material {
  vec4 color;  // rgb, w = lit
  vec4 tex;    // scale, cos, sin, duty
  ivec4 kind;  // pattern (-1 none, 0 checker, 1 stripes, 2 noise), seed's bits
  vec4 a, b;   // color_a, color_b
};
layout(std430, binding = 0) readonly buffer Materials { Material mat[]; };
uniform vec3 u_cam_pos;
uniform vec3 u_forward;
uniform int u_ortho;
uniform int u_lambert;
uniform vec3 u_ambient;
uniform float u_exposure;
uniform int u_tonemap;
uniform int u_lights;
uniform int u_light_type[16];   // 0 directional, 1 point, 2 spot
uniform vec3 u_light_l[16];     // -direction
uniform vec3 u_light_c[16];     // colour
uniform float u_light_i[16];    // intensity
uniform vec3 u_light_p[16];     // position
uniform vec3 u_light_cone[16];  // range, cos_inner, cos_outer
uniform int u_light_shadow[16];  // casts shadows
uniform int u_shadows;           // the scene declares shadows
uniform int u_occluders;
// Every triangle of the draw, in gl_PrimitiveID order, 3 vec4 each: a triangle's corners
// (a.w < 0), or a disk impostor's disk (a = centre, radius; b = normal).
layout(std430, binding = 1) readonly buffer Occluders { vec4 occ[]; };
)") + kDiskCoverage + R"(
// A shadow ray (origin o, direction d, t in (0, tfar)) against every triangle and disk:
// Möller–Trumbore and the disk's plane + radius, the first hit ends it (any hit blocks).
bool Occluded(vec3 o, vec3 d, float tfar) {
  for (int i = 0; i < u_occluders; ++i) {
    vec4 a = occ[3 * i], b = occ[3 * i + 1], c = occ[3 * i + 2];
    if (a.w >= 0.0) {
      precise float dn = dot(d, b.xyz);
      if (dn == 0.0) continue;
      precise float t = dot(a.xyz - o, b.xyz) / dn;
      if (!(t > 0.0 && t < tfar)) continue;
      precise vec3 q = o + d * t - a.xyz;
      precise float q2 = dot(q, q);
      precise float r2 = a.w * a.w;
      if (q2 <= r2) return true;
      continue;
    }
    precise vec3 e1 = b.xyz - a.xyz;
    precise vec3 e2 = c.xyz - a.xyz;
    precise vec3 pv = cross(d, e2);
    precise float det = dot(e1, pv);
    if (det == 0.0) continue;
    precise vec3 tv = o - a.xyz;
    precise float u = dot(tv, pv) / det;
    if (u < 0.0 || u > 1.0) continue;
    precise vec3 qv = cross(tv, e1);
    precise float v = dot(d, qv) / det;
    if (v < 0.0 || u + v > 1.0) continue;
    precise float t = dot(e2, qv) / det;
    if (t > 0.0 && t < tfar) return true;
  }
  return false;
}

// The tracer's ShadowRays (scenes/tracer_shade.cpp) for one light at the surface point p:
// the geometric normal ng (the primitive's, facing the viewer), the ray from p offset by
// RayEpsilon(p) = 1e-4 + max|p|·1e-6 to ng's side of the light, towards the light.
bool Shadowed(int l, vec3 p, vec3 dir, vec3 n) {
  if (u_shadows == 0 || l >= 32 || u_light_shadow[l] == 0) return false;
  int i = gl_PrimitiveID;
  vec4 a = occ[3 * i], b = occ[3 * i + 1], c = occ[3 * i + 2];
  vec3 ng = a.w >= 0.0 ? b.xyz : cross(b.xyz - a.xyz, c.xyz - a.xyz);
  float len = length(ng);
  ng = len > 0.0 ? ng / len : -dir;
  if (dot(ng, dir) > 0.0) ng = -ng;
  vec3 L;
  float tfar = uintBitsToFloat(0x7f800000u);  // +inf
  if (u_light_type[l] == 0) {
    L = u_light_l[l];
  } else {
    precise vec3 v = u_light_p[l] - p;
    precise float dist = length(v);
    if (!(dist > 0.0)) return false;
    L = v / dist;
    tfar = dist * (1.0 - 1e-5);
  }
  if (dot(ng, L) <= 0.0 && dot(n, L) <= 0.0) return false;
  precise float eps = 1e-4 + max(abs(p.x), max(abs(p.y), abs(p.z))) * 1e-6;
  vec3 side = dot(ng, L) > 0.0 ? ng : -ng;
  precise vec3 o = p + side * eps;
  return Occluded(o, L, tfar);
}
// scenes/light_eval.h LightIncidence, operation for operation.
bool Incidence(int l, vec3 p, out vec3 L, out float falloff) {
  L = u_light_l[l];
  falloff = 1.0;
  if (u_light_type[l] == 0) return true;
  precise vec3 v = u_light_p[l] - p;
  precise float d2 = dot(v, v);
  if (!(d2 > 0.0)) return false;
  precise vec3 vn = v / sqrt(d2);
  precise float f = 1.0 / d2;
  float range = u_light_cone[l].x;
  if (range > 0.0) {
    precise float q = d2 / (range * range);
    f *= clamp(1.0 - q * q, 0.0, 1.0);
  }
  if (u_light_type[l] == 2) {
    precise float scale = 1.0 / max(0.001, u_light_cone[l].y - u_light_cone[l].z);
    precise float offset = -u_light_cone[l].z * scale;
    precise float cd = dot(-u_light_l[l], -vn);
    precise float s = clamp(cd * scale + offset, 0.0, 1.0);
    s *= s;
    f *= s;
  }
  L = vn;
  falloff = f;
  return true;
}

float Tonemap(float v) {
  if (u_tonemap == 1) return isinf(v) ? 1.0 : v / (1.0 + v);
  if (u_tonemap == 2) {
    precise float x = v * 0.6;
    if (x > 1e15) return 2.51 / 2.43;
    precise float r = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
    return r;
  }
  return v;
}

float Display(float v) {
  if (!(v > 0.0)) v = 0.0;
  return clamp(Tonemap(v * u_exposure), 0.0, 1.0);
}

// 64-bit unsigned arithmetic on (low, high) words, for the noise hash (scenes/tracer.cpp
// EvaluatePattern), without GL_ARB_gpu_shader_int64.
uvec2 Mul64(uvec2 a, uvec2 b) {
  uint hi, lo;
  umulExtended(a.x, b.x, hi, lo);
  return uvec2(lo, hi + a.x * b.y + a.y * b.x);
}
uvec2 Add64(uvec2 a, uvec2 b) {
  uint carry;
  uint lo = uaddCarry(a.x, b.x, carry);
  return uvec2(lo, a.y + b.y + carry);
}
uvec2 Shr64(uvec2 a, int n) { return uvec2((a.x >> n) | (a.y << (32 - n)), a.y >> n); }  // 0 < n < 32
// static_cast<int64_t> of an integer-valued float, as x86-64 converts it (out of range,
// inf or NaN: 0x8000000000000000), as two's-complement words.
uvec2 Int64Of(float f) {
  if (abs(f) < 2147483648.0) {
    int i = int(f);
    return uvec2(uint(i), i < 0 ? 0xffffffffu : 0u);
  }
  if (!(abs(f) < 9223372036854775808.0)) return uvec2(0u, 0x80000000u);
  float hi = floor(f / 4294967296.0);  // exact: a power of two, and f's low bits are 0
  float lo = f - hi * 4294967296.0;    // exact: the bits of f below 2^32
  return uvec2(uint(lo), uint(int(hi)));
}

// The tracer's EvaluatePattern, operation for operation (point sampling at uv).
float Pattern(Material m, vec2 uv) {
  if (m.kind.x == 0) {
    precise float a = abs(floor(uv.x * m.tex.x) + floor(uv.y * m.tex.x));
    return (a < 16777216.0 && (int(a) & 1) != 0) ? 1.0 : 0.0;
  }
  if (m.kind.x == 1) {
    precise float d = (uv.x * m.tex.y + uv.y * m.tex.z) * m.tex.x;
    precise float f = d - floor(d);
    return f < m.tex.w ? 1.0 : 0.0;
  }
  precise float fx = floor(uv.x * m.tex.x);
  precise float fy = floor(uv.y * m.tex.x);
  uvec2 h = Mul64(Int64Of(fx), uvec2(0x7f4a7c15u, 0x9e3779b9u)) ^
            Mul64(Add64(Int64Of(fy), uvec2(0xd9b4e019u, 0x632be59bu)), uvec2(0x1ce4e5b9u, 0xbf58476du)) ^
            uvec2(0u, uint(m.kind.y));
  h ^= Shr64(h, 31);
  h = Mul64(h, uvec2(0x133111ebu, 0x94d049bbu));
  h ^= Shr64(h, 29);
  return float(h.y >> 8) * (1.0 / 16777216.0);
}

void main() {
  DiskCoverage();
  Material m = mat[v_ids.y];
  precise vec3 base = m.color.rgb;
  if (m.kind.x >= 0) {
    float t = Pattern(m, v_uv);
    base = m.a.rgb + (m.b.rgb - m.a.rgb) * t;
  }
  precise vec3 c;
  if (m.color.w < 0.5 || u_lambert == 0) {
    c = base;
  } else {
    vec3 dir = u_ortho == 1 ? u_forward : v_pos - u_cam_pos;
    float len = length(v_nrm);
    // The tracer's safe_normalize: a zero normal falls back to facing the camera.
    vec3 n = (len > 0.0 && !isinf(len)) ? v_nrm / len : -dir;
    if (dot(n, dir) > 0.0) n = -n;
    c = u_ambient * base;
    for (int l = 0; l < u_lights; ++l) {
      vec3 L;
      float falloff;
      if (!Incidence(l, v_pos, L, falloff)) continue;
      precise float ndotl = dot(n, L);
      if (ndotl <= 0.0) continue;
      if (Shadowed(l, v_pos, dir, n)) continue;
      precise vec3 e = u_light_c[l] * (u_light_i[l] * falloff);
      c += base * e * ndotl;
    }
  }
  o_color = vec4(Display(c.r), Display(c.g), Display(c.b), 1.0);
}
)";
const char* const kSceneFragment = kSceneFragmentText.c_str();

static const std::string kIdFragmentText = std::string(R"(#version 450 core
flat in ivec2 v_ids;
in vec3 v_pos;
in vec3 v_nrm;
in vec2 v_uv;
layout(location = 0) out uint o_id;
)") + kDiskCoverage + R"(
void main() {
  DiskCoverage();
  o_id = uint(v_ids.x + 1);
}
)";
const char* const kIdFragment = kIdFragmentText.c_str();

const char* const kFullscreenVertex = R"(#version 450 core
void main() {
  vec2 p = vec2(float((gl_VertexID & 1) * 4 - 1), float((gl_VertexID & 2) * 2 - 1));
  gl_Position = vec4(p, 0.0, 1.0);
}
)";

const char* const kResolveMsaaFragment = R"(#version 450 core
layout(binding = 0) uniform sampler2DMS u_src;
uniform int u_samples;
layout(location = 0) out vec4 o_color;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  precise vec3 sum = vec3(0.0);
  for (int s = 0; s < u_samples; ++s) sum += texelFetch(u_src, p, s).rgb;
  o_color = vec4(sum / float(u_samples), 1.0);
}
)";

const char* const kResolveGridFragment = R"(#version 450 core
layout(binding = 0) uniform sampler2D u_src;
uniform int u_grid;
layout(location = 0) out vec4 o_color;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy) * u_grid;
  precise vec3 sum = vec3(0.0);
  for (int j = 0; j < u_grid; ++j)
    for (int i = 0; i < u_grid; ++i) sum += texelFetch(u_src, p + ivec2(i, j), 0).rgb;
  o_color = vec4(sum / float(u_grid * u_grid), 1.0);
}
)";

const char* const kEncodeFragment = R"(#version 450 core
layout(binding = 0) uniform sampler2D u_src;
layout(location = 0) out vec4 o_color;
float Encode(float v) {
  if (!(v > 0.0)) return 0.0;
  if (v >= 1.0) return 1.0;
  if (v <= 0.0031308) return 12.92 * v;
  precise float e = 1.055 * pow(v, 1.0 / 2.4) - 0.055;
  return e;
}
float Code(float v) { return floor(Encode(v) * 255.0 + 0.5) / 255.0; }
void main() {
  vec3 c = texelFetch(u_src, ivec2(gl_FragCoord.xy), 0).rgb;
  o_color = vec4(Code(c.r), Code(c.g), Code(c.b), 1.0);
}
)";

const char* const kUnpackIdsCompute = R"(#version 450 core
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform usampler2DMS u_ids;
layout(std430, binding = 1) writeonly buffer Out { uint ids[]; };
uniform int u_samples;
uniform ivec2 u_size;
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= u_size.x || p.y >= u_size.y) return;
  for (int s = 0; s < u_samples; ++s) ids[(p.y * u_size.x + p.x) * u_samples + s] = texelFetch(u_ids, p, s).r;
}
)";

}  // namespace aalab::raster
