#include "sim/keys/effect_doc.hpp"

#include <cmath>
#include <sstream>

namespace grains::sim {

const char* key_type_name(KeyType t) {
  switch (t) {
    case KeyType::Number: return "number";
    case KeyType::Integer: return "integer";
    case KeyType::Bool: return "boolean";
    case KeyType::String: return "string";
    case KeyType::Vec3: return "vector [x, y, z]";
    case KeyType::NumberList: return "list of numbers";
    case KeyType::Map: return "map";
    case KeyType::List: return "list";
    case KeyType::Bool3: return "list of 3 booleans";
  }
  return "?";
}

std::string KeySpec::range_text() const {
  const bool has_lo = std::isfinite(min), has_hi = std::isfinite(max);
  if (!has_lo && !has_hi) return {};
  std::ostringstream o;
  o.precision(10);
  if (has_lo && has_hi) {
    o << (min_exclusive ? "(" : "[") << min << ", " << max << (max_exclusive ? ")" : "]");
  } else if (has_lo) {
    o << (min_exclusive ? "> " : ">= ") << min;
  } else {
    o << (max_exclusive ? "< " : "<= ") << max;
  }
  return o.str();
}

KeySpec& KeySpec::def(double v) {
  std::ostringstream o;
  o.precision(10);
  o << v;
  default_value = o.str();
  default_number = v;
  return *this;
}

bool KeySpec::in_range(double v) const {
  if (std::isnan(v)) return false;
  if (min_exclusive ? !(v > min) : !(v >= min)) return false;
  if (max_exclusive ? !(v < max) : !(v <= max)) return false;
  return true;
}

const EffectDoc* find_effect_doc(const std::string& name) {
  for (const auto& d : effect_docs())
    if (d.name == name) return &d;
  return nullptr;
}

}  // namespace grains::sim
