/// Named, typed, range-checked parameters for methods and metrics, and the
/// "name:key=value,key=value" spec syntax (docs/design.md "Names").
#pragma once
#include <map>
#include <string>
#include <vector>

namespace aalab {

/// The type of a parameter.
enum class ParamKind { kFloat, kInt, kChoice };

/// One parameter's definition: name, type, default, allowed range or choices, one-line help.
struct ParamDef {
  std::string name;
  ParamKind kind = ParamKind::kFloat;
  double default_number = 0.0;       ///< for kFloat / kInt
  std::string default_choice;        ///< for kChoice
  double min = 0.0;                  ///< inclusive, for kFloat / kInt
  double max = 0.0;                  ///< inclusive, for kFloat / kInt
  std::vector<std::string> choices;  ///< for kChoice
  std::string help;

  /// "name=default [min..max]" or "name=default {a|b|c}", for listings and errors.
  std::string Describe() const;
};

/// Convenience constructors for registry tables.
ParamDef FloatParam(std::string name, double def, double min, double max, std::string help);
ParamDef IntParam(std::string name, int def, int min, int max, std::string help);
ParamDef ChoiceParam(std::string name, std::string def, std::vector<std::string> choices, std::string help);

/// Resolved parameter values: every defined parameter has a value (default or override).
class ParamValues {
 public:
  double Number(const std::string& name) const;
  int Int(const std::string& name) const;
  const std::string& Choice(const std::string& name) const;
  bool Has(const std::string& name) const;
  /// Values in definition order as (name, text) pairs, numbers formatted with %.17g trimmed.
  const std::vector<std::pair<std::string, std::string>>& Ordered() const { return ordered_; }
  /// Names the user overrode, in the order given.
  const std::vector<std::string>& Overridden() const { return overridden_; }

  void SetNumber(const std::string& name, double v, bool overridden);
  void SetChoice(const std::string& name, const std::string& v, bool overridden);

 private:
  void Record(const std::string& name, const std::string& text, bool overridden);
  std::map<std::string, double> numbers_;
  std::map<std::string, std::string> choices_;
  std::vector<std::pair<std::string, std::string>> ordered_;
  std::vector<std::string> overridden_;
};

/// A parsed "name:key=value,..." spec (not yet checked against a definition table).
struct Spec {
  std::string name;
  std::vector<std::pair<std::string, std::string>> overrides;
};

/// Splits a spec string. Throws UserError on malformed syntax (empty name, missing '=',
/// repeated key), naming the spec.
Spec ParseSpec(const std::string& text);

/// Resolves overrides against definitions. `what` names the owner in messages
/// ("method 'fxaa1-p2'"). Unknown keys, bad numbers, out-of-range values and unknown choices
/// throw UserError listing what is allowed.
ParamValues ResolveParams(const std::string& what, const std::vector<ParamDef>& defs,
                          const std::vector<std::pair<std::string, std::string>>& overrides);

/// Formats a double with the fewest significant digits that read back as the same double, in
/// fixed notation from 1e-4 up to 1e6 and scientific outside ("0.125", "16", "20", "100",
/// "0.0001", "1e+09", "2.5e-05", "0.3333333333333333"). Method specs and parameter lists are
/// spelled with it.
std::string FormatNumber(double v);

/// Reports written before 2026-11-28 spelled some whole numbers in scientific notation
/// ("2e+01" for 20). Returns `text` printed again by FormatNumber when it holds an 'e' and reads
/// whole as a finite number; any other text (a choice, a plain number) is returned as it is.
std::string RespellNumber(const std::string& text);

/// A method spec "name:k=v,k=v" with each value put through RespellNumber, so a spec read from
/// an older report ("smaa-ultra:corner_rounding=2e+01") matches today's ("...=20").
std::string RespellSpecNumbers(const std::string& spec);

/// Splits "a,b,c" into items ("" gives none). An empty item or a trailing comma is a UserError naming
/// `what` and the text.
std::vector<std::string> SplitCommaList(const std::string& text, const std::string& what);

/// Joins names with ", " (for "allowed: a, b, c" messages).
std::string JoinNames(const std::vector<std::string>& names);

}  // namespace aalab
