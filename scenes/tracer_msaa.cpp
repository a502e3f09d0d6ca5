// MSAA on the ray tracer: visibility per coverage sample, shading per primitive (docs/msaa.md).
//
// Hardware MSAA rasterises each primitive against N sample positions (coverage and depth
// per sample) but runs the pixel shader once per primitive and pixel, at the pixel centre
// (or the centroid location), and writes that one colour to every covered sample that
// passes the depth test (D3D11.3 functional spec §3.5.4-3.5.5, §19.2.4). Emulated here:
//   1. Visibility: one camera ray per coverage sample, closest hit = (shape, primitive).
//      With alpha_test=sample the alpha test runs at each sample and a cut-out hit is
//      skipped (as Trace does); with alpha_test=shade the samples keep their closest hit.
//   2. Fragments: the distinct primitives a pixel's samples see, with their coverage mask.
//      Convex analytic shapes (sphere, capsule, cylinder) count their front and back
//      surface as two primitives, as a tessellated mesh would.
//   3. One shading point per fragment:
//      centre   the pixel-centre ray on the primitive. When the centre ray's closest hit is
//               the primitive, that hit (so interior pixels shade exactly like `none`);
//               otherwise the centre ray through the primitive's plane, barycentrics
//               unclamped (attributes extrapolated past the edge, as the hardware
//               interpolates them) for triangles and disks. Shapes whose surface ends at
//               their outline (sphere, capsule, cylinder) have no surface there: they, and
//               planes the centre ray does not reach in front of the camera, use the first
//               covered sample in index order instead (the centroid rule's choice).
//      centroid the centre when every sample is covered, else the first covered sample
//               in index order (D3D11.3 §3.5.5). Coverage here is visible coverage: the
//               samples where the primitive is the closest surface (hardware uses its raster
//               coverage before the depth test; they differ only where another surface hides
//               part of the primitive inside the pixel).
//      With alpha_test=shade the alpha test runs at the shading point; when it fails the
//      fragment is discarded from all its samples (like `discard` at pixel frequency),
//      which continue past it and may join or form fragments behind it (next round).
//      With alpha_test=a2c (alpha-to-coverage) the shading point's continuous alpha keeps
//      ⌊α·N + d⌋ samples (d: the pixel's 4×4 Bayer threshold) in sample index order; the
//      fragment's other samples continue past it like discarded ones.
//      A fragment's shading point is fixed in the round where it is first seen.
//   4. Shading: every kept fragment through the same shading code as Trace (textures,
//      lighting, specular, shadow rays), its colour copied to its samples.
#include <cmath>
#include <optional>

#include "core/error.h"
#include "scenes/tracer_internal.h"

namespace aalab {

using namespace tracer_detail;

namespace {

constexpr int kMaxMsaaSamples = 16;

bool IsPlanar(ShapeKind k) { return k == ShapeKind::kTriangles || k == ShapeKind::kDisk; }

/// The back surface of a convex analytic shape (a ray leaving it); planar shapes have none.
bool BackSurface(const Shape& s, const Hit& h, glm::vec3 dir) {
  return !IsPlanar(s.kind) && glm::dot(h.ng, dir) > 0.0f;
}

/// A primitive seen by some of a pixel's samples.
struct Fragment {
  int shape = -1;
  unsigned prim = 0;
  bool back = false;
  int next = -1;      // next fragment of the same pixel (-1: last)
  uint32_t mask = 0;  // covered samples, bit s = sample index s
  int first = 0;      // global index of its first covered sample at creation
  bool discarded = false;
  uint32_t keep = 0xFFFFFFFFu;  // alpha-to-coverage: the samples it keeps (bit s)
  Hit hit;                      // shading point, seen along the ray (org, dir)
  glm::vec3 org{0.0f}, dir{0.0f};
};

/// The ray through the plane of a planar primitive (triangle: barycentrics unclamped; disk:
/// its plane, radius ignored); nothing when the plane is parallel to the ray or not in front.
std::optional<Hit> PlaneHit(const Shape& s, unsigned prim, glm::vec3 org, glm::vec3 dir) {
  Hit h;
  h.prim = prim;
  if (s.kind == ShapeKind::kTriangles) {
    const glm::uvec3 tri = s.triangles[prim];
    const glm::vec3 v0 = s.positions[tri.x];
    const glm::vec3 e1 = s.positions[tri.y] - v0;
    const glm::vec3 e2 = s.positions[tri.z] - v0;
    const glm::vec3 pv = glm::cross(dir, e2);
    const float det = glm::dot(e1, pv);
    if (!(std::fabs(det) > 0.0f)) return std::nullopt;
    const float inv = 1.0f / det;
    const glm::vec3 tv = org - v0;
    const glm::vec3 qv = glm::cross(tv, e1);
    h.u = glm::dot(tv, pv) * inv;
    h.v = glm::dot(dir, qv) * inv;
    h.t = glm::dot(e2, qv) * inv;
    h.ng = glm::cross(e1, e2);
  } else {
    const float denom = glm::dot(dir, s.normal);
    if (!(std::fabs(denom) > 0.0f)) return std::nullopt;
    h.t = glm::dot(s.center - org, s.normal) / denom;
    h.ng = s.normal;
  }
  if (!(h.t > 0.0f) || !std::isfinite(h.t) || !std::isfinite(h.u) || !std::isfinite(h.v)) return std::nullopt;
  return h;
}

/// Per-thread working memory of TraceMsaa, reused from call to call.
struct MsaaScratch {
  std::vector<glm::vec3> org, dir, corg, cdir;
  std::vector<float> tnear, tfar, ctnear, ctfar;
  std::vector<Hit> hits, chits, layer_hits;
  std::vector<int> sample_frag, pixel_head, pending, next, shade_index, covered_px, centre_of;
  std::vector<SamplePos> cpos;
  std::vector<Fragment> frags;
  std::vector<Hit> shade_hits;
  std::vector<glm::vec3> shade_org, shade_dir;
  std::vector<SampleResult> shade_out;
  LayerScratch layers;
  ShadeScratch shade;
};

}  // namespace

void Tracer::TraceMsaa(const SamplePos* sample_pos, const SamplePos* centre_pos, int pixels, const MsaaSpec& msaa,
                       int width, int height, SampleResult* out, uint32_t* shading_evals, TraceCounters* counters,
                       TextureFootprint footprint) const {
  const Impl& im = *impl_;
  const Scene& sc = scene_;
  const int N = msaa.samples;
  AALAB_CHECK(N >= 1 && N <= kMaxMsaaSamples, "MSAA sample count must be 1..16");
  TraceCounters local;
  const int count = pixels * N;
  local.samples = static_cast<uint64_t>(count);
  if (pixels <= 0) {
    if (counters) *counters += local;
    return;
  }
  thread_local MsaaScratch scratch;
  MsaaScratch& S = scratch;
  const size_t n_all = static_cast<size_t>(count), n_px = static_cast<size_t>(pixels);
  const float inf = std::numeric_limits<float>::infinity();
  const bool alpha = sc.Has(Effect::kAlphaTest) && im.any_alpha;
  const bool alpha_per_sample = alpha && msaa.alpha_test == MsaaAlphaTest::kSample;
  const bool alpha_at_shade = alpha && msaa.alpha_test == MsaaAlphaTest::kShade;
  const bool alpha_a2c = alpha && msaa.alpha_test == MsaaAlphaTest::kCoverage;
  const uint32_t full_mask = (1u << N) - 1u;

  // 1. Coverage rays: closest hit per sample (through cut-outs only with alpha_test=sample).
  glm::vec3* org = Sized(S.org, n_all);
  glm::vec3* dir = Sized(S.dir, n_all);
  float* tnear = Sized(S.tnear, n_all);
  float* tfar = Sized(S.tfar, n_all);
  CameraRays(im, sc.camera, sample_pos, count, width, height, org, dir);
  std::fill(tnear, tnear + count, 0.0f);
  std::fill(tfar, tfar + count, inf);
  Hit* hits = Sized(S.hits, n_all);
  const Footprint fp{width, height, footprint};
  ClosestVisibleHits(im, sc, alpha_per_sample, org, dir, count, tnear, tfar, hits, S.layers, local, fp);

  // Pixel-centre rays (shading rays, not coverage): their closest hit, no alpha test; only
  // for pixels where some sample sees a surface (nothing is shaded in the others). Packed:
  // centre k is pixel covered_px[k]; centre_of[p] = k (-1: none).
  std::vector<int>& covered_px = S.covered_px;
  covered_px.clear();
  int* centre_of = Sized(S.centre_of, n_px);
  SamplePos* cpos = Sized(S.cpos, n_px);
  for (int p = 0; p < pixels; ++p) {
    centre_of[p] = -1;
    for (int s = 0; s < N; ++s) {
      if (hits[p * N + s].shape >= 0) {
        centre_of[p] = static_cast<int>(covered_px.size());
        cpos[covered_px.size()] = centre_pos[p];
        covered_px.push_back(p);
        break;
      }
    }
  }
  const int n_centre = static_cast<int>(covered_px.size());
  glm::vec3* corg = Sized(S.corg, n_px);
  glm::vec3* cdir = Sized(S.cdir, n_px);
  float* ctnear = Sized(S.ctnear, n_px);
  float* ctfar = Sized(S.ctfar, n_px);
  Hit* chits = Sized(S.chits, n_px);
  CameraRays(im, sc.camera, cpos, n_centre, width, height, corg, cdir);
  std::fill(ctnear, ctnear + n_centre, 0.0f);
  std::fill(ctfar, ctfar + n_centre, inf);
  IntersectRays(im.scene, corg, cdir, ctnear, ctfar, nullptr, n_centre, chits, true);
  local.primary_rays += static_cast<uint64_t>(n_centre);

  // The shading point of a new fragment f of pixel p (see the file comment).
  auto place_shading_point = [&](Fragment& f, int p) {
    const Shape& shape = sc.shapes[f.shape];
    const bool at_centre = msaa.shading == MsaaShading::kCenter || f.mask == full_mask;
    p = centre_of[p];  // a pixel with a fragment has a centre ray
    if (at_centre) {
      const Hit& ch = chits[p];
      if (ch.shape == f.shape && ch.prim == f.prim && BackSurface(shape, ch, cdir[p]) == f.back) {
        f.hit = ch;
        f.org = corg[p];
        f.dir = cdir[p];
        return;
      }
      if (IsPlanar(shape.kind)) {
        if (const auto h = PlaneHit(shape, f.prim, corg[p], cdir[p])) {
          f.hit = *h;
          f.hit.shape = f.shape;
          f.org = corg[p];
          f.dir = cdir[p];
          return;
        }
      }
    }
    f.hit = hits[f.first];
    f.org = org[f.first];
    f.dir = dir[f.first];
  };

  // 2-3. Fragments per pixel, in rounds: a round groups the samples that found a new hit;
  // with alpha_test=shade, fragments whose alpha test fails send their samples on.
  int* sample_frag = Sized(S.sample_frag, n_all);
  std::fill(sample_frag, sample_frag + count, -1);
  int* pixel_head = Sized(S.pixel_head, n_px);
  std::fill(pixel_head, pixel_head + pixels, -1);
  std::vector<Fragment>& frags = S.frags;
  frags.clear();
  std::vector<int>& pending = S.pending;
  std::vector<int>& next = S.next;
  pending.resize(n_all);
  for (int i = 0; i < count; ++i) pending[static_cast<size_t>(i)] = i;
  uint64_t discarded = 0;
  for (int layer = 0;; ++layer) {
    const size_t round_start = frags.size();
    for (const int i : pending) {  // ascending: pixel by pixel, samples in index order
      const Hit& h = hits[i];
      if (h.shape < 0) continue;
      const int p = i / N, s = i % N;
      const bool back = BackSurface(sc.shapes[h.shape], h, dir[i]);
      int f = pixel_head[p];
      int last = -1;
      while (f >= 0 && !(frags[f].shape == h.shape && frags[f].prim == h.prim && frags[f].back == back)) {
        last = f;
        f = frags[f].next;
      }
      if (f < 0) {
        f = static_cast<int>(frags.size());
        Fragment nf;
        nf.shape = h.shape;
        nf.prim = h.prim;
        nf.back = back;
        nf.first = i;
        frags.push_back(nf);
        (last < 0 ? pixel_head[p] : frags[last].next) = f;
      }
      frags[f].mask |= 1u << s;
      sample_frag[i] = f;
    }
    for (size_t f = round_start; f < frags.size(); ++f) {
      Fragment& fr = frags[f];
      place_shading_point(fr, fr.first / N);
      const Material& m = sc.materials[sc.shapes[fr.shape].material];
      if (alpha_at_shade && m.CutOut()) {
        const Surface srf = SurfaceAt(sc, fr.hit, fr.org, fr.dir);
        ++local.texture_lookups;
        if (!CutoutKeeps(im, sc, m, fr.hit, srf, fr.org, fr.dir, fp)) {
          fr.discarded = true;
          ++discarded;
        }
      }
      if (alpha_a2c && m.CutOut()) {
        const Surface srf = SurfaceAt(sc, fr.hit, fr.org, fr.dir);
        ++local.texture_lookups;
        const SamplePos c = centre_pos[fr.first / N];
        fr.keep = AlphaToCoverageMask(CutoutAlpha(im, sc, m, fr.hit, srf, fr.org, fr.dir, fp), N,
                                      static_cast<int>(std::floor(c.x)), static_cast<int>(std::floor(c.y)));
        if ((fr.mask & fr.keep) == 0) {
          fr.discarded = true;
          ++discarded;
        }
      }
    }
    next.clear();
    for (const int i : pending) {
      const int f = sample_frag[i];
      if (f < 0 || (!frags[f].discarded && ((frags[f].keep >> (i % N)) & 1u))) continue;
      sample_frag[i] = -1;
      tnear[i] = ContinuePast(hits[i].t);
      if (layer + 1 < kMaxAlphaLayers) next.push_back(i);
    }
    if (next.empty()) break;
    const int n = static_cast<int>(next.size());
    Hit* lh = Sized(S.layer_hits, static_cast<size_t>(n));
    IntersectRays(im.scene, org, dir, tnear, tfar, next.data(), n, lh, false);
    local.primary_rays += static_cast<uint64_t>(n);
    local.coverage_rays += static_cast<uint64_t>(n);
    for (int k = 0; k < n; ++k) hits[next[static_cast<size_t>(k)]] = lh[k];
    pending.swap(next);
  }

  // 4. One shading evaluation per kept fragment, copied to its samples.
  const size_t nf = frags.size();
  int* shade_index = Sized(S.shade_index, nf);
  Hit* shade_hits = Sized(S.shade_hits, nf);
  glm::vec3* shade_org = Sized(S.shade_org, nf);
  glm::vec3* shade_dir = Sized(S.shade_dir, nf);
  int n_shade = 0;
  for (size_t f = 0; f < nf; ++f) {
    shade_index[f] = -1;
    if (frags[f].discarded) continue;
    shade_index[f] = n_shade;
    shade_hits[n_shade] = frags[f].hit;
    shade_org[n_shade] = frags[f].org;
    shade_dir[n_shade] = frags[f].dir;
    ++n_shade;
  }
  SampleResult* shaded = Sized(S.shade_out, nf);
  ShadeHits(im, sc, alpha, shade_hits, shade_org, shade_dir, n_shade, S.shade, shaded, local, fp);
  CompositeBlended(im, sc, alpha, shade_hits, shade_org, shade_dir, n_shade, shaded, local, fp);
  local.shading_evals += discarded;  // a discarded fragment ran its shader up to the alpha test
  SampleResult background;
  background.rgb[0] = sc.background.x;
  background.rgb[1] = sc.background.y;
  background.rgb[2] = sc.background.z;
  for (int i = 0; i < count; ++i) {
    const int f = sample_frag[i];
    out[i] = f < 0 ? background : shaded[shade_index[f]];
  }
  if (shading_evals) {
    for (int p = 0; p < pixels; ++p) {
      uint32_t k = 0;
      for (int f = pixel_head[p]; f >= 0; f = frags[f].next) ++k;
      shading_evals[p] = k;
    }
  }
  if (counters) *counters += local;
}

}  // namespace aalab
