#include "gpu/texture_probe.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>
#include <vector>

#include "core/hash.h"
#include "core/sampler.h"
#include "methods/cuda/post_filters_cuda.h"

namespace aalab {
namespace {

__global__ void ProbeKernel(cudaTextureObject_t lin, float* out, int n) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i > n) return;
  out[i] = tex2D<float4>(lin, 0.5f + static_cast<float>(i) / static_cast<float>(n), 0.5f).x;
}

// Row a of a 512×256 texture holds (a, b) at texels (2b, 2b+1): fetch at u = 2b + 1, the
// midpoint of their centres; also the point fetch of texel (2b+1, a) = b.
__global__ void PairKernel(cudaTextureObject_t lin, cudaTextureObject_t pt, float* half, float* point) {
  const int b = blockIdx.x * blockDim.x + threadIdx.x;
  const int a = blockIdx.y;
  if (b >= 256) return;
  half[a * 256 + b] = tex2D<float4>(lin, 2.0f * b + 1.0f, a + 0.5f).x;
  point[a * 256 + b] = tex2D<float4>(pt, 2.0f * b + 1.5f, a + 0.5f).x;
}

}  // namespace

TextureProbe ProbeTextureFilter() {
  constexpr int kN = 4096;
  cuda::GpuFrame frame(2, 1);
  const uint8_t texels[8] = {0, 0, 0, 255, 255, 0, 0, 255};
  frame.Upload(texels);
  float* d = nullptr;
  cuda::Check(cudaMalloc(&d, (kN + 1) * sizeof(float)), "cudaMalloc");
  ProbeKernel<<<(kN + 256) / 256, 256>>>(frame.LinearPx(), d, kN);
  cuda::Check(cudaGetLastError(), "probe launch");
  std::vector<float> h(kN + 1);
  cuda::Check(cudaMemcpy(h.data(), d, h.size() * sizeof(float), cudaMemcpyDeviceToHost), "probe download");
  cudaFree(d);
  TextureProbe p;
  p.samples = kN + 1;
  std::set<float> distinct;
  for (int i = 0; i <= kN; ++i) {
    const double f = static_cast<double>(i) / kN;
    const double g = h[i] * 255.0;
    p.err_float = std::max(p.err_float, std::fabs(g - f * 255.0));
    p.err_round256 = std::max(p.err_round256, std::fabs(g - std::round(f * 256.0) / 256.0 * 255.0));
    p.err_trunc256 = std::max(p.err_trunc256, std::fabs(g - std::floor(f * 256.0) / 256.0 * 255.0));
    distinct.insert(h[i]);
  }
  p.distinct_values = static_cast<int>(distinct.size());

  cuda::GpuFrame pairs(512, 256);
  std::vector<uint8_t> tex(512 * 256 * 4, 255);
  for (int a = 0; a < 256; ++a) {
    for (int b = 0; b < 256; ++b) {
      tex[(a * 512 + 2 * b) * 4] = static_cast<uint8_t>(a);
      tex[(a * 512 + 2 * b + 1) * 4] = static_cast<uint8_t>(b);
    }
  }
  pairs.Upload(tex.data());
  float *dh = nullptr, *dp = nullptr;
  cuda::Check(cudaMalloc(reinterpret_cast<void**>(&dh), 65536 * sizeof(float)), "cudaMalloc");
  cuda::Check(cudaMalloc(reinterpret_cast<void**>(&dp), 65536 * sizeof(float)), "cudaMalloc");
  PairKernel<<<dim3(1, 256), 256>>>(pairs.LinearPx(), pairs.Point(), dh, dp);
  cuda::Check(cudaGetLastError(), "pair probe launch");
  std::vector<float> hh(65536), hp(65536);
  cuda::Check(cudaMemcpy(hh.data(), dh, hh.size() * sizeof(float), cudaMemcpyDeviceToHost), "probe download");
  cuda::Check(cudaMemcpy(hp.data(), dp, hp.size() * sizeof(float), cudaMemcpyDeviceToHost), "probe download");
  cudaFree(dh);
  cudaFree(dp);
  for (int b = 0; b < 256; ++b) {
    if (hp[b] != static_cast<float>(b) / 255.0f) ++p.unorm_mismatches;
    if (hp[b] != UnormToFloat(static_cast<uint8_t>(b))) ++p.unorm_mismatches_cpu;
  }
  for (int a = 0; a < 256; ++a) {
    for (int b = 0; b < 256; ++b) {
      // BilinearSampler::Sample at fractions (0.5, 0): BilinearBlend = lerp(lerp(a, b, 0.5),
      // lerp(a', b', 0.5), 0) = a + 0.5·(b − a), texels UnormToFloat.
      const float fa = UnormToFloat(static_cast<uint8_t>(a)), fb = UnormToFloat(static_cast<uint8_t>(b));
      const float cpu = FilterLerp(fa, fb, 0.5f);
      const float gpu = hh[a * 256 + b];
      ++p.half_pairs;
      if (gpu != cpu) ++p.half_mismatches;
      p.half_max_err = std::max(p.half_max_err, std::fabs(static_cast<double>(gpu) - cpu));
    }
  }
  return p;
}

}  // namespace aalab

// ---------------------------------------------------------------------------------------
// Raw probe data (texture_probe.h): collected once, written as files and checked against the
// rule of core/sampler.h.

namespace aalab {
namespace {

constexpr int kQuad8W = 1024, kQuad8H = 512, kQuad8N = 262144;
constexpr int kQuadFW = 256, kQuadFH = 256, kQuadFN = 131072;

__global__ void PairWeightKernel(cudaTextureObject_t lin, const int* ks, int nk, float* out) {
  const int b = blockIdx.x * blockDim.x + threadIdx.x;
  const int a = blockIdx.y;
  const int k = blockIdx.z;
  if (b >= 256 || k >= nk) return;
  const float u = 2.0f * b + 0.5f + static_cast<float>(ks[k]) * (1.0f / 256.0f);
  out[(static_cast<size_t>(k) * 256 + a) * 256 + b] = tex2D<float4>(lin, u, a + 0.5f).x;
}

__global__ void QuadKernel(cudaTextureObject_t lin, const short4* p, float4* out, int n) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const short4 q = p[i];
  out[i] = tex2D<float4>(lin, q.x + 0.5f + q.z * (1.0f / 256.0f), q.y + 0.5f + q.w * (1.0f / 256.0f));
}

// axis 0: the coordinate is u (v at the centre of row 0); axis 1: it is v (u at column 0).
__global__ void CoordKernel(cudaTextureObject_t t, const float* c, float* out, int n, int axis, float centre) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const float4 r = axis == 0 ? tex2D<float4>(t, c[i], centre) : tex2D<float4>(t, centre, c[i]);
  out[i] = r.x;
}

void WriteFile(const std::string& path, const void* data, size_t bytes) {
  std::ofstream f(path, std::ios::binary);
  f.write(static_cast<const char*>(data), static_cast<std::streamsize>(bytes));
  if (!f) throw std::runtime_error("cannot write " + path);
}

template <class T>
T* DeviceCopy(const std::vector<T>& v) {
  T* d = nullptr;
  cuda::Check(cudaMalloc(reinterpret_cast<void**>(&d), v.size() * sizeof(T)), "cudaMalloc");
  cuda::Check(cudaMemcpy(d, v.data(), v.size() * sizeof(T), cudaMemcpyHostToDevice), "upload");
  return d;
}

template <class T>
std::vector<T> HostCopy(const T* d, size_t n) {
  std::vector<T> v(n);
  cuda::Check(cudaMemcpy(v.data(), d, n * sizeof(T), cudaMemcpyDeviceToHost), "download");
  return v;
}

template <class T>
void Append(std::vector<char>& buf, const T& v) {
  const char* p = reinterpret_cast<const char*>(&v);
  buf.insert(buf.end(), p, p + sizeof(T));
}

// Random fetch positions: texel (x, y) in [0, w−2] × [0, h−2], 8-bit fractions kx, ky.
std::vector<short4> QuadPositions(int n, int w, int h, uint32_t salt) {
  std::vector<short4> p(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const uint32_t a = MixBits32(static_cast<uint32_t>(i) * 2654435761U + salt);
    const uint32_t g = MixBits32(a ^ 0x85ebca6bU);
    p[i] = make_short4(static_cast<short>(a % (w - 1)), static_cast<short>((a >> 16) % (h - 1)),
                       static_cast<short>(g & 255), static_cast<short>((g >> 8) & 255));
  }
  return p;
}

std::vector<float4> FetchQuads(cudaTextureObject_t t, const std::vector<short4>& p) {
  short4* dp = DeviceCopy(p);
  float4* dout = nullptr;
  cuda::Check(cudaMalloc(reinterpret_cast<void**>(&dout), p.size() * sizeof(float4)), "cudaMalloc");
  const int n = static_cast<int>(p.size());
  QuadKernel<<<(n + 255) / 256, 256>>>(t, dp, dout, n);
  cuda::Check(cudaGetLastError(), "quad launch");
  std::vector<float4> out = HostCopy(dout, p.size());
  cudaFree(dp);
  cudaFree(dout);
  return out;
}

// The coordinates probed along one axis of a texture of `size` texels: sweeps in 1/1024
// steps over [−3, 5] and [size − 8, size + 3], with each multiple of 1/512 there and its two
// float neighbours (the rounding ties); as normalised coordinates these are divided by the
// size, plus 16 384 hashed ones in [−0.01, 1.01].
std::vector<float> AxisCoords(int size, bool normalized) {
  std::vector<float> us;
  for (const float lo : {-3.0f, static_cast<float>(size - 8)}) {
    const float hi = lo < 0.0f ? 5.0f : static_cast<float>(size + 3);
    for (float u = lo; u <= hi; u += 1.0f / 1024.0f) us.push_back(u);
    for (int n = static_cast<int>(lo) * 512; n <= static_cast<int>(hi) * 512; ++n) {
      const float t = static_cast<float>(n) / 512.0f;
      us.push_back(std::nextafter(t, -1e9f));
      us.push_back(t);
      us.push_back(std::nextafter(t, 1e9f));
    }
  }
  if (!normalized) return us;
  std::vector<float> ss;
  for (float u : us) ss.push_back(u / static_cast<float>(size));
  for (uint32_t i = 0; i < 16384; ++i) {
    ss.push_back(-0.01f +
                 1.02f * static_cast<float>(MixBits32(i + 77U * static_cast<uint32_t>(size)) >> 8) / 16777216.0f);
  }
  return ss;
}

}  // namespace

TextureProbeData CollectTextureProbeData() {
  TextureProbeData d;
  // Pairs at fixed weights.
  d.pair_weights = {1, 2, 3, 4, 5, 16, 17, 37, 64, 85, 100, 127, 128, 129, 171, 200, 254, 255};
  {
    cuda::GpuFrame pairs(512, 256);
    std::vector<uint8_t> tex(512 * 256 * 4, 255);
    for (int a = 0; a < 256; ++a) {
      for (int b = 0; b < 256; ++b) {
        tex[(a * 512 + 2 * b) * 4] = static_cast<uint8_t>(a);
        tex[(a * 512 + 2 * b + 1) * 4] = static_cast<uint8_t>(b);
      }
    }
    pairs.Upload(tex.data());
    int* dk = DeviceCopy(d.pair_weights);
    const int nk = static_cast<int>(d.pair_weights.size());
    const size_t n = static_cast<size_t>(nk) * 65536;
    float* dout = nullptr;
    cuda::Check(cudaMalloc(reinterpret_cast<void**>(&dout), n * sizeof(float)), "cudaMalloc");
    PairWeightKernel<<<dim3(1, 256, static_cast<unsigned>(nk)), 256>>>(pairs.LinearPx(), dk, nk, dout);
    cuda::Check(cudaGetLastError(), "pair weight launch");
    d.pairs = HostCopy(dout, n);
    cudaFree(dk);
    cudaFree(dout);
  }
  // 2-D fetches of an RGBA8 texture at random 8-bit fractions.
  {
    d.quad8_tex.resize(static_cast<size_t>(kQuad8W) * kQuad8H * 4);
    for (size_t i = 0; i < d.quad8_tex.size(); ++i) {
      d.quad8_tex[i] = static_cast<uint8_t>(MixBits32(static_cast<uint32_t>(i) ^ 0x9e3779b9U) >> 24);
    }
    cuda::GpuFrame f(kQuad8W, kQuad8H);
    f.Upload(d.quad8_tex.data());
    const std::vector<short4> p = QuadPositions(kQuad8N, kQuad8W, kQuad8H, 17U);
    const std::vector<float4> out = FetchQuads(f.LinearPx(), p);
    for (int i = 0; i < kQuad8N; ++i) {
      d.quad8.push_back({p[i].x, p[i].y, p[i].z, p[i].w, {out[i].x, out[i].y, out[i].z, out[i].w}});
    }
  }
  // Coordinates → weights, along x and y, unnormalised and normalised, through textures of
  // several sizes whose texels alternate 0 and 255 along the probed axis.
  for (int size : {16, 97, 1080, 1920, 2160, 2560, 3840, 5120}) {
    for (int axis = 0; axis < 2; ++axis) {
      const int w = axis == 0 ? size : 1, h = axis == 0 ? 1 : size;
      cuda::GpuFrame f(w, h);
      std::vector<uint8_t> tex(static_cast<size_t>(size) * 4, 255);
      for (int x = 0; x < size; ++x) tex[static_cast<size_t>(x) * 4] = (x & 1) ? 255 : 0;
      f.Upload(tex.data());
      for (int normalized = 0; normalized < 2; ++normalized) {
        const std::vector<float> cs = AxisCoords(size, normalized != 0);
        float* dc = DeviceCopy(cs);
        float* dout = nullptr;
        cuda::Check(cudaMalloc(reinterpret_cast<void**>(&dout), cs.size() * sizeof(float)), "cudaMalloc");
        const int n = static_cast<int>(cs.size());
        CoordKernel<<<(n + 255) / 256, 256>>>(normalized ? f.LinearNorm() : f.LinearPx(), dc, dout, n, axis,
                                              normalized ? 0.5f : 0.5f);
        cuda::Check(cudaGetLastError(), "coordinate probe launch");
        const std::vector<float> out = HostCopy(dout, cs.size());
        cudaFree(dc);
        cudaFree(dout);
        for (int i = 0; i < n; ++i) d.coords.push_back({size, axis, normalized, cs[i], out[i]});
      }
    }
  }
  // 2-D fetches of an RGBA32F texture (values in [0, 1)).
  {
    d.quadf_tex.resize(static_cast<size_t>(kQuadFW) * kQuadFH * 4);
    for (size_t i = 0; i < d.quadf_tex.size(); ++i) {
      d.quadf_tex[i] = static_cast<float>(MixBits32(static_cast<uint32_t>(i) + 12345U) >> 8) / 16777216.0f;
    }
    cudaArray_t arr = nullptr;
    const cudaChannelFormatDesc desc = cudaCreateChannelDesc<float4>();
    cuda::Check(cudaMallocArray(&arr, &desc, kQuadFW, kQuadFH), "cudaMallocArray");
    cuda::Check(
        cudaMemcpy2DToArray(arr, 0, 0, d.quadf_tex.data(), kQuadFW * 16, kQuadFW * 16, kQuadFH, cudaMemcpyHostToDevice),
        "upload");
    cudaResourceDesc res{};
    res.resType = cudaResourceTypeArray;
    res.res.array.array = arr;
    cudaTextureDesc td{};
    td.addressMode[0] = cudaAddressModeClamp;
    td.addressMode[1] = cudaAddressModeClamp;
    td.filterMode = cudaFilterModeLinear;
    td.readMode = cudaReadModeElementType;
    cudaTextureObject_t t = 0;
    cuda::Check(cudaCreateTextureObject(&t, &res, &td, nullptr), "cudaCreateTextureObject");
    const std::vector<short4> p = QuadPositions(kQuadFN, kQuadFW, kQuadFH, 3U);
    const std::vector<float4> out = FetchQuads(t, p);
    cudaDestroyTextureObject(t);
    cudaFreeArray(arr);
    for (int i = 0; i < kQuadFN; ++i) {
      d.quadf.push_back({p[i].x, p[i].y, p[i].z, p[i].w, {out[i].x, out[i].y, out[i].z, out[i].w}});
    }
  }
  return d;
}

void WriteTextureProbeData(const TextureProbeData& d, const std::string& dir) {
  std::filesystem::create_directories(dir);
  std::vector<char> buf;
  Append(buf, static_cast<int32_t>(d.pair_weights.size()));
  for (int k : d.pair_weights) Append(buf, static_cast<int32_t>(k));
  for (float v : d.pairs) Append(buf, v);
  WriteFile(dir + "/pairs.bin", buf.data(), buf.size());
  WriteFile(dir + "/quad8_tex.bin", d.quad8_tex.data(), d.quad8_tex.size());
  buf.clear();
  for (const auto& q : d.quad8) {
    for (int16_t v : {q.x, q.y, q.kx, q.ky}) Append(buf, v);
    for (float v : q.out) Append(buf, v);
  }
  WriteFile(dir + "/quad8.bin", buf.data(), buf.size());
  buf.clear();
  // Blocks of one size, axis and kind: int32 size, axis, normalized, count, then count float
  // coordinates and count uint16 results q (the result is q/65535, exactly recoverable).
  for (size_t i = 0; i < d.coords.size();) {
    size_t j = i;
    while (j < d.coords.size() && d.coords[j].size == d.coords[i].size && d.coords[j].axis == d.coords[i].axis &&
           d.coords[j].normalized == d.coords[i].normalized) {
      ++j;
    }
    for (int32_t v : {d.coords[i].size, d.coords[i].axis, d.coords[i].normalized, static_cast<int32_t>(j - i)}) {
      Append(buf, v);
    }
    for (size_t k = i; k < j; ++k) Append(buf, d.coords[k].coord);
    for (size_t k = i; k < j; ++k) {
      Append(buf, static_cast<uint16_t>(std::lround(static_cast<double>(d.coords[k].out) * 65535.0)));
    }
    i = j;
  }
  WriteFile(dir + "/coord.bin", buf.data(), buf.size());
  WriteFile(dir + "/quadf_tex.bin", d.quadf_tex.data(), d.quadf_tex.size() * sizeof(float));
  buf.clear();
  for (const auto& q : d.quadf) {
    for (int16_t v : {q.x, q.y, q.kx, q.ky}) Append(buf, v);
    for (float v : q.out) Append(buf, v);
  }
  WriteFile(dir + "/quadf.bin", buf.data(), buf.size());
}

TextureRuleCheck CheckTextureRule(const TextureProbeData& d) {
  TextureRuleCheck r;
  const size_t nk = d.pair_weights.size();
  for (size_t i = 0; i < nk; ++i) {
    const HwWeights w = HwWeightsOf(d.pair_weights[i], 0);
    for (int a = 0; a < 256; ++a) {
      for (int b = 0; b < 256; ++b) {
        const float rule = HwFilter8(static_cast<uint8_t>(a), static_cast<uint8_t>(b), 0, 0, w);
        ++r.pairs;
        if (rule != d.pairs[(i * 256 + a) * 256 + b]) ++r.pair_mismatches;
      }
    }
  }
  for (const auto& q : d.quad8) {
    const uint8_t* t = d.quad8_tex.data();
    auto at = [&](int x, int y, int c) { return t[(static_cast<size_t>(y) * kQuad8W + x) * 4 + c]; };
    const HwWeights w = HwWeightsOf(q.kx, q.ky);
    for (int c = 0; c < 4; ++c) {
      const float rule =
          HwFilter8(at(q.x, q.y, c), at(q.x + 1, q.y, c), at(q.x, q.y + 1, c), at(q.x + 1, q.y + 1, c), w);
      ++r.quad8;
      if (rule != q.out[c]) ++r.quad8_mismatches;
    }
  }
  for (const auto& c : d.coords) {
    // The texels alternate 0 (even) and 255 (odd) along the axis; a 1-texel-wide other axis.
    const HwFootprint f = c.normalized ? HwFootprintNormalized(c.coord, c.coord, c.size, c.size)
                                       : HwFootprintAt(c.coord, c.coord, c.size, c.size);
    auto texel = [&](int x) { return static_cast<uint8_t>((std::clamp(x, 0, c.size - 1) & 1) ? 255 : 0); };
    const float rule = HwFilter8(texel(f.x0), texel(f.x0 + 1), 0, 0, HwWeightsOf(f.kx, 0));
    ++r.coords;
    if (rule != c.out) {
      if (r.coord_mismatches < 8) {
        std::fprintf(stderr, "texture rule: size %d axis %d %s coordinate %.9g: GPU %.9g, rule %.9g\n", c.size, c.axis,
                     c.normalized ? "normalised" : "texel", c.coord, c.out, rule);
      }
      ++r.coord_mismatches;
    }
  }
  for (const auto& q : d.quadf) {
    const float* t = d.quadf_tex.data();
    auto at = [&](int x, int y, int c) { return t[(static_cast<size_t>(y) * kQuadFW + x) * 4 + c]; };
    const HwWeights w = HwWeightsOf(q.kx, q.ky);
    for (int c = 0; c < 4; ++c) {
      const float rule =
          HwFilterFloat(at(q.x, q.y, c), at(q.x + 1, q.y, c), at(q.x, q.y + 1, c), at(q.x + 1, q.y + 1, c), w);
      ++r.quadf;
      if (rule != q.out[c]) ++r.quadf_mismatches;
    }
  }
  return r;
}

}  // namespace aalab
