// Image textures: decoding through OpenImageIO, box-filtered mip chains, wrap modes,
// bilinear / trilinear / anisotropic sampling (scenes/texture_image.h).
#include "scenes/texture_image.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>

#include "core/color.h"
#include "core/error.h"

namespace aalab {

size_t MipChain::Bytes() const {
  size_t n = 0;
  for (const MipLevel& l : levels) n += l.texels.size() * sizeof(glm::vec4);
  return n;
}

size_t MipChain::Bytes8() const { return Bytes() / 4; }

MipChain BuildMipChain(MipLevel level0, std::string name) {
  MipChain chain;
  chain.name = std::move(name);
  chain.levels.push_back(std::move(level0));
  while (chain.levels.back().width > 1 || chain.levels.back().height > 1) {
    const MipLevel& src = chain.levels.back();
    MipLevel dst;
    dst.width = std::max(1, src.width / 2);
    dst.height = std::max(1, src.height / 2);
    dst.texels.assign(static_cast<size_t>(dst.width) * dst.height, glm::vec4(0.0f));
    for (int y = 0; y < dst.height; ++y) {
      // Source rows of this texel: 2y, 2y+1, plus the odd last row on the last texel.
      const int y0 = std::min(2 * y, src.height - 1);
      const int y1 = (y == dst.height - 1) ? src.height - 1 : std::min(2 * y + 1, src.height - 1);
      for (int x = 0; x < dst.width; ++x) {
        const int x0 = std::min(2 * x, src.width - 1);
        const int x1 = (x == dst.width - 1) ? src.width - 1 : std::min(2 * x + 1, src.width - 1);
        glm::dvec4 sum(0.0);
        int n = 0;
        for (int sy = y0; sy <= y1; ++sy) {
          for (int sx = x0; sx <= x1; ++sx) {
            sum += glm::dvec4(src.texels[static_cast<size_t>(sy) * src.width + sx]);
            ++n;
          }
        }
        dst.texels[static_cast<size_t>(y) * dst.width + x] = glm::vec4(sum / static_cast<double>(n));
      }
    }
    chain.levels.push_back(std::move(dst));
  }
  return chain;
}

namespace {

std::unique_ptr<OIIO::ImageInput> OpenImage(OIIO::Filesystem::IOMemReader& mem, const std::string& name,
                                            const std::string& path, const uint8_t* data, const std::string& hint) {
  std::unique_ptr<OIIO::ImageInput> in;
  if (data) {
    const std::string fake = "embedded." + (hint.empty() ? std::string("png") : hint);
    OIIO::ImageSpec config;
    void* proxy = &mem;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    in = OIIO::ImageInput::open(fake, &config, &mem);
  } else {
    in = OIIO::ImageInput::open(path);
  }
  if (!in) {
    const std::string why = OIIO::geterror();
    throw UserError("texture " + name + " cannot be decoded" + (why.empty() ? std::string() : ": " + why));
  }
  return in;
}

}  // namespace

size_t TextureHeader::Bytes8Chain() const {
  size_t n = 0;
  for (int w = width, h = height;; w = std::max(1, w / 2), h = std::max(1, h / 2)) {
    n += static_cast<size_t>(w) * static_cast<size_t>(h) * 4;
    if (w == 1 && h == 1) break;
  }
  return n;
}

TextureHeader ProbeTextureImage(const std::string& name, const std::string& path, const uint8_t* data, size_t size,
                                const std::string& hint) {
  OIIO::Filesystem::IOMemReader mem(const_cast<uint8_t*>(data), size);
  const std::unique_ptr<OIIO::ImageInput> in = OpenImage(mem, name, path, data, hint);
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.width > kMaxTextureSize || spec.height > kMaxTextureSize) {
    throw UserError("texture " + name + " has size " + std::to_string(spec.width) + "x" +
                    std::to_string(spec.height) + " (allowed: 1 to " + std::to_string(kMaxTextureSize) +
                    " texels a side)");
  }
  if (spec.nchannels < 1 || spec.nchannels > 4) {
    throw UserError("texture " + name + " has " + std::to_string(spec.nchannels) + " channels (allowed: 1 to 4)");
  }
  return {spec.width, spec.height, spec.nchannels};
}

MipLevel DecodeTextureImage(const std::string& name, const std::string& path, const uint8_t* data, size_t size,
                            const std::string& hint, bool srgb) {
  // The memory reader outlives the input (declared first, destroyed last). OpenImageIO 2.4's
  // PNG/JPEG readers take the proxy from the configuration's "oiio:ioproxy" attribute.
  OIIO::Filesystem::IOMemReader mem(const_cast<uint8_t*>(data), size);
  std::unique_ptr<OIIO::ImageInput> in;
  if (data) {
    const std::string fake = "embedded." + (hint.empty() ? std::string("png") : hint);
    OIIO::ImageSpec config;
    void* proxy = &mem;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    in = OIIO::ImageInput::open(fake, &config, &mem);
  } else {
    in = OIIO::ImageInput::open(path);
  }
  if (!in) {
    const std::string why = OIIO::geterror();
    throw UserError("texture " + name + " cannot be decoded" + (why.empty() ? std::string() : ": " + why));
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.width > kMaxTextureSize || spec.height > kMaxTextureSize) {
    throw UserError("texture " + name + " has size " + std::to_string(spec.width) + "x" +
                    std::to_string(spec.height) + " (allowed: 1 to " + std::to_string(kMaxTextureSize) +
                    " texels a side)");
  }
  const int nc = spec.nchannels;
  if (nc < 1 || nc > 4) {
    throw UserError("texture " + name + " has " + std::to_string(nc) + " channels (allowed: 1 to 4)");
  }
  std::vector<float> raw(static_cast<size_t>(spec.width) * spec.height * nc);
  if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, raw.data())) {
    throw UserError("texture " + name + " cannot be decoded: " + in->geterror());
  }
  MipLevel level;
  level.width = spec.width;
  level.height = spec.height;
  level.texels.resize(static_cast<size_t>(spec.width) * spec.height);
  for (size_t i = 0; i < level.texels.size(); ++i) {
    const float* p = &raw[i * nc];
    glm::vec4 t;
    if (nc <= 2) {
      t = glm::vec4(p[0], p[0], p[0], nc == 2 ? p[1] : 1.0f);
    } else {
      t = glm::vec4(p[0], p[1], p[2], nc == 4 ? p[3] : 1.0f);
    }
    for (int c = 0; c < 4; ++c) {
      if (!std::isfinite(t[c])) throw UserError("texture " + name + " has a non-finite texel");
    }
    if (srgb) {
      for (int c = 0; c < 3; ++c) t[c] = SrgbDecode(t[c]);
    }
    level.texels[i] = t;
  }
  return level;
}

float MipLambda(const UvDerivs& d, int width, int height) {
  const float w = static_cast<float>(width), h = static_cast<float>(height);
  const float lx = std::hypot(d.dx.x * w, d.dx.y * h);
  const float ly = std::hypot(d.dy.x * w, d.dy.y * h);
  const float rho = std::max(lx, ly);
  return std::log2(rho);
}

int WrapIndex(int i, int n, WrapMode mode) {
  switch (mode) {
    case WrapMode::kRepeat: {
      const int r = i % n;
      return r < 0 ? r + n : r;
    }
    case WrapMode::kClampToEdge:
      return std::clamp(i, 0, n - 1);
    case WrapMode::kMirroredRepeat: {
      const int period = 2 * n;
      int r = i % period;
      if (r < 0) r += period;
      return r < n ? r : period - 1 - r;
    }
  }
  return 0;
}

namespace {

/// A texel coordinate far outside the texture would overflow int: fold it into one repeat
/// period (or clamp) in double first, which changes no texel it selects.
double FoldCoord(double x, int n, WrapMode mode) {
  if (std::fabs(x) < 1e8) return x;
  if (mode == WrapMode::kClampToEdge) return x < 0 ? -1.0 : static_cast<double>(n);
  const double period = mode == WrapMode::kRepeat ? n : 2.0 * n;
  return x - std::floor(x / period) * period;
}

}  // namespace

glm::vec4 SampleBilinear(const MipLevel& level, glm::vec2 uv, WrapMode wrap_s, WrapMode wrap_t) {
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return level.texels[0];
  const double x = FoldCoord(static_cast<double>(uv.x) * level.width - 0.5, level.width, wrap_s);
  const double y = FoldCoord(static_cast<double>(uv.y) * level.height - 0.5, level.height, wrap_t);
  const double fx = std::floor(x), fy = std::floor(y);
  const float ax = static_cast<float>(x - fx), ay = static_cast<float>(y - fy);
  const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
  const int i0 = WrapIndex(x0, level.width, wrap_s), i1 = WrapIndex(x0 + 1, level.width, wrap_s);
  const int j0 = WrapIndex(y0, level.height, wrap_t), j1 = WrapIndex(y0 + 1, level.height, wrap_t);
  auto at = [&](int i, int j) { return level.texels[static_cast<size_t>(j) * level.width + i]; };
  const glm::vec4 top = at(i0, j0) * (1.0f - ax) + at(i1, j0) * ax;
  const glm::vec4 bot = at(i0, j1) * (1.0f - ax) + at(i1, j1) * ax;
  return top * (1.0f - ay) + bot * ay;
}

namespace {

glm::vec4 SampleLevelLerp(const MipChain& chain, glm::vec2 uv, float lambda, WrapMode ws, WrapMode wt) {
  const int last = static_cast<int>(chain.levels.size()) - 1;
  if (!(lambda > 0.0f)) return SampleBilinear(chain.levels[0], uv, ws, wt);  // magnification, NaN
  if (lambda >= static_cast<float>(last)) return SampleBilinear(chain.levels[last], uv, ws, wt);
  const int l0 = static_cast<int>(std::floor(lambda));
  const float f = lambda - static_cast<float>(l0);
  const glm::vec4 a = SampleBilinear(chain.levels[l0], uv, ws, wt);
  if (f == 0.0f) return a;
  const glm::vec4 b = SampleBilinear(chain.levels[l0 + 1], uv, ws, wt);
  return a * (1.0f - f) + b * f;
}

}  // namespace

glm::vec4 SampleTexture(const MipChain& chain, glm::vec2 uv, const UvDerivs& d, WrapMode wrap_s, WrapMode wrap_t,
                        const TextureFilter& filter) {
  if (filter.level0_only) return SampleBilinear(chain.levels[0], uv, wrap_s, wrap_t);
  const MipLevel& l0 = chain.levels[0];
  if (filter.max_aniso <= 1) return SampleLevelLerp(chain, uv, MipLambda(d, l0.width, l0.height), wrap_s, wrap_t);
  // Anisotropic: N probes along the major axis, each with the level of the minor axis
  // stretched so that N probes cover the major one (the EXT_texture_filter_anisotropic rule).
  const float w = static_cast<float>(l0.width), h = static_cast<float>(l0.height);
  const float lx = std::hypot(d.dx.x * w, d.dx.y * h);
  const float ly = std::hypot(d.dy.x * w, d.dy.y * h);
  const float pmax = std::max(lx, ly), pmin = std::min(lx, ly);
  if (!(pmax > 0.0f) || !std::isfinite(pmax)) return SampleLevelLerp(chain, uv, MipLambda(d, l0.width, l0.height), wrap_s, wrap_t);
  const float ratio = pmin > 0.0f ? pmax / pmin : static_cast<float>(filter.max_aniso);
  const int n = std::clamp(static_cast<int>(std::ceil(ratio)), 1, filter.max_aniso);
  const float lambda = std::log2(pmax / static_cast<float>(n));
  const glm::vec2 major = lx >= ly ? d.dx : d.dy;
  glm::vec4 sum(0.0f);
  for (int k = 0; k < n; ++k) {
    const float t = (static_cast<float>(k) + 0.5f) / static_cast<float>(n) - 0.5f;
    sum += SampleLevelLerp(chain, uv + major * t, lambda, wrap_s, wrap_t);
  }
  return sum / static_cast<float>(n);
}

SamplerFilter SamplerFilterOf(int mag, int min) {
  SamplerFilter f;
  f.mag_nearest = mag == 9728;
  f.min_nearest = min == 9728 || min == 9984 || min == 9986;
  f.mip = (min == 9728 || min == 9729) ? SamplerFilter::Mip::kNone
          : (min == 9984 || min == 9985) ? SamplerFilter::Mip::kNearest
                                         : SamplerFilter::Mip::kLinear;
  return f;
}

glm::vec4 SampleNearest(const MipLevel& level, glm::vec2 uv, WrapMode wrap_s, WrapMode wrap_t) {
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return level.texels[0];
  const double x = FoldCoord(static_cast<double>(uv.x) * level.width, level.width, wrap_s);
  const double y = FoldCoord(static_cast<double>(uv.y) * level.height, level.height, wrap_t);
  const int i = WrapIndex(static_cast<int>(std::floor(x)), level.width, wrap_s);
  const int j = WrapIndex(static_cast<int>(std::floor(y)), level.height, wrap_t);
  return level.texels[static_cast<size_t>(j) * level.width + i];
}

glm::vec4 SampleTextureFiltered(const MipChain& chain, glm::vec2 uv, const UvDerivs& d, WrapMode wrap_s,
                                WrapMode wrap_t, const SamplerFilter& sampler, const TextureFilter& filter) {
  if (sampler == SamplerFilter{}) return SampleTexture(chain, uv, d, wrap_s, wrap_t, filter);
  auto tap = [&](const MipLevel& l, bool nearest) {
    return nearest ? SampleNearest(l, uv, wrap_s, wrap_t) : SampleBilinear(l, uv, wrap_s, wrap_t);
  };
  if (filter.level0_only) return tap(chain.levels[0], sampler.mag_nearest);
  const MipLevel& l0 = chain.levels[0];
  const float lambda = MipLambda(d, l0.width, l0.height);
  if (!(lambda > 0.0f)) return tap(l0, sampler.mag_nearest);  // magnification (and NaN)
  const int last = static_cast<int>(chain.levels.size()) - 1;
  switch (sampler.mip) {
    case SamplerFilter::Mip::kNone:
      return tap(l0, sampler.min_nearest);
    case SamplerFilter::Mip::kNearest: {
      // OpenGL 4.6 eq. 8.13: level ⌈λ + ½⌉ − 1 (round half down), clamped to the chain.
      const int k = std::clamp(static_cast<int>(std::ceil(lambda + 0.5f)) - 1, 0, last);
      return tap(chain.levels[static_cast<size_t>(k)], sampler.min_nearest);
    }
    case SamplerFilter::Mip::kLinear:
      break;
  }
  if (lambda >= static_cast<float>(last)) return tap(chain.levels[static_cast<size_t>(last)], sampler.min_nearest);
  const int k = static_cast<int>(std::floor(lambda));
  const float f = lambda - static_cast<float>(k);
  const glm::vec4 a = tap(chain.levels[static_cast<size_t>(k)], sampler.min_nearest);
  if (f == 0.0f) return a;
  return a * (1.0f - f) + tap(chain.levels[static_cast<size_t>(k) + 1], sampler.min_nearest) * f;
}

}  // namespace aalab
