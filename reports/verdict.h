/// The one-line verdict per scene: which method wins on edge PSNR and on FLIP, by how much
/// over `none`, at what time cost, and whether the two axes disagree. Computed once here and
/// shown both on the run page (reports/html_report.cpp) and in the terminal after `aalab run`.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "reports/result.h"

namespace aalab {

/// Two edge PSNRs closer than this (dB) are a tie (the page shows two decimals).
inline constexpr double kVerdictPsnrTieDb = 0.005;
/// Two mean FLIP values closer than this are a tie (FLIP is in [0, 1]).
inline constexpr double kVerdictFlipTie = 5e-5;

/// The winner on one axis of one scene.
struct AxisVerdict {
  std::string metric;                  ///< "edge_psnr_db" or "flip_mean"
  std::string winner;                  ///< first row in report order within the tie tolerance of the best value
  std::vector<std::string> tied;       ///< the other specs within the tie tolerance of the best value
  double value = 0;                    ///< the winner's value
  std::optional<double> none_value;    ///< `none`'s value on this axis (absent: no none row or null)
  double time_ms = 0;                  ///< the winner's median total time per frame
  std::optional<double> none_time_ms;  ///< `none`'s median total time (absent: no none row)
};

/// A scene's verdict: each axis's winner (absent when no row has a value) and the line.
struct SceneVerdict {
  std::string scene;
  std::optional<AxisVerdict> edge_psnr, flip;
  bool disagree = false;  ///< both axes have winners and no method wins (or ties for the win) on both
  std::string line;       ///< plain text, one line, without the scene name
};

/// The verdict of one scene from the report's rows (rows of other scenes are ignored). Rows that
/// are not applicable are skipped; a null metric leaves that row out of that axis only.
SceneVerdict VerdictForScene(const std::vector<ResultRow>& rows, const std::string& scene);

/// One verdict per scene of `report`, in report order.
std::vector<SceneVerdict> Verdicts(const Report& report);

/// The terminal block: "verdict (…):" then "  scene: line" per scene; empty when no scenes.
std::string FormatVerdicts(const std::vector<SceneVerdict>& verdicts);

}  // namespace aalab
