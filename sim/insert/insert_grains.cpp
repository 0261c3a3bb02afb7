#include "sim/insert/insert_grains.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>

#include "contact/correlation/ball_kernels.hpp"
#include "contact/correlation/overlap_field.hpp"
#include "sim/insert/grain_geometry.hpp"
#include "sim/insert/obstacles.hpp"
#include "sim/scene/placement.hpp"

namespace grains::sim::insert {

namespace gc = grains::correlation;

Quat uniform_rotation(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double u1 = u(rng), u2 = 2 * M_PI * u(rng), u3 = 2 * M_PI * u(rng);
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
  return Quat(a * std::sin(u2), a * std::cos(u2), b * std::sin(u3), b * std::cos(u3)).normalized();
}

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The state shared by both methods: sizes to place, the exact check, the
// output and the clock.
struct Job {
  const InsertionConfig& c;
  const Domain& domain;
  std::mt19937_64 rng;
  std::vector<double> sizes;  // bounding radii, largest first
  Obstacles obstacles;
  std::vector<NewGrain> out;
  InsertStats st;
  Clock::time_point t0 = Clock::now();

  Job(const InsertionConfig& cfg, const SceneGrains& scene, const Domain& d, const Walls& walls, std::uint64_t seed)
      : c(cfg), domain(d), rng(seed), obstacles(d, walls, reach(cfg, scene)) {
    sizes = sample_radii(c.grains.size, c.grains.count, rng);
    for (auto& r : sizes) r *= c.grains.shape.bounding_factor;
    std::sort(sizes.begin(), sizes.end(), std::greater<>());
    for (std::size_t i = 0; i < scene.sphere_r.size(); ++i) obstacles.add_sphere(scene.sphere_x[i], scene.sphere_r[i]);
    for (std::size_t i = 0; i < scene.ell_x.size(); ++i)
      obstacles.add_ellipsoid(scene.ell_x[i], contact::quadratic_form(scene.ell_axes[i], scene.ell_q[i]),
                              scene.ell_axes[i].maxCoeff());
    st.requested = c.grains.count;
  }
  static double reach(const InsertionConfig& c, const SceneGrains& s) {
    double b = 0;
    for (double r : s.sphere_r) b = std::max(b, r);
    for (const auto& a : s.ell_axes) b = std::max(b, a.maxCoeff());
    return b + c.grains.size.largest() * c.grains.shape.bounding_factor;
  }
  bool done() const { return out.size() == sizes.size(); }
  bool out_of_time() const { return c.budget > 0 && since(t0) > c.budget; }
  double next_size() const { return sizes[out.size()]; }
  Quat orientation() {
    if (c.grains.shape.kind == ShapeConfig::Kind::Sphere) return Quat::Identity();
    return c.grains.shape.random_orientation ? uniform_rotation(rng) : c.grains.shape.orientation;
  }
  // Inside the region with the whole grain (its bounding sphere).
  bool in_region(const Vec3& x, double q) const {
    for (int d = 0; d < 3; ++d)
      if (x[d] < c.region.lo[d] + q || x[d] > c.region.hi[d] - q) return false;
    return true;
  }
  // Exact check; on success the grain is placed.
  bool try_place(const Vec3& x, const Quat& o) {
    const double q = next_size();
    ++st.trials;
    if (!in_region(x, q)) return false;
    const GrainParts g = grain_parts(c.grains.shape, q, x, o);
    if (!obstacles.fits(g)) return false;
    obstacles.add(g);
    out.push_back({x, q, o});
    return true;
  }
};

void run_random(Job& j) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::int64_t fails = 0;
  while (!j.done() && fails < j.c.attempts) {
    if ((j.st.trials & 63) == 0 && j.out_of_time()) break;
    const double q = j.next_size();
    Vec3 x;
    for (int d = 0; d < 3; ++d) x[d] = j.c.region.lo[d] + q + u(j.rng) * (j.c.region.hi[d] - j.c.region.lo[d] - 2 * q);
    const Quat o = j.orientation();
    if (j.try_place(x, o))
      fails = 0;
    else
      ++fails;
  }
}

// Radii rounded up to classes (1.05)^k times the smallest: each class costs
// one spreading pass of the scene's spectrum, and a larger ball only makes
// the field more conservative.
double round_up_radius(double r, double r0) {
  constexpr double g = 1.05;
  if (r <= r0) return r0;
  const double k = std::ceil(std::log(r / r0) / std::log(g) - 1e-9);
  return r0 * std::pow(g, k);
}

// The scene's balls that can reach the grid's nodes (centres within r +
// reach of the nodes' box [lo, hi]), with their images along periodic axes.
// SceneOverlap pads for exactly these.
struct SceneBalls {
  std::vector<double> centres, radii;
};

void add_ball(SceneBalls& b, const Vec3& x, double r, double reach, const Domain& dom, const Vec3& lo, const Vec3& hi) {
  std::array<std::array<double, 3>, 3> shifts{};
  std::array<int, 3> n{};
  for (int d = 0; d < 3; ++d) {
    shifts[d][n[d]++] = 0;
    if (!dom.periodic[d]) continue;
    const double L = dom.hi[d] - dom.lo[d];
    shifts[d][n[d]++] = L;
    shifts[d][n[d]++] = -L;
  }
  for (int a = 0; a < n[0]; ++a)
    for (int bb = 0; bb < n[1]; ++bb)
      for (int c = 0; c < n[2]; ++c) {
        const Vec3 y = x + Vec3(shifts[0][a], shifts[1][bb], shifts[2][c]);
        if (((y.array() + (r + reach)) < lo.array()).any() || ((y.array() - (r + reach)) > hi.array()).any()) continue;
        b.centres.insert(b.centres.end(), {y[0], y[1], y[2]});
        b.radii.push_back(r);
      }
}

void run_fft(Job& j, const SceneGrains& scene, int threads) {
  const auto& c = j.c;
  const double qmax = j.sizes.front();
  // The grain's cover (largest size), inflated by the margin.
  std::vector<Vec3> yc;
  std::vector<double> ys;
  cover_balls(c.grains.shape, qmax, yc, ys);
  // The largest ball sets the margin, the threshold and the default spacing
  // (a clump's small balls would make the grid needlessly fine; positions
  // where only a small ball overlaps are rejected by the exact check).
  const double s_ref = *std::max_element(ys.begin(), ys.end());
  const double delta = c.margin * s_ref;
  std::vector<double> shape_c, shape_r;
  double reach = 0;
  for (std::size_t k = 0; k < ys.size(); ++k) {
    shape_c.insert(shape_c.end(), {yc[k][0], yc[k][1], yc[k][2]});
    shape_r.push_back(ys[k] + delta);
    reach = std::max(reach, yc[k].norm() + ys[k] + delta);
  }
  // Grid of candidate centres: the region less the bounding radius.
  const double h = c.spacing > 0 ? c.spacing : 0.25 * s_ref;
  gc::GridSpec grid;
  grid.periodic = {false, false, false};
  Vec3 span;
  for (int d = 0; d < 3; ++d) {
    span[d] = c.region.hi[d] - c.region.lo[d] - 2 * qmax;
    if (span[d] < 0) return;  // nothing fits (refused at set-up for the nominal size)
    grid.spacing[d] = h;
  }
  // The nodes of round `round`: the first on the region's corner, later ones
  // shifted by a random fraction of a cell, so that each field looks between
  // the nodes of the earlier ones (pockets smaller than the spacing).
  auto place_grid = [&](int round) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int d = 0; d < 3; ++d) {
      const double shift = round == 1 ? 0.0 : std::min(u(j.rng) * h, span[d]);
      grid.origin[d] = c.region.lo[d] + qmax + shift;
      grid.dims[d] = static_cast<int>(std::floor((span[d] - shift) / h + 1e-9)) + 1;
    }
  };
  gc::OverlapFieldOptions fo;
  fo.mode_factor = c.mode_factor;
  fo.tolerance = 1e-4;
  fo.upsampling = 1.25;
  fo.threads = threads;

  // Scene balls, radii rounded up; the grains placed here join them at each round.
  double scene_rmin = std::numeric_limits<double>::infinity();
  std::vector<Vec3> bx;
  std::vector<double> br;
  auto push_grain_balls = [&](const Vec3& x, double r) {
    bx.push_back(x);
    br.push_back(r);
    scene_rmin = std::min(scene_rmin, r);
  };
  for (std::size_t i = 0; i < scene.sphere_r.size(); ++i) push_grain_balls(scene.sphere_x[i], scene.sphere_r[i]);
  std::vector<Vec3> ec;
  std::vector<double> er;
  auto push_ellipsoid = [&](const Vec3& x, const Vec3& axes, const Quat& q) {
    ec.clear();
    er.clear();
    ellipsoid_cover(axes, ec, er);
    const Eigen::Matrix3d R = q.toRotationMatrix();
    for (std::size_t k = 0; k < er.size(); ++k) push_grain_balls(x + R * ec[k], er[k]);
  };
  for (std::size_t i = 0; i < scene.ell_x.size(); ++i) push_ellipsoid(scene.ell_x[i], scene.ell_axes[i], scene.ell_q[i]);

  std::vector<std::uint32_t> cand, near;  // nodes: free, near-free
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pool;  // (node, orientation) of both kinds, this round
  std::vector<Quat> orient;
  std::vector<double> field;
  const bool spin = c.grains.shape.kind != ShapeConfig::Kind::Sphere && c.grains.shape.random_orientation;
  // Ellipsoids that turn: one field per round, of the grain's core, the ball
  // of its smallest semi-axis about its centre, which the grain contains in
  // every orientation. Where the grain fits in some orientation its core
  // fits: the core's free and near-free cells hold every place for every
  // orientation, and each trial there draws the orientation at random.
  // (Measured against a field per trial orientation, bench/RESULTS.md: more
  // grains at every budget for the larger grains and the short budgets,
  // 4 % fewer at 8 s for the smaller.) Clumps keep one field per orientation:
  // their centre of mass need not lie inside them.
  const bool core_field = spin && c.grains.shape.kind == ShapeConfig::Kind::Ellipsoid;
  const double core_s = qmax * c.grains.shape.axes_rel.minCoeff();
  const double core_delta = c.margin * core_s;
  const std::vector<double> core_c = {0.0, 0.0, 0.0}, core_r = {core_s + core_delta};
  const int n_orient = core_field ? 1 : (spin ? c.orientations : 1);
  // The balls each field correlates with the scene, and the largest one's
  // radius and margin, which set the thresholds.
  const std::vector<double>& field_c = core_field ? core_c : shape_c;
  const std::vector<double>& field_r = core_field ? core_r : shape_r;
  const double field_s = core_field ? core_s : s_ref, field_delta = core_field ? core_delta : delta;
  std::size_t joined = 0;  // grains of j.out already in bx/br
  constexpr int kMaxRounds = 100;
  int idle = 0;  // consecutive rounds that placed nothing
  while (!j.done() && !j.out_of_time() && j.st.rounds < kMaxRounds) {
    ++j.st.rounds;
    place_grid(j.st.rounds);
    for (; joined < j.out.size(); ++joined) {
      const auto& g = j.out[joined];
      if (c.grains.shape.kind == ShapeConfig::Kind::Ellipsoid)
        push_ellipsoid(g.x, g.r * c.grains.shape.axes_rel, g.o);
      else {
        const GrainParts p = grain_parts(c.grains.shape, g.r, g.x, g.o);
        for (std::size_t k = 0; k < p.radii.size(); ++k) push_grain_balls(p.centres[k], p.radii[k]);
      }
    }
    Vec3 lo, hi;  // the nodes' box
    for (int d = 0; d < 3; ++d) {
      lo[d] = grid.origin[d];
      hi[d] = grid.origin[d] + (grid.dims[d] - 1) * h;
    }
    SceneBalls sb;
    const double r0 = std::isfinite(scene_rmin) ? scene_rmin : s_ref;
    for (std::size_t i = 0; i < br.size(); ++i) add_ball(sb, bx[i], round_up_radius(br[i], r0), reach, j.domain, lo, hi);
    // Threshold: half the smallest lens a touching grain makes once inflated.
    const double threshold = 0.5 * gc::lens_volume(r0 + field_s, r0, field_s + field_delta);
    // A free position off the nodes: the nearest node is within h sqrt(3)/2,
    // where the inflated grain penetrates each neighbour by at most
    // delta + h sqrt(3)/2; with up to kNear such neighbours V stays below this.
    constexpr double kNear = 4;
    constexpr int kTrialsPerCell = 4;
    const double threshold_near =
        kNear * gc::lens_volume(r0 + field_s, r0, field_s + field_delta + 0.5 * std::sqrt(3.0) * h);
    orient.clear();
    for (int k = 0; k < n_orient; ++k) orient.push_back(spin ? uniform_rotation(j.rng) : j.orientation());
    // The orientation of a trial at a node of field k.
    auto trial_orientation = [&](std::size_t k) { return core_field ? uniform_rotation(j.rng) : orient[k]; };
    // Trials per free node: the core's nodes draw the orientation each time.
    const int node_trials = core_field ? kTrialsPerCell : 1;
    const std::size_t before = j.out.size();
    const double fields_before = j.st.field_seconds;
    std::int64_t visited = 0;
    std::uniform_real_distribution<double> jitter(-0.5 * h, 0.5 * h);
    std::unique_ptr<gc::SceneOverlap> ov;
    pool.clear();
    // One orientation at a time: its field, then its candidates, so that a
    // time budget sees grains placed from the first field on.
    for (std::size_t k = 0; k < orient.size() && !j.done() && !j.out_of_time(); ++k) {
      const auto tf = Clock::now();
      cand.clear();
      near.clear();
      if (sb.radii.empty()) {
        // Nothing near: every node is a candidate.
        for (std::size_t n = 0; n < grid.num_nodes(); ++n) cand.push_back(static_cast<std::uint32_t>(n));
      } else {
        if (!ov) ov = std::make_unique<gc::SceneOverlap>(gc::BallSet{sb.centres, sb.radii}, grid, reach, fo);
        const Eigen::Matrix3d R = orient[k].toRotationMatrix();
        std::array<double, 9> rm;
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) rm[3 * a + b] = R(a, b);
        field = ov->field(gc::BallSet{field_c, field_r}, rm);
        ++j.st.fields;
        for (std::size_t n = 0; n < field.size(); ++n)
          if (field[n] <= threshold)
            cand.push_back(static_cast<std::uint32_t>(n));
          else if (field[n] <= threshold_near)
            near.push_back(static_cast<std::uint32_t>(n));
      }
      j.st.field_seconds += since(tf);
      j.st.candidates += static_cast<std::int64_t>(cand.size() + near.size());
      for (const auto n : cand) pool.emplace_back(n, static_cast<std::uint32_t>(k));
      for (const auto n : near) pool.emplace_back(n, static_cast<std::uint32_t>(k));
      std::shuffle(cand.begin(), cand.end(), j.rng);
      std::shuffle(near.begin(), near.end(), j.rng);
      // The nodes first, then random points in the cells of the near-free
      // nodes (a few each): pockets smaller than the grid spacing or the margin.
      for (const auto n : cand) {
        if (j.done()) break;
        if ((++visited & 63) == 0 && j.out_of_time()) break;
        const auto t = grid.node(n);
        for (int q = 0; q < node_trials; ++q)
          if (j.try_place(Vec3(t[0], t[1], t[2]), trial_orientation(k))) break;
      }
      for (const auto n : near) {
        if (j.done()) break;
        if ((++visited & 63) == 0 && j.out_of_time()) break;
        const auto t = grid.node(n);
        for (int q = 0; q < kTrialsPerCell; ++q)
          if (j.try_place(Vec3(t[0] + jitter(j.rng), t[1] + jitter(j.rng), t[2] + jitter(j.rng)), trial_orientation(k)))
            break;
      }
    }
    const double round_field_seconds = j.st.field_seconds - fields_before;
    // Pocket search: random points in the cells of this round's free and
    // near-free nodes, cells drawn uniformly. Free space only shrinks as
    // grains are placed, so these cells still hold every place a grain can
    // go (up to the kNear bound), at a far higher hit rate than trials over
    // the whole region; a new field is computed only after as many failures
    // in a row as kTrialsPerCell per cell.
    // It also runs at least as long as this round's fields took: a field is
    // worth computing again only when the pockets have cost as much.
    if (!pool.empty()) {
      std::uniform_int_distribution<std::size_t> pick(0, pool.size() - 1);
      const auto patience = static_cast<std::int64_t>(std::max<std::size_t>(1000, kTrialsPerCell * pool.size()));
      const auto t_pockets = Clock::now();
      std::int64_t fails = 0;
      while (!j.done() && (fails < patience || since(t_pockets) < round_field_seconds)) {
        if ((++visited & 63) == 0 && j.out_of_time()) break;
        const auto& [n, k] = pool[pick(j.rng)];
        const auto t = grid.node(n);
        // Grains that turn: every other trial in a fresh orientation (a
        // pocket too tight for the field's orientation may take another).
        const Quat o = spin && (fails & 1) ? uniform_rotation(j.rng) : trial_orientation(k);
        if (j.try_place(Vec3(t[0] + jitter(j.rng), t[1] + jitter(j.rng), t[2] + jitter(j.rng)), o))
          fails = 0;
        else
          ++fails;
      }
    }
    // Two rounds in a row placed nothing (two grids, new orientations): the
    // region is full at this resolution.
    idle = j.out.size() == before ? idle + 1 : 0;
    if (idle == 2) break;
  }
}

}  // namespace

std::vector<NewGrain> insert_grains(const InsertionConfig& c, const SceneGrains& scene, const Domain& domain,
                                    const Walls& walls, std::uint64_t seed, int threads, InsertStats* stats) {
  Job j(c, scene, domain, walls, seed);
  if (!j.sizes.empty()) {
    if (c.method == InsertionConfig::Method::Random)
      run_random(j);
    else
      run_fft(j, scene, threads);
  }
  j.st.placed = static_cast<std::int64_t>(j.out.size());
  j.st.seconds = since(j.t0);
  if (stats) *stats = j.st;
  return std::move(j.out);
}

}  // namespace grains::sim::insert
