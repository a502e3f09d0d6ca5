// glTF images (scenes/gltf_load.h, gltf_detail::ReadGltfImages): where each image's bytes are
// (a file, a buffer view, a data URI), every header read and the file's RGBA8 budget summed
// before the first texel is decoded, then the decodes and mip chains: one parallel task per
// image (ParallelFor), each chain in its own slot, so the bits never depend on the threads.
// An image used by several textures with the same colour space is decoded once and shared
// (gltf_load.cpp keys the wanted list by (image, sRGB)).
#include <filesystem>

#include "core/error.h"
#include "core/parallel.h"
#include "io/image_io.h"
#include "scenes/gltf_load.h"

namespace aalab {
namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

/// Where image `index`'s bytes are: a file, or memory (bufferView or data URI).
struct GltfImageBytes {
  std::string name, file, hint;
  std::vector<uint8_t> data;
};

GltfImageBytes LocateImage(const GltfDoc& d, long long index) {
  const Json& im = d.j["images"][static_cast<size_t>(index)];
  const std::string at = GltfAt("/images", static_cast<size_t>(index));
  GltfImageBytes s;
  const std::string mime =
      im.contains("mimeType") && im["mimeType"].is_string() ? im["mimeType"].get<std::string>() : "";
  s.hint = mime == "image/jpeg" ? "jpg" : "png";
  if (im.contains("bufferView")) {
    const long long v = GltfIndex(d, im, "bufferView", at, "bufferViews");
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
    if (!GltfBase64Decode(uri, comma == std::string::npos ? uri.size() : comma + 1, s.data)) {
      d.Fail(GltfAt(at, "uri"), "is a data URI that is not valid base64");
    }
    s.name = "image " + std::to_string(index) + " (data URI) in '" + d.path + "'";
    return s;
  }
  const fs::path p = GltfUriFile(d, uri, GltfAt(at, "uri"));
  std::error_code ec;
  if (!fs::is_regular_file(p, ec)) d.Fail(GltfAt(at, "uri"), "image '" + p.string() + "' not found");
  s.file = p.string();
  s.name = "'" + p.string() + "'";
  return s;
}

}  // namespace

namespace gltf_detail {

void ReadGltfImages(const GltfDoc& d, const std::vector<std::pair<long long, bool>>& wanted, bool decode,
                    GltfContent& out) {
  std::vector<GltfImageBytes> sources;
  size_t budget = 0;
  for (const auto& [img, srgb] : wanted) {
    GltfImageBytes src = LocateImage(d, img);
    if (!src.file.empty()) out.files_read.push_back(src.file);
    if (decode) {
      const TextureHeader h = ProbeTextureImage(src.name, src.file, src.file.empty() ? src.data.data() : nullptr,
                                                src.data.size(), src.hint);
      budget += h.Bytes8Chain();
      if (budget > kMaxGltfTextureBytes8) {
        d.Fail(GltfAt("/images", static_cast<size_t>(img)), "the textures' RGBA8 mip chains exceed the budget of " +
                                                                std::to_string(kMaxGltfTextureBytes8 >> 20) + " MiB");
      }
      // The command's decode budget (io), charged here in file order rather than by the
      // parallel decodes below: past it, the same image is named at any thread count.
      try {
        ChargeDecodeBudget(static_cast<size_t>(h.width) * static_cast<size_t>(h.height),
                           src.file.empty() ? src.name : src.file);
      } catch (const UserError& e) {
        throw UserError("texture " + src.name + " cannot be decoded: " + e.what());
      }
    }
    sources.push_back(std::move(src));
  }
  if (decode) {
    // Each image decodes and builds its chain alone (one task each, its own slot), so the
    // thread count changes when, never what.
    // A failure is kept in its slot and the first in file order is thrown, whatever finished first.
    std::vector<std::shared_ptr<const MipChain>> chains(sources.size());
    std::vector<std::string> errors(sources.size());
    ParallelFor(static_cast<int>(sources.size()), [&](int k) {
      const auto i = static_cast<size_t>(k);
      const GltfImageBytes& src = sources[i];
      try {
        MipLevel level = DecodeTextureImage(src.name, src.file, src.file.empty() ? src.data.data() : nullptr,
                                            src.data.size(), src.hint, wanted[i].second, true);
        chains[i] = std::make_shared<const MipChain>(BuildMipChain(std::move(level), src.name));
      } catch (const UserError& e) {
        errors[i] = e.what();
      }
    });
    for (const std::string& e : errors) {
      if (!e.empty()) throw UserError(e);
    }
    for (auto& c : chains) {
      out.texture_bytes += c->Bytes();
      out.texture_bytes8 += c->Bytes8();
      out.images.push_back(std::move(c));
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
