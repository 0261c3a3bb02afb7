#pragma once
// The values of a law's own case-file keys (e.g. contact.linear.stiffness),
// in the order the law declares its keys; NaN = not given. A law reads them
// in its prepare() when the pair table is mixed; nothing else needs to know
// what they mean, so a new law adds keys without touching the parser.
#include <array>
#include <limits>

namespace grains::sim {

inline constexpr int kMaxLawKeys = 8;

struct LawValues {
  std::array<double, kMaxLawKeys> v;
  LawValues() { v.fill(std::numeric_limits<double>::quiet_NaN()); }
  bool given(int k) const { return v[k] == v[k]; }
  double operator[](int k) const { return v[k]; }
  double& operator[](int k) { return v[k]; }
  /// This value where given, else `fallback`'s.
  LawValues over(const LawValues& fallback) const {
    LawValues out = fallback;
    for (int k = 0; k < kMaxLawKeys; ++k)
      if (given(k)) out.v[k] = v[k];
    return out;
  }
};

/// The declared defaults of a law's keys, N::keys() (NaN where a key has none).
template <class N>
LawValues law_defaults() {
  LawValues v;
  const auto keys = N::keys();
  for (std::size_t k = 0; k < keys.size(); ++k) v[static_cast<int>(k)] = keys[k].default_number;
  return v;
}

}  // namespace grains::sim
