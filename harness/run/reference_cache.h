/// The reference cache: a folder (shared by the shards of a run, or by runs on one machine)
/// holding rendered references, so each is rendered once (docs/cluster.md).
///
/// An entry is keyed by everything the reference's bits depend on: the scene's content
/// (SceneContentHash: a moving scene's frame is its own scene), the frame size, the sample
/// grid, the seed, sampled or exact, and the program (tool version, git commit and a hash of
/// the running executable's bytes: a rebuilt binary never reads an older binary's entries).
/// The file name is the FNV-1a 64 of the key text; the file repeats the key text and ends
/// with a checksum, and both are checked on every read. Entries are written to a unique
/// temporary name and renamed into place, so concurrent shards writing the same entry (same
/// bits: rendering is deterministic) never leave a torn file. Nothing is ever evicted: delete
/// the folder when you like.
#pragma once
#include <optional>
#include <string>

#include "scenes/render.h"
#include "scenes/scene.h"
#include "scenes/tracer.h"

namespace aalab {

/// What a cache entry holds: the reference (image, edge masks, grid) and the mean squared
/// difference of its two independent halves (all the noise floor needs: the halves themselves
/// are not stored, so `ref.half_a`/`half_b` are empty when read from the cache), the cost
/// counters of rendering it, and how long the render took when it was made. 20 bytes a pixel.
struct CachedReference {
  Reference ref;
  double halves_mse = 0;  ///< MeanSquaredError(half_a, half_b).mse
  uint64_t primary_rays = 0, shadow_rays = 0, texture_lookups = 0;
  double render_ms = 0;
};

class ReferenceCache {
 public:
  /// Uses (and creates) folder `dir`. UserError when it cannot be created or is not a folder.
  explicit ReferenceCache(std::string dir);

  /// The key text of a reference (see the header comment).
  static std::string Key(const Scene& scene, int width, int height, int grid, uint64_t seed, bool exact);

  /// The entry for `key`, or nullopt when absent. UserError naming the file when it exists
  /// but is damaged or holds another key (delete it and run again).
  std::optional<CachedReference> Load(const std::string& key) const;

  /// Stores the entry atomically (temporary file + rename). UserError when it cannot write.
  void Store(const std::string& key, const CachedReference& entry) const;

  /// The file an entry lives in.
  std::string PathOf(const std::string& key) const;

  const std::string& Dir() const { return dir_; }

 private:
  std::string dir_;
};

/// The reference of `scene` (whose BVH is `tracer`) at width × height: read from `cache` when
/// it holds it, else rendered (grid × grid samples, or the exact reference) and, with a cache,
/// stored. `*from_cache` tells which.
CachedReference ObtainReference(const Scene& scene, const Tracer& tracer, int width, int height, int grid,
                                uint64_t seed, bool exact, const ReferenceCache* cache, bool* from_cache);

}  // namespace aalab
