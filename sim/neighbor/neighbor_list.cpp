#include "sim/neighbor/neighbor_list.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <type_traits>

namespace grains::sim {

bool NeighborList::needs_rebuild(const ParticleStore& p, const Walls& walls, double time) const {
  const std::size_t n = p.n_owned();
  if (x_build_.size() != n) return true;
  double m2 = 0;
  for (std::size_t i = 0; i < n; ++i) m2 = std::max(m2, (p.x[i] - x_build_[i]).squaredNorm());
  const double m = std::sqrt(m2);
  return 2 * m > skin_ || m + walls.max_displacement(time - build_time_) > skin_;
}

void NeighborList::build(ParticleStore& p, const Walls& walls, const Vec3& lo_bound, const Vec3& hi_bound, double time,
                         bool sort) {
  const std::size_t n = p.n_owned();
  // Remember the old rows by global id, so history can follow its pair.
  if (history_size_ > 0) {
    old_row_start_ = row_start;
    old_history_.swap(history);
    old_partner_id_.resize(partner.size());
    for (std::size_t k = 0; k < partner.size(); ++k) old_partner_id_[k] = old_row_id_.empty() ? -1 : old_row_id_[partner[k]];
  }

  double rmax = 0;
  for (std::size_t i = 0; i < n; ++i) rmax = std::max(rmax, p.radius[i]);
  // The grid spans the particles' bounding box (within the given bounds), so
  // a sparse scene in a large domain does not pay for empty cells; cells
  // grow when there would be far more cells than particles.
  Vec3 lo = lo_bound, hi = hi_bound;
  if (n > 0) {
    Vec3 blo = p.x[0], bhi = p.x[0];
    for (std::size_t i = 1; i < n; ++i) {
      blo = blo.cwiseMin(p.x[i]);
      bhi = bhi.cwiseMax(p.x[i]);
    }
    lo = lo.cwiseMax(blo);
    hi = hi.cwiseMin(bhi).cwiseMax(lo + Vec3::Constant(1e-12));
  }
  double cell = std::max(2 * rmax + skin_, 1e-300);
  std::array<int, 3> dims;
  for (;;) {
    for (int d = 0; d < 3; ++d) dims[d] = std::max(1, static_cast<int>(std::floor((hi[d] - lo[d]) / cell)));
    if (static_cast<double>(dims[0]) * dims[1] * dims[2] <= 4.0 * static_cast<double>(n) + 64) break;
    cell *= 1.26;
  }
  const Vec3 inv(dims[0] / (hi[0] - lo[0]), dims[1] / (hi[1] - lo[1]), dims[2] / (hi[2] - lo[2]));
  auto cell_of = [&](const Vec3& x, int d) {
    const int c = static_cast<int>((x[d] - lo[d]) * inv[d]);
    return std::clamp(c, 0, dims[d] - 1);
  };
  const std::size_t ncells = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  std::vector<std::uint32_t> cell_id(n), cell_start(ncells + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = (static_cast<std::size_t>(cell_of(p.x[i], 2)) * dims[1] + cell_of(p.x[i], 1)) * dims[0] +
                   cell_of(p.x[i], 0);
    cell_id[i] = static_cast<std::uint32_t>(c);
    ++cell_start[c + 1];
  }
  std::partial_sum(cell_start.begin(), cell_start.end(), cell_start.begin());
  std::vector<std::size_t> order(n);
  {
    std::vector<std::uint32_t> fill(cell_start.begin(), cell_start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) order[fill[cell_id[i]]++] = i;
  }
  if (sort) {
    p.permute(order);  // particles now sorted by cell
    for (std::size_t k = 0; k < n; ++k) order[k] = k;
  }
  // order[k]: particle index of the k-th slot in cell order.

  // Candidate pairs from the 13 forward neighbour cells and the own cell.
  std::vector<std::uint32_t> pi, pj;
  pi.reserve(8 * n);
  pj.reserve(8 * n);
  static const int stencil[14][3] = {{0, 0, 0},  {1, 0, 0},  {-1, 1, 0}, {0, 1, 0},  {1, 1, 0},
                                     {-1, -1, 1}, {0, -1, 1}, {1, -1, 1}, {-1, 0, 1}, {0, 0, 1},
                                     {1, 0, 1},  {-1, 1, 1}, {0, 1, 1},  {1, 1, 1}};
  // Balls of the same clump never interact: in scenes with clumps (the
  // `body` field exists) their pairs are left out here, by a separate
  // instantiation of the loop, so sphere scenes pay nothing for the check.
  auto collect = [&](auto exclude_same_body) {
  for (int cz = 0; cz < dims[2]; ++cz)
    for (int cy = 0; cy < dims[1]; ++cy)
      for (int cx = 0; cx < dims[0]; ++cx) {
        const std::size_t c = (static_cast<std::size_t>(cz) * dims[1] + cy) * dims[0] + cx;
        for (int s = 0; s < 14; ++s) {
          const int nx = cx + stencil[s][0], ny = cy + stencil[s][1], nz = cz + stencil[s][2];
          if (nx < 0 || ny < 0 || nz < 0 || nx >= dims[0] || ny >= dims[1] || nz >= dims[2]) continue;
          const std::size_t c2 = (static_cast<std::size_t>(nz) * dims[1] + ny) * dims[0] + nx;
          for (auto a = cell_start[c]; a < cell_start[c + 1]; ++a) {
            const std::size_t i = order[a];
            const auto b0 = s == 0 ? a + 1 : cell_start[c2];
            for (auto b = b0; b < cell_start[c2 + 1]; ++b) {
              const std::size_t j = order[b];
              if constexpr (decltype(exclude_same_body)::value)
                if (p.body[i] >= 0 && p.body[i] == p.body[j]) continue;
              const double cut = p.radius[i] + p.radius[j] + skin_;
              if ((p.x[i] - p.x[j]).squaredNorm() < cut * cut) {
                const bool i_first = p.id[i] < p.id[j];
                pi.push_back(static_cast<std::uint32_t>(i_first ? i : j));
                pj.push_back(static_cast<std::uint32_t>(i_first ? j : i));
              }
            }
          }
        }
      }
  };
  if (p.fields().has(Field::Body))
    collect(std::true_type{});
  else
    collect(std::false_type{});
  // Counting sort of the pairs into rows.
  row_start.assign(n + 1, 0);
  for (auto i : pi) ++row_start[i + 1];
  std::partial_sum(row_start.begin(), row_start.end(), row_start.begin());
  partner.resize(pi.size());
  {
    std::vector<std::uint32_t> fill(row_start.begin(), row_start.end() - 1);
    for (std::size_t k = 0; k < pi.size(); ++k) partner[fill[pi[k]]++] = pj[k];
  }
  // Keep each row ordered by partner index: better locality, deterministic order.
  for (std::size_t i = 0; i < n; ++i) std::sort(partner.begin() + row_start[i], partner.begin() + row_start[i + 1]);

  compute_pair_constants(p);
  history.assign(partner.size() * static_cast<std::size_t>(history_size_), 0.0);
  if (history_size_ > 0) carry_history(p);

  // Wall near lists.
  plane_near.assign(walls.planes.size(), {});
  cylinder_near.assign(walls.cylinders.size(), {});
  for (std::size_t w = 0; w < walls.planes.size(); ++w) {
    const auto& wall = walls.planes[w];
    for (std::size_t i = 0; i < n; ++i)
      if (contact::plane_distance(p.x[i], wall.point, wall.normal) < p.radius[i] + skin_)
        plane_near[w].push_back(static_cast<std::uint32_t>(i));
  }
  for (std::size_t w = 0; w < walls.cylinders.size(); ++w) {
    auto s = walls.cylinders[w].surface;  // widened by the skin
    s.t_min -= skin_;
    s.t_max += skin_;
    s.radius += s.inside ? -skin_ : skin_;
    contact::ContactGeometry g;
    for (std::size_t i = 0; i < n; ++i)
      if (contact::sphere_cylinder(p.x[i], p.radius[i], s, g)) cylinder_near[w].push_back(static_cast<std::uint32_t>(i));
  }

  x_build_.assign(p.x.begin(), p.x.begin() + static_cast<std::ptrdiff_t>(n));
  build_time_ = time;
  if (history_size_ > 0) old_row_id_.assign(p.id.begin(), p.id.begin() + static_cast<std::ptrdiff_t>(n));
  ++stats_.builds;
  stats_.pairs = partner.size();
}

void NeighborList::compute_pair_constants(const ParticleStore& p) {
  const std::size_t rows = row_start.empty() ? 0 : row_start.size() - 1;
  pair_constants.resize(partner.size());
  for (std::size_t i = 0; i < rows; ++i)
    for (auto k = row_start[i]; k < row_start[i + 1]; ++k) {
      const auto j = partner[k];
      const double rs = p.radius[i] + p.radius[j];
      // may_touch starts true: history carried over (or restored) may be non-zero.
      pair_constants[k] = {rs * rs, p.radius[i] * p.radius[j] / rs, p.mass[i] * p.mass[j] / (p.mass[i] + p.mass[j]),
                           true};
    }
}

void NeighborList::restore(const ParticleStore& p, BuildState b) {
  build_time_ = b.time;
  x_build_ = std::move(b.x);
  old_row_id_ = std::move(b.row_id);
  stats_.builds = b.builds;
  stats_.pairs = partner.size();
  compute_pair_constants(p);
}

void NeighborList::carry_history(const ParticleStore& p) {
  if (old_row_id_.empty()) return;
  const std::size_t n = p.n_owned();
  std::int64_t max_id = 0;
  for (auto id : old_row_id_) max_id = std::max(max_id, id);
  row_of_id_.assign(static_cast<std::size_t>(max_id) + 1, -1);
  for (std::size_t r = 0; r < old_row_id_.size(); ++r) row_of_id_[old_row_id_[r]] = static_cast<std::int32_t>(r);
  const std::size_t H = static_cast<std::size_t>(history_size_);
  for (std::size_t i = 0; i < n; ++i) {
    const auto id = p.id[i];
    if (id > max_id || row_of_id_[id] < 0) continue;
    const auto r = static_cast<std::size_t>(row_of_id_[id]);
    for (auto k = row_start[i]; k < row_start[i + 1]; ++k) {
      const auto pid = p.id[partner[k]];
      for (auto ko = old_row_start_[r]; ko < old_row_start_[r + 1]; ++ko)
        if (old_partner_id_[ko] == pid) {
          std::copy_n(old_history_.begin() + static_cast<std::ptrdiff_t>(ko * H), H,
                      history.begin() + static_cast<std::ptrdiff_t>(k * H));
          break;
        }
    }
  }
}

}  // namespace grains::sim
