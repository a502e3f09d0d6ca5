/// The output folder of `run`, `sweep` and `merge`: checked before any work, written through
/// DIR.partial and moved into place only when everything succeeded, so a failed command never
/// leaves a half-written result.
#pragma once
#include <filesystem>
#include <string>

namespace aalab {

class OutFolder {
 public:
  /// Checks `dir`: not empty, not a file, and, when it exists and is not empty, holding
  /// `marker` (the report file a previous run wrote): a folder of other files is never
  /// replaced. UserError naming the folder otherwise. Creates nothing.
  OutFolder(const std::string& dir, const std::string& marker);
  /// Removes DIR.partial if Commit() was not reached.
  ~OutFolder();
  OutFolder(const OutFolder&) = delete;
  OutFolder& operator=(const OutFolder&) = delete;

  /// Creates DIR.partial afresh (removing a leftover one) and returns it.
  const std::filesystem::path& Begin();
  /// DIR.partial.
  const std::filesystem::path& Partial() const { return partial_; }
  /// Replaces DIR with DIR.partial.
  void Commit();

 private:
  std::filesystem::path dir_, partial_;
  bool begun_ = false, committed_ = false;
};

}  // namespace aalab
