#include "harness/run/scene_pass.h"

#include <cstdio>
#include <functional>
#include <map>
#include <set>
#include <utility>

#include "core/color.h"
#include "core/parallel.h"
#include "core/timer.h"
#include "harness/run/image_scene.h"
#include "harness/run/out_folder.h"
#include "harness/run/score_rows.h"
#include "harness/run/sequence.h"
#include "io/image_io.h"
#include "scenes/motion.h"

namespace aalab {
namespace fs = std::filesystem;

namespace {

/// Display-linear float image (decoded) of an sRGB-encoded float image, for EXR output.
ImageF DecodeToLinear(const ImageF& encoded) {
  ImageF out(encoded.Width(), encoded.Height(), encoded.Channels());
  for (size_t i = 0; i < encoded.Data().size(); ++i) out.Data()[i] = SrgbDecode(encoded.Data()[i]);
  return out;
}

/// Where a scene's frames come from (one strategy per kind of scene, chosen once).
struct FrameSource {
  bool anew = false;  ///< prepared anew at every frame (else once, at frame 0)
  /// Prepares frame k; adds the time spent building the frame's scene to *scene_ms.
  std::function<std::unique_ptr<PreparedScene>(int k, double* scene_ms)> prepare;
};

/// A captured sequence (a view with N frames) is read anew at every frame, as a moving scene
/// is rendered anew; it has no reference to cache.
FrameSource CapturedFrames(const ScenePass& pass, SceneSource& source) {
  return {true, [&pass, &source](int k, double*) {
            const RunSettings& s = pass.settings;
            return PrepareSource(source, s.width, s.height, pass.plan.scenes.grid, s.seed, s.repeat,
                                 pass.plan.scenes.exact, pass.clock, nullptr, k, pass.plan.viewing.ppd);
          }};
}

/// A moving scene is built, traced and referenced anew at every frame.
FrameSource MovingFrames(const ScenePass& pass, std::shared_ptr<const Scene> sequence) {
  return {true, [&pass, sequence](int k, double* scene_ms) {
            const RunSettings& s = pass.settings;
            Stopwatch build;
            pass.clock->Enter("references");
            auto frame_scene = std::make_unique<Scene>(SceneAtFrame(*sequence, k));
            const double scene_build_ms = build.ElapsedMs();
            auto prepared =
                PrepareScene(std::move(frame_scene), s.width, s.height, pass.plan.scenes.grid, s.seed, s.repeat,
                             pass.plan.scenes.exact, pass.clock, pass.cache, pass.plan.viewing.ppd);
            *scene_ms += scene_build_ms;
            return prepared;
          }};
}

/// A still scene (or a still image-scene view) is prepared once, at frame 0.
FrameSource StillFrames(const ScenePass& pass, SceneSource& source, std::shared_ptr<const Scene> sequence) {
  return {false, [&pass, &source, sequence](int, double*) {
            const RunSettings& s = pass.settings;
            if (sequence) source.scene = std::make_unique<Scene>(*sequence);
            return PrepareSource(source, s.width, s.height, pass.plan.scenes.grid, s.seed, s.repeat,
                                 pass.plan.scenes.exact, pass.clock, pass.cache, 0, pass.plan.viewing.ppd);
          }};
}

/// The files of one scene: frame k's reference and outputs of a sequence as they come, and
/// the last frame's images queued and written in parallel at the scene's end (Flush); a
/// bit-identical output is stored once.
class SceneImages {
 public:
  SceneImages(fs::path tmp, const std::string& name, bool frame_exr)
      : tmp_(std::move(tmp)), rel_dir_("images/" + name), frame_exr_(frame_exr) {
    fs::create_directories(tmp_ / rel_dir_);
  }

  /// A sequence frame's reference: PNG, and display-linear EXR with --frame-exr.
  void ReferenceFrame(const Reference& ref, const std::string& tag) {
    const std::string rel = rel_dir_ + "/reference" + tag + ".png";
    WriteImage8((tmp_ / rel).string(), ToUnorm8(ref.image));
    reference_frames.push_back(rel);
    if (!frame_exr_) return;
    const std::string exr = rel_dir_ + "/reference" + tag + ".exr";
    WriteImageF((tmp_ / exr).string(), DecodeToLinear(ref.image));
    reference_frames_exr.push_back(exr);
  }

  /// The scene's reference images (the last frame's; `ref` must live until Flush).
  void QueueReference(const Reference& ref, SceneResult* sr) {
    const fs::path dir = tmp_ / rel_dir_;
    writes_.push_back([dir, &ref] { WriteImageF((dir / "reference.exr").string(), DecodeToLinear(ref.image)); });
    writes_.push_back([dir, &ref] { WriteImage8((dir / "reference.png").string(), ToUnorm8(ref.image)); });
    writes_.push_back([dir, &ref] { WriteImage8((dir / "edge_mask.png").string(), ToUnorm8(ref.edge_mask)); });
    sr->images = {{"reference_exr", rel_dir_ + "/reference.exr"},
                  {"reference_png", rel_dir_ + "/reference.png"},
                  {"edge_mask", rel_dir_ + "/edge_mask.png"}};
  }

  /// A sequence frame's output; returns its path relative to the report folder.
  std::string OutputFrame(const std::string& spec, const std::string& tag, const Image8& output) {
    const std::string rel = rel_dir_ + "/" + SpecFileName(spec) + tag + ".png";
    WriteImage8((tmp_ / rel).string(), output);
    return rel;
  }

  /// The plan's debug views of the last frame's input (--debug-views), into row.images.
  void DebugViews(const MethodPlan& plan, const MethodOutput& mo, SamplerArithmetic sampler, ResultRow* row) {
    for (const auto& view : plan.debug_views) {
      PostOptions opt;
      opt.debug_view = view;
      opt.sampler = sampler;
      const std::string rel = rel_dir_ + "/" + SpecFileName(plan.spec) + ".debug-" + view + ".png";
      WriteImage8((tmp_ / rel).string(), plan.post(mo.input, opt, nullptr));
      (*row).images["debug_" + view] = rel;
    }
  }

  /// The last frame's output PNG (once per distinct output), queued as soon as the row is
  /// hashed: it needs no score, so it can be written beside the scores (RunAndScoreRows).
  void QueueOutputPng(const std::string& spec, const std::shared_ptr<MethodOutput>& mo) {
    const auto [it, fresh] = file_of_hash_.emplace(mo->row.output_hash, rel_dir_ + "/" + SpecFileName(spec));
    if (!fresh) return;
    const fs::path tmp = tmp_;
    const std::string base = it->second;
    writes_.push_back([tmp, base, mo] { WriteImage8((tmp / (base + ".png")).string(), mo->output); });
  }

  /// The last frame's output (unless QueueOutputPng queued it) and FLIP map, queued (once per
  /// distinct output), into row.images.
  void QueueOutput(const std::string& spec, std::shared_ptr<MethodOutput> mo, int fw, int fh, ResultRow* row) {
    const auto [it, fresh] = file_of_hash_.emplace(row->output_hash, rel_dir_ + "/" + SpecFileName(spec));
    const std::string base = it->second;
    const fs::path tmp = tmp_;
    if (fresh) writes_.push_back([tmp, base, mo] { WriteImage8((tmp / (base + ".png")).string(), mo->output); });
    if (flip_queued_.insert(base).second) {
      writes_.push_back(
          [tmp, base, mo, fw, fh] { WriteGrey8((tmp / (base + ".flip.png")).string(), fw, fh, mo->flip_grey); });
    }
    row->images["output"] = base + ".png";
    row->images["flip_map"] = base + ".flip.png";
  }

  /// The writes queued so far, handed over (to run beside the scores); Flush writes the rest.
  std::vector<std::function<void()>> TakeWrites() { return std::exchange(writes_, {}); }

  void Flush() {
    ParallelFor(static_cast<int>(writes_.size()), [&](int i) { writes_[static_cast<size_t>(i)](); });
  }

  std::vector<std::string> reference_frames, reference_frames_exr;

 private:
  fs::path tmp_;
  std::string rel_dir_;
  bool frame_exr_;
  std::vector<std::function<void()>> writes_;
  std::map<std::string, std::string> file_of_hash_;
  std::set<std::string> flip_queued_;
};

/// The row's name: aalab's method m, or the supplied output after the methods.
const std::string& RowSpec(const RunPlan& plan, size_t m) {
  return m < plan.methods.size() ? plan.methods[m].spec : plan.supplied[m - plan.methods.size()];
}

/// One scene of the run, frame by frame.
class SceneRun {
 public:
  SceneRun(const ScenePass& pass, SceneSource& source)
      : pass_(pass),
        name_(source.Name()),
        frames_(pass.plan.FramesOf(source)),
        images_(pass.tmp, name_, pass.settings.frame_exr),
        // A sequence per (scene, method): methods with memory keep their state from frame
        // to frame; a still run is a sequence of one frame. Image-scene views are still scenes.
        sequence_(std::move(source.scene)),
        captured_(source.view && source.view->frames > 1),
        moves_((sequence_ && sequence_->animation.Moves()) || captured_),
        source_(captured_ ? CapturedFrames(pass, source)
                : moves_  ? MovingFrames(pass, sequence_)
                          : StillFrames(pass, source, sequence_)),
        states_(pass.plan.methods.size()) {
    for (size_t m = 0; m < pass.plan.RowsPerFrame(); ++m) {
      tracks_.emplace_back(pass.plan.viewing.ppd, pass.plan.viewing.fps, frames_);
    }
  }

  SceneResult Run(std::vector<ResultRow>* rows) {
    for (int k = 0; k < frames_; ++k) {
      const std::string tag = frames_ > 1 ? ".f" + std::to_string(k) : "";
      PrepareFrame(k, tag);
      const bool last = k == frames_ - 1;
      // On the last frame, the images that need no score (the reference's, every distinct
      // output's PNG) are written beside the scores, once the timed renders are done.
      const BesideJobs beside = [this](const std::vector<std::shared_ptr<MethodOutput>>& rows) {
        for (size_t m = 0; m < rows.size(); ++m) {
          if (rows[m]->row.not_applicable.empty()) images_.QueueOutputPng(RowSpec(pass_.plan, m), rows[m]);
        }
        return images_.TakeWrites();
      };
      std::vector<std::shared_ptr<MethodOutput>> outs =
          ScoreFrameRows(pass_, *prepared_, &states_, name_ + tag, last, last ? beside : nullptr);
      for (size_t m = 0; m < outs.size(); ++m) RecordRow(m, k, tag, std::move(outs[m]), rows);
    }
    return Finish();
  }

 private:
  /// Prepares frame k when the source needs it (the first frame; every frame of a moving or
  /// captured sequence) and writes a sequence's frame reference.
  void PrepareFrame(int k, const std::string& tag) {
    if (!prepared_ || source_.anew) {
      prepared_ = source_.prepare(k, &scene_ms_);
      prepared_->sequence_scene = sequence_;
      // A capture's mismatch warnings (image scenes): said now, kept for the report (the
      // first frames that have any, then a count).
      for (const auto& w : prepared_->info.warnings) {
        std::fprintf(stderr, "aalab: warning: scene '%s': %s\n", name_.c_str(), w.c_str());
        if (warnings_.size() < 3)
          warnings_.push_back(w);
        else
          ++more_warnings_;
      }
      scene_ms_ += prepared_->info.bvh_build_ms;
      reference_ms_ += prepared_->info.reference_ms;
    }
    prepared_->frame = k;
    pass_.clock->Enter("image_writing");
    if (frames_ > 1) images_.ReferenceFrame(prepared_->ref, tag);
    if (k == frames_ - 1) {  // `prepared_` (and so its reference) lives until the scene's writes are done
      result_ = prepared_->info;
      result_.warnings = warnings_;
      if (more_warnings_)
        result_.warnings.push_back(std::to_string(more_warnings_) + " more frame(s) with such warnings");
      images_.QueueReference(prepared_->ref, &result_);
    }
    pass_.progress->Step(name_ + tag + " reference");
  }

  /// Row m of frame k: a sequence's frame output and track; on the last frame, the row's
  /// debug views and images and the row itself into the report.
  void RecordRow(size_t m, int k, const std::string& tag, std::shared_ptr<MethodOutput> mo,
                 std::vector<ResultRow>* rows) {
    const bool last = k == frames_ - 1;
    ResultRow& row = mo->row;
    if (!row.not_applicable.empty()) {  // a renderer-side method on an image scene: no images
      if (last) rows->push_back(std::move(row));
      return;
    }
    const std::string& spec = RowSpec(pass_.plan, m);
    pass_.clock->Enter("image_writing");
    if (frames_ > 1) tracks_[m].AddFrame(*mo, *prepared_, images_.OutputFrame(spec, tag, mo->output));
    if (!last) return;
    const MethodPlan* plan = m < pass_.plan.methods.size() ? &pass_.plan.methods[m] : nullptr;
    if (pass_.settings.debug_views && plan && plan->post) images_.DebugViews(*plan, *mo, pass_.settings.sampler, &row);
    mo->input = Image8();  // only the output and FLIP map wait for the scene's writes
    images_.QueueOutput(spec, mo, prepared_->info.width, prepared_->info.height, &row);
    if (frames_ > 1) tracks_[m].Finish(&row);
    rows->push_back(row);
  }

  /// The scene's end: states and the metrics' reference sides freed (not needed by the
  /// writes; ~50 MB at 960x540), the sequence's facts, the queued images written.
  SceneResult Finish() {
    states_.clear();
    if (prepared_) {
      prepared_->flip_reference.reset();
      prepared_->ssim_reference.reset();
    }
    if (frames_ > 1) {
      result_.frames = frames_;
      result_.moves = moves_;
      result_.frame_images = images_.reference_frames;
      result_.frame_exr_images = images_.reference_frames_exr;
      result_.sequence_scene_ms = scene_ms_;
      result_.sequence_reference_ms = reference_ms_;
    }
    pass_.clock->Enter("image_writing");
    images_.Flush();
    return std::move(result_);
  }

  const ScenePass& pass_;
  const std::string name_;
  const int frames_;
  SceneImages images_;
  const std::shared_ptr<const Scene> sequence_;
  const bool captured_;
  const bool moves_;
  FrameSource source_;
  std::vector<std::unique_ptr<TemporalState>> states_;
  std::vector<SequenceTrack> tracks_;
  std::unique_ptr<PreparedScene> prepared_;
  SceneResult result_;
  double scene_ms_ = 0, reference_ms_ = 0;
  std::vector<std::string> warnings_;
  int more_warnings_ = 0;
};

}  // namespace

std::vector<std::shared_ptr<MethodOutput>> ScoreFrameRows(const ScenePass& pass, const PreparedScene& prepared,
                                                          std::vector<std::unique_ptr<TemporalState>>* states,
                                                          const std::string& step_prefix, bool last_frame,
                                                          const BesideJobs& beside) {
  const RunPlan& plan = pass.plan;
  const RunSettings& s = pass.settings;
  const MethodRunSettings run{s.seed, s.repeat, s.sampler, pass.clock};
  // aalab's methods (run, then scored together), then the user's supplied outputs (scored, not run).
  std::vector<std::shared_ptr<MethodOutput>> outs =
      RunAndScoreRows(prepared, plan.methods, run, states, last_frame && s.debug_views, beside);
  for (size_t m = plan.methods.size(); m < plan.RowsPerFrame(); ++m) {
    outs.push_back(std::make_shared<MethodOutput>(SuppliedOutputRow(prepared, RowSpec(plan, m), s.repeat, pass.clock)));
  }
  for (size_t m = 0; m < outs.size(); ++m) {
    const bool na = !outs[m]->row.not_applicable.empty();
    pass.progress->Step(step_prefix + " " + RowSpec(plan, m) + (na ? " (not applicable)" : ""));
  }
  return outs;
}

SceneResult RunScene(const ScenePass& pass, SceneSource& source, std::vector<ResultRow>* rows) {
  return SceneRun(pass, source).Run(rows);
}

}  // namespace aalab
