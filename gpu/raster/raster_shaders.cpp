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

// glTF materials (scenes/tracer_gltf.cpp ShadeGltf, CutoutKeeps, BackFaceCulled, HitUvDerivs;
// scenes/texture_image.cpp MipLambda, SampleBilinear, the trilinear lerp), compiled in only
// for scenes with glTF materials (AALAB_GLTF 1), so every other scene's shader is unchanged.
// Textures are aalab's own 8-bit mip chains in a storage buffer, decoded through aalab's
// tables and filtered here by the tracer's rule (not the texture unit's), so texels,
// weights and λ are the tracer's up to float rounding; the UV footprint is the tracer's:
// the UV where the rays one pixel right and down meet the triangle's plane, in double.
const char* const kGltfShading = R"(
in vec3 v_tan;
flat in float v_tw;
uniform vec3 u_right;
uniform vec3 u_up;
uniform float u_half_h;
uniform vec2 u_fp_size;    // the footprint's image: the target's width and height
uniform int u_gltf_flags;  // 1 textures, 2 normal_map, 4 alpha_test (the scene's effects)
// Per triangle (gl_PrimitiveID order) 2 vec4: uv0, uv1; uv2, material (its int bits), 0.
layout(std430, binding = 2) readonly buffer TriInfo { vec4 tri[]; };
// Per image: (first level entry, levels, format 0 sRGB / 1 linear, 0); then per level
// (first texel, width, height, 0).
layout(std430, binding = 3) readonly buffer Images { ivec4 img[]; };
layout(std430, binding = 4) readonly buffer Texels { uint texel[]; };  // RGBA8, r in the low byte
layout(std430, binding = 5) readonly buffer Decode { float dec[]; };   // 256 sRGB, then 256 linear
const float kPi = 3.14159265358979;

// WrapIndex (scenes/texture_image.cpp); GLSL's % is undefined for negative operands.
int WrapIdx(int i, int n, int mode) {
  if (i >= 0 && i < n) return i;
  if (mode == 1) return clamp(i, 0, n - 1);
  int period = mode == 0 ? n : 2 * n;
  int r = i >= 0 ? i % period : period - 1 - ((-i - 1) % period);
  if (mode == 0) return r;
  return r < n ? r : period - 1 - r;
}
vec4 Texel(int format, ivec4 lv, int i, int j) {
  uint c = texel[lv.x + j * lv.y + i];
  int o = format == 0 ? 0 : 256;
  return vec4(dec[o + int(c & 255u)], dec[o + int((c >> 8) & 255u)], dec[o + int((c >> 16) & 255u)],
              dec[256 + int(c >> 24)]);
}
// SampleBilinear: texel centres at (i + 0.5)/W; the coordinate in double as the tracer's.
vec4 Bilinear(ivec4 ref, int level, vec2 uv) {
  ivec4 im = img[ref.x];
  ivec4 lv = img[im.x + level];
  if (isnan(uv.x) || isinf(uv.x) || isnan(uv.y) || isinf(uv.y)) return Texel(im.z, lv, 0, 0);
  double x = double(uv.x) * double(lv.y) - 0.5LF;
  double y = double(uv.y) * double(lv.z) - 0.5LF;
  double fx = floor(x), fy = floor(y);
  float ax = float(x - fx), ay = float(y - fy);
  int x0 = int(fx), y0 = int(fy);
  int i0 = WrapIdx(x0, lv.y, ref.y), i1 = WrapIdx(x0 + 1, lv.y, ref.y);
  int j0 = WrapIdx(y0, lv.z, ref.z), j1 = WrapIdx(y0 + 1, lv.z, ref.z);
  precise vec4 top = Texel(im.z, lv, i0, j0) * (1.0 - ax) + Texel(im.z, lv, i1, j0) * ax;
  precise vec4 bot = Texel(im.z, lv, i0, j1) * (1.0 - ax) + Texel(im.z, lv, i1, j1) * ax;
  precise vec4 r = top * (1.0 - ay) + bot * ay;
  return r;
}
// SampleTexture (isotropic): λ = log2(max(|dx·(W, H)|, |dy·(W, H)|)), the lengths as hypot
// (in double: the correctly rounded length), clamped to the chain; λ ≤ 0 or NaN: level 0.
vec4 SampleTex(ivec4 ref, vec2 uv, vec2 dx, vec2 dy) {
  ivec4 im = img[ref.x];
  ivec4 l0 = img[im.x];
  double ax = double(dx.x * float(l0.y)), ay = double(dx.y * float(l0.z));
  double bx = double(dy.x * float(l0.y)), by = double(dy.y * float(l0.z));
  float lx = float(sqrt(ax * ax + ay * ay)), ly = float(sqrt(bx * bx + by * by));
  float lambda = log2(max(lx, ly));
  int last = im.y - 1;
  if (!(lambda > 0.0)) return Bilinear(ref, 0, uv);
  if (lambda >= float(last)) return Bilinear(ref, last, uv);
  int k = int(floor(lambda));
  precise float f = lambda - float(k);
  vec4 a = Bilinear(ref, k, uv);
  if (f == 0.0) return a;
  vec4 b = Bilinear(ref, k + 1, uv);
  precise vec4 r = a * (1.0 - f) + b * f;
  return r;
}

// UvOnPlane: where the ray (o, d) meets the triangle's plane, its uv, in double.
bool UvOnPlane(dvec3 p0, dvec3 e1, dvec3 e2, dvec3 n, dvec4 gram, vec2 uv0, vec2 uv1, vec2 uv2, vec3 o, vec3 d,
               out dvec2 uv) {
  uv = dvec2(0.0LF);
  double denom = dot(n, dvec3(d));
  if (!(abs(denom) > 1e-300LF)) return false;
  double t = dot(n, p0 - dvec3(o)) / denom;
  if (!(t > 0.0LF)) return false;
  dvec3 q = dvec3(o) + dvec3(d) * t - p0;
  double d20 = dot(q, e1), d21 = dot(q, e2);
  if (!(gram.w > 0.0LF)) return false;
  double w1 = (gram.z * d20 - gram.y * d21) / gram.w;
  double w2 = (gram.x * d21 - gram.y * d20) / gram.w;
  dvec2 u0 = dvec2(uv0);
  uv = u0 + w1 * (dvec2(uv1) - u0) + w2 * (dvec2(uv2) - u0);
  return true;
}
// HitUvDerivs at one pixel's footprint (1 px of the target): the uv one pixel right and
// down minus the uv at the pixel's own ray, on the triangle's plane. Unusable rays: the
// tracer's 1e30 (the coarsest level).
void UvDerivs(vec3 org, vec3 dir, out vec2 dx, out vec2 dy) {
  const vec2 huge = vec2(1e30, 0.0);
  dx = huge;
  dy = huge;
  int i = gl_PrimitiveID;
  dvec3 p0 = dvec3(occ[3 * i].xyz);
  dvec3 e1 = dvec3(occ[3 * i + 1].xyz) - p0, e2 = dvec3(occ[3 * i + 2].xyz) - p0;
  dvec3 n = cross(e1, e2);
  double d00 = dot(e1, e1), d01 = dot(e1, e2), d11 = dot(e2, e2);
  dvec4 gram = dvec4(d00, d01, d11, d00 * d11 - d01 * d01);
  vec4 ta = tri[2 * i], tb = tri[2 * i + 1];
  precise float aspect = u_fp_size.x / u_fp_size.y;
  precise float sx = 2.0 * 1.0 / u_fp_size.x * u_half_h * aspect;
  precise float sy = 2.0 * 1.0 / u_fp_size.y * u_half_h;
  vec3 ox = org, oy = org, dxr = dir, dyr = dir;
  if (u_ortho == 1) {
    ox = org + u_right * sx;
    oy = org - u_up * sy;
  } else {
    precise float f = dot(dir, u_forward);
    if (!(f > 0.0)) return;
    precise float a = dot(dir, u_right) / f;
    precise float b = dot(dir, u_up) / f;
    precise vec3 rx = u_forward + u_right * (a + sx) + u_up * b;
    precise vec3 ry = u_forward + u_right * a + u_up * (b - sy);
    dxr = rx * (1.0 / sqrt(dot(rx, rx)));
    dyr = ry * (1.0 / sqrt(dot(ry, ry)));
  }
  dvec2 uv, ux, uy;
  if (!UvOnPlane(p0, e1, e2, n, gram, ta.xy, ta.zw, tb.xy, org, dir, uv)) return;
  if (UvOnPlane(p0, e1, e2, n, gram, ta.xy, ta.zw, tb.xy, ox, dxr, ux)) dx = vec2(ux - uv);
  if (UvOnPlane(p0, e1, e2, n, gram, ta.xy, ta.zw, tb.xy, oy, dyr, uy)) dy = vec2(uy - uv);
}

// A shadow ray's cut-out test at a triangle hit (u, v): the tracer's CutoutKeeps with a zero
// footprint (level 0, bilinear) at the hit's uv, for MASK materials under alpha_test.
bool ShadowCutoutKeeps(int i, float u, float v) {
  if ((u_gltf_flags & 4) == 0) return true;
  vec4 ta = tri[2 * i], tb = tri[2 * i + 1];
  Material m = mat[floatBitsToInt(tb.z)];
  if (m.g_flags.x == 0 || m.g_flags.z != 1) return true;
  precise float a = m.g_base.w;
  if (m.g_tex[0].x >= 0) {
    precise float w = 1.0 - u - v;
    precise vec2 uv = ta.xy * w + ta.zw * u + tb.xy * v;
    a *= Bilinear(m.g_tex[0], 0, uv).w;
  }
  return a >= m.g_pbr.w;
}

// glm::normalize: v · (1 / sqrt(v·v)).
vec3 GlmNormalize(vec3 v) {
  precise vec3 r = v * (1.0 / sqrt(dot(v, v)));
  return r;
}

// The colour of a glTF fragment before the display transform; discards the fragments the
// tracer's camera ray passes through (back faces of single-sided materials, MASK below the
// cutoff).
vec3 ShadeGltfFragment(Material m) {
  vec3 org = u_ortho == 1 ? v_pos - u_forward * dot(v_pos - u_cam_pos, u_forward) : u_cam_pos;
  vec3 dir = u_ortho == 1 ? u_forward : GlmNormalize(v_pos - u_cam_pos);
  int i = gl_PrimitiveID;
  precise vec3 e1 = occ[3 * i + 1].xyz - occ[3 * i].xyz;
  precise vec3 e2 = occ[3 * i + 2].xyz - occ[3 * i].xyz;
  precise vec3 face = cross(e1, e2);
  if (m.g_flags.w == 0 && dot(face, dir) > 0.0) discard;  // BackFaceCulled
  bool textures = (u_gltf_flags & 1) != 0;
  bool any_tex = textures && (m.g_tex[0].x >= 0 || m.g_tex[1].x >= 0 || m.g_tex[2].x >= 0);
  bool mask = (u_gltf_flags & 4) != 0 && m.g_flags.z == 1;
  vec2 dx = vec2(0.0), dy = vec2(0.0);
  if (any_tex || (mask && m.g_tex[0].x >= 0)) UvDerivs(org, dir, dx, dy);
  vec4 base_tex = vec4(1.0);
  if (m.g_tex[0].x >= 0 && (textures || mask)) base_tex = SampleTex(m.g_tex[0], v_uv, dx, dy);
  if (mask) {
    precise float a = m.g_base.w * base_tex.w;
    if (!(a >= m.g_pbr.w)) discard;  // CutoutKeeps
  }
  precise vec4 base = m.g_base;
  if (textures && m.g_tex[0].x >= 0) base *= base_tex;
  if (m.g_flags.y != 0) return base.rgb;
  // FillSurface: the geometric and the interpolated normal, each facing the ray.
  float fl = length(face);
  vec3 ng = fl > 0.0 ? face / fl : -dir;
  if (dot(ng, dir) > 0.0) ng = -ng;
  float nlen = length(v_nrm);
  vec3 n = (nlen > 0.0 && !isinf(nlen)) ? v_nrm / nlen : ng;
  if (dot(n, dir) > 0.0) n = -n;
  vec3 srf_n = n;
  precise float metallic = m.g_pbr.x, roughness = m.g_pbr.y;
  if (textures && m.g_tex[1].x >= 0) {
    vec4 mr = SampleTex(m.g_tex[1], v_uv, dx, dy);
    roughness *= mr.y;
    metallic *= mr.z;
  }
  metallic = clamp(metallic, 0.0, 1.0);
  roughness = clamp(roughness, 0.0, 1.0);
  if ((u_gltf_flags & 2) != 0 && m.g_tex[2].x >= 0 && textures) {
    // NormalMapped: (T, B = N × T · w, N) of the front face, turned like the unmapped normal.
    vec3 tex = SampleTex(m.g_tex[2], v_uv, dx, dy).xyz;
    float l0 = length(v_nrm);
    if (l0 > 0.0) {
      vec3 n0 = v_nrm / l0;
      bool back = dot(n0, srf_n) < 0.0;
      precise vec3 t = v_tan - n0 * dot(n0, v_tan);
      float tl = length(t);
      if (tl > 0.0 && !isinf(tl)) {
        t /= tl;
        precise vec3 b = cross(n0, t) * (v_tw < 0.0 ? -1.0 : 1.0);
        precise vec3 mm = (tex * 2.0 - 1.0) * vec3(m.g_pbr.z, m.g_pbr.z, 1.0);
        precise vec3 nm = t * mm.x + b * mm.y + n0 * mm.z;
        float nl = length(nm);
        if (nl > 0.0 && !isinf(nl)) {
          nm /= nl;
          n = back ? -nm : nm;
        }
      }
    }
  }
  precise float alpha = max(roughness * roughness, 1e-3);
  precise float a2 = alpha * alpha;
  precise vec3 c_diff = base.rgb * (1.0 - metallic);
  precise vec3 f0 = vec3(0.04) * (1.0 - metallic) + base.rgb * metallic;
  vec3 v = -dir;
  precise float nv = max(dot(n, v), 1e-4);
  precise float vis_v = nv + sqrt(a2 + (1.0 - a2) * nv * nv);
  precise vec3 c = u_ambient * (c_diff + f0);
  for (int l = 0; l < u_lights; ++l) {
    vec3 L;
    float falloff;
    if (!Incidence(l, v_pos, L, falloff)) continue;
    precise float nl = dot(n, L);
    if (nl <= 0.0 || dot(ng, L) <= 0.0) continue;
    if (Shadowed(l, v_pos, dir, srf_n)) continue;
    vec3 hv = GlmNormalize(L + v);
    precise float vh = clamp(dot(v, hv), 0.0, 1.0);
    precise float nh = max(dot(n, hv), 0.0);
    double om = double(1.0 - vh);
    float fw = float(om * om * om * om * om);  // std::pow(1 − vh, 5), rounded once
    precise vec3 F = f0 + (vec3(1.0) - f0) * fw;
    precise float dd = nh * nh * (a2 - 1.0) + 1.0;
    precise float D = a2 / (kPi * dd * dd);
    precise float vis = 1.0 / ((nl + sqrt(a2 + (1.0 - a2) * nl * nl)) * vis_v);
    precise vec3 f = (vec3(1.0) - F) * c_diff / kPi + F * (D * vis);
    c += kPi * f * u_light_c[l] * (u_light_i[l] * falloff) * nl;
  }
  return c;
}
)";

}  // namespace

static const std::string kSceneVertexText = R"(#version 450 core
#ifndef AALAB_GLTF
#define AALAB_GLTF 0
#endif
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
#if AALAB_GLTF
layout(location = 5) in vec4 a_tan;
out vec3 v_tan;
flat out float v_tw;  // the first corner's handedness (glProvokingVertex(GL_FIRST_VERTEX_CONVENTION))
#endif
void main() {
#if AALAB_GLTF
  v_tan = a_tan.xyz;
  v_tw = a_tan.w;
#endif
  v_pos = a_pos;
  v_disk = a_disk;
  v_nrm = a_nrm;
  v_uv = a_uv;
  v_ids = a_ids;
  gl_Position = u_view_proj * vec4(a_pos, 1.0);
}
)";
const char* const kSceneVertex = kSceneVertexText.c_str();

static const std::string kSceneFragmentText = std::string(R"(#version 450 core
#ifndef AALAB_GLTF
#define AALAB_GLTF 0
#endif
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
  vec4 g_base;     // glTF baseColorFactor
  vec4 g_pbr;      // metallic, roughness, normal scale, alpha cutoff
  ivec4 g_flags;   // glTF material, unlit, alpha mode (1 MASK), double-sided
  ivec4 g_tex[3];  // baseColor, metallicRoughness, normal: image (-1 none), wrap s, wrap t
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
#if AALAB_GLTF
bool ShadowCutoutKeeps(int tri, float u, float v);
#endif
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
#if AALAB_GLTF
    if (t > 0.0 && t < tfar && ShadowCutoutKeeps(i, u, v)) return true;
#else
    if (t > 0.0 && t < tfar) return true;
#endif
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

#if AALAB_GLTF
)" + std::string(kGltfShading) + R"(
#endif
void main() {
  DiskCoverage();
  Material m = mat[v_ids.y];
#if AALAB_GLTF
  if (m.g_flags.x != 0) {
    vec3 g = ShadeGltfFragment(m);
    o_color = vec4(Display(g.r), Display(g.g), Display(g.b), 1.0);
    return;
  }
#endif
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
