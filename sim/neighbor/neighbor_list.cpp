#include "sim/neighbor/neighbor_list.hpp"

#include "sim/neighbor/size_classes.hpp"
#include "sim/state/free_heap.hpp"
#include "sim/state/huge_pages.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <type_traits>

namespace grains::sim {

namespace {

// From this many grains (images included) a build gives its freed
// temporaries back to the kernel before it allocates the contact history.
constexpr std::size_t kReleaseHeapFrom = std::size_t{1} << 17;

// The linked-cell grid over the particles' bounding box (within the given
// bounds), so a sparse scene in a large domain does not pay for empty
// cells; cells grow when there would be far more cells than particles.
struct CellGrid {
  Vec3 lo, inv;
  std::array<int, 3> dims{1, 1, 1};
  std::vector<std::uint32_t> cell_start;  // per cell, into order
  std::vector<std::size_t> order;         // particle indices in cell order

  CellGrid(const ParticleStore& p, std::size_t n, double skin, const Vec3& lo_bound, const Vec3& hi_bound) {
    double rmax = 0;
    for (std::size_t i = 0; i < n; ++i) rmax = std::max(rmax, p.radius[i]);
    lo = lo_bound;
    Vec3 hi = hi_bound;
    if (n > 0) {
      Vec3 blo = p.x[0], bhi = p.x[0];
      for (std::size_t i = 1; i < n; ++i) {
        blo = blo.cwiseMin(p.x[i]);
        bhi = bhi.cwiseMax(p.x[i]);
      }
      // Ghosts (periodic images, other ranks) may lie outside the bounds.
      lo = n > p.n_owned() ? blo : lo.cwiseMax(blo);
      hi = (n > p.n_owned() ? bhi : hi.cwiseMin(bhi)).cwiseMax(lo + Vec3::Constant(1e-12));
    }
    double cell = std::max(2 * rmax + skin, 1e-300);
    for (;;) {
      for (int d = 0; d < 3; ++d) dims[d] = std::max(1, static_cast<int>(std::floor((hi[d] - lo[d]) / cell)));
      if (static_cast<double>(dims[0]) * dims[1] * dims[2] <= 4.0 * static_cast<double>(n) + 64) break;
      cell *= 1.26;
    }
    inv = Vec3(dims[0] / (hi[0] - lo[0]), dims[1] / (hi[1] - lo[1]), dims[2] / (hi[2] - lo[2]));
    const std::size_t ncells = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
    std::vector<std::uint32_t> cell_id;
    assign_huge(cell_id, n, std::uint32_t{0});
    assign_huge(cell_start, ncells + 1, std::uint32_t{0});
    for (std::size_t i = 0; i < n; ++i) {
      const auto c = (static_cast<std::size_t>(cell_of(p.x[i], 2)) * dims[1] + cell_of(p.x[i], 1)) * dims[0] +
                     cell_of(p.x[i], 0);
      cell_id[i] = static_cast<std::uint32_t>(c);
      ++cell_start[c + 1];
    }
    std::partial_sum(cell_start.begin(), cell_start.end(), cell_start.begin());
    assign_huge(order, n, std::size_t{0});
    std::vector<std::uint32_t> fill(cell_start.begin(), cell_start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) order[fill[cell_id[i]]++] = i;
  }
  int cell_of(const Vec3& x, int d) const {
    const int c = static_cast<int>((x[d] - lo[d]) * inv[d]);
    return std::clamp(c, 0, dims[d] - 1);
  }
};

// The smallest skin of a pair among the first n particles: skin per grain f
// (0: the one skin), radii less `growth` (their value at the build).
double least_pair_skin(const ParticleStore& p, std::size_t n, double f, double skin, double growth) {
  if (f <= 0) return skin;
  double s = skin;
  for (std::size_t i = 0; i < n; ++i) s = std::min(s, 2 * f * (p.radius[i] - growth));
  return s;
}

// The cell grid of one size class: its members (particle indices) in cell
// order, cells at least `cell` wide over the members' bounding box.
struct ClassGrid {
  Vec3 lo, inv;
  std::array<int, 3> dims{1, 1, 1};
  std::vector<std::uint32_t> cell_start, order;

  ClassGrid() = default;
  ClassGrid(const ParticleStore& p, const std::vector<std::uint32_t>& members, double cell) {
    Vec3 hi = p.x[members[0]];
    lo = hi;
    for (auto i : members) lo = lo.cwiseMin(p.x[i]), hi = hi.cwiseMax(p.x[i]);
    hi = hi.cwiseMax(lo + Vec3::Constant(1e-12));
    const double m = static_cast<double>(members.size());
    for (;;) {
      for (int d = 0; d < 3; ++d) dims[d] = std::max(1, static_cast<int>(std::floor((hi[d] - lo[d]) / cell)));
      if (static_cast<double>(dims[0]) * dims[1] * dims[2] <= 4.0 * m + 64) break;
      cell *= 1.26;
    }
    inv = Vec3(dims[0] / (hi[0] - lo[0]), dims[1] / (hi[1] - lo[1]), dims[2] / (hi[2] - lo[2]));
    cell_start.assign(static_cast<std::size_t>(dims[0]) * dims[1] * dims[2] + 1, 0);
    std::vector<std::uint32_t> cell_id(members.size());
    for (std::size_t k = 0; k < members.size(); ++k) {
      cell_id[k] = static_cast<std::uint32_t>(index(cell_of(p.x[members[k]])));
      ++cell_start[cell_id[k] + 1];
    }
    std::partial_sum(cell_start.begin(), cell_start.end(), cell_start.begin());
    order.resize(members.size());
    std::vector<std::uint32_t> fill(cell_start.begin(), cell_start.end() - 1);
    for (std::size_t k = 0; k < members.size(); ++k) order[fill[cell_id[k]]++] = members[k];
  }
  std::array<int, 3> cell_of(const Vec3& x) const {
    std::array<int, 3> c;
    for (int d = 0; d < 3; ++d) c[d] = std::clamp(static_cast<int>((x[d] - lo[d]) * inv[d]), 0, dims[d] - 1);
    return c;
  }
  std::size_t index(const std::array<int, 3>& c) const {
    return (static_cast<std::size_t>(c[2]) * dims[1] + c[1]) * dims[0] + c[0];
  }
};

// The pair test of a build for one grain i against the grains order[b0 ..
// b1): (i, j) goes into the candidate pairs (smaller global id first) when
// it is within the cut-off r_i + r_j + skin(i, j). Left out: two ghosts, a
// grain and its own image (Ghosts), two balls of one clump (Bodies). No
// branch on the outcome (in a pour about one candidate in five is kept,
// unpredictably), i's fields held: each candidate is written at pi/pj[m]
// and m moves on only when it is kept. pi and pj must have room for b1 - b0
// more from m. Returns the new m.
template <bool Bodies, bool Ghosts, class Index, class Skin>
inline std::size_t consider_row(const ParticleStore& p, std::size_t n_own, std::size_t i, const Index* order,
                                std::size_t b0, std::size_t b1, Skin&& skin, std::uint32_t* pi, std::uint32_t* pj,
                                std::size_t m) {
  const Vec3 xi = p.x[i];
  const double ri = p.radius[i];
  const std::int64_t id_i = p.id[i];
  const auto ui = static_cast<std::uint32_t>(i);
  for (std::size_t b = b0; b < b1; ++b) {
    const std::size_t j = order[b];
    const double cut = ri + p.radius[j] + skin(i, j);
    const double dx = xi[0] - p.x[j][0], dy = xi[1] - p.x[j][1], dz = xi[2] - p.x[j][2];
    bool keep = dx * dx + dy * dy + dz * dz < cut * cut;  // (x_i - x_j).squaredNorm(), same order
    const std::int64_t id_j = p.id[j];
    if constexpr (Ghosts) keep = keep & !((i >= n_own) & (j >= n_own)) & (id_i != id_j);
    if constexpr (Bodies) keep = keep & !((p.body[i] >= 0) & (p.body[i] == p.body[j]));
    const auto uj = static_cast<std::uint32_t>(j);
    const bool i_first = id_i < id_j;
    pi[m] = i_first ? ui : uj;
    pj[m] = i_first ? uj : ui;
    m += keep;
  }
  return m;
}

// The half stencil of cell (cx, cy, cz), the own cell and the 13 forward
// neighbour cells (each pair of cells once: (+1, 0, 0); (-1..1, +1, 0);
// (-1..1, -1..1, +1)), as at most 5 runs of particles [lo, hi) of a grid's
// cell order: cells are in x-fastest order, so the cells cx - 1 .. cx + 1
// of one (y, z) row hold one contiguous run (in a dense bed a cell holds
// one or two grains: a loop per cell would be mostly loop). Run 0 is the
// own row from the own cell's first particle on (the caller starts it
// after the row's grain); empty runs are left out. Returns the number of
// runs.
inline int half_stencil_runs(const std::array<int, 3>& dims, const std::uint32_t* cell_start, int cx, int cy, int cz,
                             std::size_t lo[5], std::size_t hi[5]) {
  constexpr int kRows[4][2] = {{1, 0}, {-1, 1}, {0, 1}, {1, 1}};  // (dy, dz) of the rows past the own one
  const auto at = [&](int x, int y, int z) {
    return cell_start[(static_cast<std::size_t>(z) * dims[1] + y) * dims[0] + x];
  };
  const int x0 = cx > 0 ? cx - 1 : 0, x1 = cx + 1 < dims[0] ? cx + 1 : cx;
  int runs = 0;
  lo[runs] = at(cx, cy, cz), hi[runs] = at(x1 + 1, cy, cz), ++runs;  // cell x1 + 1: the next row's first, or the end
  for (const auto& d : kRows) {
    const int ny = cy + d[0], nz = cz + d[1];
    if (ny < 0 || nz < 0 || ny >= dims[1] || nz >= dims[2]) continue;
    lo[runs] = at(x0, ny, nz), hi[runs] = at(x1 + 1, ny, nz);
    if (lo[runs] < hi[runs]) ++runs;
  }
  return runs;
}

// Room in pi, pj for `more` candidates past the `kept` ones: they grow by a
// small step past what is kept (within their capacity, no new block), so
// the pages they touch are those push_back would touch.
inline void room_for(std::vector<std::uint32_t>& pi, std::vector<std::uint32_t>& pj, std::size_t kept,
                     std::size_t more) {
  if (kept + more > pi.size()) pi.resize(kept + more + 1024), pj.resize(pi.size());
}

// The candidate pairs of the grains of cell (cx, cy, cz) of a grid (dims,
// cell_start, order): each against the later grains of its own cell and
// those of the 13 forward cells. Returns the new count kept.
template <bool Bodies, bool Ghosts, class Index, class Skin>
std::size_t cell_pairs(const ParticleStore& p, std::size_t n_own, const std::array<int, 3>& dims,
                       const std::uint32_t* cell_start, const Index* order, int cx, int cy, int cz, Skin&& skin,
                       std::vector<std::uint32_t>& pi, std::vector<std::uint32_t>& pj, std::size_t kept) {
  const std::size_t c = (static_cast<std::size_t>(cz) * dims[1] + cy) * dims[0] + cx;
  if (cell_start[c] == cell_start[c + 1]) return kept;
  std::size_t run_lo[5], run_hi[5];
  const int runs = half_stencil_runs(dims, cell_start, cx, cy, cz, run_lo, run_hi);
  std::size_t room = 0;
  for (int u = 0; u < runs; ++u) room += run_hi[u] - run_lo[u];
  for (std::size_t a = cell_start[c]; a < cell_start[c + 1]; ++a) {
    run_lo[0] = a + 1;  // the own cell after a, then cell cx + 1
    room_for(pi, pj, kept, room);
    for (int u = 0; u < runs; ++u)
      kept = consider_row<Bodies, Ghosts>(p, n_own, order[a], order, run_lo[u], run_hi[u], skin, pi.data(), pj.data(),
                                          kept);
  }
  return kept;
}

}  // namespace

template <bool Bodies, bool Ghosts>
void NeighborList::collect_by_size_class(const ParticleStore& p, double rmin, double rmax,
                                         std::vector<std::uint32_t>& pi, std::vector<std::uint32_t>& pj) const {
  const std::size_t n = p.size(), n_own = p.n_owned();
  const SizeClasses size_class(rmin, rmax);
  const int classes = size_class.count;
  std::vector<std::vector<std::uint32_t>> members(static_cast<std::size_t>(classes));
  std::vector<double> class_rmax(static_cast<std::size_t>(classes), 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const int k = size_class.of(p.radius[i]);
    members[static_cast<std::size_t>(k)].push_back(static_cast<std::uint32_t>(i));
    class_rmax[static_cast<std::size_t>(k)] = std::max(class_rmax[static_cast<std::size_t>(k)], p.radius[i]);
  }
  // The widest cut-off of a pair within class k, and of one with a smaller
  // class: 2 R_k + its skin + reach, R_k the class's largest radius.
  std::vector<ClassGrid> grids;
  grids.reserve(static_cast<std::size_t>(classes));
  for (int k = 0; k < classes; ++k) {
    const double R = class_rmax[static_cast<std::size_t>(k)];
    const double s = skin_fraction_ > 0 ? std::min(2 * skin_fraction_ * R, skin_) : skin_;
    if (members[static_cast<std::size_t>(k)].empty())
      grids.emplace_back();  // no grains of this size
    else
      grids.emplace_back(p, members[static_cast<std::size_t>(k)], std::max(2 * R + s + reach_, 1e-300));
  }
  const auto skin = [&](std::size_t i, std::size_t j) { return pair_skin(p, i, j) + reach_; };
  std::size_t kept = pi.size();
  for (int a = 0; a < classes; ++a) {
    if (members[static_cast<std::size_t>(a)].empty()) continue;
    const ClassGrid& g = grids[static_cast<std::size_t>(a)];
    // Within the class: the half stencil.
    for (int cz = 0; cz < g.dims[2]; ++cz)
      for (int cy = 0; cy < g.dims[1]; ++cy)
        for (int cx = 0; cx < g.dims[0]; ++cx)
          kept = cell_pairs<Bodies, Ghosts>(p, n_own, g.dims, g.cell_start.data(), g.order.data(), cx, cy, cz, skin, pi,
                                            pj, kept);
    // With every larger class: each grain of this class (in its cell order)
    // against the cells of the larger class's grid that its reach to that
    // class (its radius, the class's largest, their skin) touches; the cells
    // being at least that wide, at most 27 (9 runs in x), and about 9 for a
    // small grain.
    for (int b = a + 1; b < classes; ++b) {
      if (members[static_cast<std::size_t>(b)].empty()) continue;
      const ClassGrid& G = grids[static_cast<std::size_t>(b)];
      const double R = class_rmax[static_cast<std::size_t>(b)];
      for (auto i : g.order) {
        const double ri = p.radius[i];
        const double s = skin_fraction_ > 0 ? std::min(skin_fraction_ * (ri + R), skin_) : skin_;
        // (padded by 1e-12 of itself: a partner at the reach is never missed by rounding)
        const double reach = (ri + R + s + reach_) * (1 + 1e-12);
        const auto lo = G.cell_of(p.x[i] - Vec3::Constant(reach)), hi = G.cell_of(p.x[i] + Vec3::Constant(reach));
        for (int dz = lo[2]; dz <= hi[2]; ++dz)
          for (int dy = lo[1]; dy <= hi[1]; ++dy) {
            const std::size_t w0 = G.cell_start[G.index({lo[0], dy, dz})];
            const std::size_t w1 = G.cell_start[G.index({hi[0], dy, dz}) + 1];
            room_for(pi, pj, kept, w1 - w0);
            kept = consider_row<Bodies, Ghosts>(p, n_own, i, G.order.data(), w0, w1, skin, pi.data(), pj.data(), kept);
          }
      }
    }
  }
  pi.resize(kept);
  pj.resize(kept);
}

std::vector<std::pair<const char*, std::size_t>> NeighborList::memory_parts() const {
  auto bytes = [](const auto& v) { return v.size() * sizeof(typename std::decay_t<decltype(v)>::value_type); };
  std::size_t near = wall_near.size() * sizeof(wall_near[0]) + wall_items.size() * sizeof(wall_items[0]);
  for (const auto& w : wall_near) near += bytes(w);
  for (const auto& w : wall_items) near += bytes(w.start) + bytes(w.items);
  return {{"neighbor_rows", bytes(row_start)},
          {"neighbor_partners", bytes(partner)},
          {"contact_history", bytes(history)},
          {"neighbor_may_touch", bytes(may_touch)},
          {"neighbor_build_state", bytes(x_build_) + bytes(build_id_)},
          {"neighbor_ordered_sums", bytes(gather_start) + bytes(gather_entry)},
          {"wall_near_lists", near},
          {"imported_history", bytes(imported_ids_) + bytes(imported_history_)}};
}

bool NeighborList::needs_rebuild(const ParticleStore& p, const Walls& walls, double time) const {
  const std::size_t n = p.n_owned();
  // Never built (a scene may start empty and fill by insertion): build.
  if (x_build_.size() != n || row_start.empty()) return true;
  if (skin_fraction_ > 0) {
    const double drift = image_speed_ * (time - build_time_) + image_travel_;
    // Each grain i within its own share of the skin: 2 (d_i + growth) / s_i
    // + drift / s_min <= 1 keeps d_i + d_j + drift below the skin of the pair
    // (at least (s_i + s_j) / 2 and at least s_min). s_i from the radius at
    // the build (at least the current one less the growth since).
    const double c = 0.5 * (1 - drift / smallest_skin_);
    double m2 = 0;
    bool any = c <= 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double d2 = (p.x[i] - x_build_[i]).squaredNorm();
      const double t = std::min(2 * skin_fraction_ * (p.radius[i] - growth_), skin_) * c - growth_;
      m2 = std::max(m2, d2);
      any = any || t < 0 || d2 > t * t;
    }
    return any || std::sqrt(m2) + growth_ + walls.max_displacement(time - build_time_) > skin_;
  }
  double m2 = 0;
  for (std::size_t i = 0; i < n; ++i) m2 = std::max(m2, (p.x[i] - x_build_[i]).squaredNorm());
  const double m = std::sqrt(m2) + growth_;
  return 2 * m + image_speed_ * (time - build_time_) + image_travel_ > skin_ || m + walls.max_displacement(time - build_time_) > skin_;
}

void NeighborList::sort_by_cell(ParticleStore& p, const Vec3& lo, const Vec3& hi) const {
  const CellGrid grid(p, p.n_owned(), skin_ + reach_, lo, hi);
  p.permute(grid.order);
}

void NeighborList::build(ParticleStore& p, const Walls& walls, const Vec3& lo_bound, const Vec3& hi_bound, double time,
                         bool sort) {
  const std::size_t n_own = p.n_owned();
  const std::size_t n = p.size();
  // The previous rows, kept only until their history is carried over by
  // global ids. Between builds a grain holds one list, not two (issue 26:
  // memory per grain); what that costs is a fresh mapping per build for the
  // new rows and history, a page fault per 4 KiB, about 0.1 % of the steps
  // between builds in a dense bed (bench/RESULTS.md). The candidate pairs
  // and the cell grid go before the history is allocated, for the same
  // reason: the peak of a build is the old list and the new one.
  std::vector<std::uint32_t> old_row_start, old_partner;
  std::vector<double> old_history;
  if (history_size_ > 0) {
    old_row_start.swap(row_start);
    old_partner.swap(partner);
    old_history.swap(history);
  }
  CellGrid grid(p, n, skin_ + reach_, lo_bound, hi_bound);
  if (sort && p.n_ghost() == 0) {
    p.permute(grid.order);  // particles now in cell order: slot k holds particle k
    std::iota(grid.order.begin(), grid.order.end(), std::size_t{0});
  }
  const auto& dims = grid.dims;
  const auto& cell_start = grid.cell_start;
  const auto& order = grid.order;

  // Candidate pairs from the 13 forward neighbour cells and the own cell.
  std::vector<std::uint32_t> pi, pj;
  reserve_huge(pi, 8 * n);
  reserve_huge(pj, 8 * n);
  // Balls of the same clump never interact: in scenes with clumps (the
  // `body` field exists) their pairs are left out here, by a separate
  // instantiation of the loop, so sphere scenes pay nothing for the check.
  // Likewise ghost-ghost pairs are left out only when ghosts exist.
  const auto skin = [&](std::size_t i, std::size_t j) { return pair_skin(p, i, j) + reach_; };
  auto collect = [&](auto exclude_same_body, auto with_ghosts) {
    std::size_t kept = pi.size();
    for (int cz = 0; cz < dims[2]; ++cz)
      for (int cy = 0; cy < dims[1]; ++cy)
        for (int cx = 0; cx < dims[0]; ++cx)
          kept = cell_pairs<decltype(exclude_same_body)::value, decltype(with_ghosts)::value>(
              p, n_own, dims, cell_start.data(), order.data(), cx, cy, cz, skin, pi, pj, kept);
    pi.resize(kept);
    pj.resize(kept);
  };
  const bool bodies = p.fields().has(Field::Body), ghosts = n > n_own;
  double rmin = n > 0 ? p.radius[0] : 0, rmax = rmin;
  for (std::size_t i = 1; i < n; ++i) rmin = std::min(rmin, p.radius[i]), rmax = std::max(rmax, p.radius[i]);
  // The same pairs either way (each row is sorted below), so the choice
  // changes only the time of the build.
  if (SizeClasses(rmin, rmax).count > 1) {
    if (bodies && ghosts)
      collect_by_size_class<true, true>(p, rmin, rmax, pi, pj);
    else if (bodies)
      collect_by_size_class<true, false>(p, rmin, rmax, pi, pj);
    else if (ghosts)
      collect_by_size_class<false, true>(p, rmin, rmax, pi, pj);
    else
      collect_by_size_class<false, false>(p, rmin, rmax, pi, pj);
  } else if (bodies && ghosts)
    collect(std::true_type{}, std::true_type{});
  else if (bodies)
    collect(std::true_type{}, std::false_type{});
  else if (ghosts)
    collect(std::false_type{}, std::true_type{});
  else
    collect(std::false_type{}, std::false_type{});
  smallest_skin_ = least_pair_skin(p, n, skin_fraction_, skin_, 0.0);
  if (frozen_) {  // two frozen grains never interact
    std::size_t kept = 0;
    for (std::size_t k = 0; k < pi.size(); ++k)
      if (p.inv_mass[pi[k]] != 0 || p.inv_mass[pj[k]] != 0) pi[kept] = pi[k], pj[kept] = pj[k], ++kept;
    pi.resize(kept);
    pj.resize(kept);
  }
  // Counting sort of the pairs into rows, in place: row_start[i + 1] first
  // holds where row i starts and is moved along it as its pairs are placed,
  // ending where row i ends (= where row i + 1 starts).
  assign_huge(row_start, n + 1, std::uint32_t{0});
  for (auto i : pi)
    if (i + 2 <= n) ++row_start[i + 2];
  std::partial_sum(row_start.begin(), row_start.end(), row_start.begin());
  assign_huge(partner, pi.size(), std::uint32_t{0});
  for (std::size_t k = 0; k < pi.size(); ++k) partner[row_start[pi[k] + 1]++] = pj[k];
  // Keep each row ordered by partner index: better locality, deterministic order.
  for (std::size_t i = 0; i < n; ++i) std::sort(partner.begin() + row_start[i], partner.begin() + row_start[i + 1]);
  std::vector<std::uint32_t>().swap(pi);
  std::vector<std::uint32_t>().swap(pj);
  std::vector<std::size_t>().swap(grid.order);
  std::vector<std::uint32_t>().swap(grid.cell_start);
  // In large scenes, what those left in the heap goes back before the
  // history is allocated (free_heap.hpp: the build's peak). Small scenes
  // rebuild often and would fault it in again each time.
  if (n >= kReleaseHeapFrom) release_free_heap();

  assign_huge(may_touch, partner.size(), std::uint8_t{1});
  assign_huge(history, partner.size() * static_cast<std::size_t>(history_size_), 0.0);
  if (history_size_ > 0) {
    carry_history(p, old_row_start, old_partner, old_history);
    std::vector<double>().swap(old_history);
    std::vector<std::uint32_t>().swap(old_partner);
    std::vector<std::uint32_t>().swap(old_row_start);
  }
  if (with_gather_) build_gather(p);

  // Wall near lists (owned particles only: walls act on what a rank integrates).
  const bool shapes = p.fields().has(Field::SemiAxes);
  wall_near.assign(walls.count(), {});
  wall_items.assign(walls.count(), {});
  walls.for_each([&](const auto& wall, std::size_t w) {
    wall.near_list(p, n_own, skin_ + reach_, shapes, wall_near[w], wall_items[w]);
    if (!std::decay_t<decltype(wall)>::near_items && !wall_items[w].items.empty())  // the stage would not read them
      throw std::logic_error("wall " + wall.name + ": its near list has items, but its kind does not say near_items = true");
    if (frozen_) drop_frozen(p, wall_near[w], wall_items[w]);
  });

  x_build_.assign(p.x.begin(), p.x.begin() + static_cast<std::ptrdiff_t>(n_own));
  build_time_ = time;
  image_travel_ = 0;
  build_id_.assign(p.id.begin(), p.id.begin() + static_cast<std::ptrdiff_t>(n));
  growth_ = 0;
  ++stats_.builds;
  stats_.pairs = partner.size();
}

void NeighborList::drop_frozen(const ParticleStore& p, std::vector<std::uint32_t>& near, NearItems& items) {
  const bool with_items = items.start.size() == near.size() + 1 && near.size() > 0;
  std::size_t kept = 0, item = 0;
  for (std::size_t m = 0; m < near.size(); ++m) {
    if (p.inv_mass[near[m]] == 0) continue;
    if (with_items) {
      for (auto k = items.start[m]; k < items.start[m + 1]; ++k) items.items[item++] = items.items[k];
      items.start[kept + 1] = static_cast<std::uint32_t>(item);
    }
    near[kept++] = near[m];
  }
  near.resize(kept);
  if (with_items) items.start.resize(kept + 1), items.items.resize(item);
}

void NeighborList::restore(const ParticleStore& p, BuildState b) {
  build_time_ = b.time;
  x_build_ = std::move(b.x);
  build_id_ = std::move(b.row_id);
  stats_.builds = b.builds;
  growth_ = b.growth;
  image_travel_ = 0;
  stats_.pairs = partner.size();
  smallest_skin_ = least_pair_skin(p, p.size(), skin_fraction_, skin_, growth_);
  may_touch.assign(partner.size(), 1);
  if (with_gather_) build_gather(p);
}

void NeighborList::renumber_ghosts(std::size_t n_owned, const std::vector<std::uint32_t>& to, std::size_t count) {
  const std::size_t rows = row_start.size() - 1;
  if (rows != n_owned + to.size() || build_id_.size() != rows)
    throw std::logic_error("NeighborList::renumber_ghosts: not the particles of the last build");
  std::size_t m = n_owned;
  for (std::size_t r = n_owned; r < rows; ++r) {
    if (to[r - n_owned] == kGone) {
      if (row_start[r] != row_start[r + 1]) throw std::logic_error("NeighborList::renumber_ghosts: a listed ghost dropped");
      continue;
    }
    row_start[m + 1] = row_start[r + 1];
    build_id_[m] = build_id_[r];
    ++m;
  }
  if (m != count) throw std::logic_error("NeighborList::renumber_ghosts: count does not match");
  row_start.resize(count + 1);
  build_id_.resize(count);
  for (auto& j : partner)
    if (j >= n_owned) {
      j = to[j - n_owned];
      if (j == kGone) throw std::logic_error("NeighborList::renumber_ghosts: a listed partner dropped");
    }
}

void NeighborList::import_history(std::int64_t a, std::int64_t b, const double* h) {
  imported_ids_.push_back(a);
  imported_ids_.push_back(b);
  imported_history_.insert(imported_history_.end(), h, h + history_size_);
}

void NeighborList::carry_history(const ParticleStore& p, const std::vector<std::uint32_t>& old_row_start,
                                 const std::vector<std::uint32_t>& old_partner,
                                 const std::vector<double>& old_history) {
  // Each new entry (ids a < b) takes the history of the first entry with
  // the same ids and a non-zero history in the previous build (its rows in
  // order, each row's entries in order), else of the first history (a, b)
  // that came with a migrating particle. The old list is searched in place,
  // through its rows sorted by id: no copy of its contacts is made, which
  // at a build that holds the old list and the new one would be 48 bytes
  // per touching contact more (issue 26: memory per grain).
  const std::size_t H = static_cast<std::size_t>(history_size_);
  const bool have_old = !build_id_.empty() && !old_row_start.empty();
  const std::size_t imports = imported_ids_.size() / 2;
  if (have_old || imports > 0) {
    // The old rows by id (ids are dense): rows_of[start[a] .. start[a+1]).
    std::vector<std::uint32_t> start, rows_of;
    // (Rows appended after the build, for inserted grains, are empty and
    // have no id at the build: left out.)
    const std::size_t old_rows = have_old ? std::min(old_row_start.size() - 1, build_id_.size()) : 0;
    if (have_old) {
      std::int64_t max_a = 0;
      for (std::size_t r = 0; r < old_rows; ++r) max_a = std::max(max_a, build_id_[r]);
      start.assign(static_cast<std::size_t>(max_a) + 2, 0);
      for (std::size_t r = 0; r < old_rows; ++r) ++start[static_cast<std::size_t>(build_id_[r]) + 1];
      std::partial_sum(start.begin(), start.end(), start.begin());
      rows_of.resize(old_rows);
      std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
      for (std::size_t r = 0; r < old_rows; ++r)
        rows_of[fill[static_cast<std::size_t>(build_id_[r])]++] = static_cast<std::uint32_t>(r);
    }
    // The imported histories by (a, b), in the order they came within one pair.
    std::vector<std::uint32_t> imp(imports);
    std::iota(imp.begin(), imp.end(), std::uint32_t{0});
    const auto pair_of = [&](std::uint32_t m) {
      return std::make_pair(imported_ids_[2 * std::size_t{m}], imported_ids_[2 * std::size_t{m} + 1]);
    };
    std::stable_sort(imp.begin(), imp.end(), [&](std::uint32_t x, std::uint32_t y) { return pair_of(x) < pair_of(y); });
    const auto nonzero = [H](const double* h) {
      bool any = false;
      for (std::size_t c = 0; c < H; ++c) any = any || h[c] != 0.0;
      return any;
    };
    const std::size_t rows = row_start.size() - 1;
    for (std::size_t i = 0; i < rows; ++i) {
      const std::int64_t a = p.id[i];
      const auto ua = static_cast<std::size_t>(a);
      const bool old_a = have_old && ua + 1 < start.size() && start[ua] < start[ua + 1];
      if (!old_a && imports == 0) continue;
      for (auto k = row_start[i]; k < row_start[i + 1]; ++k) {
        const std::int64_t b = p.id[partner[k]];
        const double* src = nullptr;
        if (old_a)
          for (auto q = start[ua]; q < start[ua + 1] && !src; ++q) {
            const auto r = rows_of[q];
            for (auto e = old_row_start[r]; e < old_row_start[r + 1]; ++e)
              if (build_id_[old_partner[e]] == b && nonzero(old_history.data() + e * H)) {
                src = old_history.data() + e * H;
                break;
              }
          }
        if (!src && imports > 0) {
          const auto it = std::lower_bound(imp.begin(), imp.end(), std::make_pair(a, b),
                                           [&](std::uint32_t m, const std::pair<std::int64_t, std::int64_t>& key) {
                                             return pair_of(m) < key;
                                           });
          if (it != imp.end() && pair_of(*it) == std::make_pair(a, b)) src = imported_history_.data() + *it * H;
        }
        if (src) std::copy_n(src, H, history.begin() + static_cast<std::ptrdiff_t>(k * H));
      }
    }
  }
  imported_ids_.clear();
  imported_history_.clear();
}

void NeighborList::build_gather(const ParticleStore& p) {
  const std::size_t n = p.n_owned();
  const std::size_t rows = row_start.empty() ? 0 : row_start.size() - 1;
  assign_huge(gather_start, n + 1, std::uint32_t{0});
  for (std::size_t i = 0; i < rows; ++i)
    for (auto k = row_start[i]; k < row_start[i + 1]; ++k) {
      if (i < n) ++gather_start[i + 1];
      if (partner[k] < n) ++gather_start[partner[k] + 1];
    }
  std::partial_sum(gather_start.begin(), gather_start.end(), gather_start.begin());
  assign_huge(gather_entry, std::size_t{gather_start.back()}, std::uint32_t{0});
  // Each owned grain's entries in the order of the other grain's global id,
  // without a sort per grain: the other grains are visited in id order and
  // each hands its entries to the grain on their other side, whose list so
  // fills in order. A grain's entries as a partner come from the list's
  // transpose (the rows of the entries that name it).
  std::vector<std::uint32_t> as_partner_start(rows + 1, 0), as_partner(partner.size()), as_partner_row(partner.size());
  for (auto j : partner) ++as_partner_start[j + 1];
  std::partial_sum(as_partner_start.begin(), as_partner_start.end(), as_partner_start.begin());
  {
    std::vector<std::uint32_t> fill(as_partner_start.begin(), as_partner_start.end() - 1);
    for (std::size_t i = 0; i < rows; ++i)
      for (auto k = row_start[i]; k < row_start[i + 1]; ++k) {
        const auto q = fill[partner[k]]++;
        as_partner[q] = k;
        as_partner_row[q] = static_cast<std::uint32_t>(i);
      }
  }
  // The local grains by global id (a grain and its periodic image share
  // one: by local index), by counting when the ids are dense enough.
  std::vector<std::uint32_t> by_id(rows);
  std::iota(by_id.begin(), by_id.end(), std::uint32_t{0});
  if (rows > 0) {
    const auto [lo, hi] = std::minmax_element(p.id.begin(), p.id.begin() + static_cast<std::ptrdiff_t>(rows));
    const auto span = static_cast<std::uint64_t>(*hi - *lo);
    if (span < 4 * static_cast<std::uint64_t>(rows) + 1024) {
      std::vector<std::uint32_t> start(static_cast<std::size_t>(span) + 2, 0);
      for (std::size_t i = 0; i < rows; ++i) ++start[static_cast<std::size_t>(p.id[i] - *lo) + 1];
      std::partial_sum(start.begin(), start.end(), start.begin());
      for (std::size_t i = 0; i < rows; ++i)
        by_id[start[static_cast<std::size_t>(p.id[i] - *lo)]++] = static_cast<std::uint32_t>(i);
    } else {
      std::stable_sort(by_id.begin(), by_id.end(), [&](std::uint32_t x, std::uint32_t y) { return p.id[x] < p.id[y]; });
    }
  }
  // Each grain's entries then by the other's id; two others of one id (a
  // grain and an image) by code, as a sort by (id, code) orders them: the
  // grains that meet such a pair are sorted afterwards (rare).
  std::vector<std::uint32_t> fill(gather_start.begin(), gather_start.end() - 1);
  std::vector<std::int64_t> last_id(n, -1);
  std::vector<std::uint32_t> tied;
  const auto append = [&](std::size_t i, std::uint32_t code, std::int64_t other_id) {
    if (last_id[i] == other_id && (tied.empty() || tied.back() != i)) tied.push_back(static_cast<std::uint32_t>(i));
    last_id[i] = other_id;
    gather_entry[fill[i]++] = code;
  };
  for (const auto o : by_id) {
    const std::int64_t id_o = p.id[o];
    for (auto k = row_start[o]; k < row_start[o + 1]; ++k)  // o the row: its partner's side 1
      if (partner[k] < n) append(partner[k], 2 * k + 1, id_o);
    for (auto q = as_partner_start[o]; q < as_partner_start[o + 1]; ++q)  // o the partner: the row's side 0
      if (as_partner_row[q] < n) append(as_partner_row[q], 2 * as_partner[q], id_o);
  }
  const auto row_of = [&](std::uint32_t k) {
    return static_cast<std::size_t>(std::upper_bound(row_start.begin(), row_start.end(), k) - row_start.begin()) - 1;
  };
  std::vector<std::pair<std::int64_t, std::uint32_t>> tmp;
  for (const auto i : tied) {
    tmp.clear();
    for (auto g = gather_start[i]; g < gather_start[i + 1]; ++g) {
      const std::uint32_t code = gather_entry[g], k = code >> 1;
      tmp.emplace_back(p.id[(code & 1u) ? row_of(k) : partner[k]], code);
    }
    std::sort(tmp.begin(), tmp.end());
    for (std::size_t m = 0; m < tmp.size(); ++m) gather_entry[gather_start[i] + m] = tmp[m].second;
  }
}

}  // namespace grains::sim
