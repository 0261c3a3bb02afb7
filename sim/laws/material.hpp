#pragma once
// Materials and the table of mixed pair parameters.
#include <string>
#include <vector>

#include "sim/laws/law_values.hpp"
#include "sim/laws/pair_params.hpp"

namespace grains::sim {

/// A material as the case file describes it. Defaults of the optional keys
/// are written once, in the key declarations (sim/laws/law_docs.cpp), from
/// which the parser fills every member.
struct Material {
  std::string name;
  double density = 0;           // kg/m^3
  double youngs_modulus = 0;    // Pa
  double poisson_ratio = 0;     // -
  double restitution = 0;       // -
  double friction = 0;          // sliding, -
  double rolling_friction = 0;  // -
  double cohesion = 0;          // cohesion energy density, J/m^3
  double surface_energy = 0;    // g, J/m^2 (adhesive normal laws)
  double shear_modulus() const { return youngs_modulus / (2 * (1 + poisson_ratio)); }
};

/// Optional override of the mixed values for one pair of materials.
struct PairOverride {
  int a = -1, b = -1;
  double restitution = -1, friction = -1, rolling_friction = -1, cohesion = -1;  // < 0: not given
  double work_of_adhesion = -1;                                                  // < 0: not given
  LawValues normal;  // the normal law's own keys for this pair (contact.pairs[].<law>); NaN: not given
};

/// The normal law (contact.model, a name from sim/laws/normal_laws.hpp) and
/// the values of its own keys (contact.<model>: {...}), defaults filled in.
struct NormalLawChoice {
  std::string name = "hertz";
  LawValues values;
};

/// n x n symmetric table of PairParams. Mixing rules (documented in
/// docs/physics.md): E* and G* from the Hertz/Mindlin formulas; restitution,
/// friction, rolling friction and cohesion are the arithmetic mean of the two
/// materials, the work of adhesion w = 2 sqrt(g_a g_b) of their surface
/// energies, unless a pair override gives them.
class PairTable {
 public:
  PairTable() = default;
  /// Throws std::invalid_argument when the normal law refuses a pair's values
  /// (the case parser has reported them with their location before).
  PairTable(const std::vector<Material>& mats, const std::vector<PairOverride>& overrides,
            const NormalLawChoice& normal = {});
  const PairParams& operator()(int a, int b) const { return table_[static_cast<std::size_t>(a) * n_ + b]; }
  int size() const { return n_; }
  bool any_friction() const;
  bool any_rolling() const;
  bool any_cohesion() const;
  bool any_adhesion() const;

 private:
  int n_ = 0;
  std::vector<PairParams> table_;
};

}  // namespace grains::sim
