// Regression (label long): poured frictionless dimers against their bond
// aspect ratio alpha = (l + 2a)/(2a) (two balls of radius a, centres l
// apart), at the volume of a sphere of diameter d: 1,200 grains in a
// 10 d x 10 d box, e = 0.1, the pour of the CI dimer test
// (test_clump_packing.cpp), alpha in {1, 1.2, 1.4, 1.6, 1.8, 2}, two
// placement seeds. Reference (packing_references.yaml `dimer_maximum`):
// jammed frictionless dimers are densest near alpha = 1.4-1.5 (Baule et al.,
// Nat. Commun. 4 (2013); Schreck, O'Hern & Silbert, PRE 84 (2011)); the
// maximum must lie at an interior aspect ratio, above both ends by more than
// the standard error of the difference.
//
// CubeResolutionSweep: phi of poured frictional cubes against the resolution
// of their sphere decomposition (issue 4: "packing fraction of poured clumps
// of a fixed shape converges as the decomposition resolution increases").
// cases/pour_clumps/cube.off at grid 4, 6, 8, 12, 16 (mu = 0.25: n3 = 8, 40,
// 120, 160, 249 balls per cube; a grid-16 pour takes ~25 min of CPU), 250 cubes of bounding radius 0.8 mm in a 6 mm x 6 mm
// box periodic in x and y (no side walls), E = 1 MPa, e = 0.5, friction 0.5,
// three placement seeds per grid; bulk phi of the union of balls 2 mm above
// the floor and below the free surface (clump_pour.hpp, pour_periodic).
// Checked against packing_references.yaml `clump_resolution_effect` and
// `clump_resolution_convergence`; recorded in docs/decomposition.md.
//
// BunnyPourAgainstResolution: the same periodic pour with
// cases/pour_clumps/bunny.off at grid 8, 12 and 16 (one seed; as many bunnies
// as hold the solid of 400 grid-8 ones, so the beds are equally deep): poured phi and
// DEM cost per step, recorded in bench/RESULTS.md (a measurement: it checks
// only that every pour keeps its grains and comes to rest).
#include <gtest/gtest.h>

#include "io/case/clump_shapes.hpp"
#include "tests/regression/clump/clump_pour.hpp"

namespace grains::test {
namespace {

// Ball radius of a dimer of bond length l = 2 a (alpha - 1) whose union has
// the volume of a sphere of diameter d: V = (8/3) pi a^3 - pi (4a + l)(2a - l)^2 / 12.
double dimer_ball_radius(double alpha, double d) {
  const double l1 = 2 * (alpha - 1);  // bond per unit a
  const double v1 = 8.0 / 3.0 * M_PI - M_PI * (4 + l1) * (2 - l1) * (2 - l1) / 12.0;  // volume per a^3
  return std::cbrt(M_PI * d * d * d / 6.0 / v1);
}

TEST(ClumpRegressionLong, DimerAspectRatioSweep) {
  const packing::Reference ref = packing::reference("dimer_maximum");
  const double d = 0.001, w = 10 * d;
  const int n = 1200;
  const std::vector<double> alphas = {1.0, 1.2, 1.4, 1.6, 1.8, 2.0};
  const std::vector<int> seeds = {3, 5};
  std::vector<double> m, se, all;
  for (double alpha : alphas) {
    std::vector<double> v;
    for (int seed : seeds) {
      const double a = dimer_ball_radius(alpha, d);
      const auto r = alpha == 1.0 ? pour("{type: sphere}", d / 2, d, n, w, 0.45, seed)
                                  : pour("{type: clump, file: " + dimer_file(1.0 / alpha, 2 * (alpha - 1) / alpha) + "}",
                                         alpha * a, d, n, w, 0.45, seed);
      EXPECT_LT(r.speed, 0.02) << "not settled at aspect ratio " << alpha;
      std::cout << "dimers, aspect ratio " << alpha << ", seed " << seed << ": phi = " << r.phi << "\n";
      v.push_back(r.phi);
      all.push_back(r.phi);
    }
    m.push_back(packing::mean(v));
    se.push_back(packing::stddev(v) / std::sqrt(static_cast<double>(v.size())));
  }
  const auto peak = static_cast<std::size_t>(std::max_element(m.begin(), m.end()) - m.begin());
  packing::record("dimer_sweep", packing::Record()
                                     .str("case", "1,200 frictionless dimers, e = 0.1, 10 d x 10 d, seeds 3 and 5")
                                     .nums("aspect_ratio", alphas)
                                     .nums("phi", m)
                                     .nums("phi_se", se)
                                     .nums("phi_all", all)
                                     .num("peak_aspect_ratio", alphas[peak]));
  packing::expect_in_band(ref, alphas[peak], "aspect ratio of the densest dimers");
  for (std::size_t end : {std::size_t{0}, alphas.size() - 1}) {
    const double gap = m[peak] - m[end], err = std::hypot(se[peak], se[end]);
    EXPECT_GT(gap, err) << "maximum at " << alphas[peak] << " not above aspect ratio " << alphas[end];
  }
}

TEST(ClumpRegressionLong, CubeResolutionSweep) {
  const packing::Reference effect = packing::reference("clump_resolution_effect");
  const packing::Reference conv = packing::reference("clump_resolution_convergence");
  const std::vector<int> grids = {4, 6, 8, 12, 16};
  const std::vector<int> seeds = {1, 2, 3};
  // One pour of the sweep, recorded as clump_resolution_grid<G>_seed<S>.json
  // when GRAINS_RESULTS_DIR is set. With GRAINS_CUBE_SWEEP_REUSE=1 a pour
  // whose record exists there is read back instead of run (the pours are
  // deterministic: a record holds what the pour gives), so the sweep can be
  // spread over processes with GRAINS_CUBE_SWEEP_ONLY="12:1,12:2" (these
  // pours only, grid:seed, no statistics) and then assembled.
  struct One {
    double phi = 0, n3 = 0, rms_speed = 0, bodies = 0, wall_s = 0, ms_per_step = 0;
  };
  const char* dir = std::getenv("GRAINS_RESULTS_DIR");
  const char* reuse = std::getenv("GRAINS_CUBE_SWEEP_REUSE");
  auto one = [&](int grid, int seed) {
    const std::string name = "clump_resolution_grid" + std::to_string(grid) + "_seed" + std::to_string(seed);
    One o;
    if (reuse && *reuse && dir && *dir && std::filesystem::exists(std::filesystem::path(dir) / (name + ".json"))) {
      const YAML::Node n = YAML::LoadFile((std::filesystem::path(dir) / (name + ".json")).string());
      for (auto [key, v] : {std::pair<const char*, double*>{"phi", &o.phi}, {"n3", &o.n3}, {"rms_speed", &o.rms_speed},
                            {"wall_s", &o.wall_s}, {"ms_per_step", &o.ms_per_step}})
        *v = n[key].as<double>();
      // (records written before "bodies" was added had it checked when written)
      o.bodies = n["bodies"] ? n["bodies"].as<double>() : PeriodicPourConfig().count;
      std::cout << "grid " << grid << ", seed " << seed << ": phi = " << o.phi << " (read from " << name << ".json)"
                << std::endl;
      return o;
    }
    PeriodicPourConfig c;
    c.grid = grid;
    c.seed = seed;
    const PeriodicPour r = pour_periodic(c);
    o = {r.phi, static_cast<double>(r.balls / std::max<std::size_t>(1, r.bodies)), r.rms_speed,
         static_cast<double>(r.bodies), r.wall_s, 1e3 * r.wall_s / static_cast<double>(r.steps)};
    packing::record(name, packing::Record()
                              .num("grid", grid)
                              .num("seed", seed)
                              .num("n3", o.n3)
                              .num("phi", o.phi)
                              .num("rms_speed", o.rms_speed)
                              .num("bodies", o.bodies)
                              .num("wall_s", o.wall_s)
                              .num("ms_per_step", o.ms_per_step));
    return o;
  };
  const int count = PeriodicPourConfig().count;
  if (const char* only = std::getenv("GRAINS_CUBE_SWEEP_ONLY"); only && *only) {
    std::istringstream in(only);
    std::string item;
    while (std::getline(in, item, ',')) {
      const One o = one(std::stoi(item.substr(0, item.find(':'))), std::stoi(item.substr(item.find(':') + 1)));
      EXPECT_EQ(o.bodies, count);
      EXPECT_LT(o.rms_speed, packing::settled_speed());
    }
    return;
  }
  std::vector<double> n3, m, se, all, ms_step, wall;
  for (int grid : grids) {
    std::vector<double> v;
    double w = 0, ms = 0, balls = 0;
    for (int seed : seeds) {
      const One o = one(grid, seed);
      EXPECT_EQ(o.bodies, count) << "clumps lost at grid " << grid << ", seed " << seed;
      EXPECT_LT(o.rms_speed, packing::settled_speed()) << "not settled at grid " << grid << ", seed " << seed;
      v.push_back(o.phi);
      all.push_back(o.phi);
      balls = o.n3;
      w += o.wall_s / static_cast<double>(seeds.size());
      ms += o.ms_per_step / static_cast<double>(seeds.size());
    }
    n3.push_back(balls);
    m.push_back(packing::mean(v));
    se.push_back(packing::stddev(v) / std::sqrt(static_cast<double>(v.size())));
    wall.push_back(w);
    ms_step.push_back(ms);
    std::cout << "cube grid " << grid << " (n3 = " << balls << "): phi = " << m.back() << " +- " << se.back()
              << " (s.e., " << seeds.size() << " seeds); " << w << " s per pour, " << ms << " ms per step" << std::endl;
  }
  // Changes of the mean between successive grids, with their standard errors.
  std::vector<double> d, sd;
  for (std::size_t i = 0; i + 1 < m.size(); ++i) {
    d.push_back(m[i + 1] - m[i]);
    sd.push_back(std::hypot(se[i + 1], se[i]));
  }
  std::size_t big = 0;
  for (std::size_t i = 1; i < d.size(); ++i)
    if (std::abs(d[i]) > std::abs(d[big])) big = i;
  const double last = d.back(), se_last = sd.back();
  for (std::size_t i = 0; i < d.size(); ++i)
    std::cout << "grid " << grids[i] << " -> " << grids[i + 1] << ": " << d[i] << " +- " << sd[i] << std::endl;
  packing::record("clump_resolution", packing::Record()
                                          .str("case", "250 frictional cubes (cube.off, mu 0.25), 6 mm periodic box, E = 1 MPa, e = 0.5, friction 0.5, seeds 1-3")
                                          .nums("grid", std::vector<double>(grids.begin(), grids.end()))
                                          .nums("n3", n3)
                                          .nums("phi", m)
                                          .nums("phi_se", se)
                                          .nums("phi_all", all)
                                          .nums("wall_s_per_pour", wall)
                                          .nums("ms_per_step", ms_step)
                                          .nums("change", d)
                                          .nums("change_se", sd)
                                          .num("largest_change_in_se", std::abs(d[big]) / sd[big])
                                          .num("last_change_in_se", last / se_last));
  // The resolution matters: the largest change between successive grids is
  // resolved beyond the seed noise (a decomposition that ignored the grid, or
  // a sweep too noisy to tell, fails here).
  packing::expect_in_band(effect, std::abs(d[big]) / sd[big], "largest change / s.e.");
  // ... and converges: the last change is smaller than the largest by more
  // than twice their combined standard error, and the two finest agree
  // within the band (in standard errors of their difference).
  EXPECT_LT(big, d.size() - 1) << "the largest change is the last one: no convergence yet";
  EXPECT_LT(std::abs(last) + 2 * std::hypot(sd[big], se_last), std::abs(d[big]))
      << "the change of phi does not shrink with the resolution";
  packing::expect_in_band(conv, last / se_last, "(phi(finest) - phi(second finest)) / s.e.");
}

TEST(ClumpRegressionLong, BunnyPourAgainstResolution) {
  const std::vector<int> grids = {8, 12, 16};
  const std::string mesh = std::string(GRAINS_SOURCE_DIR) + "/cases/pour_clumps/bunny.off";
  // Every grid's clump is scaled to the same bounding radius, and the finer
  // unions hold less solid (0.54, 0.37, 0.31 mm^3 per bunny at grid 8, 12,
  // 16): the count grows so that every bed holds the solid of 400 grid-8
  // bunnies and is as deep (with 400 at every grid the grid-16 bulk slab was
  // only 2.2 mm thick).
  const double v8 = io::clump_shape_from_mesh(mesh, 8, 0.25)->volume;
  std::vector<double> n3, phi, ms_step, wall, dt, counts;
  for (int grid : grids) {
    PeriodicPourConfig c;
    c.mesh = mesh;
    c.grid = grid;
    // A bunny fills less of its bounding sphere than a cube: 400 grid-8
    // bunnies make a bed about as deep as 250 cubes (fill up to 0.1 m,
    // 0.14 s of fall); more bunnies fill proportionally higher and fall longer.
    const double scale = v8 / io::clump_shape_from_mesh(mesh, grid, 0.25)->volume;
    c.count = static_cast<int>(std::lround(400 * scale));
    c.fill_top = 0.1 * scale;
    c.end = 0.22 + std::sqrt(2 * c.fill_top / 9.81) - std::sqrt(2 * 0.1 / 9.81);
    counts.push_back(c.count);
    const PeriodicPour r = pour_periodic(c);
    EXPECT_EQ(r.bodies, static_cast<std::size_t>(c.count)) << "bunnies lost at grid " << grid;
    EXPECT_LT(r.rms_speed, packing::settled_speed()) << "not settled at grid " << grid;
    n3.push_back(static_cast<double>(r.balls / std::max<std::size_t>(1, r.bodies)));
    phi.push_back(r.phi);
    wall.push_back(r.wall_s);
    dt.push_back(r.dt);
    ms_step.push_back(1e3 * r.wall_s / static_cast<double>(r.steps));
  }
  packing::record("bunny_resolution", packing::Record()
                                          .str("case", "frictional bunnies (bunny.off, mu 0.25) with the solid of 400 grid-8 bunnies, 6 mm periodic box, E = 1 MPa, e = 0.5, friction 0.5, seed 1")
                                          .nums("grid", std::vector<double>(grids.begin(), grids.end()))
                                          .nums("count", counts)
                                          .nums("n3", n3)
                                          .nums("phi", phi)
                                          .nums("dt", dt)
                                          .nums("wall_s_per_pour", wall)
                                          .nums("ms_per_step", ms_step));
}

}  // namespace
}  // namespace grains::test
