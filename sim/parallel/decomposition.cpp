#include "sim/parallel/decomposition.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "sim/scene/scene.hpp"

namespace grains::sim {

Decomposition::Decomposition(const Domain& d, int ranks, double min_width, std::array<int, 3> requested)
    : periodic_(d.periodic), lo_(d.lo), hi_(d.hi), min_width_(min_width) {
  const Vec3 L = d.hi - d.lo;
  double best = std::numeric_limits<double>::infinity();
  bool found = false;
  for (int nx = 1; nx <= ranks; ++nx) {
    if (ranks % nx) continue;
    for (int ny = 1; ny <= ranks / nx; ++ny) {
      if ((ranks / nx) % ny) continue;
      const int nz = ranks / nx / ny;
      const std::array<int, 3> n{nx, ny, nz};
      bool ok = true;
      for (int k = 0; k < 3; ++k) {
        if (requested[k] > 0 && requested[k] != n[k]) ok = false;
        if (n[k] > 1 && L[k] / n[k] < min_width) ok = false;
      }
      if (!ok) continue;
      // Area of the internal cut planes (periodic dims cut once more).
      double area = 0;
      for (int k = 0; k < 3; ++k) {
        const double face = L[(k + 1) % 3] * L[(k + 2) % 3];
        const int planes = n[k] == 1 ? 0 : periodic_[k] ? n[k] : n[k] - 1;
        area += planes * face;
      }
      if (area < best * (1 - 1e-12)) {
        best = area;
        dims_ = n;
        found = true;
      }
    }
  }
  if (!found) {
    std::ostringstream m;
    m << "cannot split the domain (" << L.x() << " x " << L.y() << " x " << L.z() << " m) over " << ranks
      << " MPI ranks";
    if (requested != std::array<int, 3>{0, 0, 0})
      m << " as " << requested[0] << " x " << requested[1] << " x " << requested[2];
    m << ": every sub-domain must be at least the ghost cut-off " << min_width
      << " m (largest diameter + skin) wide; use fewer ranks or OpenMP threads";
    throw std::runtime_error(m.str());
  }
  for (int k = 0; k < 3; ++k) {
    cuts_[k].resize(static_cast<std::size_t>(dims_[k]) + 1);
    for (int c = 0; c <= dims_[k]; ++c) cuts_[k][static_cast<std::size_t>(c)] = lo_[k] + L[k] * c / dims_[k];
    cuts_[k].back() = hi_[k];
  }
}

std::array<int, 3> Decomposition::coords(int rank) const {
  return {rank % dims_[0], (rank / dims_[0]) % dims_[1], rank / (dims_[0] * dims_[1])};
}

int Decomposition::rank_at(std::array<int, 3> c) const { return (c[2] * dims_[1] + c[1]) * dims_[0] + c[0]; }

int Decomposition::owner(const Vec3& x) const {
  std::array<int, 3> c{};
  for (int k = 0; k < 3; ++k) {
    const auto& cut = cuts_[k];
    // First cut above x, among the interior cuts.
    const auto it = std::upper_bound(cut.begin() + 1, cut.end() - 1, x[k]);
    c[k] = static_cast<int>(it - (cut.begin() + 1));
  }
  return rank_at(c);
}

int Decomposition::neighbor(int rank, int d, int dir, bool& wraps) const {
  auto c = coords(rank);
  c[d] += dir;
  wraps = false;
  if (c[d] < 0 || c[d] >= dims_[d]) {
    if (!periodic_[d]) return -1;
    c[d] = (c[d] + dims_[d]) % dims_[d];
    wraps = true;
  }
  return rank_at(c);
}

Vec3 Decomposition::lo(int rank) const {
  const auto c = coords(rank);
  return {cuts_[0][c[0]], cuts_[1][c[1]], cuts_[2][c[2]]};
}

Vec3 Decomposition::hi(int rank) const {
  const auto c = coords(rank);
  return {cuts_[0][c[0] + 1], cuts_[1][c[1] + 1], cuts_[2][c[2] + 1]};
}

void Decomposition::resize(int k, double lo, double hi) {
  auto& cut = cuts_[static_cast<std::size_t>(k)];
  const double f = (hi - lo) / (hi_[k] - lo_[k]);
  for (auto& c : cut) c = lo + (c - lo_[k]) * f;
  cut.front() = lo_[k] = lo;
  cut.back() = hi_[k] = hi;
  if (dims_[k] > 1)
    for (std::size_t c = 0; c + 1 < cut.size(); ++c)
      if (cut[c + 1] - cut[c] < min_width_) {
        std::ostringstream m;
        m << "the cell shrank along " << "xyz"[k] << " to " << hi - lo << " m: a sub-domain of its " << dims_[k]
          << " ranks there is now narrower than the ghost cut-off " << min_width_
          << " m; use fewer ranks along that axis (parallel.dims)";
        throw std::runtime_error(m.str());
      }
}

bool Decomposition::set_cuts(const std::array<std::vector<double>, 3>& cuts) {
  for (int d = 0; d < 3; ++d) {
    const auto& c = cuts[d];
    if (c.size() != cuts_[d].size() || c.front() != cuts_[d].front() || c.back() != cuts_[d].back()) return false;
    for (std::size_t k = 1; k < c.size(); ++k)
      if (!(c[k] > c[k - 1])) return false;
  }
  cuts_ = cuts;
  return true;
}

bool Decomposition::balance(const std::vector<Vec3>& x, std::size_t n, const Comm& comm, const double* weight) {
  constexpr int kBins = 2048;
  bool changed = false;
  for (int k = 0; k < 3; ++k) {
    if (dims_[k] == 1) continue;
    const double L = hi_[k] - lo_[k];
    std::vector<double> h(kBins, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const int b = std::clamp(static_cast<int>((x[i][k] - lo_[k]) / L * kBins), 0, kBins - 1);
      h[static_cast<std::size_t>(b)] += weight ? weight[i] : 1.0;
    }
    comm.sum_in_place(h);
    double total = 0;
    for (double v : h) total += v;
    if (total <= 0) continue;
    std::vector<double> cut(static_cast<std::size_t>(dims_[k]) + 1);
    cut.front() = lo_[k];
    cut.back() = hi_[k];
    double acc = 0;
    int b = 0;
    for (int c = 1; c < dims_[k]; ++c) {
      const double target = total * c / dims_[k];
      while (b < kBins && acc + h[static_cast<std::size_t>(b)] < target) acc += h[static_cast<std::size_t>(b++)];
      // Linear interpolation inside bin b.
      const double inb = b < kBins && h[static_cast<std::size_t>(b)] > 0 ? (target - acc) / h[static_cast<std::size_t>(b)] : 0;
      cut[static_cast<std::size_t>(c)] = lo_[k] + (b + inb) * L / kBins;
    }
    // Every slab at least min_width: push cuts up from below, then down from above.
    for (int c = 1; c < dims_[k]; ++c)
      cut[c] = std::max(cut[c], cut[c - 1] + min_width_);
    for (int c = dims_[k] - 1; c >= 1; --c)
      cut[c] = std::min(cut[c], cut[c + 1] - min_width_);
    if (cut != cuts_[k]) changed = true;
    cuts_[k] = cut;
  }
  return changed;
}

double Decomposition::imbalance(std::size_t n_owned, const Comm& comm) {
  return imbalance(static_cast<double>(n_owned), comm);
}

double Decomposition::imbalance(double n, const Comm& comm) {
  const double mx = comm.max(n), total = comm.sum(n);
  return total > 0 ? mx / (total / comm.size()) : 1.0;
}

std::string Decomposition::describe() const {
  std::ostringstream o;
  o << dims_[0] << " x " << dims_[1] << " x " << dims_[2] << " ranks";
  for (int k = 0; k < 3; ++k) {
    if (dims_[k] == 1) continue;
    o << "; cuts " << "xyz"[k] << ":";
    for (double c : cuts_[k]) o << " " << c;
  }
  return o.str();
}

}  // namespace grains::sim
