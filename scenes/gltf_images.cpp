// glTF images (scenes/gltf_load.h, gltf_detail::ReadGltfImages): where each image's bytes are
// (a file, a buffer view, a data URI), every header read and the file's RGBA8 budget summed
// before the first texel is decoded, then the decodes and mip chains.
#include <filesystem>

#include "core/error.h"
#include "scenes/gltf_load.h"

namespace aalab {
namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

std::string At(const std::string& base, const std::string& key) { return base + "/" + key; }
std::string At(const std::string& base, size_t i) { return base + "/" + std::to_string(i); }

long long Index(const GltfDoc& d, const Json& o, const char* key, const std::string& at, const char* list) {
  const long long n = static_cast<long long>(GltfArray(d, d.j, list, "").size());
  if (!o.is_object() || !o.contains(key)) return -1;
  const Json& v = o.at(key);
  if (!v.is_number_integer() && !v.is_number_unsigned()) d.Fail(At(at, key), "must be an integer index into /" + std::string(list));
  if (v.is_number_unsigned() ? v.get<unsigned long long>() >= static_cast<unsigned long long>(n) : (v.get<long long>() < 0 || v.get<long long>() >= n)) {
    d.Fail(At(at, key), "names " + std::string(list) + " " + v.dump() + ", which does not exist (" + std::to_string(n) +
                            " defined) (rule: index out of range)");
  }
  return v.get<long long>();
}

/// Where image `index`'s bytes are: a file, or memory (bufferView or data URI).
struct ImageSource {
  std::string name, file, hint;
  std::vector<uint8_t> data;
};

ImageSource LocateImage(const GltfDoc& d, long long index) {
  const Json& im = d.j["images"][static_cast<size_t>(index)];
  const std::string at = At("/images", static_cast<size_t>(index));
  ImageSource s;
  const std::string mime = im.contains("mimeType") && im["mimeType"].is_string() ? im["mimeType"].get<std::string>() : "";
  s.hint = mime == "image/jpeg" ? "jpg" : "png";
  if (im.contains("bufferView")) {
    const long long v = Index(d, im, "bufferView", at, "bufferViews");
    size_t size = 0;
    const uint8_t* p = d.ViewBytes(v, &size);
    s.data.assign(p, p + size);
    s.name = "image " + std::to_string(index) + " embedded in '" + d.path + "'";
    return s;
  }
  if (!im.contains("uri") || !im["uri"].is_string()) d.Fail(at, "needs a uri or a bufferView");
  const std::string uri = im["uri"].get<std::string>();
  if (uri.rfind("data:", 0) == 0) {
    const size_t comma = uri.find(',');
    if (uri.rfind("data:image/jpeg", 0) == 0) s.hint = "jpg";
    static const std::string kB64 = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    uint32_t acc = 0;
    int bits = 0;
    for (size_t i = comma == std::string::npos ? uri.size() : comma + 1; i < uri.size() && uri[i] != '='; ++i) {
      const size_t v = kB64.find(uri[i]);
      if (v == std::string::npos) d.Fail(At(at, "uri"), "is a data URI that is not valid base64");
      acc = (acc << 6) | static_cast<uint32_t>(v);
      bits += 6;
      if (bits >= 8) {
        bits -= 8;
        s.data.push_back(static_cast<uint8_t>((acc >> bits) & 0xFF));
      }
    }
    s.name = "image " + std::to_string(index) + " (data URI) in '" + d.path + "'";
    return s;
  }
  const fs::path p = fs::path(d.path).parent_path() / uri;
  std::error_code ec;
  if (!fs::is_regular_file(p, ec)) d.Fail(At(at, "uri"), "image '" + p.string() + "' not found");
  s.file = p.string();
  s.name = "'" + p.string() + "'";
  return s;
}

}  // namespace

namespace gltf_detail {

void ReadGltfImages(const GltfDoc& d, const std::vector<std::pair<long long, bool>>& wanted, bool decode,
                    GltfContent& out) {
  std::vector<ImageSource> sources;
  size_t budget = 0;
  for (const auto& [img, srgb] : wanted) {
    ImageSource src = LocateImage(d, img);
    if (!src.file.empty()) out.files_read.push_back(src.file);
    if (decode) {
      const TextureHeader h = ProbeTextureImage(src.name, src.file, src.file.empty() ? src.data.data() : nullptr, src.data.size(), src.hint);
      budget += h.Bytes8Chain();
      if (budget > kMaxGltfTextureBytes8) {
        d.Fail(At("/images", static_cast<size_t>(img)), "the textures' RGBA8 mip chains exceed the budget of " +
                                                            std::to_string(kMaxGltfTextureBytes8 >> 20) + " MiB");
      }
    }
    sources.push_back(std::move(src));
  }
  if (decode) {
    for (size_t k = 0; k < sources.size(); ++k) {
      const ImageSource& src = sources[k];
      MipLevel level = DecodeTextureImage(src.name, src.file, src.file.empty() ? src.data.data() : nullptr, src.data.size(), src.hint, wanted[k].second);
      out.images.push_back(std::make_shared<const MipChain>(BuildMipChain(std::move(level), src.name)));
      out.texture_bytes += out.images.back()->Bytes();
      out.texture_bytes8 += out.images.back()->Bytes8();
    }
  } else {
    // No decode: a 1 × 1 white image per texture keeps every TextureRef valid.
    for (size_t k = 0; k < sources.size(); ++k) {
      MipLevel l;
      l.width = l.height = 1;
      l.texels = {glm::vec4(1.0f)};
      out.images.push_back(std::make_shared<const MipChain>(BuildMipChain(std::move(l), sources[k].name)));
    }
  }
}

}  // namespace gltf_detail
}  // namespace aalab
