#pragma once
// Helpers for tests that run real scenes from case text.
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "io/case/case.hpp"
#include "io/run/simulation.hpp"

namespace grains::test {

inline io::Simulation from_yaml(const std::string& yaml, const std::vector<std::string>& sets = {}) {
  return io::make_simulation(io::parse_case(yaml, "test.yaml", sets));
}

/// Runs s quietly (no progress line) into `dir`, emptied first; the run's summary.
inline io::RunSummary run_into(io::Simulation& s, const std::filesystem::path& dir) {
  std::filesystem::remove_all(dir);
  io::RunOptions opt;
  opt.out_dir = dir;
  opt.quiet = true;
  return io::run(s, opt);
}

/// A material block in YAML.
inline std::string material(const std::string& name, double rho, double E, double nu, double e, double mu,
                            double mu_r = 0) {
  std::ostringstream o;
  o.precision(17);
  o << "  - {name: " << name << ", density: " << rho << ", youngs_modulus: " << E << ", poisson_ratio: " << nu
    << ", restitution: " << e << ", friction: " << mu << ", rolling_friction: " << mu_r << "}\n";
  return o.str();
}

/// A one-particle set at centre c with radius r and velocity v.
inline std::string single(const std::string& name, const std::string& mat, const sim::Vec3& c, double r,
                          const sim::Vec3& v) {
  std::ostringstream o;
  o.precision(17);
  const sim::Vec3 lo = c - sim::Vec3::Constant(r), hi = c + sim::Vec3::Constant(r * 1.5);
  o << "  - {name: " << name << ", material: " << mat << ", radius: " << r << ", count: 1, velocity: [" << v[0]
    << ", " << v[1] << ", " << v[2] << "], placement: {type: lattice, region: {min: [" << lo[0] << ", " << lo[1]
    << ", " << lo[2] << "], max: [" << hi[0] << ", " << hi[1] << ", " << hi[2] << "]}}}\n";
  return o.str();
}

/// Index of the particle with global id `gid` (particles may be re-sorted).
inline std::size_t index_of(const sim::ParticleStore& p, std::int64_t gid) {
  for (std::size_t i = 0; i < p.n_owned(); ++i)
    if (p.id[i] == gid) return i;
  return p.n_owned();
}

}  // namespace grains::test
