// The lockstep Hertz–Mindlin sphere kernel (sim/laws/sphere_lanes.hpp)
// against the scalar loop of the same stage (GRAINS_SIMD=scalar): a cluster
// of overlapping spheres of two materials with random motion and random
// springs, some of them sliding, over several steps, serial and with the
// ordered (deterministic) sums, in clusters small and large (the lanes
// prefetch in large ones); also with one material (its constants written
// once per batch) and with frozen grains (m* is the other grain's mass).
// Forces, torques and springs must agree to the bit, batch boundaries and
// padded lanes included (and, on a processor with AVX-512F, the list passes
// of sphere_lanes_screen.hpp with the lanes they carry into the next batch).
#include <gtest/gtest.h>

#include <cstdlib>
#include <random>
#include <string>

#include "sim/laws/pair_contact_stage.hpp"
#include "sim/laws/sphere_lanes_screen.hpp"

namespace grains::sim {
namespace {

using HertzMindlin = ContactLaw<HertzNormal, SpringTangential, NoRolling, NoCohesion>;

enum class Kind { TwoMaterials, OneMaterial, Frozen, Wide, Sparse };

Scene cluster(int n, std::uint64_t seed, bool deterministic, Kind kind = Kind::TwoMaterials) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Scene s;
  s.domain.lo = Vec3(-1, -1, -1), s.domain.hi = Vec3(1, 1, 1);
  Material m;
  m.name = "m";
  m.density = 2500;
  m.youngs_modulus = 1e7;
  m.poisson_ratio = 0.3;
  m.restitution = 0.5;
  m.friction = 0.5;
  s.materials = {m, m};
  s.materials[1].youngs_modulus = 4e7;
  s.materials[1].poisson_ratio = 0.2;
  s.materials[1].friction = 0.2;
  if (kind == Kind::OneMaterial) s.materials.pop_back();
  s.pairs = PairTable(s.materials, {}, NormalLawChoice{"hertz", {}});
  s.particles.configure(FieldSet(Field::AngularVelocity) | Field::Torque | Field::Inertia, 0);
  // Random centres at about one sphere volume per sphere: most neighbours
  // overlap, some deeply, some not at all.
  const double side = 0.0045 * std::cbrt(n);
  for (int k = 0; k < n; ++k) {
    // Wide: every 40th sphere six times as large, so that some rows of the
    // list hold far more entries than a lane group or a window of the
    // vector first pass (sphere_lanes_screen_avx512.cpp, _avx2.cpp).
    const double r = 0.005 * (1 + 0.3 * std::abs(u(rng))) * (kind == Kind::Wide && k % 40 == 0 ? 6 : 1);
    const auto i = s.particles.add(k, side * Vec3(u(rng), u(rng), u(rng)), Vec3(u(rng), u(rng), u(rng)), r,
                                   2500 * 4.0 / 3.0 * M_PI * r * r * r, kind == Kind::OneMaterial ? 0 : k % 2);
    s.particles.omega[i] = 100 * Vec3(u(rng), u(rng), u(rng));
    if (kind == Kind::Frozen && k % 5 == 0) s.particles.inv_mass[i] = 0;
  }
  s.neighbors.set_frozen(kind == Kind::Frozen);
  s.clock.dt = 1e-6;
  s.deterministic = deterministic;
  s.neighbors.set_gather(deterministic);
  // Sparse: a skin of almost a diameter, so that most list entries do not
  // touch and a window of the AVX-512 first pass often ends before a batch
  // fills, inside a row.
  s.neighbors.configure(HertzMindlin::history_size, kind == Kind::Sparse ? 0.008 : 0.001);
  s.neighbors.build(s.particles, s.walls, s.domain.lo, s.domain.hi, 0, false);
  // Springs in the tangent plane: none on every other entry, else from short
  // to far beyond the Coulomb limit.
  auto& nl = s.neighbors;
  for (std::size_t i = 0; i + 1 < nl.row_start.size(); ++i)
    for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
      const Vec3 nrm = (s.particles.x[i] - s.particles.x[nl.partner[k]]).normalized();
      const Vec3 r(u(rng), u(rng), u(rng));
      const Vec3 h = k % 2 ? Vec3(2e-4 * std::abs(u(rng)) * (r - nrm * nrm.dot(r))) : Vec3::Zero();
      for (int c = 0; c < 3; ++c) nl.history[3 * k + c] = h[c];
    }
  return s;
}

void compare(bool deterministic, Kind kind = Kind::TwoMaterials) {
  // 40000 grains: past the size from which the lanes prefetch the partners.
  for (int n : {3, 40, 300, 40000}) {
    Scene a = cluster(n, 7 + n, deterministic, kind), b = cluster(n, 7 + n, deterministic, kind);
    // The lanes stage as the environment chooses (GRAINS_SIMD=baseline: the
    // baseline copy, see CMakeLists.txt), the scalar one by GRAINS_SIMD=scalar.
    const char* env = std::getenv("GRAINS_SIMD");
    const std::string saved = env ? env : "";
    PairContactStage<HertzMindlin> lanes;
    ::setenv("GRAINS_SIMD", "scalar", 1);
    PairContactStage<HertzMindlin> scalar;
    if (env)
      ::setenv("GRAINS_SIMD", saved.c_str(), 1);
    else
      ::unsetenv("GRAINS_SIMD");
    int touching = 0;
    for (int step = 0; step < 4; ++step) {
      for (Scene* s : {&a, &b}) {
        for (auto& f : s->particles.f) f.setZero();
        for (auto& t : s->particles.torque) t.setZero();
        // The grains move a little between steps: pairs come apart and close.
        for (std::size_t i = 0; i < s->particles.size(); ++i) s->particles.x[i] += 2e-4 * s->particles.v[i];
      }
      lanes.run(a);
      scalar.run(b);
      for (std::size_t i = 0; i < a.particles.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
          ASSERT_EQ(a.particles.f[i][c], b.particles.f[i][c]) << "n " << n << " step " << step << " particle " << i;
          ASSERT_EQ(a.particles.torque[i][c], b.particles.torque[i][c]) << "n " << n << " particle " << i;
        }
      }
      ASSERT_EQ(a.neighbors.history.size(), b.neighbors.history.size());
      for (std::size_t k = 0; k < a.neighbors.history.size(); ++k)
        ASSERT_EQ(a.neighbors.history[k], b.neighbors.history[k]) << "n " << n << " step " << step << " entry " << k;
      for (const auto t : a.neighbors.may_touch) touching += t;
    }
    if (n >= 40) {
      EXPECT_GT(touching, 4 * 33) << "the clusters should fill more than one batch";
    }
  }
}

TEST(SphereLanes, SerialSumsEqualTheScalarLoopBitwise) { compare(false); }
TEST(SphereLanes, OrderedSumsEqualTheScalarLoopBitwise) { compare(true); }
TEST(SphereLanes, OneMaterialEqualsTheScalarLoopBitwise) {
  compare(false, Kind::OneMaterial);
  compare(true, Kind::OneMaterial);
}
TEST(SphereLanes, WideSizesEqualTheScalarLoopBitwise) {
  compare(false, Kind::Wide);
  compare(true, Kind::Wide);
  // Some row is longer than a window of the first pass (64 entries).
  Scene s = cluster(3000, 11, false, Kind::Wide);
  std::uint32_t longest = 0;
  for (std::size_t i = 0; i + 1 < s.neighbors.row_start.size(); ++i)
    longest = std::max(longest, s.neighbors.row_start[i + 1] - s.neighbors.row_start[i]);
  EXPECT_GT(longest, 64u);
}
TEST(SphereLanes, SparseClustersEqualTheScalarLoopBitwise) {
  compare(false, Kind::Sparse);
  compare(true, Kind::Sparse);
}
TEST(SphereLanes, FrozenGrainsEqualTheScalarLoopBitwise) {
  compare(false, Kind::Frozen);
  compare(true, Kind::Frozen);
}

TEST(SphereLanes, ListPassesWithTheKernelsAvx512OrAvx2Copy) {
  // The comparisons above cover the vector list passes only where they run:
  // with the kernel's AVX-512 copy (this run on such a processor) or its
  // AVX2 copy (the run under GRAINS_SIMD=avx2 of CMakeLists.txt), never
  // under GRAINS_SIMD=baseline.
  const std::string copy = sphere_lanes_instruction_set();
  const bool vector = copy == "avx512" || copy == "avx2";
  EXPECT_EQ(sphere_screen() != nullptr, vector) << copy;
  EXPECT_EQ(sphere_kernel_gathered() != nullptr, vector) << copy;
#if defined(__x86_64__)
  const char* env = std::getenv("GRAINS_SIMD");
  if (!env && __builtin_cpu_supports("avx512f")) {
    EXPECT_EQ(copy, "avx512") << "this processor has AVX-512F";
  }
  if (env && std::string(env) == "avx2" && __builtin_cpu_supports("avx2")) {
    EXPECT_EQ(copy, "avx2") << "GRAINS_SIMD=avx2 on a processor with AVX2";
  }
#endif
}

TEST(SphereLanes, SomeSpringsSlide) {
  // The comparison above must cover the Coulomb branch: with springs this
  // long, many contacts are at the limit after a step.
  Scene a = cluster(300, 307, false);
  const std::vector<double> before = a.neighbors.history;
  PairContactStage<HertzMindlin> stage;
  stage.run(a);
  int sliding = 0, sticking = 0;
  const auto& nl = a.neighbors;
  for (std::size_t i = 0; i + 1 < nl.row_start.size(); ++i)
    for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
      if (!nl.may_touch[k]) continue;
      // A spring in the tangent plane that sticks only grows by v_t dt (at
      // most a few 1e-6 m here); one that slides is cut back to mu F_n / k_t.
      const Vec3 h0(before[3 * k], before[3 * k + 1], before[3 * k + 2]);
      const Vec3 h(nl.history[3 * k], nl.history[3 * k + 1], nl.history[3 * k + 2]);
      if (h0.norm() < 5e-5) continue;
      (h.norm() < h0.norm() - 1e-5 ? sliding : sticking)++;
    }
  EXPECT_GT(sliding, 0);
  EXPECT_GT(sticking, 0);
  EXPECT_STRNE(sphere_lanes_instruction_set(), "");
}

}  // namespace
}  // namespace grains::sim
