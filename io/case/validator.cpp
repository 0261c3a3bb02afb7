#include "io/case/validator.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace grains::io {

namespace {
std::string join(const std::vector<std::string>& v, const std::string& sep) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? sep : "") + v[i];
  return s;
}
std::string describe(const YAML::Node& n) {
  switch (n.Type()) {
    case YAML::NodeType::Map: return "a map";
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Null: return "nothing";
    case YAML::NodeType::Scalar: return "'" + n.Scalar() + "'";
    default: return "an undefined value";
  }
}
}  // namespace

CaseError::CaseError(std::vector<std::string> msgs)
    : std::runtime_error(join(msgs, "\n")), messages(std::move(msgs)) {}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string closest(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t bd = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const auto& c : candidates) {
    const auto d = edit_distance(word, c);
    if (d < bd) {
      bd = d;
      best = c;
    }
  }
  return best;
}

std::string Validator::where(const YAML::Node& n) const {
  for (const auto& [node, text] : overrides_)
    if (node.is(n)) return "--set " + text;
  // A node looked up under a missing key has no position (yaml-cpp throws
  // when asked for it): the file is all we can say then.
  if (!n.IsDefined()) return file_;
  YAML::Mark m;
  try {
    m = n.Mark();
  } catch (const YAML::Exception&) {
    return file_;
  }
  if (m.is_null()) return file_;
  return file_ + ":" + std::to_string(m.line + 1) + ":" + std::to_string(m.column + 1);
}

void Validator::error(const YAML::Node& at, const std::string& context, const std::string& msg) {
  errors_.push_back(where(at) + ": " + (context.empty() ? "" : context + ": ") + msg);
}

void Validator::throw_if_errors() const {
  if (!errors_.empty()) throw CaseError(errors_);
}

bool Validator::check_map(const YAML::Node& n, const sim::EffectDoc& doc, const std::string& ctx) {
  if (!n.IsMap()) {
    error(n, ctx, "expected a map of keys (" + doc.section + "), got " + describe(n));
    return false;
  }
  std::vector<std::string> valid;
  for (const auto& k : doc.keys) valid.push_back(k.name);
  for (const auto& kv : n) {
    if (!kv.first.IsScalar()) {  // e.g. `? [a, b] : 1` or a tagged key
      error(kv.first, ctx, "keys must be plain names, got " + describe(kv.first) + "; valid keys: " + join(valid, ", "));
      continue;
    }
    const std::string k = kv.first.Scalar();
    if (doc.find(k)) continue;
    const std::string guess = closest(k, valid);
    error(kv.first, ctx,
          "unknown key '" + k + "'" + (guess.empty() ? "" : "; did you mean '" + guess + "'?") +
              " valid keys: " + join(valid, ", "));
  }
  for (const auto& k : doc.keys)
    if (k.required && !n[k.name])
      error(n, ctx, "missing required key '" + k.name + "' (" + k.doc + (k.unit.empty() ? "" : ", in " + k.unit) + ")");
  return true;
}

const sim::KeySpec& Validator::spec(const sim::EffectDoc& doc, const std::string& k) const {
  const auto* s = doc.find(k);
  if (!s) throw std::logic_error("key '" + k + "' is not declared in " + doc.name);
  return *s;
}

void Validator::check_range(const YAML::Node& n, const sim::KeySpec& s, double v, const std::string& ctx) {
  if (!s.in_range(v)) {
    std::ostringstream o;
    o.precision(10);
    o << s.name << " = " << v << (s.unit.empty() ? "" : " " + s.unit) << " is out of range; valid: " << s.range_text();
    error(n, ctx, o.str());
  }
}

bool Validator::to_number(const YAML::Node& n, const std::string& ctx, const std::string& what, double& out) {
  if (n.IsScalar()) {
    const std::string& t = n.Scalar();
    // yaml-cpp accepts ".inf"/".nan"; we accept plain decimal and exponent forms.
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (!t.empty() && end == t.c_str() + t.size() && std::isfinite(v)) {
      out = v;
      return true;
    }
  }
  error(n, ctx, what + " must be a finite number, got " + describe(n));
  return false;
}

double Validator::number(const YAML::Node& map, const sim::EffectDoc& doc, const std::string& k,
                         const std::string& ctx, double fallback) {
  const auto& s = spec(doc, k);
  const YAML::Node n = map[k];
  if (!n) return fallback;
  double v;
  if (!to_number(n, ctx, k, v)) return fallback;
  check_range(n, s, v, ctx);
  return v;
}

std::int64_t Validator::integer(const YAML::Node& map, const sim::EffectDoc& doc, const std::string& k,
                                const std::string& ctx, std::int64_t fallback) {
  const auto& s = spec(doc, k);
  const YAML::Node n = map[k];
  if (!n) return fallback;
  double v;
  if (!to_number(n, ctx, k, v)) return fallback;
  if (v != std::floor(v)) {
    error(n, ctx, k + " must be a whole number, got '" + n.Scalar() + "'");
    return fallback;
  }
  check_range(n, s, v, ctx);
  return static_cast<std::int64_t>(v);
}

bool Validator::boolean(const YAML::Node& map, const sim::EffectDoc& doc, const std::string& k,
                        const std::string& ctx, bool fallback) {
  (void)spec(doc, k);
  const YAML::Node n = map[k];
  if (!n) return fallback;
  if (n.IsScalar()) {
    const std::string t = n.Scalar();
    if (t == "true" || t == "True" || t == "yes" || t == "on") return true;
    if (t == "false" || t == "False" || t == "no" || t == "off") return false;
  }
  error(n, ctx, k + " must be true or false, got " + describe(n));
  return fallback;
}

std::string Validator::string(const YAML::Node& map, const sim::EffectDoc& doc, const std::string& k,
                              const std::string& ctx, const std::string& fallback) {
  const auto& s = spec(doc, k);
  const YAML::Node n = map[k];
  if (!n) return fallback;
  if (!n.IsScalar()) {
    error(n, ctx, k + " must be a string, got " + describe(n));
    return fallback;
  }
  const std::string v = n.Scalar();
  if (!s.choices.empty() && std::find(s.choices.begin(), s.choices.end(), v) == s.choices.end()) {
    const std::string guess = closest(v, s.choices);
    error(n, ctx,
          k + " = '" + v + "' is not valid" + (guess.empty() ? "" : "; did you mean '" + guess + "'?") +
              " valid: " + join(s.choices, ", "));
    return fallback;
  }
  return v;
}

sim::Vec3 Validator::vec3(const YAML::Node& map, const sim::EffectDoc& doc, const std::string& k,
                          const std::string& ctx, const sim::Vec3& fallback) {
  (void)spec(doc, k);
  const YAML::Node n = map[k];
  if (!n) return fallback;
  if (!n.IsSequence() || n.size() != 3) {
    error(n, ctx, k + " must be a vector of 3 numbers [x, y, z], got " + describe(n) +
                      (n.IsSequence() ? " with " + std::to_string(n.size()) + " entries" : ""));
    return fallback;
  }
  sim::Vec3 v;
  for (int i = 0; i < 3; ++i)
    if (!to_number(n[i], ctx, k + "[" + std::to_string(i) + "]", v[i])) return fallback;
  return v;
}

std::array<bool, 3> Validator::bool3(const YAML::Node& map, const sim::EffectDoc& doc, const std::string& k,
                                     const std::string& ctx, std::array<bool, 3> fallback) {
  (void)spec(doc, k);
  const YAML::Node n = map[k];
  if (!n) return fallback;
  auto one = [](const YAML::Node& e, bool& out) {
    if (!e.IsScalar()) return false;
    const std::string t = e.Scalar();
    if (t == "true" || t == "True" || t == "yes" || t == "on") return out = true, true;
    if (t == "false" || t == "False" || t == "no" || t == "off") return out = false, true;
    return false;
  };
  bool b = false;
  if (one(n, b)) return {b, b, b};
  std::array<bool, 3> v{};
  if (n.IsSequence() && n.size() == 3 && one(n[0], v[0]) && one(n[1], v[1]) && one(n[2], v[2])) return v;
  error(n, ctx, k + " must be true, false or a list of 3 booleans [x, y, z], got " + describe(n) +
                    (n.IsSequence() ? " with " + std::to_string(n.size()) + " entries" : ""));
  return fallback;
}

std::vector<double> Validator::numbers(const YAML::Node& map, const sim::EffectDoc& doc, const std::string& k,
                                       const std::string& ctx) {
  (void)spec(doc, k);
  const YAML::Node n = map[k];
  std::vector<double> out;
  if (!n) return out;
  if (!n.IsSequence()) {
    error(n, ctx, k + " must be a list of numbers, got " + describe(n));
    return out;
  }
  for (std::size_t i = 0; i < n.size(); ++i) {
    double v;
    if (to_number(n[i], ctx, k + "[" + std::to_string(i) + "]", v)) out.push_back(v);
  }
  return out;
}

}  // namespace grains::io
