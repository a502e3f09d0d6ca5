/// The glTF 2.0 file as written (scenes/gltf_load.h builds the scene from it): the JSON
/// document, its buffers in memory (GLB BIN chunk, data URIs, external files), buffer views
/// (EXT_meshopt_compression views decoded), and typed accessor reads. Every index, count,
/// stride and offset is checked with overflow-safe arithmetic before a byte is read; a
/// failure is one UserError naming the file, the JSON path (RFC 6901 pointer) and the rule.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace aalab {

/// Largest number of elements an accessor may declare.
inline constexpr long long kMaxGltfAccessorCount = 1ll << 27;
/// Deepest node hierarchy accepted (walked without recursion; deeper is refused).
inline constexpr int kMaxGltfNodeDepth = 1 << 16;

/// The extensions aalab draws (what extensionsRequired may name).
const std::vector<std::string>& GltfSupportedExtensions();

struct GltfDoc {
  std::string path;
  nlohmann::json j;
  std::vector<std::vector<uint8_t>> buffers;  ///< each buffer's bytes (byteLength of them)
  /// Per buffer view: its bytes when decoded from EXT_meshopt_compression (else empty).
  std::vector<std::vector<uint8_t>> decoded_views;
  /// Used extensions that are not drawn (for the one warning).
  std::vector<std::string> ignored_extensions;

  /// Throws UserError "glTF file 'path': at /json/path: rule".
  [[noreturn]] void Fail(const std::string& json_path, const std::string& rule) const;
  /// The bytes of buffer view `view` (validated) and their count.
  const uint8_t* ViewBytes(long long view, size_t* size) const;
};

/// Reads and checks the file: GLB container or JSON, asset.version a string "2.x",
/// extensionsRequired all supported (one message listing every unsupported one), buffers
/// present and long enough, buffer views inside buffers, accessors inside views (sparse ones
/// too), meshopt views decoded. Throws UserError as GltfDoc::Fail.
GltfDoc ReadGltfDoc(const std::string& path);

/// The JSON pointer `base`/`key` and `base`/`i` (for messages).
std::string GltfAt(const std::string& base, const std::string& key);
std::string GltfAt(const std::string& base, size_t i);
/// The index member `key` of `o` (at `at`) into the top-level array `list`: -1 when absent;
/// a non-integer or an index outside the array fails (rule: index out of range).
long long GltfIndex(const GltfDoc& d, const nlohmann::json& o, const char* key, const std::string& at,
                    const char* list);
/// The file a relative URI names (`uri` of a buffer or image, at JSON path `at`): the URI
/// percent-decoded (RFC 3986 §2.1; glTF 2.0 §3.3: "my%20tex.png" names "my tex.png") and
/// resolved against the glTF file's folder. A '%' without two hex digits after it, or
/// "%00", fails at `at` naming the escape.
std::string GltfUriFile(const GltfDoc& d, const std::string& uri, const std::string& at);
/// Decodes base64 (standard or URL-safe alphabet, '=' padding ends it) from in[from..] and
/// appends the bytes to out; false on a character outside the alphabet.
bool GltfBase64Decode(const std::string& in, size_t from, std::vector<uint8_t>& out);

/// An integer member `key` of object `o` at JSON path `at`: `fallback` when absent, else it
/// must be an integer in [lo, hi] (the rule is named in the failure).
long long GltfInt(const GltfDoc& d, const nlohmann::json& o, const char* key, const std::string& at, long long fallback,
                  long long lo, long long hi);
/// A number member (any JSON number), finite and in [lo, hi]; `fallback` when absent.
double GltfNum(const GltfDoc& d, const nlohmann::json& o, const char* key, const std::string& at, double fallback,
               double lo, double hi);
/// The array member `key` (empty array when absent; a non-array fails).
const nlohmann::json& GltfArray(const GltfDoc& d, const nlohmann::json& o, const char* key, const std::string& at);
/// `count` numbers of array member `key` (absent: `fallback`); each finite.
std::vector<double> GltfNumbers(const GltfDoc& d, const nlohmann::json& o, const char* key, const std::string& at,
                                size_t count, const std::vector<double>& fallback);

/// Accessor `index` (referenced from JSON path `from`) as floats, `comps` per element,
/// normalized integers mapped as the specification's §3.11 says; `types` the accessor types
/// allowed ("VEC3", ...). Sparse substitution applied.
std::vector<float> ReadGltfFloats(const GltfDoc& d, long long index, const std::string& from, int comps);
/// Accessor `index` as unsigned integers (indices, joints): component types 5121/5123/5125.
std::vector<uint32_t> ReadGltfUints(const GltfDoc& d, long long index, const std::string& from, int comps);
/// The element count of accessor `index`.
long long GltfAccessorCount(const GltfDoc& d, long long index, const std::string& from);

/// One primitive's vertex streams as floats by attribute name ("POSITION", ...; components
/// per element as asked), and its indices (none: drawn in vertex order).
struct GltfPrimData {
  long long vertices = 0;
  std::map<std::string, std::vector<float>> attr;
  std::vector<uint32_t> indices;
  bool has_indices = false;
};

/// Decodes a KHR_draco_mesh_compression primitive extension `ext` (at JSON path `at`): the
/// attributes named in both `ext.attributes` and `comps` (components each), and the faces
/// as indices. Throws as GltfDoc::Fail when the data does not decode or an attribute is
/// missing or of the wrong width (scenes/gltf_draco.cpp, through Debian's libdraco).
void DecodeGltfDraco(const GltfDoc& d, const nlohmann::json& ext, const std::string& at,
                     const std::map<std::string, int>& comps, GltfPrimData& out);

}  // namespace aalab
