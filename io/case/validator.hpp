#pragma once
// Checks YAML nodes against the key declarations of the effects
// (sim/keys/effect_doc.hpp) and collects every problem with its location,
// so a user sees all mistakes of a case file at once:
//   case.yaml:12:5: materials[0]: unknown key 'frction'; did you mean 'friction'? valid keys: ...
#include <array>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "sim/keys/effect_doc.hpp"
#include "sim/state/particle_store.hpp"

namespace grains::io {

struct CaseError : std::runtime_error {
  explicit CaseError(std::vector<std::string> msgs);
  std::vector<std::string> messages;
};

/// Levenshtein distance, for "did you mean".
std::size_t edit_distance(const std::string& a, const std::string& b);
/// The closest candidate within a small distance, or empty.
std::string closest(const std::string& word, const std::vector<std::string>& candidates);

class Validator {
 public:
  explicit Validator(std::string file) : file_(std::move(file)) {}

  /// Marks a node as coming from a `--set` override (its location is then
  /// reported as the override, not as a line of the file).
  void mark_override(const YAML::Node& n, std::string text) { overrides_.push_back({n, std::move(text)}); }

  std::string where(const YAML::Node& n) const;
  void error(const YAML::Node& at, const std::string& context, const std::string& msg);
  void error_at(const std::string& where, const std::string& msg) { errors_.push_back(where + ": " + msg); }
  bool ok() const { return errors_.empty(); }
  const std::vector<std::string>& errors() const { return errors_; }
  /// Throws CaseError if any error was recorded.
  void throw_if_errors() const;

  /// Is the node a map? Then: unknown keys (with suggestions), missing
  /// required keys. Returns false if the node is not a map.
  bool check_map(const YAML::Node& n, const sim::EffectDoc& doc, const std::string& context);

  // Typed getters: on a wrong type or a value out of the declared range they
  // record an error and return the fallback. `k` must be a key of doc.
  double number(const YAML::Node& map, const sim::EffectDoc& doc, const std::string& k, const std::string& ctx,
                double fallback = 0);
  /// A number key whose fallback is its declared default (KeySpec::def).
  double number_or_default(const YAML::Node& map, const sim::EffectDoc& doc, const std::string& k,
                           const std::string& ctx) {
    return number(map, doc, k, ctx, spec(doc, k).default_number);
  }
  std::int64_t integer(const YAML::Node& map, const sim::EffectDoc& doc, const std::string& k,
                       const std::string& ctx, std::int64_t fallback = 0);
  bool boolean(const YAML::Node& map, const sim::EffectDoc& doc, const std::string& k, const std::string& ctx,
               bool fallback = false);
  std::string string(const YAML::Node& map, const sim::EffectDoc& doc, const std::string& k,
                     const std::string& ctx, const std::string& fallback = "");
  sim::Vec3 vec3(const YAML::Node& map, const sim::EffectDoc& doc, const std::string& k, const std::string& ctx,
                 const sim::Vec3& fallback = sim::Vec3::Zero());
  /// One boolean for all three axes, or a list of three.
  std::array<bool, 3> bool3(const YAML::Node& map, const sim::EffectDoc& doc, const std::string& k,
                            const std::string& ctx, std::array<bool, 3> fallback = {false, false, false});
  std::vector<double> numbers(const YAML::Node& map, const sim::EffectDoc& doc, const std::string& k,
                              const std::string& ctx);
  /// A scalar as a number (no range check); records an error if it is not one.
  bool to_number(const YAML::Node& n, const std::string& ctx, const std::string& what, double& out);

  const std::string& file() const { return file_; }

 private:
  const sim::KeySpec& spec(const sim::EffectDoc& doc, const std::string& k) const;
  void check_range(const YAML::Node& n, const sim::KeySpec& s, double v, const std::string& ctx);
  std::string file_;
  std::vector<std::string> errors_;
  std::vector<std::pair<YAML::Node, std::string>> overrides_;
};

}  // namespace grains::io
