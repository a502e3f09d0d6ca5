// Paths aalab did not choose (io/safe_path.h).
#include "io/safe_path.h"

#include "core/error.h"

namespace aalab {
namespace fs = std::filesystem;

namespace {

bool Inside(const fs::path& outer, const fs::path& inner) {
  auto o = outer.begin(), i = inner.begin();
  for (; o != outer.end(); ++o, ++i) {
    if (o->empty()) continue;  // a trailing "/" of outer
    if (i == inner.end() || *o != *i) return false;
  }
  return true;
}

/// "" when `name` is a plain file name, else why not.
std::string WhyNotPlain(const std::string& name) {
  if (name.empty()) return "is empty";
  if (name == "." || name == "..") return "is a folder reference, not a name";
  if (name.size() > 200) return "is longer than 200 bytes";
  if (name[0] == '.') return "starts with '.' (aalab's own files do)";
  for (const char c : name) {
    if (c == '/' || c == '\\') return "holds a path separator";
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return "holds a control character";
  }
  return "";
}

}  // namespace

fs::path ResolveInside(const fs::path& base, const std::string& rel, const std::string& what) {
  const std::string rule = "; paths in this file are relative to its folder '" + base.string() +
                           "' and must stay inside it (no absolute paths, no '..' out of it, no symlinks out of it)";
  if (rel.empty()) throw UserError(what + ": an empty path" + rule);
  if (rel.find('\0') != std::string::npos) throw UserError(what + ": the path holds a NUL byte" + rule);
  const fs::path r(rel);
  if (r.is_absolute() || r.has_root_name() || r.has_root_directory()) {
    throw UserError(what + ": '" + rel + "' is an absolute path" + rule);
  }
  const fs::path joined = (base / r).lexically_normal();
  const fs::path b = fs::absolute(base).lexically_normal(), abs_joined = (b / r).lexically_normal();
  if (!Inside(b, abs_joined) || abs_joined == b) throw UserError(what + ": '" + rel + "' leaves the folder" + rule);
  std::error_code ec;
  const fs::path real_base = fs::weakly_canonical(b, ec);
  const fs::path real = ec ? fs::path() : fs::weakly_canonical(abs_joined, ec);
  if (ec || !Inside(real_base, real) || real == real_base) {
    throw UserError(what + ": '" + rel + "' leads out of the folder through a symlink (to '" + real.string() + "')" +
                    rule);
  }
  return joined;
}

void CheckOutputName(const std::string& name, const std::string& what, const std::vector<std::string>& reserved) {
  if (const std::string why = WhyNotPlain(name); !why.empty()) {
    throw UserError(what + ": the name '" + name + "' " + why +
                    "; names that become output files must be plain file names (no '/', '\\', '..', leading '.' or "
                    "control characters, at most 200 bytes), so nothing is written outside --out");
  }
  for (const auto& r : reserved) {
    if (name == r) {
      throw UserError(what + ": the name '" + name + "' is reserved for aalab's own files in the output (reserved: " +
                      [&] {
                        std::string s;
                        for (const auto& x : reserved) s += (s.empty() ? "" : ", ") + x;
                        return s;
                      }() +
                      "); give it another name");
    }
  }
}

const std::string& CheckOutputRelPath(const std::string& rel, const std::string& what) {
  const fs::path p(rel);
  if (rel.empty() || p.is_absolute() || p.has_root_name() || p.has_root_directory()) {
    throw UserError(what + ": '" + rel + "' is " + (rel.empty() ? "empty" : "an absolute path") +
                    "; paths in an aalab output are relative to its folder and stay inside it");
  }
  size_t start = 0;
  while (start <= rel.size()) {
    const size_t end = std::min(rel.find('/', start), rel.size());
    const std::string part = rel.substr(start, end - start);
    if (const std::string why = WhyNotPlain(part); !why.empty()) {
      throw UserError(what + ": '" + rel + "' has a component '" + part + "' that " + why +
                      "; paths in an aalab output are made of plain names and stay inside its folder");
    }
    start = end + 1;
  }
  return rel;
}

}  // namespace aalab
