// KHR_draco_mesh_compression (scenes/gltf_doc.h): the primitive's bufferView decoded by
// Debian's libdraco; attributes by the unique ids the extension names, converted to float
// (normalized integers as draco's ConvertValue maps them), faces as triangle indices.
#include <draco/compression/decode.h>

#include "scenes/gltf_doc.h"

namespace aalab {

void DecodeGltfDraco(const GltfDoc& d, const nlohmann::json& ext, const std::string& at,
                     const std::map<std::string, int>& comps, GltfPrimData& out) {
  const long long view = GltfInt(d, ext, "bufferView", at, -1, 0, static_cast<long long>(d.decoded_views.size()) - 1);
  if (view < 0) d.Fail(at + "/bufferView", "is required");
  if (!ext.contains("attributes") || !ext["attributes"].is_object())
    d.Fail(at + "/attributes", "is required (an object)");
  size_t size = 0;
  const uint8_t* bytes = d.ViewBytes(view, &size);
  draco::DecoderBuffer buf;
  buf.Init(reinterpret_cast<const char*>(bytes), size);
  draco::Decoder dec;
  auto result = dec.DecodeMeshFromBuffer(&buf);
  if (!result.ok() || !result.value())
    d.Fail(at, "Draco data does not decode (" + result.status().error_msg_string() + ")");
  const std::unique_ptr<draco::Mesh> mesh = std::move(result).value();
  out.vertices = mesh->num_points();
  for (const auto& [name, n] : comps) {
    if (!ext["attributes"].contains(name)) continue;
    const long long id = GltfInt(d, ext["attributes"], name.c_str(), at + "/attributes", -1, 0, 1 << 30);
    const draco::PointAttribute* a = mesh->GetAttributeByUniqueId(static_cast<uint32_t>(id));
    if (!a)
      d.Fail(at + "/attributes/" + name, "names Draco attribute " + std::to_string(id) + ", which the data lacks");
    if (a->num_components() != n) {
      d.Fail(at + "/attributes/" + name, "Draco attribute has " + std::to_string(a->num_components()) +
                                             " components (needs " + std::to_string(n) + ")");
    }
    std::vector<float>& v = out.attr[name];
    v.assign(static_cast<size_t>(out.vertices) * n, 0.0f);
    for (draco::PointIndex i(0); i < mesh->num_points(); ++i) {
      if (!a->ConvertValue<float>(a->mapped_index(i), static_cast<int8_t>(n), &v[static_cast<size_t>(i.value()) * n])) {
        d.Fail(at + "/attributes/" + name, "Draco attribute does not convert to float");
      }
    }
  }
  out.has_indices = true;
  out.indices.clear();
  out.indices.reserve(static_cast<size_t>(mesh->num_faces()) * 3);
  for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) out.indices.push_back(mesh->face(f)[k].value());
  }
}

}  // namespace aalab
