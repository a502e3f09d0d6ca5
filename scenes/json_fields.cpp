#include "scenes/json_fields.h"

#include <cfloat>

#include "core/error.h"
#include "core/params.h"

namespace aalab {

namespace {

constexpr size_t kShownChars = 60;

// An abbreviated rendering for messages. nlohmann's dump() recurses once per nesting level
// and overflows the stack on deeply nested input (a 2 MB file of '[' is enough), so arrays
// and objects are written here with a depth limit and a character budget instead.
void Abbreviate(const nlohmann::json& v, std::string& out, int depth) {
  if (out.size() > kShownChars) return;
  if (!v.is_structured()) {
    std::string s = v.dump();
    if (s.size() > kShownChars) s.resize(kShownChars + 1);  // long strings: cut, "..." follows
    out += s;
    return;
  }
  const bool array = v.is_array();
  if (depth >= 4) {
    out += array ? "[...]" : "{...}";
    return;
  }
  out += array ? '[' : '{';
  bool first = true;
  for (auto it = v.begin(); it != v.end() && out.size() <= kShownChars; ++it) {
    if (!first) out += ',';
    first = false;
    if (!array) out += nlohmann::json(it.key()).dump() + ':';
    Abbreviate(*it, out, depth + 1);
  }
  out += array ? ']' : '}';
}

}  // namespace

std::string JsonField::Shown() const {
  std::string s;
  Abbreviate(value_, s, 0);
  if (s.size() > kShownChars) s = s.substr(0, kShownChars - 3) + "...";
  return s;
}

void JsonField::Fail(const std::string& message) const {
  throw UserError(origin_ + ": " + (path_.empty() ? "/" : path_) + ": " + message);
}

void JsonField::RequireObject(const std::set<std::string>& allowed) const {
  if (!value_.is_object()) Fail("expected an object, got " + Shown());
  for (auto it = value_.begin(); it != value_.end(); ++it) {
    if (!allowed.count(it.key())) {
      std::vector<std::string> names(allowed.begin(), allowed.end());
      Fail("unknown field '" + it.key() + "' (allowed: " + JoinNames(names) + ")");
    }
  }
}

JsonField JsonField::Child(const std::string& key) const {
  if (!value_.is_object()) Fail("expected an object, got " + Shown());
  if (!value_.contains(key)) Fail("missing required field '" + key + "'");
  return JsonField(value_.at(key), origin_, path_ + "/" + key);
}

JsonField JsonField::At(size_t index) const {
  return JsonField(value_.at(index), origin_, path_ + "/" + std::to_string(index));
}

size_t JsonField::ArraySize() const {
  if (!value_.is_array()) Fail("expected an array, got " + Shown());
  return value_.size();
}

std::string JsonField::String() const {
  if (!value_.is_string()) Fail("expected a string, got " + Shown());
  return value_.get<std::string>();
}

std::string JsonField::Choice(const std::vector<std::string>& choices) const {
  const std::string s = String();
  for (const auto& c : choices) {
    if (c == s) return s;
  }
  Fail("'" + s + "' is not allowed (allowed: " + JoinNames(choices) + ")");
}

double JsonField::Number(double min, double max, bool open_min) const {
  if (!value_.is_number()) Fail("expected a number, got " + Shown());
  const double v = value_.get<double>();
  if (!std::isfinite(v)) Fail("expected a finite number, got " + Shown());
  if (v < min || v > max || (open_min && v <= min)) {
    Fail(Shown() + " is out of range (allowed: " + (open_min ? "> " : ">= ") + FormatNumber(min) +
         " and <= " + FormatNumber(max) + ")");
  }
  // Scene values are stored as float: a value that must stay above `min` must not round
  // down onto it (1e-300 > 0, but it is 0 as a float).
  if (open_min && !(std::fabs(static_cast<float>(v) - static_cast<float>(min)) >= FLT_MIN)) {
    Fail(Shown() + " is too close to " + FormatNumber(min) + ": it rounds to " + FormatNumber(min) +
         " in single precision (allowed: > " + FormatNumber(min) + ")");
  }
  return v;
}

int JsonField::Integer(int min, int max) const {
  if (!value_.is_number_integer()) Fail("expected an integer, got " + Shown());
  const auto v = value_.get<long long>();
  if (v < min || v > max) {
    Fail(Shown() + " is out of range (allowed: " + std::to_string(min) + ".." + std::to_string(max) + ")");
  }
  return static_cast<int>(v);
}

bool JsonField::Bool() const {
  if (!value_.is_boolean()) Fail("expected true or false, got " + Shown());
  return value_.get<bool>();
}

glm::vec3 JsonField::Vec3(double min, double max) const {
  if (!value_.is_array() || value_.size() != 3) Fail("expected an array of 3 numbers, got " + Shown());
  glm::vec3 v;
  for (int i = 0; i < 3; ++i) v[i] = static_cast<float>(At(i).Number(min, max));
  return v;
}

glm::vec2 JsonField::Vec2(double min, double max) const {
  if (!value_.is_array() || value_.size() != 2) Fail("expected an array of 2 numbers, got " + Shown());
  glm::vec2 v;
  for (int i = 0; i < 2; ++i) v[i] = static_cast<float>(At(i).Number(min, max));
  return v;
}

double JsonField::NumberOr(const std::string& key, double def, double min, double max, bool open_min) const {
  return Has(key) ? Child(key).Number(min, max, open_min) : def;
}

glm::vec3 JsonField::Vec3Or(const std::string& key, glm::vec3 def, double min, double max) const {
  return Has(key) ? Child(key).Vec3(min, max) : def;
}

bool JsonField::BoolOr(const std::string& key, bool def) const { return Has(key) ? Child(key).Bool() : def; }

std::string JsonField::StringOr(const std::string& key, const std::string& def) const {
  return Has(key) ? Child(key).String() : def;
}

}  // namespace aalab
