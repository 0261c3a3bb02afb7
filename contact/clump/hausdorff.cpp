#include "contact/clump/hausdorff.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace grains::clump {

HausdorffResult measure_hausdorff(const mesh::TriangleMesh& mesh, const MeshDistance& distance, const BallUnion& U,
                                  double spacing, const DistanceGrid* grid) {
  if (!(spacing > 0.0)) throw std::invalid_argument("measure_hausdorff: sample spacing must be positive");
  HausdorffResult res;
  if (grid) res.node_cover_radius = 0.0;
  auto note_s = [&](const Eigen::Vector3d& p) {
    if (grid) res.node_cover_radius = std::max(res.node_cover_radius, grid->distance_to_inside_node(p));
    const double d = std::max(0.0, U.signed_distance_bound(p));
    if (d > res.mesh_to_union) {
      res.mesh_to_union = d;
      if (d > res.hausdorff) {
        res.hausdorff = d;
        res.worst = p;
      }
    }
  };
  // Mesh surface.
  for (const auto& f : mesh.faces) {
    const Eigen::Vector3d& a = mesh.vertices[f[0]];
    const Eigen::Vector3d ab = mesh.vertices[f[1]] - a, ac = mesh.vertices[f[2]] - a;
    const double longest = std::max({ab.norm(), ac.norm(), (ac - ab).norm()});
    const int k = std::max(1, static_cast<int>(std::ceil(longest / spacing)));
    for (int i = 0; i <= k; ++i)
      for (int j = 0; i + j <= k; ++j) {
        note_s(a + (double(i) / k) * ab + (double(j) / k) * ac);
        ++res.mesh_samples;
      }
  }
  // Voids of U inside S: cell centres of the distance grid inside S.
  if (grid) {
    for (int kk = 0; kk + 1 < grid->n; ++kk)
      for (int jj = 0; jj + 1 < grid->n; ++jj)
        for (int ii = 0; ii + 1 < grid->n; ++ii) {
          const Eigen::Vector3d p = grid->node(ii, jj, kk) + Eigen::Vector3d::Constant(0.5 * grid->h);
          if (grid->interpolate(p) < 0.0) {
            note_s(p);
            ++res.interior_samples;
          }
        }
  }
  // Exposed boundary of U.
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  const double tol = 1e-9 * (U.hi() - U.lo()).norm();
  for (const auto& b : U.balls()) {
    const int n = std::max(24, static_cast<int>(std::ceil(4.0 * std::numbers::pi * b.radius * b.radius / (spacing * spacing))));
    for (int i = 0; i < n; ++i) {
      const double z = 1.0 - (2.0 * i + 1.0) / n;
      const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
      const double phi = golden * i;
      const Eigen::Vector3d q = b.center + b.radius * Eigen::Vector3d(rho * std::cos(phi), rho * std::sin(phi), z);
      if (U.contains(q, -tol)) continue;  // inside another ball: not on the boundary of U
      ++res.union_samples;
      double d = std::max(0.0, distance.signed_distance(q));
      // A claimed excess over the current maximum is checked with the
      // winding number, robust where the pseudo-normal sign is not.
      if (d > res.union_to_mesh && distance.winding_number(q) > 0.5) d = 0.0;
      if (d > res.union_to_mesh) {
        res.union_to_mesh = d;
        if (d > res.hausdorff) {
          res.hausdorff = d;
          res.worst = q;
        }
      }
    }
  }
  return res;
}

}  // namespace grains::clump
