#include "sim/scene/placement.hpp"

#include "sim/neighbor/size_classes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <unordered_map>

namespace grains::sim {

double SizeDistribution::smallest() const {
  switch (kind) {
    case Kind::Fixed: return radius;
    case Kind::Discrete: return *std::min_element(values.begin(), values.end());
    default: return min;
  }
}
double SizeDistribution::largest() const {
  switch (kind) {
    case Kind::Fixed: return radius;
    case Kind::Discrete: return *std::max_element(values.begin(), values.end());
    default: return max;
  }
}

std::vector<double> sample_radii(const SizeDistribution& d, std::int64_t count, std::mt19937_64& rng) {
  std::vector<double> r(static_cast<std::size_t>(count));
  using K = SizeDistribution::Kind;
  switch (d.kind) {
    case K::Fixed: std::fill(r.begin(), r.end(), d.radius); break;
    case K::Uniform: {
      std::uniform_real_distribution<double> u(d.min, d.max);
      for (auto& x : r) x = u(rng);
      break;
    }
    case K::Normal:
    case K::LogNormal: {
      // Truncated by rejection to [min, max]; for the log-normal, mean and
      // stddev are those of the radius, converted to the underlying normal.
      double mu = d.mean, sigma = d.stddev;
      if (d.kind == K::LogNormal) {
        const double s2 = std::log(1 + (d.stddev * d.stddev) / (d.mean * d.mean));
        sigma = std::sqrt(s2);
        mu = std::log(d.mean) - 0.5 * s2;
      }
      std::normal_distribution<double> nd(mu, sigma);
      for (auto& x : r) {
        for (int t = 0;; ++t) {
          double v = nd(rng);
          if (d.kind == K::LogNormal) v = std::exp(v);
          if ((v >= d.min && v <= d.max) || t > 1000) {
            x = std::clamp(v, d.min, d.max);
            break;
          }
        }
      }
      break;
    }
    case K::Discrete: {
      std::discrete_distribution<std::size_t> dd(d.weights.begin(), d.weights.end());
      for (auto& x : r) x = d.values[dd(rng)];
      break;
    }
  }
  return r;
}

namespace {

// Grid of placed spheres for overlap queries. In a periodic domain
// distances are taken to the nearest image and queries near a periodic face
// look through it. Two ways to fill it: insert() one grain at a time into a
// hash of cells (random filling, which queries as it places), or assign()
// every grain at once into one array sorted by cell (the overlap check: no
// allocation per cell, which for 10^6 grains was 2 million small blocks
// and 50 MB of heap left fragmented under the run's arrays, issue 26).
class PlacementGrid {
 public:
  PlacementGrid(double cell, const Domain& d) : cell_(cell), dom_(d) {}
  void insert(const Vec3& x, std::size_t idx) { cells_[key(cell_of(x))].push_back(idx); }
  /// The grains `members` (ascending) in cell order, each cell's in the
  /// order given.
  void assign(const std::vector<PlacedParticle>& p, const std::vector<std::uint32_t>& members) {
    std::vector<std::pair<long long, std::uint32_t>> e;
    e.reserve(members.size());
    for (auto i : members) e.emplace_back(key(cell_of(p[i].x)), i);
    std::sort(e.begin(), e.end());
    sorted_key_.resize(e.size());
    sorted_idx_.resize(e.size());
    for (std::size_t k = 0; k < e.size(); ++k) sorted_key_[k] = e[k].first, sorted_idx_[k] = e[k].second;
  }
  /// b - a, to the nearest periodic image (at set-up: time 0).
  Vec3 delta(const Vec3& a, const Vec3& b) const { return dom_.nearest_image(b - a, 0.0); }
  /// Calls overlaps(j) for the spheres within `reach` of x (and some
  /// beyond), until one returns true. reach: at most one cell by default.
  template <class Fn>
  bool any_near(const Vec3& x, Fn&& overlaps, double reach = 0) const {
    reach = reach > 0 ? reach : cell_;
    const int m = std::max(1, static_cast<int>(std::ceil(reach / cell_)));
    // x and its images across the periodic faces it is near.
    std::array<std::array<double, 2>, 3> shifts{};
    std::array<int, 3> n{1, 1, 1};
    for (int k = 0; k < 3; ++k) {
      shifts[k][0] = 0;
      if (!dom_.periodic[k]) continue;
      const double L = dom_.hi[k] - dom_.lo[k];
      if (x[k] - dom_.lo[k] < reach) shifts[k][n[k]++] = L;
      else if (dom_.hi[k] - x[k] < reach) shifts[k][n[k]++] = -L;
    }
    for (int a = 0; a < n[0]; ++a)
      for (int b = 0; b < n[1]; ++b)
        for (int c = 0; c < n[2]; ++c)
          if (near_cells(Vec3(x[0] + shifts[0][a], x[1] + shifts[1][b], x[2] + shifts[2][c]), overlaps, m)) return true;
    return false;
  }

 private:
  template <class Fn>
  bool near_cells(const Vec3& x, Fn& overlaps, int m) const {
    const auto c = cell_of(x);
    for (int dz = -m; dz <= m; ++dz)
      for (int dy = -m; dy <= m; ++dy)
        for (int dx = -m; dx <= m; ++dx) {
          const long long k = key({c[0] + dx, c[1] + dy, c[2] + dz});
          if (!sorted_key_.empty()) {
            auto a = std::lower_bound(sorted_key_.begin(), sorted_key_.end(), k) - sorted_key_.begin();
            for (auto b = static_cast<std::size_t>(a); b < sorted_key_.size() && sorted_key_[b] == k; ++b)
              if (overlaps(sorted_idx_[b])) return true;
            continue;
          }
          auto it = cells_.find(k);
          if (it == cells_.end()) continue;
          for (auto j : it->second)
            if (overlaps(j)) return true;
        }
    return false;
  }
  std::array<long, 3> cell_of(const Vec3& x) const {
    return {static_cast<long>(std::floor(x[0] / cell_)), static_cast<long>(std::floor(x[1] / cell_)),
            static_cast<long>(std::floor(x[2] / cell_))};
  }
  static long long key(const std::array<long, 3>& c) {
    return ((static_cast<long long>(c[0]) & 0x1FFFFF) << 42) | ((static_cast<long long>(c[1]) & 0x1FFFFF) << 21) |
           (static_cast<long long>(c[2]) & 0x1FFFFF);
  }
  double cell_;
  Domain dom_;
  std::unordered_map<long long, std::vector<std::size_t>> cells_;
  std::vector<long long> sorted_key_;
  std::vector<std::uint32_t> sorted_idx_;
};

std::string fmt(double v) {
  std::ostringstream o;
  o.precision(6);
  o << v;
  return o.str();
}

}  // namespace

std::vector<PlacedParticle> place_particles(const SceneConfig& c) {
  double rmax = 0;
  for (const auto& s : c.sets) rmax = std::max(rmax, s.size.largest() * s.shape.bounding_factor);
  PlacementGrid grid(2 * rmax, c.domain);
  // Only random filling queries the grid as it places; a scene without it
  // (positions files, lattices) fills none (check_overlaps checks them).
  const bool fills = std::any_of(c.sets.begin(), c.sets.end(),
                                 [](const auto& s) { return s.placement.kind == Placement::Kind::RandomFill; });
  std::vector<PlacedParticle> out;
  for (std::size_t si = 0; si < c.sets.size(); ++si) {
    const auto& set = c.sets[si];
    std::mt19937_64 rng(set.placement.seed);
    const auto& reg = set.placement.region;
    auto free_at = [&](const Vec3& x, double r) {
      return !grid.any_near(x, [&](std::size_t j) {
        return grid.delta(x, out[j].x).squaredNorm() < (out[j].r + r) * (out[j].r + r);
      });
    };
    auto put = [&](const Vec3& x, double r, std::size_t k) {
      if (fills) grid.insert(x, out.size());
      out.push_back({x, r, static_cast<int>(si), k});
    };
    switch (set.placement.kind) {
      case Placement::Kind::RandomFill: {
        auto radii = sample_radii(set.size, set.count, rng);
        for (auto& r : radii) r *= set.shape.bounding_factor;
        std::sort(radii.begin(), radii.end(), std::greater<>());  // largest first
        std::uniform_real_distribution<double> u(0.0, 1.0);
        const std::int64_t budget = 2000;  // consecutive failed attempts before giving up
        for (std::size_t k = 0; k < radii.size(); ++k) {
          const double r = radii[k];
          const Vec3 lo = reg.lo + Vec3::Constant(r), hi = reg.hi - Vec3::Constant(r);
          if ((hi.array() < lo.array()).any())
            throw SetupError(set.where + ": particle set '" + set.name + "': a particle of radius " + fmt(r) +
                             " m does not fit in the fill region; make the region larger than the diameter");
          bool placed = false;
          for (std::int64_t t = 0; t < budget && !placed; ++t) {
            const Vec3 x(lo[0] + u(rng) * (hi[0] - lo[0]), lo[1] + u(rng) * (hi[1] - lo[1]),
                         lo[2] + u(rng) * (hi[2] - lo[2]));
            if (free_at(x, r)) {
              put(x, r, k);
              placed = true;
            }
          }
          if (!placed) {
            const Vec3 e = reg.hi - reg.lo;
            double vol = 0;
            for (std::size_t q = 0; q < k; ++q) vol += 4.0 / 3.0 * M_PI * radii[q] * radii[q] * radii[q];
            throw SetupError(set.where + ": particle set '" + set.name + "': placed only " + std::to_string(k) +
                             " of " + std::to_string(set.count) +
                             " particles in the fill region (solid fraction reached " +
                             fmt(vol / (e[0] * e[1] * e[2])) +
                             "; random filling stalls near 0.3). Enlarge placement.region or lower count");
          }
        }
        break;
      }
      case Placement::Kind::Lattice: {
        const double rl = set.size.largest() * set.shape.bounding_factor;
        const double a = set.placement.spacing > 0 ? set.placement.spacing : 2 * rl * (1 + 1e-6);
        std::array<long, 3> n{};
        for (int d = 0; d < 3; ++d) n[d] = static_cast<long>(std::floor((reg.hi[d] - reg.lo[d] - 2 * rl) / a)) + 1;
        if (n[0] <= 0 || n[1] <= 0 || n[2] <= 0)
          throw SetupError(set.where + ": particle set '" + set.name + "': the lattice region is smaller than one particle");
        const std::int64_t cap = static_cast<std::int64_t>(n[0]) * n[1] * n[2];
        const std::int64_t want = set.count > 0 ? set.count : cap;
        if (want > cap)
          throw SetupError(set.where + ": particle set '" + set.name + "': the lattice region holds " +
                           std::to_string(cap) + " sites at spacing " + fmt(a) + " m but count is " +
                           std::to_string(want) + "; enlarge the region or lower count");
        auto radii = sample_radii(set.size, want, rng);
        for (auto& r : radii) r *= set.shape.bounding_factor;
        for (std::int64_t k = 0; k < want; ++k) {
          const long ix = k % n[0], iy = (k / n[0]) % n[1], iz = k / (n[0] * n[1]);
          const Vec3 x = reg.lo + Vec3::Constant(rl) + a * Vec3(ix, iy, iz);
          put(x, radii[k], static_cast<std::size_t>(k));
        }
        break;
      }
      case Placement::Kind::File: {
        const auto& pos = set.placement.positions;
        std::vector<double> radii = set.placement.radii;
        if (radii.empty()) radii = sample_radii(set.size, static_cast<std::int64_t>(pos.size()), rng);
        for (auto& r : radii) r *= set.shape.bounding_factor;
        for (std::size_t k = 0; k < pos.size(); ++k) put(pos[k], radii[k], k);
        break;
      }
    }
  }
  return out;
}

void check_overlaps(const SceneConfig& c, const std::vector<PlacedParticle>& p) {
  if (p.empty()) return;
  double rmin = p[0].r, rmax = 0;
  for (const auto& q : p) rmin = std::min(rmin, q.r), rmax = std::max(rmax, q.r);
  // A wide size distribution is checked by size class (radii within a factor
  // 2, as the neighbour lists search it): one grid sized by the largest
  // grain would hold hundreds of small grains per cell. Each grain looks into
  // every class's grid as far as it and that class's largest grain reach.
  const SizeClasses size_class(rmin, rmax);
  const int classes = size_class.count;
  auto class_of = [&](double r) { return size_class.of(r); };
  std::vector<double> class_rmax(static_cast<std::size_t>(classes), 0.0);
  for (const auto& q : p) {
    auto& R = class_rmax[static_cast<std::size_t>(class_of(q.r))];
    R = std::max(R, q.r);
  }
  std::vector<PlacementGrid> grids;
  for (double R : class_rmax) grids.emplace_back(2 * std::max(R, rmin), c.domain);
  {
    std::vector<std::vector<std::uint32_t>> members(static_cast<std::size_t>(classes));
    for (std::size_t i = 0; i < p.size(); ++i)
      members[static_cast<std::size_t>(class_of(p[i].r))].push_back(static_cast<std::uint32_t>(i));
    for (std::size_t k = 0; k < grids.size(); ++k) grids[k].assign(p, members[k]);
  }
  // Each grain against those before it, as if placed one by one: the pair
  // reported is the first grain that overlaps one placed before it.
  for (std::size_t i = 0; i < p.size(); ++i) {
    std::size_t other = 0;
    const auto test = [&](std::size_t j) {
      if (j >= i) return false;
      if (c.sets[p[i].set].frozen && c.sets[p[j].set].frozen) return false;  // frozen grains never meet
      const double d = grids[0].delta(p[i].x, p[j].x).norm();
      const double ov = p[i].r + p[j].r - d;
      if (ov > c.overlap_tolerance * std::min(p[i].r, p[j].r)) {
        other = j;
        return true;
      }
      return false;
    };
    bool bad = false;
    if (classes == 1)
      bad = grids[0].any_near(p[i].x, test);
    else
      for (std::size_t k = 0; k < grids.size() && !bad; ++k)
        if (class_rmax[k] > 0) bad = grids[k].any_near(p[i].x, test, p[i].r + class_rmax[k]);
    if (bad) {
      const auto& a = p[other];
      const auto& b = p[i];
      auto where = [&](const PlacedParticle& q) {
        const auto& s = c.sets[q.set];
        if (s.placement.kind == Placement::Kind::File && q.index_in_set < s.placement.position_line.size())
          return s.placement.where(q.index_in_set);
        return s.where;
      };
      const double ov = a.r + b.r - grids[0].delta(a.x, b.x).norm();
      throw SetupError(where(b) + ": initial particles overlap: particle " + std::to_string(b.index_in_set) +
                       " of set '" + c.sets[b.set].name + "' and particle " + std::to_string(a.index_in_set) +
                       " of set '" + c.sets[a.set].name + "' overlap by " + fmt(ov) + " m (" +
                       fmt(100 * ov / std::min(a.r, b.r)) + "% of the smaller radius; at most " +
                       fmt(100 * c.overlap_tolerance) + "% is accepted, neighbor.overlap_tolerance" +
                       (c.sets[a.set].frozen != c.sets[b.set].frozen
                            ? "; frozen grains may overlap each other, not the grains that move"
                            : "") +
                       ")" +
                       (where(a) != where(b) ? " (other particle at " + where(a) + ")" : ""));
    }
  }
}

}  // namespace grains::sim
