/// Image scenes: a user's own frames as scenes (docs/own-frames.md). A JSON manifest
/// ({"aalab_image_scene": 1, "views": [...]}) lists views; each view is the renderer's 1x frame
/// (8-bit, display-encoded), a reference (scene-linear EXR through the view's display transform,
/// or an 8/16-bit display-encoded PNG/TIFF) and optionally depth, object ids or a ready edge
/// mask. A view runs like a scene for every method that needs only the 1x frame (`none` and
/// the post filters); the others get a "not applicable" row.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/color.h"
#include "core/image.h"
#include "scenes/image_sequence.h"
#include "harness/run/pipeline.h"

namespace aalab {

/// One view of an image scene (one frame of it, for a sequence), read and validated.
struct ImageView {
  std::string name;  ///< lowercase-kebab, unique in the run
  std::string description;
  std::string manifest;                ///< the manifest's path, as given
  size_t index = 0;                    ///< position in the manifest's "views"
  Image8 frame;                        ///< the 1x frame (RGBA8, alpha 255)
  ImageF reference;                    ///< sRGB-encoded float RGB, not quantised (what Reference::image holds)
  std::string reference_note;          ///< how the reference file was read
  ImageF edge_mask_raw;                ///< the mask before dilation (the given mask when one was given)
  ImageF edge_mask;                    ///< the mask the edge metrics use
  std::string edge_mask_source;        ///< how the mask was made, for the report
  int frames = 1;                      ///< frames in the view's sequence (1: a still view)
  int frame_index = 0;                 ///< the frame this holds
  std::optional<double> frame_ms;      ///< the 1x frame's render time per frame, when given
  std::vector<SuppliedFrame> outputs;  ///< the user's own AA outputs of this frame
  /// Motion vectors and jitter given (TAA can run): this frame's jitter and, from frame 1 on,
  /// TAA's `previous` positions derived from the motion vectors (image_sequence.h).
  bool has_motion = false;
  Jitter jitter{0.0f, 0.0f};
  std::vector<float> previous;
  std::string motion_note;  ///< the motion-vector convention, in words
  /// The manifest's `reference_info`: what made the reference ("" / 0 when not given).
  std::string reference_origin;
  int reference_spp = 0;
  int width = 0, height = 0;  ///< the frame's size (kept in the light copy a run plans with)
};

/// Whether `path` names an image-scene manifest: a readable JSON file whose top level is an
/// object with "aalab_image_scene" or "views". Anything else (a scene file, a library name,
/// a file that is not JSON) is false and goes to the scene loader, which reports its errors.
bool IsImageSceneManifest(const std::string& path);

/// Reads a manifest and every image it names (paths relative to the manifest's folder).
/// Throws UserError with one message naming the manifest, the JSON path and what is allowed
/// for: unknown fields, a missing or wrong "aalab_image_scene" (must be 1), no views, a bad or
/// duplicate view name, missing/unreadable images, wrong file type or bit depth, sizes that
/// differ, out-of-range depth, a mask that is not 0/255, conflicting edge sources.
std::vector<ImageView> LoadImageScene(const std::string& manifest_path);

/// One entry of `--scenes`: a scene the tracer renders, or a view of an image scene.
struct SceneSource {
  std::unique_ptr<Scene> scene;  ///< set for a rendered scene
  /// Set for an image-scene view: its name, manifest and index only (validated, pixels not
  /// kept); PrepareSource reads the images again, so a run holds one view's pixels at a time.
  std::unique_ptr<ImageView> view;
  const std::string& Name() const;
  /// Frames of the source's own sequence: a sequence view's N, else 1.
  int Frames() const { return view ? view->frames : 1; }
};

/// Loads every name: library names and scene files through LoadScenes, manifests through
/// LoadImageScene (each view one source, in manifest order). Names must be unique across all.
std::vector<SceneSource> LoadSceneSources(const std::vector<std::string>& names);

/// PrepareScene for a rendered scene; for a view (read again from its manifest; UserError if
/// the file changed since LoadSceneSources), a PreparedScene without scene or tracer:
/// the view's frame as the 1x frame (render time unknown: 0, no cost counters), its
/// reference and edge mask, crops as PrepareScene picks them, and no noise floor (a user's
/// reference has no independent halves; the report gives the reason). `width`, `height`,
/// `grid` and `seed` apply to rendered scenes only.
/// For a sequence view, `frame` picks the frame (0..N−1) and the source is only read (a
/// view source stays usable for the next frame); rendered scenes ignore it.
std::unique_ptr<PreparedScene> PrepareSource(SceneSource& source, int width, int height, int grid, uint64_t seed,
                                             int repeat, bool exact_reference = false, StageClock* clock = nullptr,
                                             const ReferenceCache* cache = nullptr, int frame = 0,
                                             double flip_ppd = kFlipDefaultPpd);

/// The names of the outputs supplied by the views among `sources`, in first-seen order.
std::vector<std::string> SuppliedOutputNames(const std::vector<SceneSource>& sources);

/// CheckReferenceKind over sources: `--reference exact` applies to rendered flat scenes only,
/// so an image-scene view (whose reference is the user's file) is refused with its name.
bool CheckReferenceKind(const std::string& kind, const std::vector<SceneSource>& sources);

/// The row of a supplied output (the user's own AA) on a prepared view: scored like any
/// method's output; `supplied` set; timings from the manifest's `ms` (one sample per repeat)
/// or empty when not given. A view without that output gets a not-applicable row.
MethodOutput SuppliedOutputRow(const PreparedScene& prepared, const std::string& name, int repeat,
                               StageClock* clock = nullptr);

}  // namespace aalab
