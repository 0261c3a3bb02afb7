#pragma once
// Deterministic random configurations for the ellipsoid tests (splitmix64, so
// the sequence does not depend on the standard library's distributions).
#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>

namespace grains::test {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : s_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return (next() >> 11) * 0x1.0p-53; }  // [0, 1)
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  double log_uniform(double a, double b) { return std::exp(uniform(std::log(a), std::log(b))); }
  double normal() {
    const double u = 1.0 - uniform(), v = uniform();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(6.283185307179586 * v);
  }
  Eigen::Vector3d unit_vector() {
    Eigen::Vector3d v(normal(), normal(), normal());
    return v / v.norm();
  }
  Eigen::Quaterniond rotation() {
    Eigen::Quaterniond q(normal(), normal(), normal(), normal());
    return q.normalized();
  }

 private:
  std::uint64_t s_;
};

}  // namespace grains::test
