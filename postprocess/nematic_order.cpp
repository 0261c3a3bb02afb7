#include "postprocess/nematic_order.hpp"

#include <cmath>
#include <random>
#include <set>
#include <stdexcept>

#include <Eigen/Eigenvalues>

namespace grains::postprocess {

namespace {

Eigen::Matrix3d order_tensor(const std::vector<Vec3>& axes) {
  Eigen::Matrix3d q = Eigen::Matrix3d::Zero();
  for (const auto& a : axes) {
    const Vec3 u = a.normalized();
    q += 1.5 * u * u.transpose();
  }
  q /= static_cast<double>(axes.size());
  q -= 0.5 * Eigen::Matrix3d::Identity();
  return q;
}

double largest_eigenvalue(const std::vector<Vec3>& axes) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(order_tensor(axes), Eigen::EigenvaluesOnly);
  return es.eigenvalues()[2];
}

}  // namespace

NematicOrder nematic_order(const std::vector<Vec3>& axes) {
  NematicOrder r;
  r.n = axes.size();
  if (axes.empty()) return r;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(order_tensor(axes));
  r.eigenvalues = es.eigenvalues();
  r.S = r.eigenvalues[2];
  r.director = es.eigenvectors().col(2).normalized();
  // Sign convention: the director's largest component positive.
  Eigen::Index k;
  r.director.cwiseAbs().maxCoeff(&k);
  if (r.director[k] < 0) r.director = -r.director;
  // Finite-N baseline: isotropic axes (normalised Gaussian vectors), fixed seed.
  std::mt19937_64 rng(12345);
  std::normal_distribution<double> g;
  const int trials = 32;
  std::vector<Vec3> iso(axes.size());
  double sum = 0;
  for (int t = 0; t < trials; ++t) {
    for (auto& u : iso) {
      do u = Vec3(g(rng), g(rng), g(rng));
      while (u.squaredNorm() < 1e-12);
    }
    sum += largest_eigenvalue(iso);
  }
  r.isotropic_baseline = sum / trials;
  return r;
}

int shape_axis(const Vec3& a) {
  int best = 0;
  double dev = -1;
  for (int k = 0; k < 3; ++k) {
    const double others = 0.5 * (a.sum() - a[k]);
    const double d = std::abs(a[k] - others) / std::max(others, 1e-300);
    if (d > dev + 1e-12) {
      dev = d;
      best = k;
    }
  }
  return best;
}

NematicOrder nematic_order(const Frame& f, const Box& region, int axis) {
  if (!f.has_orientation())
    throw std::runtime_error("nematic order needs particle orientations; '" + f.file.string() +
                             "' has no 'orientation' array");
  std::vector<Vec3> u;
  int ax = axis;
  std::set<std::int64_t> bodies_seen;  // clump balls: one axis per clump
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (!f.body.empty() && !bodies_seen.insert(f.body[i]).second) continue;
    if (!((f.x[i].array() >= region.lo.array()).all() && (f.x[i].array() <= region.hi.array()).all())) continue;
    if (ax < 0) ax = f.has_ellipsoids() ? shape_axis(f.semi_axes[i]) : 0;
    u.push_back(f.orientation[i] * Vec3::Unit(ax));
  }
  auto r = nematic_order(u);
  r.axis = ax < 0 ? 0 : ax;
  return r;
}

}  // namespace grains::postprocess
