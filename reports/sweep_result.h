/// The result of `aalab sweep` (harness/run/sweep.h runs it): the grid's axes, each point's
/// objectives averaged over scenes, the Pareto front, the best points and the rows; and the
/// text of its values, shared by the CLI summary (SweepSummaryText) and the page
/// (reports/sweep_page.h).
#pragma once
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "reports/compare.h"
#include "reports/result.h"

namespace aalab {

/// One swept parameter and its values (canonical text, as the method resolves them).
struct GridAxis {
  std::string name;
  std::vector<std::string> values;
};

/// An objective averaged over scenes: arithmetic mean of the per-scene values; +inf when any
/// scene is identical to the reference (higher-is-better metrics); empty with a reason when
/// any scene's value is null for another reason.
struct ObjectiveMean {
  std::optional<double> mean;
  std::string null_reason;
};

/// One grid point, summarised over scenes.
struct SweepPoint {
  std::vector<std::pair<std::string, std::string>> overrides;  ///< axis name → value
  std::string spec;                                            ///< canonical spec
  std::map<std::string, ObjectiveMean> objectives;
  double mean_time_ms = 0;    ///< mean over scenes of the method time's median (MethodTime)
  double time_spread_ms = 0;  ///< mean over scenes of the method time's max − min over repeats (its noise)
  bool pareto = false;        ///< on the front of the first objective vs time
};

/// The suggested point against the shipped default on one scene.
struct SweepSceneChange {
  std::string scene;
  struct Value {
    std::string objective;
    std::optional<double> at_default, suggested;  ///< +inf: identical to the reference
  };
  std::vector<Value> values;                ///< one per objective
  double default_ms = 0, suggested_ms = 0;  ///< the method time's median
  double default_spread_ms = 0, suggested_spread_ms = 0;
};

/// A crop of one point's output (or of the reference) written by the sweep.
struct SweepCrop {
  std::string scene;
  std::string role;  ///< "reference", "default", "suggested", "best <objective>", "extreme <overrides>"
  std::string spec;  ///< the point's spec ("" for the reference)
  int window = 0;    ///< index into the scene's crop windows
  std::string path;  ///< relative to the sweep folder
};

struct SweepResult {
  std::string method;  ///< registry name
  std::vector<GridAxis> axes;
  std::vector<std::string> objectives;
  std::string objective_note;  ///< set when the default objective fell back to psnr_db
  int reference_renders = 0;   ///< PrepareScene calls (one per rendered scene; image-scene views render none)
  std::vector<SweepPoint> points;
  std::vector<size_t> pareto_front;             ///< indices into points, by time
  std::map<std::string, size_t> best;           ///< objective → best point (absent when all are null)
  std::map<std::string, int> best_ties;         ///< objective → other points with the same best mean
  std::string suggested_preset;                 ///< spec of the suggested point (SummarizeSweep's rule)
  std::optional<size_t> suggested;              ///< its index
  std::string suggestion_rule;                  ///< how it was chosen, in words
  std::optional<size_t> default_point;          ///< the point whose swept values are the --method's own
  std::string default_note;                     ///< why there is none (the defaults are not on the grid)
  std::vector<std::string> disagreements;       ///< objectives whose picks differ, said loudly
  std::vector<SweepSceneChange> scene_changes;  ///< suggested vs default, per scene
  std::vector<SweepCrop> crops;                 ///< written by an unsharded sweep (empty after a merge)
  Report report;                                ///< context, settings, scenes, rows (scene-major); a shard's block
  std::vector<size_t> row_point;                ///< point index of each report row
  std::vector<std::string> specs;               ///< every grid point's spec, in grid order
  std::string base_spec;                        ///< --method as given
  std::string out_dir;
};

/// "name=value,name=value" (no spaces), in the given order.
std::string JoinOverrides(const std::vector<std::pair<std::string, std::string>>& overrides);

/// A metric's value as the sweep prints it: 3 decimals for dB metrics, else %.6g; "inf" / "-inf".
std::string SweepValueText(const std::string& metric, double v);

/// An objective mean as text: SweepValueText plus " dB" for finite dB means, or
/// "null (reason)".
std::string SweepMeanText(const std::string& metric, const ObjectiveMean& m);

/// a better than b (strictly) for `better`; empty values are worst.
bool StrictlyBetter(const std::optional<double>& a, const std::optional<double>& b, Better better);

}  // namespace aalab
