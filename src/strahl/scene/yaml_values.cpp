// The values of YAML scene files (yaml_reader.h): maps, lists and their keys, numbers (YAML 1.2's
// core schema), whole numbers, booleans, vectors, colours, ranges and indices of refraction — each
// checked, errors at the offending node's file:line:column.

#include "strahl/scene/yaml_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "strahl/scene/validate.h"
#include "strahl/util/number_syntax.h"

namespace strahl {

bool named_ior(const std::string& name, Real& ior) {
  static const std::map<std::string, Real> kIors = {{"vacuum", 1.0},  {"air", 1.0003},    {"water", 1.333},
                                                    {"ice", 1.31},    {"acrylic", 1.491}, {"glass", 1.5},
                                                    {"diamond", 2.419}};
  const auto it = kIors.find(name);
  if (it == kIors.end()) return false;
  ior = it->second;
  return true;
}

FileLoc YamlReader::loc(const YAML::Node& n) const {
  const YAML::Mark m = n.Mark();
  return FileLoc{name_, m.line >= 0 ? m.line + 1 + line_offset_ : 0, m.column >= 0 ? m.column + 1 : 0};
}

void YamlReader::map(const YAML::Node& n, const std::string& what) const {
  if (!n.IsMap()) fail(n, what + " must be a map of keys to values");
}

void YamlReader::sequence(const YAML::Node& n, const std::string& what) const {
  if (!n.IsSequence()) fail(n, what + " must be a list");
}

void YamlReader::keys(const YAML::Node& n, Keys allowed, const std::string& what) const {
  std::vector<std::string> seen;
  for (const auto& kv : n) {
    const std::string key = kv.first.Scalar();
    // yaml-cpp keeps the first of repeated keys; a repeated key is almost always a mistake.
    if (std::find(seen.begin(), seen.end(), key) != seen.end()) fail(kv.first, "repeated key '" + key + "' in " + what);
    seen.push_back(key);
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      std::string list;
      for (std::string_view k : allowed) list += (list.empty() ? "" : ", ") + std::string(k);
      fail(kv.first, "unknown key '" + key + "' in " + what + " (allowed: " + list + ")");
    }
  }
}

YAML::Node YamlReader::required(const YAML::Node& n, const char* key, const std::string& what) const {
  const YAML::Node v = n[key];
  if (!v) fail(n, what + " needs '" + key + "'");
  return v;
}

std::string YamlReader::scalar(const YAML::Node& n, const std::string& what) const {
  if (!n.IsScalar()) fail(n, what + " must be a single value");
  return n.Scalar();
}

// Numbers follow YAML 1.2's core schema (util/number_syntax.h, docs/scene-format.md "Numbers"):
// a quoted scalar or one tagged !!str is text, not a number, as YAML says.
void YamlReader::plain(const YAML::Node& n, const std::string& what, const char* kind) const {
  const std::string& tag = n.Tag();
  if (tag == "!" || tag == "tag:yaml.org,2002:str")
    fail(n, what + " must be " + kind + ", not the quoted text \"" + n.Scalar() + "\" (write it without quotes)");
}

Real YamlReader::number(const YAML::Node& n, const std::string& what) const {
  if (!n.IsScalar()) fail(n, what + " must be a number");
  plain(n, what, "a number");
  const number::Real r = number::parse_real(n.Scalar());
  if (r.status == number::Real::Status::NotANumber) fail(n, what + " must be a number (got '" + n.Scalar() + "')");
  if (r.status == number::Real::Status::TooLarge)
    fail(n, what + " must be a finite number (" + n.Scalar() + " is beyond the largest double, about 1.8e308)");
  if (!std::isfinite(r.value)) fail(n, what + " must be a finite number");
  return r.value;
}

// A whole number in [lo, hi]: decimal (leading zeros too: 010 is 10), 0o octal, 0x hex, or a
// real of whole value (1e3); never wrapped or clamped.
std::uint64_t YamlReader::whole(const YAML::Node& n, const std::string& what, std::int64_t lo, std::uint64_t hi) const {
  if (!n.IsScalar()) fail(n, what + " must be a whole number");
  plain(n, what, "a whole number");
  const number::Integer r = number::parse_integer(n.Scalar(), lo, hi);
  switch (r.status) {
    case number::Integer::Status::Ok: return r.unsigned_value;
    case number::Integer::Status::NotANumber: fail(n, what + " must be a whole number (got '" + n.Scalar() + "')");
    case number::Integer::Status::NotWhole: fail(n, what + " must be a whole number (got '" + n.Scalar() + "')");
    case number::Integer::Status::OutOfRange: fail(n, number::range_message(what, lo, hi, n.Scalar()));
  }
  return 0;
}

int YamlReader::integer(const YAML::Node& n, const std::string& what, int lo, int hi) const {
  return static_cast<int>(whole(n, what, lo, std::uint64_t(hi)));  // lo ≥ 0 for every setting
}

// YAML 1.2 core booleans only: true/True/TRUE, false/False/FALSE (not 1.1's yes, on, y).
bool YamlReader::boolean(const YAML::Node& n, const std::string& what) const {
  const std::string s = n.IsScalar() ? n.Scalar() : std::string();
  const bool quoted = n.IsScalar() && (n.Tag() == "!" || n.Tag() == "tag:yaml.org,2002:str");
  if (!quoted && (s == "true" || s == "True" || s == "TRUE")) return true;
  if (!quoted && (s == "false" || s == "False" || s == "FALSE")) return false;
  fail(n, what + " must be true or false" + (n.IsScalar() ? " (got '" + s + "')" : std::string()));
}

Vec3 YamlReader::vec3(const YAML::Node& n, const std::string& what) const {
  if (!n.IsSequence() || n.size() != 3) fail(n, what + " must be a list of three numbers [x, y, z]");
  return {number(n[0], what), number(n[1], what), number(n[2], what)};
}

// A colour: [r, g, b] or one number for grey; components must not be negative.
Vec3 YamlReader::color(const YAML::Node& n, const std::string& what) const {
  const Vec3 c = n.IsScalar() ? Vec3(number(n, what)) : vec3(n, what);
  validate::non_negative(c, loc(n), what);
  return c;
}

Real YamlReader::non_negative(const YAML::Node& n, const std::string& what) const {
  const Real v = number(n, what);
  validate::non_negative(v, loc(n), what);
  return v;
}

Real YamlReader::positive(const YAML::Node& n, const std::string& what) const {
  const Real v = number(n, what);
  validate::positive(v, loc(n), what);
  return v;
}

Real YamlReader::unit(const YAML::Node& n, const std::string& what) const {
  const Real v = number(n, what);
  validate::in_range(v, 0, 1, loc(n), what);
  return v;
}

// An index of refraction by number or by name; errors name the key (`ior`, `medium_ior`).
Real YamlReader::ior(const YAML::Node& n, const std::string& what) const {
  Real v = 0;
  if (n.IsScalar() && named_ior(n.Scalar(), v)) return v;
  if (n.IsScalar() && number::parse_real(n.Scalar()).status == number::Real::Status::NotANumber && n.Tag() == "?")
    fail(n, "unknown " + what + " '" + n.Scalar() + "' (a number or one of vacuum, air, water, ice, acrylic, glass, diamond)");
  return positive(n, what);
}

}  // namespace strahl
