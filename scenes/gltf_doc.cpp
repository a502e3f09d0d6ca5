// The glTF file as written (scenes/gltf_doc.h): container, JSON, buffers, views, accessors.
// The checks follow the glTF 2.0 specification §3.6 (buffers, views, accessors: every
// element inside its view, `byteStride` in [4, 252] and a multiple of 4) and the Khronos
// validator's rules for indices and types. Arithmetic on counts, strides and offsets is done
// in unsigned 128-bit (each JSON integer is at most 2^63), so no declared value can overflow.
#include "scenes/gltf_doc.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/error.h"

namespace aalab {
namespace fs = std::filesystem;
using Json = nlohmann::json;
using u128 = unsigned __int128;

const std::vector<std::string>& GltfSupportedExtensions() {
  static const std::vector<std::string> k = {
      "KHR_materials_unlit",   "KHR_texture_transform",   "KHR_materials_emissive_strength",
      "KHR_mesh_quantization", "EXT_meshopt_compression", "KHR_draco_mesh_compression",
      "KHR_lights_punctual"};
  return k;
}

void GltfDoc::Fail(const std::string& json_path, const std::string& rule) const {
  throw UserError("glTF file '" + path + "': at " + (json_path.empty() ? std::string("/") : json_path) + ": " + rule);
}

namespace {

std::string ReadBytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw UserError("glTF file '" + path + "' cannot be read");
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

uint32_t Le32(const std::string& b, size_t at) {
  uint32_t v = 0;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

std::string JoinList(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

bool Base64DecodeImpl(const std::string& in, size_t from, std::vector<uint8_t>& out) {
  auto val = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+' || c == '-') return 62;
    if (c == '/' || c == '_') return 63;
    return -1;
  };
  uint32_t acc = 0;
  int bits = 0;
  for (size_t i = from; i < in.size(); ++i) {
    if (in[i] == '=') break;
    const int v = val(in[i]);
    if (v < 0) return false;
    acc = (acc << 6) | static_cast<uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<uint8_t>((acc >> bits) & 0xFF));
    }
  }
  return true;
}

int ComponentBytes(long long type) {
  switch (type) {
    case 5120:
    case 5121: return 1;
    case 5122:
    case 5123: return 2;
    case 5125:
    case 5126: return 4;
    default: return 0;
  }
}

int TypeComponents(const std::string& t) {
  static const std::map<std::string, int> k = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4},
                                               {"MAT2", 4},   {"MAT3", 9}, {"MAT4", 16}};
  auto it = k.find(t);
  return it == k.end() ? 0 : it->second;
}

std::string At(const std::string& base, const std::string& key) { return GltfAt(base, key); }
std::string At(const std::string& base, size_t i) { return GltfAt(base, i); }

/// Loads buffer i's bytes.
std::vector<uint8_t> LoadBuffer(const GltfDoc& d, const Json& b, size_t i, const std::string& glb_bin, bool has_bin) {
  const std::string at = At("/buffers", i);
  const long long len = GltfInt(d, b, "byteLength", at, -1, 1, 1ll << 40);
  if (len < 1) d.Fail(At(at, "byteLength"), "is required (an integer >= 1)");
  std::vector<uint8_t> bytes;
  if (!b.contains("uri")) {
    const bool fallback =
        b.contains("extensions") && b["extensions"].is_object() && b["extensions"].contains("EXT_meshopt_compression");
    if (fallback) return {};  // a meshopt fallback buffer: never read (its views are decoded)
    if (!has_bin || i != 0)
      d.Fail(at, "has no uri and no GLB BIN chunk holds it (only buffer 0 of a .glb may omit uri)");
    if (static_cast<size_t>(len) > glb_bin.size()) {
      d.Fail(At(at, "byteLength"),
             "declares " + std::to_string(len) + " bytes but the GLB BIN chunk has " + std::to_string(glb_bin.size()));
    }
    bytes.assign(glb_bin.begin(), glb_bin.begin() + len);
    return bytes;
  }
  if (!b["uri"].is_string()) d.Fail(At(at, "uri"), "must be a string");
  const std::string uri = b["uri"].get<std::string>();
  if (uri.rfind("data:", 0) == 0) {
    const size_t comma = uri.find(',');
    if (comma == std::string::npos || uri.rfind(";base64", comma) == std::string::npos ||
        !GltfBase64Decode(uri, comma + 1, bytes)) {
      d.Fail(At(at, "uri"), "is a data URI that is not valid base64");
    }
  } else {
    const fs::path bp = GltfUriFile(d, uri, At(at, "uri"));
    std::error_code ec;
    if (!fs::is_regular_file(bp, ec)) d.Fail(At(at, "uri"), "file '" + bp.string() + "' not found");
    const std::string s = ReadBytes(bp.string());
    bytes.assign(s.begin(), s.end());
  }
  if (bytes.size() < static_cast<size_t>(len)) {
    d.Fail(At(at, "byteLength"),
           "declares " + std::to_string(len) + " bytes but the data has " + std::to_string(bytes.size()));
  }
  bytes.resize(static_cast<size_t>(len));
  return bytes;
}

/// Decodes an EXT_meshopt_compression buffer view (the extension's specification: modes
/// ATTRIBUTES, TRIANGLES, INDICES; filters NONE, OCTAHEDRAL, QUATERNION, EXPONENTIAL).
std::vector<uint8_t> DecodeMeshopt(const GltfDoc& d, const Json& e, const std::string& at) {
  const long long b = GltfInt(d, e, "buffer", at, -1, 0, static_cast<long long>(d.buffers.size()) - 1);
  if (b < 0) d.Fail(At(at, "buffer"), "is required");
  const long long off = GltfInt(d, e, "byteOffset", at, 0, 0, 1ll << 40);
  const long long len = GltfInt(d, e, "byteLength", at, -1, 1, 1ll << 40);
  const long long stride = GltfInt(d, e, "byteStride", at, -1, 1, 256);
  const long long count = GltfInt(d, e, "count", at, -1, 1, kMaxGltfAccessorCount);
  if (len < 0 || stride < 0 || count < 0) d.Fail(at, "needs byteLength, byteStride and count");
  const auto& src = d.buffers[static_cast<size_t>(b)];
  if (static_cast<u128>(off) + static_cast<u128>(len) > src.size())
    d.Fail(at, "compressed bytes lie outside buffer " + std::to_string(b));
  const std::string mode = e.contains("mode") && e["mode"].is_string() ? e["mode"].get<std::string>() : "";
  const std::string filter = e.contains("filter") && e["filter"].is_string() ? e["filter"].get<std::string>() : "NONE";
  std::vector<uint8_t> out(static_cast<size_t>(count) * static_cast<size_t>(stride));
  const uint8_t* p = src.data() + off;
  int rc = -1;
  if (mode == "ATTRIBUTES") {
    rc = stride % 4 == 0 ? meshopt_decodeVertexBuffer(out.data(), count, stride, p, len) : -1;
    if (rc == 0 && filter == "OCTAHEDRAL")
      meshopt_decodeFilterOct(out.data(), count, stride);
    else if (rc == 0 && filter == "QUATERNION")
      meshopt_decodeFilterQuat(out.data(), count, stride);
    else if (rc == 0 && filter == "EXPONENTIAL")
      meshopt_decodeFilterExp(out.data(), count, stride);
    else if (rc == 0 && filter != "NONE")
      d.Fail(At(at, "filter"), "'" + filter + "' is not a meshopt filter");
  } else if (mode == "TRIANGLES" && (stride == 2 || stride == 4) && count % 3 == 0) {
    rc = meshopt_decodeIndexBuffer(out.data(), count, stride, p, len);
  } else if (mode == "INDICES" && (stride == 2 || stride == 4)) {
    rc = meshopt_decodeIndexSequence(out.data(), count, stride, p, len);
  } else {
    d.Fail(At(at, "mode"), "'" + mode + "' with byteStride " + std::to_string(stride) + " is not a valid meshopt mode");
  }
  if (rc != 0) d.Fail(at, "meshopt data does not decode (meshoptimizer error " + std::to_string(rc) + ")");
  return out;
}

void CheckAccessor(const GltfDoc& d, const Json& a, size_t i, const std::vector<long long>& view_len) {
  const std::string at = At("/accessors", i);
  if (!a.is_object()) d.Fail(at, "must be an object");
  const long long count = GltfInt(d, a, "count", at, -1, 1, kMaxGltfAccessorCount);
  if (count < 1) d.Fail(At(at, "count"), "is required (1 to " + std::to_string(kMaxGltfAccessorCount) + ")");
  const int cb = ComponentBytes(GltfInt(d, a, "componentType", at, -1, 0, 1 << 20));
  if (cb == 0) d.Fail(At(at, "componentType"), "must be one of 5120, 5121, 5122, 5123, 5125, 5126");
  const int nc = TypeComponents(a.contains("type") && a["type"].is_string() ? a["type"].get<std::string>() : "");
  if (nc == 0) d.Fail(At(at, "type"), "must be one of SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3, MAT4");
  auto check_range = [&](long long view, long long off, u128 stride, u128 elem, long long n, const std::string& where) {
    if (view < 0 || view >= static_cast<long long>(view_len.size())) {
      d.Fail(At(where, "bufferView"), "names bufferView " + std::to_string(view) + ", which does not exist");
    }
    const u128 need = static_cast<u128>(off) + static_cast<u128>(n - 1) * stride + elem;
    if (need > static_cast<u128>(view_len[static_cast<size_t>(view)])) {
      d.Fail(where, "reads " + std::to_string(n) + " elements beyond bufferView " + std::to_string(view) + " (" +
                        std::to_string(view_len[static_cast<size_t>(view)]) + " bytes) (rule: accessor bounds)");
    }
  };
  if (a.contains("bufferView")) {
    const long long v = GltfInt(d, a, "bufferView", at, -1, 0, 1ll << 40);
    const long long off = GltfInt(d, a, "byteOffset", at, 0, 0, 1ll << 62);
    if (off % cb != 0) d.Fail(At(at, "byteOffset"), "must be a multiple of the component size " + std::to_string(cb));
    const u128 elem = static_cast<u128>(cb) * nc;
    u128 stride = elem;
    if (v >= 0 && v < static_cast<long long>(view_len.size())) {
      const Json& bv = d.j["bufferViews"][static_cast<size_t>(v)];
      const long long s = GltfInt(d, bv, "byteStride", At("/bufferViews", static_cast<size_t>(v)), 0, 4, 252);
      if (s > 0) {
        if (static_cast<u128>(s) < elem)
          d.Fail(At(at, "bufferView"), "its byteStride " + std::to_string(s) + " is shorter than one element");
        stride = static_cast<u128>(s);
      }
    }
    check_range(v, off, stride, elem, count, at);
  }
  if (a.contains("sparse")) {
    const std::string sp = At(at, "sparse");
    const Json& s = a["sparse"];
    const long long n = GltfInt(d, s, "count", sp, -1, 1, count);
    if (n < 1) d.Fail(At(sp, "count"), "is required (1 to the accessor's count)");
    if (!s.contains("indices") || !s.contains("values")) d.Fail(sp, "needs indices and values");
    const long long it = GltfInt(d, s["indices"], "componentType", At(sp, "indices"), -1, 5121, 5125);
    if (it != 5121 && it != 5123 && it != 5125) d.Fail(At(sp, "indices/componentType"), "must be 5121, 5123 or 5125");
    check_range(GltfInt(d, s["indices"], "bufferView", At(sp, "indices"), -1, 0, 1ll << 40),
                GltfInt(d, s["indices"], "byteOffset", At(sp, "indices"), 0, 0, 1ll << 62), ComponentBytes(it),
                ComponentBytes(it), n, At(sp, "indices"));
    check_range(GltfInt(d, s["values"], "bufferView", At(sp, "values"), -1, 0, 1ll << 40),
                GltfInt(d, s["values"], "byteOffset", At(sp, "values"), 0, 0, 1ll << 62), static_cast<u128>(cb) * nc,
                static_cast<u128>(cb) * nc, n, At(sp, "values"));
  }
}

/// The raw view of accessor `index` after CheckAccessor: base pointer, stride, element size.
struct RawAccessor {
  const uint8_t* data = nullptr;  ///< null: all zeros
  size_t stride = 0;
  long long count = 0;
  int ctype = 0, comps = 0;
  bool normalized = false;
  std::string type;
};

RawAccessor Raw(const GltfDoc& d, long long index, const std::string& from) {
  const Json& list = GltfArray(d, d.j, "accessors", "");
  if (index < 0 || index >= static_cast<long long>(list.size())) {
    d.Fail(from, "names accessor " + std::to_string(index) + ", which does not exist (rule: index out of range)");
  }
  const Json& a = list[static_cast<size_t>(index)];
  RawAccessor r;
  r.count = a["count"].get<long long>();
  r.ctype = a["componentType"].get<int>();
  r.type = a["type"].get<std::string>();
  r.comps = TypeComponents(r.type);
  r.normalized = a.contains("normalized") && a["normalized"].is_boolean() && a["normalized"].get<bool>();
  r.stride = static_cast<size_t>(ComponentBytes(r.ctype)) * static_cast<size_t>(r.comps);
  if (a.contains("bufferView")) {
    const long long v = a["bufferView"].get<long long>();
    size_t size = 0;
    r.data = d.ViewBytes(v, &size) + a.value("byteOffset", 0ll);
    const Json& bv = d.j["bufferViews"][static_cast<size_t>(v)];
    if (bv.contains("byteStride")) r.stride = bv["byteStride"].get<size_t>();
  }
  return r;
}

float Component(const uint8_t* p, int ctype, bool normalized) {
  switch (ctype) {
    case 5120: {
      int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(v / 127.0f, -1.0f) : v;
    }
    case 5121: {
      uint8_t v = *p;
      return normalized ? v / 255.0f : v;
    }
    case 5122: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0f, -1.0f) : v;
    }
    case 5123: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0f : v;
    }
    case 5125: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return static_cast<float>(v);
    }
    default: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

uint32_t UComponent(const uint8_t* p, int ctype) {
  switch (ctype) {
    case 5121: return *p;
    case 5123: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    default: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

/// Applies the sparse substitution of accessor `index` through `put(element, source, ctype)`.
template <typename Put>
void ApplySparse(const GltfDoc& d, long long index, int elem_bytes, Put put) {
  const Json& a = d.j["accessors"][static_cast<size_t>(index)];
  if (!a.contains("sparse")) return;
  const Json& s = a["sparse"];
  const long long n = s["count"].get<long long>();
  const long long count = a["count"].get<long long>();
  const int it = s["indices"]["componentType"].get<int>();
  size_t sz = 0;
  const uint8_t* ip =
      d.ViewBytes(s["indices"]["bufferView"].get<long long>(), &sz) + s["indices"].value("byteOffset", 0ll);
  const uint8_t* vp =
      d.ViewBytes(s["values"]["bufferView"].get<long long>(), &sz) + s["values"].value("byteOffset", 0ll);
  for (long long k = 0; k < n; ++k) {
    const uint32_t e = UComponent(ip + k * ComponentBytes(it), it);
    if (e >= count) {
      d.Fail("/accessors/" + std::to_string(index) + "/sparse/indices",
             "index " + std::to_string(e) + " is beyond the accessor's " + std::to_string(count) +
                 " elements (rule: index out of range)");
    }
    put(static_cast<size_t>(e), vp + k * elem_bytes);
  }
}

/// The document's shape (glTF 2.0 JSON schema, the parts every reader relies on): the
/// top-level lists are arrays of objects, `scene` indexes `scenes`, and throughout the tree
/// every `name` is a string and every `extensions` an object of objects. Walked with an
/// explicit stack (no recursion however deep the JSON nests).
void CheckShapes(const GltfDoc& d) {
  static const char* kLists[] = {"accessors", "animations", "buffers", "bufferViews", "cameras",
                                 "images",    "materials",  "meshes",  "nodes",       "samplers",
                                 "scenes",    "skins",      "textures"};
  for (const char* list : kLists) {
    const Json& a = GltfArray(d, d.j, list, "");
    for (size_t i = 0; i < a.size(); ++i) {
      if (!a[i].is_object()) d.Fail(At("/" + std::string(list), i), "must be an object");
    }
  }
  if (d.j.contains("scene")) {
    const long long n = static_cast<long long>(GltfArray(d, d.j, "scenes", "").size());
    const long long s = GltfInt(d, d.j, "scene", "", 0, 0, 1ll << 40);
    if (s >= n)
      d.Fail("/scene", "names scene " + std::to_string(s) + ", which does not exist (" + std::to_string(n) +
                           " defined) (rule: index out of range)");
  }
  std::vector<std::pair<const Json*, std::string>> stack = {{&d.j, ""}};
  while (!stack.empty()) {
    const auto [v, at] = stack.back();
    stack.pop_back();
    if (v->is_object()) {
      for (auto it = v->begin(); it != v->end(); ++it) {
        const std::string child = At(at, it.key());
        if (it.key() == "extras") continue;  // application data: any JSON
        if (it.key() == "name" && !it.value().is_string()) d.Fail(child, "must be a string");
        if (it.key() == "extensions") {
          if (!it.value().is_object()) d.Fail(child, "must be an object");
          for (auto e = it.value().begin(); e != it.value().end(); ++e) {
            if (!e.value().is_object()) d.Fail(At(child, e.key()), "must be an object");
          }
        }
        if (it.value().is_structured()) stack.emplace_back(&it.value(), child);
      }
    } else if (v->is_array() && !v->empty() && v->front().is_structured()) {
      for (size_t i = 0; i < v->size(); ++i) stack.emplace_back(&(*v)[i], At(at, i));
    }
  }
}

}  // namespace

std::string GltfAt(const std::string& base, const std::string& key) { return base + "/" + key; }
std::string GltfAt(const std::string& base, size_t i) { return base + "/" + std::to_string(i); }

std::string GltfUriFile(const GltfDoc& d, const std::string& uri, const std::string& at) {
  std::string name;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] != '%') {
      name += uri[i];
      continue;
    }
    const auto hex = [&uri](size_t k) { return k < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[k])); };
    if (!hex(i + 1) || !hex(i + 2)) {
      d.Fail(at, "has a bad percent escape '" + uri.substr(i, 3) + "' at character " + std::to_string(i) +
                     " (a URI writes a byte as '%' and two hex digits, e.g. %20 for a space, %25 for '%')");
    }
    const char c = static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
    if (c == '\0') d.Fail(at, "has the escape '%00' (a NUL byte), which no file name holds");
    name += c;
    i += 2;
  }
  return (fs::path(d.path).parent_path() / name).string();
}

bool GltfBase64Decode(const std::string& in, size_t from, std::vector<uint8_t>& out) {
  return Base64DecodeImpl(in, from, out);
}

long long GltfIndex(const GltfDoc& d, const Json& o, const char* key, const std::string& at, const char* list) {
  const long long n = static_cast<long long>(GltfArray(d, d.j, list, "").size());
  if (!o.is_object() || !o.contains(key)) return -1;
  const Json& v = o.at(key);
  if (!v.is_number_integer() && !v.is_number_unsigned())
    d.Fail(At(at, key), "must be an integer index into /" + std::string(list));
  if (v.is_number_unsigned() ? v.get<unsigned long long>() >= static_cast<unsigned long long>(n)
                             : (v.get<long long>() < 0 || v.get<long long>() >= n)) {
    d.Fail(At(at, key), "names " + std::string(list) + " " + v.dump() + ", which does not exist (" + std::to_string(n) +
                            " defined) (rule: index out of range)");
  }
  return v.get<long long>();
}

const uint8_t* GltfDoc::ViewBytes(long long view, size_t* size) const {
  const size_t v = static_cast<size_t>(view);
  if (!decoded_views[v].empty()) {
    *size = decoded_views[v].size();
    return decoded_views[v].data();
  }
  const Json& bv = j["bufferViews"][v];
  const auto& buf = buffers[bv["buffer"].get<size_t>()];
  *size = bv["byteLength"].get<size_t>();
  return buf.data() + bv.value("byteOffset", 0ll);
}

long long GltfInt(const GltfDoc& d, const Json& o, const char* key, const std::string& at, long long fallback,
                  long long lo, long long hi) {
  if (!o.is_object() || !o.contains(key)) return fallback;
  const Json& v = o.at(key);
  const std::string where = At(at, key);
  if (v.is_number_unsigned()) {
    if (v.get<unsigned long long>() > static_cast<unsigned long long>(hi)) {
      d.Fail(where, std::to_string(v.get<unsigned long long>()) + " is out of range (allowed: " + std::to_string(lo) +
                        " to " + std::to_string(hi) + ")");
    }
  } else if (!v.is_number_integer()) {
    d.Fail(where, "must be an integer");
  }
  const long long x = v.get<long long>();
  if (x < lo || x > hi)
    d.Fail(where,
           std::to_string(x) + " is out of range (allowed: " + std::to_string(lo) + " to " + std::to_string(hi) + ")");
  return x;
}

double GltfNum(const GltfDoc& d, const Json& o, const char* key, const std::string& at, double fallback, double lo,
               double hi) {
  if (!o.is_object() || !o.contains(key)) return fallback;
  const Json& v = o.at(key);
  if (!v.is_number()) d.Fail(At(at, key), "must be a number");
  const double x = v.get<double>();
  if (!(x >= lo && x <= hi))
    d.Fail(At(at, key),
           std::to_string(x) + " is out of range (allowed: " + std::to_string(lo) + " to " + std::to_string(hi) + ")");
  return x;
}

const Json& GltfArray(const GltfDoc& d, const Json& o, const char* key, const std::string& at) {
  static const Json kEmpty = Json::array();
  if (!o.is_object() || !o.contains(key)) return kEmpty;
  if (!o.at(key).is_array()) d.Fail(At(at, key), "must be an array");
  return o.at(key);
}

std::vector<double> GltfNumbers(const GltfDoc& d, const Json& o, const char* key, const std::string& at, size_t count,
                                const std::vector<double>& fallback) {
  if (!o.is_object() || !o.contains(key)) return fallback;
  const Json& a = o.at(key);
  if (!a.is_array() || a.size() != count)
    d.Fail(At(at, key), "must be an array of " + std::to_string(count) + " numbers");
  std::vector<double> v;
  for (size_t i = 0; i < count; ++i) {
    if (!a[i].is_number() || !std::isfinite(a[i].get<double>())) d.Fail(At(At(at, key), i), "must be a finite number");
    v.push_back(a[i].get<double>());
  }
  return v;
}

long long GltfAccessorCount(const GltfDoc& d, long long index, const std::string& from) {
  return Raw(d, index, from).count;
}

std::vector<float> ReadGltfFloats(const GltfDoc& d, long long index, const std::string& from, int comps) {
  const RawAccessor r = Raw(d, index, from);
  if (r.comps != comps) {
    d.Fail(from, "accessor " + std::to_string(index) + " has type " + r.type + " (" + std::to_string(r.comps) +
                     " components; this use needs " + std::to_string(comps) + ")");
  }
  std::vector<float> out(static_cast<size_t>(r.count) * comps, 0.0f);
  const int cb = ComponentBytes(r.ctype);
  if (r.data) {
    for (long long i = 0; i < r.count; ++i) {
      const uint8_t* p = r.data + static_cast<size_t>(i) * r.stride;
      for (int c = 0; c < comps; ++c)
        out[static_cast<size_t>(i) * comps + c] = Component(p + c * cb, r.ctype, r.normalized);
    }
  }
  ApplySparse(d, index, cb * comps, [&](size_t e, const uint8_t* p) {
    for (int c = 0; c < comps; ++c) out[e * comps + c] = Component(p + c * cb, r.ctype, r.normalized);
  });
  return out;
}

std::vector<uint32_t> ReadGltfUints(const GltfDoc& d, long long index, const std::string& from, int comps) {
  const RawAccessor r = Raw(d, index, from);
  if (r.comps != comps || (r.ctype != 5121 && r.ctype != 5123 && r.ctype != 5125)) {
    d.Fail(from, "accessor " + std::to_string(index) + " must be unsigned integers (5121, 5123, 5125) with " +
                     std::to_string(comps) + " component(s)");
  }
  std::vector<uint32_t> out(static_cast<size_t>(r.count) * comps, 0u);
  const int cb = ComponentBytes(r.ctype);
  if (r.data) {
    for (long long i = 0; i < r.count; ++i) {
      for (int c = 0; c < comps; ++c)
        out[static_cast<size_t>(i) * comps + c] =
            UComponent(r.data + static_cast<size_t>(i) * r.stride + c * cb, r.ctype);
    }
  }
  ApplySparse(d, index, cb * comps, [&](size_t e, const uint8_t* p) {
    for (int c = 0; c < comps; ++c) out[e * comps + c] = UComponent(p + c * cb, r.ctype);
  });
  return out;
}

GltfDoc ReadGltfDoc(const std::string& path) {
  GltfDoc d;
  d.path = path;
  const std::string bytes = ReadBytes(path);
  std::string text = bytes, bin;
  bool has_bin = false;
  if (bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0) {
    if (bytes.size() < 20) d.Fail("", "truncated GLB header (rule: GLB container)");
    if (Le32(bytes, 4) != 2) d.Fail("", "GLB container version " + std::to_string(Le32(bytes, 4)) + " (allowed: 2)");
    const uint64_t json_len = Le32(bytes, 12);
    if (Le32(bytes, 16) != 0x4E4F534Au || 20 + json_len > bytes.size()) d.Fail("", "GLB has no complete JSON chunk");
    text = bytes.substr(20, json_len);
    const uint64_t bin_at = 20 + json_len;
    if (bin_at + 8 <= bytes.size() && Le32(bytes, bin_at + 4) == 0x004E4942u) {
      const uint64_t bin_len = Le32(bytes, bin_at);
      if (bin_at + 8 + bin_len > bytes.size()) d.Fail("", "GLB BIN chunk is truncated");
      bin = bytes.substr(bin_at + 8, bin_len);
      has_bin = true;
    }
  }
  try {
    d.j = Json::parse(text);
  } catch (const Json::exception& e) {
    d.Fail("", std::string("not valid JSON (") + e.what() + ")");
  }
  if (!d.j.is_object()) d.Fail("", "the JSON document is not an object");
  const Json& j = d.j;
  if (!j.contains("asset") || !j["asset"].is_object()) d.Fail("/asset", "is required (an object with version \"2.0\")");
  if (!j["asset"].contains("version") || !j["asset"]["version"].is_string()) {
    d.Fail("/asset/version", "must be a string such as \"2.0\" (rule: numeric or missing version)");
  }
  CheckShapes(d);
  const std::string version = j["asset"]["version"].get<std::string>();
  if (version.rfind("2.", 0) != 0) d.Fail("/asset/version", "'" + version + "' (allowed: 2.x; glTF 1.0 is not read)");
  // Extensions: every required one must be drawn (one message listing all that are not);
  // used ones that are not drawn are collected for one warning.
  const auto& sup = GltfSupportedExtensions();
  std::vector<std::string> missing;
  for (const Json& e : GltfArray(d, j, "extensionsRequired", "")) {
    if (!e.is_string()) d.Fail("/extensionsRequired", "must hold strings");
    if (std::find(sup.begin(), sup.end(), e.get<std::string>()) == sup.end()) missing.push_back(e.get<std::string>());
  }
  if (!missing.empty()) {
    d.Fail("/extensionsRequired",
           "requires " + JoinList(missing) + ", which aalab does not draw (supported: " + JoinList(sup) + ")");
  }
  for (const Json& e : GltfArray(d, j, "extensionsUsed", "")) {
    if (!e.is_string()) d.Fail("/extensionsUsed", "must hold strings");
    if (std::find(sup.begin(), sup.end(), e.get<std::string>()) == sup.end())
      d.ignored_extensions.push_back(e.get<std::string>());
  }
  // Buffers, then views, then accessors: each checked before anything refers to it.
  const Json& buffers = GltfArray(d, j, "buffers", "");
  for (size_t i = 0; i < buffers.size(); ++i) d.buffers.push_back(LoadBuffer(d, buffers[i], i, bin, has_bin));
  const Json& views = GltfArray(d, j, "bufferViews", "");
  std::vector<long long> view_len;
  d.decoded_views.resize(views.size());
  for (size_t i = 0; i < views.size(); ++i) {
    const Json& v = views[i];
    const std::string at = At("/bufferViews", i);
    if (!v.is_object()) d.Fail(at, "must be an object");
    const long long b = GltfInt(d, v, "buffer", at, -1, 0, 1ll << 40);
    if (b < 0 || b >= static_cast<long long>(d.buffers.size())) {
      d.Fail(At(at, "buffer"),
             "names buffer " + std::to_string(b) + ", which does not exist (rule: index out of range)");
    }
    const long long off = GltfInt(d, v, "byteOffset", at, 0, 0, 1ll << 62);
    const long long len = GltfInt(d, v, "byteLength", at, -1, 1, 1ll << 62);
    if (len < 1) d.Fail(At(at, "byteLength"), "is required (an integer >= 1)");
    const long long stride = GltfInt(d, v, "byteStride", at, 0, 4, 252);
    if (stride % 4 != 0) d.Fail(At(at, "byteStride"), std::to_string(stride) + " is not a multiple of 4");
    const bool meshopt =
        v.contains("extensions") && v["extensions"].is_object() && v["extensions"].contains("EXT_meshopt_compression");
    if (meshopt) {
      d.decoded_views[i] =
          DecodeMeshopt(d, v["extensions"]["EXT_meshopt_compression"], At(at, "extensions/EXT_meshopt_compression"));
      if (static_cast<long long>(d.decoded_views[i].size()) < len)
        d.Fail(at, "decoded meshopt data is shorter than byteLength");
      d.decoded_views[i].resize(static_cast<size_t>(len));
    } else if (static_cast<u128>(off) + static_cast<u128>(len) > d.buffers[static_cast<size_t>(b)].size()) {
      d.Fail(at, "bytes " + std::to_string(off) + " + " + std::to_string(len) + " lie outside buffer " +
                     std::to_string(b) + " (" + std::to_string(d.buffers[static_cast<size_t>(b)].size()) +
                     " bytes) (rule: buffer view bounds)");
    }
    view_len.push_back(len);
  }
  const Json& accessors = GltfArray(d, j, "accessors", "");
  for (size_t i = 0; i < accessors.size(); ++i) CheckAccessor(d, accessors[i], i, view_len);
  return d;
}

}  // namespace aalab
