/// Typed, path-tracking reads from JSON for scene validation: every error names the file,
/// the JSON path, the bad value and what is allowed.
#pragma once
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace aalab {

/// A JSON value with its path inside a named document.
class JsonField {
 public:
  JsonField(const nlohmann::json& value, std::string origin, std::string path)
      : value_(value), origin_(std::move(origin)), path_(std::move(path)) {}

  const nlohmann::json& Value() const { return value_; }
  const std::string& Path() const { return path_; }
  bool Has(const std::string& key) const { return value_.is_object() && value_.contains(key); }

  /// Throws UserError "<origin>: <path>: <message>".
  [[noreturn]] void Fail(const std::string& message) const;

  /// Requires an object whose keys are all in `allowed`; names unknown keys.
  void RequireObject(const std::set<std::string>& allowed) const;
  JsonField Child(const std::string& key) const;  ///< required member
  JsonField At(size_t index) const;               ///< array element
  size_t ArraySize() const;                       ///< requires an array

  std::string String() const;
  /// One of `choices` (error lists them).
  std::string Choice(const std::vector<std::string>& choices) const;
  /// A finite number in [min, max] (inclusive unless `open_min`: min < x).
  double Number(double min, double max, bool open_min = false) const;
  int Integer(int min, int max) const;
  bool Bool() const;
  glm::vec3 Vec3(double min = -1e30, double max = 1e30) const;
  glm::vec2 Vec2(double min = -1e30, double max = 1e30) const;

  // Optional members with defaults.
  double NumberOr(const std::string& key, double def, double min, double max, bool open_min = false) const;
  glm::vec3 Vec3Or(const std::string& key, glm::vec3 def, double min = -1e30, double max = 1e30) const;
  bool BoolOr(const std::string& key, bool def) const;
  std::string StringOr(const std::string& key, const std::string& def) const;

 private:
  std::string Shown() const;  ///< the value, abbreviated, for messages
  const nlohmann::json& value_;
  std::string origin_;
  std::string path_;
};

}  // namespace aalab
