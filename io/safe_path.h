/// The one rule for paths aalab did not choose itself (issue #39). Every path read from a
/// report, a manifest, a scene file or a glTF file, and every name that becomes part of an
/// output path (a scene name, a method spec, a supplied output's name), goes through these
/// functions before aalab opens or creates anything with it:
///
///  - ResolveInside: a path read from a file is relative to that file's folder and must stay
///    inside it once `.`/`..` and the symlinks of its existing part are resolved. An absolute
///    path, `../x` leaving the folder, or a symlink pointing out of it is refused, naming the
///    field, the path and the rule. (Use it for report image paths, manifest frames and
///    captures, scene-file meshes, glTF URIs.)
///  - CheckOutputName: a name used as ONE path component under an output folder must be a
///    plain file name: not empty, not `.`/`..`, no `/` or `\`, no control characters, not
///    starting with `.` (aalab's own files `.aalab-output`, `.aalab-lock` start with one), at
///    most 200 bytes, and not one of the caller's reserved names (`reference`, method names).
///  - CheckOutputRelPath: a relative path under an output folder (`images/circle/none.png`
///    named by a shard's report) must be relative and made of CheckOutputName components, so
///    `--out DIR` + path stays inside DIR whatever the report says.
///
/// All three throw UserError: "<what>: '<path>' <why>; <the rule>". `what` names the field and
/// the file it came from, e.g. "rows[3].images.output of report 'shard0/report.json'".
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace aalab {

/// The file names an output folder of aalab's holds for its own use, never a user row's name.
inline const std::vector<std::string>& ReservedOutputNames() {
  static const std::vector<std::string> names = {"reference", "edge_mask", "images", "report.json", "index.html"};
  return names;
}

/// `rel` (read from `what`) joined to `base` and checked to stay inside `base` (lexically, and
/// again with the symlinks of the existing part resolved). Returns base/rel, normalised.
std::filesystem::path ResolveInside(const std::filesystem::path& base, const std::string& rel, const std::string& what);

/// Checks that `name` is one plain path component (see above) and not in `reserved`.
void CheckOutputName(const std::string& name, const std::string& what, const std::vector<std::string>& reserved = {});

/// Checks that `rel` is a relative path of plain components (no `..`, `.`, empty or
/// hidden components, no absolute root); returns it unchanged.
const std::string& CheckOutputRelPath(const std::string& rel, const std::string& what);

}  // namespace aalab
