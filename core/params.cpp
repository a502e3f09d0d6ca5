#include "core/params.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <set>

#include "core/error.h"

namespace aalab {

std::string FormatNumber(double v) {
  // The fewest significant digits P that read back as v, printed by "%g" at precision
  // max(P, 6): the digits are those P (a 6-digit rounding of v is them padded with zeros, which
  // "%g" drops), and the notation is "%g"'s at its default precision, scientific only below
  // 1e-4 or from 1e6 on. At precision P itself "%g" chose scientific for every exponent >= P, so
  // 20 printed "2e+01" and 100 "1e+02".
  char buf[64];
  int prec = 1;
  for (; prec < 17; ++prec) {
    std::snprintf(buf, sizeof buf, "%.*g", prec, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  std::snprintf(buf, sizeof buf, "%.*g", prec < 6 ? 6 : prec, v);
  return buf;
}

std::string RespellNumber(const std::string& text) {
  if (text.find_first_of("eE") == std::string::npos) return text;
  double v = 0;
  const auto res = std::from_chars(text.data(), text.data() + text.size(), v);
  if (res.ec != std::errc() || res.ptr != text.data() + text.size() || !std::isfinite(v)) return text;
  return FormatNumber(v);
}

std::string RespellSpecNumbers(const std::string& spec) {
  const size_t colon = spec.find(':');
  if (colon == std::string::npos) return spec;
  std::string out = spec.substr(0, colon + 1);
  size_t start = colon + 1;
  while (start <= spec.size()) {
    size_t comma = spec.find(',', start);
    if (comma == std::string::npos) comma = spec.size();
    const std::string item = spec.substr(start, comma - start);
    const size_t eq = item.find('=');
    out += eq == std::string::npos ? item : item.substr(0, eq + 1) + RespellNumber(item.substr(eq + 1));
    if (comma < spec.size()) out += ',';
    start = comma + 1;
  }
  return out;
}

std::vector<std::string> SplitCommaList(const std::string& text, const std::string& what) {
  std::vector<std::string> out;
  if (text.empty()) return out;
  size_t start = 0;
  while (start <= text.size()) {
    size_t comma = text.find(',', start);
    if (comma == std::string::npos) comma = text.size();
    if (comma == start) {
      throw UserError(what + " '" + text + "' " +
                      (start == text.size() && start > 0 ? "ends with a comma" : "has an empty item"));
    }
    out.push_back(text.substr(start, comma - start));
    start = comma + 1;
  }
  return out;
}

std::string JoinNames(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) {
    if (i) out += ", ";
    out += names[i];
  }
  return out;
}

std::string ParamDef::Describe() const {
  if (kind == ParamKind::kChoice) {
    std::string s = name + "=" + default_choice + " {";
    for (size_t i = 0; i < choices.size(); ++i) s += (i ? "|" : "") + choices[i];
    return s + "}";
  }
  return name + "=" + FormatNumber(default_number) + " [" + FormatNumber(min) + ".." + FormatNumber(max) + "]" +
         (kind == ParamKind::kInt ? " integer" : "");
}

ParamDef FloatParam(std::string name, double def, double min, double max, std::string help) {
  ParamDef d;
  d.name = std::move(name);
  d.kind = ParamKind::kFloat;
  d.default_number = def;
  d.min = min;
  d.max = max;
  d.help = std::move(help);
  return d;
}

ParamDef IntParam(std::string name, int def, int min, int max, std::string help) {
  ParamDef d = FloatParam(std::move(name), def, min, max, std::move(help));
  d.kind = ParamKind::kInt;
  return d;
}

ParamDef ChoiceParam(std::string name, std::string def, std::vector<std::string> choices, std::string help) {
  ParamDef d;
  d.name = std::move(name);
  d.kind = ParamKind::kChoice;
  d.default_choice = std::move(def);
  d.choices = std::move(choices);
  d.help = std::move(help);
  return d;
}

double ParamValues::Number(const std::string& name) const {
  auto it = numbers_.find(name);
  AALAB_CHECK(it != numbers_.end(), "no numeric parameter '" + name + "'");
  return it->second;
}

int ParamValues::Int(const std::string& name) const { return static_cast<int>(Number(name)); }

const std::string& ParamValues::Choice(const std::string& name) const {
  auto it = choices_.find(name);
  AALAB_CHECK(it != choices_.end(), "no choice parameter '" + name + "'");
  return it->second;
}

bool ParamValues::Has(const std::string& name) const { return numbers_.count(name) || choices_.count(name); }

void ParamValues::Record(const std::string& name, const std::string& text, bool overridden) {
  bool found = false;
  for (auto& kv : ordered_) {
    if (kv.first == name) {
      kv.second = text;
      found = true;
    }
  }
  if (!found) ordered_.emplace_back(name, text);
  if (overridden) overridden_.push_back(name);
}

void ParamValues::SetNumber(const std::string& name, double v, bool overridden) {
  numbers_[name] = v;
  Record(name, FormatNumber(v), overridden);
}

void ParamValues::SetChoice(const std::string& name, const std::string& v, bool overridden) {
  choices_[name] = v;
  Record(name, v, overridden);
}

Spec ParseSpec(const std::string& text) {
  Spec spec;
  const auto colon = text.find(':');
  spec.name = text.substr(0, colon);
  if (spec.name.empty()) throw UserError("empty name in spec '" + text + "'");
  if (colon == std::string::npos) return spec;
  const std::string rest = text.substr(colon + 1);
  if (rest.empty()) throw UserError("spec '" + text + "' has ':' but no key=value after it");
  std::set<std::string> seen;
  size_t start = 0;
  while (start <= rest.size()) {
    size_t comma = rest.find(',', start);
    if (comma == std::string::npos) comma = rest.size();
    const std::string item = rest.substr(start, comma - start);
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == item.size()) {
      throw UserError("spec '" + text + "': '" + item + "' is not key=value");
    }
    const std::string key = item.substr(0, eq);
    if (!seen.insert(key).second) throw UserError("spec '" + text + "': '" + key + "' given twice");
    spec.overrides.emplace_back(key, item.substr(eq + 1));
    start = comma + 1;
  }
  return spec;
}

ParamValues ResolveParams(const std::string& what, const std::vector<ParamDef>& defs,
                          const std::vector<std::pair<std::string, std::string>>& overrides) {
  ParamValues values;
  for (const auto& d : defs) {
    if (d.kind == ParamKind::kChoice) {
      values.SetChoice(d.name, d.default_choice, false);
    } else {
      values.SetNumber(d.name, d.default_number, false);
    }
  }
  for (const auto& [key, text] : overrides) {
    const ParamDef* def = nullptr;
    for (const auto& d : defs) {
      if (d.name == key) def = &d;
    }
    if (!def) {
      std::vector<std::string> names;
      for (const auto& d : defs) names.push_back(d.Describe());
      throw UserError(what + ": unknown parameter '" + key + "' (" +
                      (names.empty() ? std::string("it takes no parameters") : "allowed: " + JoinNames(names)) + ")");
    }
    if (def->kind == ParamKind::kChoice) {
      bool ok = false;
      for (const auto& c : def->choices) ok = ok || c == text;
      if (!ok) {
        throw UserError(what + ": parameter '" + key + "' = '" + text +
                        "' is not allowed (allowed: " + JoinNames(def->choices) + ")");
      }
      values.SetChoice(key, text, true);
      continue;
    }
    double v = 0.0;
    const char* first = text.data();
    const char* last = text.data() + text.size();
    auto res = std::from_chars(first, last, v);
    if (res.ec != std::errc() || res.ptr != last || !std::isfinite(v)) {
      throw UserError(what + ": parameter '" + key + "' = '" + text + "' is not a number (" + def->Describe() + ")");
    }
    if (def->kind == ParamKind::kInt && v != std::floor(v)) {
      throw UserError(what + ": parameter '" + key + "' = '" + text + "' must be an integer (" + def->Describe() + ")");
    }
    if (v < def->min || v > def->max) {
      throw UserError(what + ": parameter '" + key + "' = '" + text + "' is out of range (" + def->Describe() + ")");
    }
    values.SetNumber(key, v, true);
  }
  return values;
}

}  // namespace aalab
