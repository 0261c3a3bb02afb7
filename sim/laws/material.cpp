#include "sim/laws/material.hpp"

#include <cmath>

#include <stdexcept>

#include "sim/laws/normal_laws.hpp"

namespace grains::sim {

PairTable::PairTable(const std::vector<Material>& mats, const std::vector<PairOverride>& overrides,
                     const NormalLawChoice& normal)
    : n_(static_cast<int>(mats.size())), table_(mats.size() * mats.size()) {
  for (int a = 0; a < n_; ++a)
    for (int b = 0; b < n_; ++b) {
      const Material& A = mats[a];
      const Material& B = mats[b];
      PairParams p;
      p.E_eff = 1.0 / ((1 - A.poisson_ratio * A.poisson_ratio) / A.youngs_modulus +
                       (1 - B.poisson_ratio * B.poisson_ratio) / B.youngs_modulus);
      p.G_eff = 1.0 / ((2 - A.poisson_ratio) / A.shear_modulus() + (2 - B.poisson_ratio) / B.shear_modulus());
      p.restitution = 0.5 * (A.restitution + B.restitution);
      p.friction = 0.5 * (A.friction + B.friction);
      p.rolling_friction = 0.5 * (A.rolling_friction + B.rolling_friction);
      p.cohesion = 0.5 * (A.cohesion + B.cohesion);
      // Two surfaces of one material: w = 2 g (Dupre); of two: the geometric
      // mean of theirs (Girifalco & Good), 2 sqrt(g_a g_b).
      p.work_of_adhesion = 2.0 * std::sqrt(A.surface_energy * B.surface_energy);
      LawValues values = normal.values;
      for (const auto& o : overrides)
        if ((o.a == a && o.b == b) || (o.a == b && o.b == a)) {
          if (o.restitution >= 0) p.restitution = o.restitution;
          if (o.friction >= 0) p.friction = o.friction;
          if (o.rolling_friction >= 0) p.rolling_friction = o.rolling_friction;
          if (o.cohesion >= 0) p.cohesion = o.cohesion;
          if (o.work_of_adhesion >= 0) p.work_of_adhesion = o.work_of_adhesion;
          values = o.normal.over(values);
        }
      std::string error;
      const bool known = with_type_named(NormalLaws{}, normal.name, [&]<class N>() { error = N::prepare(p, values); });
      if (!known) throw std::invalid_argument("unknown normal law '" + normal.name + "'");
      if (!error.empty())
        throw std::invalid_argument("contact." + normal.name + " for materials " + A.name + " and " + B.name + ": " +
                                    error);
      table_[static_cast<std::size_t>(a) * n_ + b] = p;
    }
}

bool PairTable::any_friction() const {
  for (const auto& p : table_)
    if (p.friction > 0) return true;
  return false;
}
bool PairTable::any_rolling() const {
  for (const auto& p : table_)
    if (p.rolling_friction > 0) return true;
  return false;
}
bool PairTable::any_adhesion() const {
  for (const auto& p : table_)
    if (p.work_of_adhesion > 0) return true;
  return false;
}
bool PairTable::any_cohesion() const {
  for (const auto& p : table_)
    if (p.cohesion > 0) return true;
  return false;
}

}  // namespace grains::sim
