// Property tests over every composition the registries make (each normal
// law of sim/laws/normal_laws.hpp with each of its examples x tangential x
// rolling x cohesion, contact_law.hpp): Newton's third law (forces and
// moments), zero force beyond contact, symmetry under exchange of the two
// bodies, a repulsive wall contact, and the Coulomb limit. A law added to a
// registry is covered here without an edit.
#include <gtest/gtest.h>

#include <random>

#include "sim/laws/pair_contact_stage.hpp"
#include "sim/walls/wall_contact_stage.hpp"

namespace grains::sim {
namespace {

// Two spheres with random kinematics; ids chosen so that `swap` exchanges
// which one is body i of the pair.
Scene two_spheres(std::mt19937_64& rng, double gap_factor, bool swap, int history, const NormalLawChoice& normal) {
  std::uniform_real_distribution<double> u(-1, 1);
  Scene s;
  s.domain.lo = Vec3(-1, -1, -1), s.domain.hi = Vec3(1, 1, 1);
  Material m;
  m.name = "m";
  m.density = 2500;
  m.youngs_modulus = 1e8;
  m.poisson_ratio = 0.3;
  m.restitution = 0.6;
  m.friction = 0.4;
  m.rolling_friction = 0.1;
  m.cohesion = 1e4;
  m.surface_energy = 0.05;  // the adhesive laws' attraction is in play (the others do not read it)
  s.materials = {m, m};
  s.materials[1].youngs_modulus = 3e8;
  s.materials[1].poisson_ratio = 0.2;
  s.pairs = PairTable(s.materials, {}, normal);
  s.particles.configure(FieldSet(Field::AngularVelocity) | Field::Torque | Field::Inertia, 0);
  const double r1 = 0.01 * (1 + 0.5 * std::abs(u(rng))), r2 = 0.01 * (1 + 0.5 * std::abs(u(rng)));
  const Vec3 dir = Vec3(u(rng), u(rng), u(rng)).normalized();
  const Vec3 x1(0.1 * u(rng), 0.1 * u(rng), 0.1 * u(rng));
  const Vec3 x2 = x1 + dir * (r1 + r2) * gap_factor;
  const Vec3 v1(u(rng), u(rng), u(rng)), v2(u(rng), u(rng), u(rng));
  const Vec3 w1 = 50 * Vec3(u(rng), u(rng), u(rng)), w2 = 50 * Vec3(u(rng), u(rng), u(rng));
  auto add = [&](std::int64_t id, const Vec3& x, const Vec3& v, const Vec3& w, double r, int mat) {
    const auto i = s.particles.add(id, x, v, r, 2500 * 4.0 / 3.0 * M_PI * r * r * r, mat);
    s.particles.omega[i] = w;
  };
  if (!swap) {
    add(0, x1, v1, w1, r1, 0);
    add(1, x2, v2, w2, r2, 1);
  } else {
    add(1, x1, v1, w1, r1, 0);
    add(0, x2, v2, w2, r2, 1);
  }
  s.clock.dt = 1e-6;
  s.neighbors.configure(history, 0.1 * r1);
  s.neighbors.build(s.particles, s.walls, s.domain.lo, s.domain.hi, 0, false);
  return s;
}

template <class Law>
void check_law(const NormalLawChoice& normal) {
  std::mt19937_64 rng(42);
  for (int trial = 0; trial < 200; ++trial) {
    const auto seed = rng();
    std::mt19937_64 r1(seed), r2(seed);
    Scene a = two_spheres(r1, 0.97, false, Law::history_size, normal);
    Scene b = two_spheres(r2, 0.97, true, Law::history_size, normal);
    PairContactStage<Law> stage;
    // Several steps so that history matters.
    for (int k = 0; k < 3; ++k) {
      for (Scene* s : {&a, &b}) {
        for (auto& f : s->particles.f) f.setZero();
        for (auto& t : s->particles.torque) t.setZero();
        stage.run(*s);
      }
    }
    const auto& p = a.particles;
    // Newton's third law for forces and for moments about the origin.
    EXPECT_LT((p.f[0] + p.f[1]).norm(), 1e-12 * (p.f[0].norm() + 1e-300)) << Law::name();
    const Vec3 L = p.torque[0] + p.torque[1] + p.x[0].cross(p.f[0]) + p.x[1].cross(p.f[1]);
    const double scale = p.torque[0].norm() + p.x[0].norm() * p.f[0].norm() + 1e-300;
    EXPECT_LT(L.norm(), 1e-12 * scale) << Law::name();
    EXPECT_GT(p.f[0].norm(), 0.0);
    // Exchange symmetry: the same physical particles get the same forces
    // whichever of them is body i of the pair.
    const auto& q = b.particles;
    for (int k = 0; k < 2; ++k) {
      const double fs = p.f[k].norm() + 1e-300, ts = p.torque[k].norm() + 1e-300;
      EXPECT_LT((p.f[k] - q.f[k]).norm(), 1e-9 * fs) << Law::name() << " particle " << k;
      EXPECT_LT((p.torque[k] - q.torque[k]).norm(), 1e-9 * ts) << Law::name() << " particle " << k;
    }
    // Beyond contact: nothing.
    Scene c = two_spheres(r1, 1.0001, false, Law::history_size, normal);
    stage.run(c);
    EXPECT_EQ(c.particles.f[0].norm(), 0.0);
    EXPECT_EQ(c.particles.f[1].norm(), 0.0);
    EXPECT_EQ(c.particles.torque[0].norm(), 0.0);
  }
}

template <class Law>
void check_wall_law(const NormalLawChoice& normal) {
  // Zero force beyond contact and a repulsive normal part in contact.
  Scene s;
  s.domain.lo = Vec3(-1, -1, -1), s.domain.hi = Vec3(1, 1, 1);
  Material m{"m", 2500, 1e8, 0.3, 0.5, 0.5, 0.1, 0.0};
  s.materials = {m};
  s.pairs = PairTable(s.materials, {}, normal);
  PlaneWall w;
  w.normal = Vec3(0, 0, 1);
  s.walls.of<sim::PlaneWall>().push_back(w);
  s.particles.configure(FieldSet(Field::AngularVelocity) | Field::Torque | Field::Inertia | Field::WallHistory,
                        Law::history_size);
  s.particles.add(0, Vec3(0, 0, 0.0101), Vec3(0.1, 0, -0.1), 0.01, 1e-3, 0);
  s.particles.add(1, Vec3(0.5, 0, 0.0099), Vec3(0.1, 0, -0.1), 0.01, 1e-3, 0);
  s.clock.dt = 1e-6;
  s.neighbors.configure(Law::history_size, 0.001);
  s.neighbors.build(s.particles, s.walls, s.domain.lo, s.domain.hi, 0, false);
  WallStage<Law> stage;
  stage.run(s);
  EXPECT_EQ(s.particles.f[0].norm(), 0.0) << Law::name();
  EXPECT_GT(s.particles.f[1].z(), 0.0) << Law::name();
}

// Every normal law with each of its examples, and every other slot.
template <class F>
void for_every_composition(F&& f) {
  for_each_type(NormalLaws{}, [&]<class N>() {
    for (const LawValues& values : N::examples()) {
      const NormalLawChoice normal{N::name, values};
      ASSERT_EQ(N::check(values), "") << N::name;
      for_each_type(TangentialLaws{}, [&]<class T>() {
        for_each_type(RollingLaws{}, [&]<class R>() {
          for_each_type(CohesionLaws{}, [&]<class C>() { f.template operator()<ContactLaw<N, T, R, C>>(normal); });
        });
      });
    }
  });
}

TEST(LawProperties, EveryCompositionObeysNewtonZeroBeyondContactAndExchangeSymmetry) {
  int count = 0;
  for_every_composition([&]<class Law>(const NormalLawChoice& normal) {
    SCOPED_TRACE(Law::name());
    check_law<Law>(normal);
    check_wall_law<Law>(normal);
    ++count;
  });
  // 4 normal laws (hertz 1, linear 6, dmt 1, jkr 1 examples) x 2 x 2 x 2.
  EXPECT_EQ(count, 9 * 8);
}

TEST(LawProperties, CoulombLimitHoldsForEveryNormalLaw) {
  for_every_composition([&]<class Law>(const NormalLawChoice& normal) {
    if constexpr (Law::T::history_size > 0) {
      Material m{"m", 2500, 1e8, 0.3, 0.5, 0.3, 0.0, 0.0};
      m.surface_energy = 0.05;  // the adhesive laws' limits are in play (the others do not read it)
      const PairTable table({m}, {}, normal);
      const PairParams& p = table(0, 0);
      contact::ContactGeometry g;
      g.normal = Vec3(0, 0, 1);
      g.overlap = 1e-5;
      g.radius = 0.005;
      double hist[Law::history_size] = {};
      for (int k = 0; k < 1000; ++k) {
        const auto r = Law::evaluate(g, Vec3(1.0, 0.3, -0.01), Vec3(3, -2, 1), 1e-3, p, 1e-6, hist);
        // The limit scales with the repulsive load (cohesion adds attraction after it).
        const double load = [&] {
          if constexpr (Law::normal_history > 0) {  // the normal law's state after the springs'
            double state = hist[Law::history_size - 1];
            return Law::N::evaluate(g.overlap, 0.01, g.radius, 1e-3, p, state).load;
          } else {
            return Law::N::evaluate(g.overlap, 0.01, g.radius, 1e-3, p).load;
          }
        }();
        const double ft = Vec3(r.force.x(), r.force.y(), 0).norm();
        EXPECT_LE(ft, p.friction * load * (1 + 1e-12)) << Law::name();
        EXPECT_GT(ft, 0.0) << Law::name();
      }
    }
  });
}

}  // namespace
}  // namespace grains::sim
