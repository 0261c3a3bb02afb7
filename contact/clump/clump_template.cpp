#include "contact/clump/clump_template.hpp"

#include "contact/clump/ball_union.hpp"
#include "contact/clump/distance_grid.hpp"
#include "contact/clump/hausdorff.hpp"
#include "contact/clump/mesh_distance.hpp"

#include <Eigen/Eigenvalues>

#include <chrono>
#include <stdexcept>

namespace grains::clump {

ClumpTemplate make_clump_template(const std::vector<Ball>& balls, double density, double finest) {
  if (!(density > 0.0)) throw std::invalid_argument("density must be positive, got " + std::to_string(density));
  const BallUnion U(balls);
  const UnionMoments m = union_moments(U, finest);
  ClumpTemplate t;
  t.density = density;
  t.volume = m.volume;
  t.volume_bound = m.volume_bound;
  t.mass = density * m.volume;
  t.centre_of_mass = m.centroid;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(density * m.inertia);
  t.inertia = eig.eigenvalues();
  Eigen::Matrix3d R = eig.eigenvectors();
  // A reproducible sign per axis (largest component positive), then right-handed.
  for (int c = 0; c < 3; ++c) {
    Eigen::Index i;
    R.col(c).cwiseAbs().maxCoeff(&i);
    if (R(i, c) < 0) R.col(c) *= -1.0;
  }
  if (R.determinant() < 0) R.col(2) *= -1.0;
  t.axes = R;
  t.balls.reserve(balls.size());
  for (const auto& b : balls) t.balls.push_back({R.transpose() * (b.center - m.centroid), b.radius});
  return t;
}

ClumpTemplate build_clump(const mesh::TriangleMesh& mesh, const ClumpOptions& opt) {
  using Clock = std::chrono::steady_clock;
  auto seconds = [](Clock::time_point a) { return std::chrono::duration<double>(Clock::now() - a).count(); };
  const auto t0 = Clock::now();
  const MeshDistance md(mesh);
  const DistanceGrid grid = compute_distance_grid(mesh, opt.decomposition.grid, &md);
  SphereDecomposition d = decompose(grid, opt.decomposition);
  const double t_dec = seconds(t0);

  const auto tm = Clock::now();
  ClumpTemplate t = make_clump_template(d.a3, opt.density, opt.integration_cells * grid.h);
  ClumpMetadata& meta = t.meta;
  meta.seconds_mass = seconds(tm);
  meta.seconds_distance_vdb = grid.seconds_vdb;
  meta.seconds_distance_exact = grid.seconds_exact;
  meta.seconds_greedy = d.seconds_greedy;
  meta.seconds_reduction = d.seconds_reduction;
  meta.source = mesh.source;
  meta.grid = d.grid;
  meta.mu = d.mu;
  meta.greedy_key = d.key == GreedyKey::distance ? "distance" : "skeletal";
  meta.epsilon = d.epsilon;
  meta.n1 = d.n1();
  meta.n3 = d.n3();
  meta.restored = d.restored;
  meta.mesh_volume = mesh::polyhedron_moments(mesh).volume;
  meta.volume_error = (t.volume - meta.mesh_volume) / meta.mesh_volume;
  meta.seconds_decomposition = t_dec;
  if (opt.measure) {
    const auto t1 = Clock::now();
    const BallUnion U(d.a3);
    const HausdorffResult h = measure_hausdorff(mesh, md, U, opt.sample_spacing_cells * grid.h, &grid);
    meta.hausdorff = h.hausdorff;
    meta.hausdorff_mesh_to_union = h.mesh_to_union;
    meta.hausdorff_union_to_mesh = h.union_to_mesh;
    meta.node_cover_radius = h.node_cover_radius;
    meta.seconds_measurement = std::chrono::duration<double>(Clock::now() - t1).count();
  }
  return t;
}

}  // namespace grains::clump
