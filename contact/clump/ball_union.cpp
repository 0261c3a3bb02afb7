#include "contact/clump/ball_union.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace grains::clump {

BallUnion::BallUnion(std::vector<Ball> balls) : balls_(std::move(balls)) {
  if (balls_.empty()) throw std::invalid_argument("a union of balls needs at least one ball");
  lo_ = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  hi_ = -lo_;
  double rsum = 0.0;
  for (const auto& b : balls_) {
    lo_ = lo_.cwiseMin(b.center - Eigen::Vector3d::Constant(b.radius));
    hi_ = hi_.cwiseMax(b.center + Eigen::Vector3d::Constant(b.radius));
    rsum += b.radius;
  }
  const Eigen::Vector3d ext = hi_ - lo_;
  // Bins about twice the mean radius, at most 64 per axis.
  bin_ = std::max({2.0 * rsum / balls_.size(), ext.maxCoeff() / 64.0, 1e-300});
  for (int d = 0; d < 3; ++d) nb_[d] = std::max(1, static_cast<int>(std::ceil(ext[d] / bin_)));
  bins_.assign(size_t(nb_[0]) * nb_[1] * nb_[2], {});
  for (size_t i = 0; i < balls_.size(); ++i) {
    const auto& b = balls_[i];
    int a[3], z[3];
    for (int d = 0; d < 3; ++d) {
      a[d] = bin_coord(b.center[d] - b.radius, d);
      z[d] = bin_coord(b.center[d] + b.radius, d);
    }
    for (int k = a[2]; k <= z[2]; ++k)
      for (int j = a[1]; j <= z[1]; ++j)
        for (int ii = a[0]; ii <= z[0]; ++ii) bins_[ii + size_t(nb_[0]) * (j + size_t(nb_[1]) * k)].push_back(int(i));
  }
  seen_.assign(balls_.size(), 0);
}

int BallUnion::bin_coord(double x, int d) const {
  return std::clamp(static_cast<int>(std::floor((x - lo_[d]) / bin_)), 0, nb_[d] - 1);
}

void BallUnion::candidates(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, std::vector<int>& out) const {
  out.clear();
  if ((lo.array() > hi_.array()).any() || (hi.array() < lo_.array()).any()) return;
  if (++tick_ == std::numeric_limits<int>::max()) {
    std::fill(seen_.begin(), seen_.end(), 0);
    tick_ = 1;
  }
  int a[3], z[3];
  for (int d = 0; d < 3; ++d) {
    a[d] = bin_coord(lo[d], d);
    z[d] = bin_coord(hi[d], d);
  }
  for (int k = a[2]; k <= z[2]; ++k)
    for (int j = a[1]; j <= z[1]; ++j)
      for (int i = a[0]; i <= z[0]; ++i)
        for (int b : bins_[i + size_t(nb_[0]) * (j + size_t(nb_[1]) * k)]) {
          if (seen_[b] == tick_) continue;
          seen_[b] = tick_;
          const auto& ball = balls_[b];
          if (((ball.center.array() + ball.radius) >= lo.array()).all() &&
              ((ball.center.array() - ball.radius) <= hi.array()).all())
            out.push_back(b);
        }
}

double BallUnion::signed_distance_bound(const Eigen::Vector3d& p) const {
  // Grow a search box until it holds a ball whose surface is nearer than the
  // box's half width (then no ball outside the box can be nearer).
  std::vector<int> cand;
  const double start = std::max(bin_, (p.cwiseMax(lo_).cwiseMin(hi_) - p).norm() + bin_);
  for (double half = start;; half *= 2.0) {
    candidates(p - Eigen::Vector3d::Constant(half), p + Eigen::Vector3d::Constant(half), cand);
    double best = std::numeric_limits<double>::infinity();
    for (int b : cand) best = std::min(best, (p - balls_[b].center).norm() - balls_[b].radius);
    if (best <= half) return best;
    if (half > 4.0 * (hi_ - lo_).norm() + start) {  // cannot happen with a non-empty set; be safe
      for (const auto& b : balls_) best = std::min(best, (p - b.center).norm() - b.radius);
      return best;
    }
  }
}

bool BallUnion::contains(const Eigen::Vector3d& p, double tol) const {
  std::vector<int> cand;
  candidates(p, p, cand);
  for (int b : cand)
    if ((p - balls_[b].center).norm() <= balls_[b].radius + tol) return true;
  return false;
}

namespace {

struct Accumulator {
  double vol = 0.0, bound = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  long cells = 0;
  Eigen::Vector3d ref = Eigen::Vector3d::Zero();  // moments about ref keep their digits
  void add_cube(const Eigen::Vector3d& centre, double s) {
    const Eigen::Vector3d c = centre - ref;
    const double v = s * s * s;
    vol += v;
    first += v * c;
    second += v * (c * c.transpose() + Eigen::Matrix3d::Identity() * (s * s / 12.0));
  }
};

void integrate(const BallUnion& U, const Eigen::Vector3d& lo, double s, double finest, const std::vector<int>& parent,
               Accumulator& acc) {
  ++acc.cells;
  const Eigen::Vector3d hi = lo + Eigen::Vector3d::Constant(s);
  const Eigen::Vector3d c = lo + Eigen::Vector3d::Constant(0.5 * s);
  std::vector<int> touching;
  touching.reserve(parent.size());
  for (int b : parent) {
    const Ball& ball = U.balls()[b];
    const double d2 = (lo - ball.center).cwiseMax(ball.center - hi).cwiseMax(0.0).squaredNorm();
    if (d2 >= ball.radius * ball.radius) continue;
    // Farthest corner from the centre inside the ball => cube inside the ball.
    const Eigen::Vector3d far = (ball.center - lo).cwiseAbs().cwiseMax((hi - ball.center).cwiseAbs());
    if (far.squaredNorm() <= ball.radius * ball.radius) {
      acc.add_cube(c, s);
      return;
    }
    touching.push_back(b);
  }
  if (touching.empty()) return;
  if (s <= finest * (1.0 + 1e-12)) {
    acc.bound += s * s * s;
    for (int b : touching) {
      if ((c - U.balls()[b].center).squaredNorm() <= U.balls()[b].radius * U.balls()[b].radius) {
        acc.add_cube(c, s);
        return;
      }
    }
    return;
  }
  const double h = 0.5 * s;
  for (int o = 0; o < 8; ++o) {
    integrate(U, lo + Eigen::Vector3d((o & 1) * h, ((o >> 1) & 1) * h, ((o >> 2) & 1) * h), h, finest, touching, acc);
  }
}

}  // namespace

UnionMoments union_moments(const BallUnion& U, double finest) {
  if (!(finest > 0.0)) throw std::invalid_argument("union_moments: finest cell size must be positive");
  const Eigen::Vector3d ext = U.hi() - U.lo();
  // Root cubes of edge finest * 2^k, about 16 per longest axis.
  double root = finest;
  while (root * 16.0 < ext.maxCoeff()) root *= 2.0;
  int n[3];
  for (int d = 0; d < 3; ++d) n[d] = std::max(1, static_cast<int>(std::ceil(ext[d] / root)));
  Accumulator acc;
  acc.ref = 0.5 * (U.lo() + U.hi());
  std::vector<int> cand;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const Eigen::Vector3d lo = U.lo() + root * Eigen::Vector3d(i, j, k);
        U.candidates(lo, lo + Eigen::Vector3d::Constant(root), cand);
        if (!cand.empty()) integrate(U, lo, root, finest, cand, acc);
      }
  UnionMoments m;
  m.volume = acc.vol;
  m.volume_bound = acc.bound;
  m.cells = acc.cells;
  if (acc.vol > 0.0) {
    const Eigen::Vector3d c = acc.first / acc.vol;
    const Eigen::Matrix3d sc = acc.second - acc.vol * c * c.transpose();
    m.centroid = c + acc.ref;
    m.inertia = sc.trace() * Eigen::Matrix3d::Identity() - sc;
  }
  return m;
}

}  // namespace grains::clump
