/// The one rule for output folders (run, sweep, merge, export-frames): checked before any
/// work, written through DIR.partial and moved into place only when everything succeeded.
///
///  - The path is normalised first: trailing slashes, `.`, `..` and symlinks resolved, so
///    `results/`, `results/.` and `results/x/..` are the folder `results`.
///  - An existing folder is replaced only when it is an earlier aalab output of the same kind
///    and holds nothing aalab did not write: aalab lists every file it wrote in DIR/.aalab-output
///    at commit, and refuses (before any work) a folder without that list, of another kind, or
///    holding any file not in the list. An empty folder is fine.
///  - The folder may neither equal nor contain an input of the command (scene files, shard
///    folders, the reference cache...).
///  - DIR.partial is created at once and holds a lock (flock on DIR.partial/.aalab-lock): a
///    second command into the same folder is refused at its start. A DIR.partial left by a
///    killed command (lock free, marker present) is removed; one aalab did not create is refused.
///  - An existing DIR that is a mount point (a container's bind mount) is refused before any
///    work: it cannot be replaced by a rename. A folder inside it is fine.
///  - Commit: DIR is checked again (a file the user added during the run is never deleted),
///    moved aside, DIR.partial renamed to DIR, the old folder removed; an interruption
///    (core/cleanup.h) removes DIR.partial and leaves DIR as it was. When the re-check
///    or a rename fails, the finished output stays in DIR.partial (without its lock, so no
///    later command removes it) and the error says where.
///  - Every input counts: the files a scene was built from (Scene::files_read: meshes, glTF
///    buffers and textures, image-scene frames and captures) are inputs like the scene file.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace aalab {

/// The file in every output folder that lists what aalab wrote there.
inline constexpr const char* kOutputMarker = ".aalab-output";

/// Normalises an output path: absolute, `.`/`..`/trailing slashes removed, symlinks of the
/// existing part resolved. UserError for an empty path or the root folder.
std::filesystem::path NormaliseOutPath(const std::string& dir, const std::string& option = "--out");

class OutFolder {
 public:
  /// Checks `dir` as above for an output of `kind` ("run", "sweep", "frames", "export", "sequences",
  /// "history"); `inputs` are
  /// the files and folders the command reads or creates (a --ref-cache that does not exist yet
  /// counts too; callers pass scene names only when they are files). Takes the
  /// lock and creates DIR.partial. UserError naming the folder and what to do otherwise.
  OutFolder(const std::string& dir, const std::string& kind, const std::vector<std::string>& inputs = {});
  /// Removes DIR.partial if Commit() was not reached.
  ~OutFolder();
  OutFolder(const OutFolder&) = delete;
  OutFolder& operator=(const OutFolder&) = delete;

  /// DIR.partial (created by the constructor), where the command writes.
  const std::filesystem::path& Begin() { return partial_; }
  const std::filesystem::path& Partial() const { return partial_; }
  /// The normalised DIR.
  const std::filesystem::path& Dir() const { return dir_; }
  /// Lists the files written in DIR.partial/.aalab-output and replaces DIR with DIR.partial
  /// (checking again that DIR holds nothing aalab did not write).
  /// Finished output that cannot be put in place (DIR changed during the run, a rename
  /// refused) is kept in DIR.partial, and the UserError says so: no work is lost.
  void Commit();

 private:
  void KeepPartial();
  std::filesystem::path dir_, partial_;
  std::string kind_;
  int lock_fd_ = -1;
  bool committed_ = false;
};

/// Checks that the output file `path` may be written: not equal to any of `inputs` (an
/// `apply` onto its own input), not a folder. Returns the normalised path.
std::string CheckOutFile(const std::string& path, const std::vector<std::string>& inputs);

/// A file or folder name from a method spec, as every output folder names a method's images:
/// ':' and ',' become '_', '=' becomes '-' (e.g. "smaa:preset=high" → "smaa_preset-high").
std::string SpecFileName(const std::string& spec);

}  // namespace aalab
