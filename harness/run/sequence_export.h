/// `aalab export-sequences`: a motion run's sequences as numbered frame folders, the layout
/// outside video metrics read (image sequences with a printf pattern), plus the run's viewing
/// condition. docs/motion.md "Exporting sequences".
#pragma once
#include <string>

namespace aalab {

/// What ExportSequences wrote.
struct SequenceExport {
  int scenes = 0;     ///< scenes with a sequence (frames > 1)
  int sequences = 0;  ///< folders written (references + method rows)
  int frames = 0;     ///< image files written
};

/// Reads RUN_DIR/report.json of a motion run (--frames N > 1) and writes, through OUT.partial
/// (harness/run/out_folder.h) and the checked image writers: OUT/<scene>/reference/NNNNN.png
/// (8-bit sRGB as the run wrote it) and, when the run had --frame-exr, NNNNN.exr (display-linear
/// float); OUT/<scene>/<spec>/NNNNN.png for every method row; OUT/sequences.json listing every
/// folder, its frame count, the file pattern and the run's viewing condition (ppd, fps,
/// display, peak luminance, ambient). A report without sequences, a missing frame file or a
/// non-empty OUT without sequences.json: UserError, nothing left behind.
SequenceExport ExportSequences(const std::string& run_dir, const std::string& out_dir);

}  // namespace aalab
