#pragma once
// A uniform cell grid over a set of points, for the neighbour queries of the
// analyses (contacts, RDF pairs, point-in-particle tests). Built once per
// frame; a query visits the cells the cube [p - reach, p + reach] touches.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace grains::postprocess {

class CellGrid {
 public:
  /// `cell` is the wanted cell edge; it is enlarged if the grid would have far
  /// more cells than points.
  CellGrid(const std::vector<Eigen::Vector3d>& x, double cell) {
    if (x.empty()) return;
    lo_ = hi_ = x[0];
    for (const auto& p : x) {
      lo_ = lo_.cwiseMin(p);
      hi_ = hi_.cwiseMax(p);
    }
    const Eigen::Vector3d ext = (hi_ - lo_).cwiseMax(1e-300);
    h_ = std::max(cell, 1e-300);
    const double max_cells = 8.0 * static_cast<double>(x.size()) + 64;
    while (((ext / h_).array().floor() + 1.0).prod() > max_cells) h_ *= 1.25;
    for (int d = 0; d < 3; ++d) n_[d] = static_cast<int>(std::floor(ext[d] / h_)) + 1;
    start_.assign(static_cast<std::size_t>(n_[0]) * n_[1] * n_[2] + 1, 0);
    std::vector<std::size_t> c(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
      c[i] = flat(coord(x[i]));
      ++start_[c[i] + 1];
    }
    for (std::size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
    items_.resize(x.size());
    std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < x.size(); ++i) items_[fill[c[i]]++] = static_cast<std::uint32_t>(i);
  }

  double cell() const { return h_; }

  /// Calls fn(j) for every point j in a cell that the cube around p touches
  /// (a superset of the points within `reach` of p).
  template <class Fn>
  void for_each_near(const Eigen::Vector3d& p, double reach, Fn&& fn) const {
    if (items_.empty()) return;
    int a[3], b[3];
    for (int d = 0; d < 3; ++d) {
      a[d] = std::max(0, static_cast<int>(std::floor((p[d] - reach - lo_[d]) / h_)));
      b[d] = std::min(n_[d] - 1, static_cast<int>(std::floor((p[d] + reach - lo_[d]) / h_)));
      if (a[d] > b[d]) return;
    }
    for (int i = a[0]; i <= b[0]; ++i)
      for (int j = a[1]; j <= b[1]; ++j)
        for (int k = a[2]; k <= b[2]; ++k) {
          const std::size_t f = flat({i, j, k});
          for (std::size_t q = start_[f]; q < start_[f + 1]; ++q) fn(static_cast<std::size_t>(items_[q]));
        }
  }

 private:
  struct Idx {
    int i, j, k;
  };
  Idx coord(const Eigen::Vector3d& p) const {
    int c[3];
    for (int d = 0; d < 3; ++d) c[d] = std::clamp(static_cast<int>(std::floor((p[d] - lo_[d]) / h_)), 0, n_[d] - 1);
    return {c[0], c[1], c[2]};
  }
  std::size_t flat(Idx c) const {
    return (static_cast<std::size_t>(c.i) * n_[1] + c.j) * n_[2] + c.k;
  }
  Eigen::Vector3d lo_{0, 0, 0}, hi_{0, 0, 0};
  double h_ = 1;
  int n_[3] = {1, 1, 1};
  std::vector<std::size_t> start_;
  std::vector<std::uint32_t> items_;
};

}  // namespace grains::postprocess
