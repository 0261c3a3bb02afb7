#pragma once
// Self-description of the case-file keys an effect accepts. Each effect
// declares its keys next to its own code; the case parser validates against
// the same declarations and `grains docs` prints them, so the documentation
// cannot drift from what is accepted.
#include <limits>
#include <string>
#include <vector>

namespace grains::sim {

enum class KeyType { Number, Integer, Bool, String, Vec3, NumberList, Map, List, Bool3 };

const char* key_type_name(KeyType t);

struct KeySpec {
  std::string name;
  KeyType type = KeyType::Number;
  bool required = false;
  std::string default_value;  // printed; empty when none
  /// The default of a number or boolean key as the parser uses it (NaN when
  /// the key has none, or its default is not a number): written once, here.
  double default_number = std::numeric_limits<double>::quiet_NaN();
  std::string unit;           // SI unit, empty when dimensionless
  std::string doc;
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  bool max_exclusive = false;
  std::vector<std::string> choices;  // for strings

  KeySpec& req() { required = true; return *this; }
  KeySpec& def(std::string d) { default_value = std::move(d); return *this; }
  /// A numeric default: printed by `grains docs` and read by the parser.
  KeySpec& def(double v);
  KeySpec& def_bool(bool b) { default_value = b ? "true" : "false"; default_number = b ? 1 : 0; return *this; }
  KeySpec& in(double lo, double hi, bool lo_excl = false, bool hi_excl = false) {
    min = lo; max = hi; min_exclusive = lo_excl; max_exclusive = hi_excl; return *this;
  }
  KeySpec& one_of(std::vector<std::string> c) { choices = std::move(c); return *this; }
  KeySpec& si(std::string u) { unit = std::move(u); return *this; }
  /// "in (0, 0.5)" style text of the valid range; empty when unbounded.
  std::string range_text() const;
  bool in_range(double v) const;
};

inline KeySpec key(std::string name, KeyType t, std::string doc) {
  KeySpec k;
  k.name = std::move(name);
  k.type = t;
  k.doc = std::move(doc);
  return k;
}

struct EffectDoc {
  std::string name;     // e.g. "walls.plane"
  std::string section;  // where it sits in the case file, e.g. "walls[] with type: plane"
  std::string summary;
  std::vector<KeySpec> keys;
  const KeySpec* find(const std::string& k) const {
    for (const auto& s : keys)
      if (s.name == k) return &s;
    return nullptr;
  }
};

/// Every section and effect of a case file, in the order `grains docs` prints them.
const std::vector<EffectDoc>& effect_docs();
const EffectDoc* find_effect_doc(const std::string& name);

}  // namespace grains::sim

namespace grains::sim {
/// Lets modules outside sim (io's outputs) add their own documentation.
void register_effect_doc(EffectDoc d);
}  // namespace grains::sim
