#include "harness/run/score_rows.h"

#include <map>
#include <string>

#include <tbb/task_arena.h>

#include "core/error.h"
#include "core/hash.h"
#include "core/parallel.h"

namespace aalab {

std::vector<std::shared_ptr<MethodOutput>> RunAndScoreRows(const PreparedScene& prepared,
                                                           const std::vector<MethodPlan>& plans,
                                                           const MethodRunSettings& run,
                                                           std::vector<std::unique_ptr<TemporalState>>* states,
                                                           bool keep_inputs, const BesideJobs& beside) {
  StageClock* const clock = run.clock;
  AALAB_CHECK(states && states->size() >= plans.size(), "one sequence state per plan");
  std::vector<std::shared_ptr<MethodOutput>> rows;
  rows.reserve(plans.size());
  // The timed part: one row after another, nothing else running.
  for (size_t m = 0; m < plans.size(); ++m) {
    auto mo = std::make_shared<MethodOutput>(RunMethod(prepared, plans[m], run, &(*states)[m], /*score=*/false));
    if (!keep_inputs) mo->input = Image8();
    rows.push_back(std::move(mo));
  }
  if (clock) clock->Enter("metrics");
  // Every row's output hash (FNV-1a: one serial chain per output, ~3 ms at 960x540), the rows
  // side by side once the timed renders are done.
  ParallelFor(static_cast<int>(rows.size()), [&](int m) {
    MethodOutput& mo = *rows[static_cast<size_t>(m)];
    if (mo.row.not_applicable.empty()) mo.row.output_hash = HashBytes(mo.output.Data().data(), mo.output.Data().size());
  });
  // The distinct outputs still to score, in row order (the first row with each hash).
  std::vector<size_t> to_score;
  std::map<std::string, size_t> first_of_hash;
  for (size_t m = 0; m < rows.size(); ++m) {
    const MethodOutput& mo = *rows[m];
    if (!mo.row.not_applicable.empty()) continue;
    const std::string& hash = mo.row.output_hash;
    if (prepared.scored_by_hash.count(hash) || first_of_hash.count(hash)) continue;
    first_of_hash.emplace(hash, m);
    to_score.push_back(m);
  }
  std::vector<PreparedScene::Scored> scores(to_score.size());
  const std::vector<std::function<void()>> jobs = beside ? beside(rows) : std::vector<std::function<void()>>();
  // Each score (and each job beside them) runs isolated: while its own parallel loops wait, a
  // thread takes no other row's score, so at most one score per thread is in flight (each
  // holds ~50 MB of planes at 960x540).
  ParallelFor(static_cast<int>(to_score.size() + jobs.size()), [&](int i) {
    const auto k = static_cast<size_t>(i);
    tbb::this_task_arena::isolate([&] {
      if (k < to_score.size())
        scores[k] = ScoreFrame(prepared, rows[to_score[k]]->output);
      else
        jobs[k - to_score.size()]();
    });
  });
  for (size_t i = 0; i < to_score.size(); ++i) {
    prepared.scored_by_hash.emplace(rows[to_score[i]]->row.output_hash, std::move(scores[i]));
  }
  for (auto& mo : rows) {
    if (!mo->row.not_applicable.empty()) continue;
    const PreparedScene::Scored& s = prepared.scored_by_hash.at(mo->row.output_hash);
    mo->row.metrics = s.metrics;
    mo->flip_grey = s.flip_grey;
  }
  return rows;
}

}  // namespace aalab
