// `aalab merge` and `aalab same-results`: the commands of sharded runs (docs/cluster.md).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "harness/cli/commands.h"
#include "core/error.h"
#include "core/exit_code.h"
#include "harness/run/merge.h"
#include "harness/run/same_results.h"
#include "harness/run/sequence_export.h"

namespace aalab {
namespace fs = std::filesystem;

void RegisterClusterCommands(CLI::App& app, Commands& commands) {
  // export-sequences (docs/motion.md "Exporting sequences")
  auto* ex = app.add_subcommand("export-sequences",
                                "write a motion run's sequences as numbered frame folders for outside video metrics");
  struct ExportArgs {
    std::string run, out;
  };
  auto ea = std::make_shared<ExportArgs>();
  ex->add_option("run", ea->run, "the run's folder (holding report.json of a run with --frames N > 1)")->required();
  ex->add_option("--out", ea->out, "output folder")->required();
  ex->callback([&commands, ea] {
    commands.action = [ea] {
      const SequenceExport r = ExportSequences(ea->run, ea->out);
      std::printf("exported %d scenes, %d sequences, %d frames\nindex: %s\n", r.scenes, r.sequences, r.frames,
                  (fs::absolute(ea->out) / "sequences.json").string().c_str());
      return ToInt(ExitCode::kOk);
    };
  });

  auto* merge = app.add_subcommand(
      "merge", "merge the shards of a run or sweep (--shard K/N) into the report one process would have written");
  struct MergeArgs {
    std::vector<std::string> dirs;
    std::string out;
  };
  auto m = std::make_shared<MergeArgs>();
  merge->add_option("shards", m->dirs, "the shard folders (all N of them, any order)")->required();
  merge->add_option("--out", m->out, "output folder for the merged report")->required();
  merge->footer(
      "Checks first, naming the folder and the problem: every folder is a shard of one split (same N), each\n"
      "K in 0..N-1 exactly once, the same settings (the thread count may differ) and the same build, each\n"
      "shard holding exactly its round-robin share. Writes report.json + index.html + images (run) or\n"
      "sweep.json + index.html (sweep) through DIR.partial. Timings and the context block are the shards'.");
  merge->callback([&commands, m] {
    commands.action = [m] {
      const MergeResult r = MergeShards(m->dirs, m->out);
      const fs::path dir = fs::absolute(r.out_dir);
      std::printf("merged %d %s shards: %zu scenes, %zu results\nhtml:   %s\n%s %s\n", r.shards, r.kind.c_str(),
                  r.scenes, r.rows, (dir / "index.html").string().c_str(), r.kind == "run" ? "report:" : "sweep: ",
                  (dir / (r.kind == "run" ? "report.json" : "sweep.json")).string().c_str());
      return ToInt(ExitCode::kOk);
    };
  });

  auto* same = app.add_subcommand(
      "same-results", "check that two run (or sweep) folders hold the same results, timings and context aside");
  auto pair = std::make_shared<std::vector<std::string>>();
  same->add_option("folders", *pair, "folder A and folder B")->required()->expected(2);
  same->footer(
      "Compares report.json (or sweep.json) with the context block, the time breakdown, the shard block, the\n"
      "thread count and every timing removed, then the bytes of every linked image.\n"
      "Exit 0: the same; 1: different (the first differences are listed); 2: could not compare.");
  same->callback([&commands, pair] {
    commands.action = [pair] {
      SameResults r;
      try {
        r = CompareResultFolders((*pair)[0], (*pair)[1]);
      } catch (const UserError& e) {
        std::fprintf(stderr, "aalab: error: %s\n", e.what());
        return ToInt(ExitCode::kCouldNotCompare);
      }
      if (r.same) {
        std::printf("same results: '%s' and '%s' (timings and context aside)\n", (*pair)[0].c_str(),
                    (*pair)[1].c_str());
        return ToInt(ExitCode::kOk);
      }
      std::printf("different results: '%s' (A) and '%s' (B)\n", (*pair)[0].c_str(), (*pair)[1].c_str());
      for (const auto& line : r.differences) std::printf("  %s\n", line.c_str());
      return ToInt(ExitCode::kFailure);
    };
  });
}

}  // namespace aalab
