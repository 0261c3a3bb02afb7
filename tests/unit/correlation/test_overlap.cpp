// Translational overlap field and truncated-mode queries against exact sums
// of sphere-sphere lens volumes.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "contact/correlation/ball_kernels.hpp"
#include "contact/correlation/ball_spectrum.hpp"
#include "contact/correlation/overlap_field.hpp"
#include "contact/correlation/truncated_overlap.hpp"
#include "scenes.hpp"

namespace gc = grains::correlation;
namespace gt = grains::correlation::testing;
constexpr double kPi = std::numbers::pi;

namespace {

// Exact sum of lens volumes between the scene and the shape (rotated by R,
// placed at t), minimum image along periodic axes.
double exact_overlap(const gt::Scene& scene, const gt::Scene& shape, const std::array<double, 9>& R,
                     const std::array<double, 3>& t, std::array<double, 3> L,
                     std::array<bool, 3> periodic) {
  double v = 0.0;
  for (std::size_t j = 0; j < shape.radii.size(); ++j) {
    const double* y = &shape.centres[3 * j];
    double p[3];
    for (int a = 0; a < 3; ++a) p[a] = t[a] + R[3 * a] * y[0] + R[3 * a + 1] * y[1] + R[3 * a + 2] * y[2];
    for (std::size_t i = 0; i < scene.radii.size(); ++i)
      v += gc::lens_volume(gt::periodic_distance(p, &scene.centres[3 * i], L, periodic), scene.radii[i],
                           shape.radii[j]);
  }
  return v;
}

std::array<double, 9> rotation(double ax, double ay, double az, double angle) {
  const double n = std::sqrt(ax * ax + ay * ay + az * az);
  ax /= n; ay /= n; az /= n;
  const double c = std::cos(angle), s = std::sin(angle), C = 1 - c;
  return {c + ax * ax * C,      ax * ay * C - az * s, ax * az * C + ay * s,
          ay * ax * C + az * s, c + ay * ay * C,      ay * az * C - ax * s,
          az * ax * C - ay * s, az * ay * C + ax * s, c + az * az * C};
}

// Max |field - exact| over all nodes, relative to the shape's volume.
double field_error(const gt::Scene& scene, const gt::Scene& shape, const std::array<double, 9>& R,
                   const gc::GridSpec& g, double mode_factor) {
  gc::OverlapFieldOptions opt;
  opt.mode_factor = mode_factor;
  opt.tolerance = 1e-9;
  const auto f = translational_overlap_field(gc::BallSet{scene.centres, scene.radii},
                                             gc::BallSet{shape.centres, shape.radii}, R, g, opt);
  std::array<double, 3> L;
  for (int d = 0; d < 3; ++d) L[d] = g.dims[d] * g.spacing[d];
  double vshape = 0.0;
  for (double r : shape.radii) vshape += 4.0 / 3.0 * kPi * r * r * r;
  double worst = 0.0;
  for (std::size_t n = 0; n < f.size(); ++n)
    worst = std::max(worst, std::abs(f[n] - exact_overlap(scene, shape, R, g.node(n), L, g.periodic)));
  return worst / vshape;
}

}  // namespace

TEST(OverlapField, SphereAgainstSceneMatchesLensSums) {
  const double L = 1.0;
  const auto scene = gt::rsa_scene(L, {0.07, 0.1}, 50, 31);
  const gt::Scene sphere{{0.0, 0.0, 0.0}, {0.09}};
  gc::GridSpec g;
  g.dims = {24, 24, 24};
  g.spacing = {L / 24, L / 24, L / 24};
  const double e1 = field_error(scene, sphere, gc::kIdentityRotation, g, 1.0);
  const double e2 = field_error(scene, sphere, gc::kIdentityRotation, g, 2.0);
  const double e4 = field_error(scene, sphere, gc::kIdentityRotation, g, 4.0);
  std::printf("sphere overlap error / sphere volume: modes x1 %.3g  x2 %.3g  x4 %.3g\n", e1, e2, e4);
  EXPECT_LT(e2, e1);
  EXPECT_LT(e4, e2);
  EXPECT_LT(e4, 0.01);
}

TEST(OverlapField, RotatedClumpInPaddedBoxMatchesLensSums) {
  const double L = 1.0;
  const auto scene = gt::rsa_scene(L, {0.08}, 30, 32);
  // A three-ball clump (overlapping members) about its reference point.
  const gt::Scene clump{{-0.06, 0.0, 0.0, 0.06, 0.0, 0.0, 0.0, 0.05, 0.02}, {0.06, 0.06, 0.05}};
  const auto R = rotation(1, 2, 3, 0.7);
  gc::GridSpec g;
  g.dims = {20, 20, 20};
  g.spacing = {L / 20, L / 20, L / 20};
  g.periodic = {true, false, true};
  const double e2 = field_error(scene, clump, R, g, 2.0);
  const double e4 = field_error(scene, clump, R, g, 4.0);
  std::printf("clump overlap error / clump volume: modes x2 %.3g  x4 %.3g\n", e2, e4);
  EXPECT_LT(e4, e2);
  EXPECT_LT(e4, 0.02);
}

TEST(OverlapField, FreeNodesAreFree) {
  // Candidates read as V <= threshold, with the shape inflated by a margin:
  // every candidate is then free for the true shape (exact check).
  const double L = 1.0;
  const auto scene = gt::rsa_scene(L, {0.1}, 40, 33);
  const double s = 0.08, margin = 0.02;
  const gt::Scene inflated{{0.0, 0.0, 0.0}, {s + margin}};
  gc::GridSpec g;
  g.dims = {32, 32, 32};
  g.spacing = {L / 32, L / 32, L / 32};
  gc::OverlapFieldOptions opt;
  opt.mode_factor = 2.0;
  const auto f = translational_overlap_field(gc::BallSet{scene.centres, scene.radii},
                                             gc::BallSet{inflated.centres, inflated.radii},
                                             gc::kIdentityRotation, g, opt);
  // A penetration of the true shape by any amount means a penetration of at
  // least `margin` for the inflated one: lens volume >= lens(r + s, r, s + margin).
  const double threshold = 0.5 * gc::lens_volume(0.1 + s, 0.1, s + margin);
  const auto nodes = gc::free_nodes(f, threshold);
  ASSERT_GT(nodes.size(), 10u);
  std::size_t truly_free = 0;
  for (std::size_t n = 0; n < f.size(); ++n) {
    const auto t = g.node(n);
    double gap = 1e300;
    for (std::size_t i = 0; i < scene.radii.size(); ++i)
      gap = std::min(gap, gt::periodic_distance(t.data(), &scene.centres[3 * i], {L, L, L},
                                                {true, true, true}) - scene.radii[i] - s);
    if (gap > margin) ++truly_free;  // free even for the inflated shape
    if (std::binary_search(nodes.begin(), nodes.end(), n)) {
      EXPECT_GT(gap, 0.0) << n;
    }
  }
  // Nodes with clearance beyond the margin are all found.
  EXPECT_GE(nodes.size(), truly_free);
}

TEST(BallSpectrum, DirectSumAgreesWithTheNufft) {
  const gt::Scene shape{{0.0, 0.0, 0.0, 0.1, -0.02, 0.0, 0.03, 0.09, 0.04}, {0.07, 0.06, 0.05}};
  const std::vector<double> w{1.0, 0.5, -0.25};
  const gc::BallSet b{shape.centres, shape.radii, w};
  const gc::PeriodicBox box{{0.0, 0.0, 0.0}, {1.0, 0.8, 1.2}};
  const std::array<int, 3> K{12, 9, 14};
  gc::SpectrumOptions so;
  so.tolerance = 1e-10;
  const auto a = gc::ball_spectrum(b, box, K, so);
  const auto d = gc::ball_spectrum_direct(b, box, K);
  double worst = 0.0, big = 0.0;
  for (std::size_t q = 0; q < a.data().size(); ++q) {
    worst = std::max(worst, std::abs(a.data()[q] - d.data()[q]));
    big = std::max(big, std::abs(d.data()[q]));
  }
  EXPECT_GT(big, 1e-3);
  EXPECT_LT(worst / big, 1e-8);
}

// In a cubic box both spectra take the ball transform from a table indexed by
// m0^2 + m1^2 + m2^2 (other boxes evaluate it per mode, as above): checked
// against the definition F(m) = sum_i w_i e^{-i k.(x_i - o)} B_hat(|k|, r_i)
// summed here, with two balls sharing a radius.
TEST(BallSpectrum, CubicBoxMatchesTheDefinition) {
  const std::vector<double> c{0.2, 0.3, 0.1, 0.55, 0.45, 0.6, 0.8, 0.15, 0.7};
  const std::vector<double> r{0.07, 0.05, 0.07};
  const std::vector<double> w{1.0, -0.5, 0.25};
  const gc::BallSet b{c, r, w};
  const gc::PeriodicBox box{{0.1, -0.2, 0.05}, {1.1, 1.1, 1.1}};
  const std::array<int, 3> K{10, 10, 10};
  gc::SpectrumOptions so;
  so.tolerance = 1e-10;
  const auto a = gc::ball_spectrum(b, box, K, so);
  const auto d = gc::ball_spectrum_direct(b, box, K);
  double worst_d = 0.0, worst_a = 0.0, big = 0.0;
  for (int m2 = -K[2]; m2 <= K[2]; ++m2)
    for (int m1 = -K[1]; m1 <= K[1]; ++m1)
      for (int m0 = 0; m0 <= K[0]; ++m0) {
        const double kx = 2 * kPi * m0 / box.period[0], ky = 2 * kPi * m1 / box.period[1],
                     kz = 2 * kPi * m2 / box.period[2];
        std::complex<double> f{0.0, 0.0};
        for (std::size_t i = 0; i < r.size(); ++i) {
          const double phase = kx * (c[3 * i] - box.origin[0]) + ky * (c[3 * i + 1] - box.origin[1]) +
                               kz * (c[3 * i + 2] - box.origin[2]);
          f += w[i] * std::polar(1.0, -phase) *
               gc::ball_indicator_transform(std::sqrt(kx * kx + ky * ky + kz * kz), r[i]);
        }
        worst_d = std::max(worst_d, std::abs(d.at(m0, m1, m2) - f));
        worst_a = std::max(worst_a, std::abs(a.at(m0, m1, m2) - f));
        big = std::max(big, std::abs(f));
      }
  EXPECT_GT(big, 1e-3);
  EXPECT_LT(worst_d / big, 1e-13);
  EXPECT_LT(worst_a / big, 1e-8);
}

TEST(SceneOverlap, BallsAroundTheGridAndSeveralOrientations) {
  // The scene's spectrum once, two orientations of a clump; the scene's balls
  // lie beyond the grid's box on every side (as around an insertion region),
  // so no node may see a periodic image of them.
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> u(-0.3, 1.3);
  gt::Scene scene;
  for (int i = 0; i < 60; ++i) {
    scene.centres.insert(scene.centres.end(), {u(rng), u(rng), u(rng)});
    scene.radii.push_back(i % 2 ? 0.08 : 0.12);
  }
  const gt::Scene shape{{0.0, 0.0, 0.0, 0.1, 0.0, 0.0, 0.0, 0.09, 0.04}, {0.07, 0.06, 0.05}};
  double reach = 0.0, vshape = 0.0;
  for (std::size_t j = 0; j < shape.radii.size(); ++j) {
    const double* y = &shape.centres[3 * j];
    reach = std::max(reach, std::sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]) + shape.radii[j]);
    vshape += 4.0 / 3.0 * kPi * std::pow(shape.radii[j], 3);
  }
  gc::GridSpec g;
  g.dims = {21, 21, 21};
  g.spacing = {0.05, 0.05, 0.05};
  g.periodic = {false, false, false};
  gc::OverlapFieldOptions opt;
  opt.mode_factor = 2.0;
  const gc::SceneOverlap ov(gc::BallSet{scene.centres, scene.radii}, g, reach, opt);
  for (const auto& R : {gc::kIdentityRotation, rotation(1, 2, 3, 0.7)}) {
    const auto f = ov.field(gc::BallSet{shape.centres, shape.radii}, R);
    ASSERT_EQ(f.size(), g.num_nodes());
    double worst = 0.0, vmax = 0.0;
    for (std::size_t n = 0; n < f.size(); ++n) {
      const double e = exact_overlap(scene, shape, R, g.node(n), {1, 1, 1}, {false, false, false});
      worst = std::max(worst, std::abs(f[n] - e));
      vmax = std::max(vmax, e);
    }
    EXPECT_GT(vmax, 0.5 * vshape);  // the field sees real overlaps
    EXPECT_LT(worst / vshape, 1.5e-2);
  }
  const gt::Scene far{{0.3, 0.0, 0.0}, {0.1}};
  EXPECT_THROW((void)ov.field(gc::BallSet{far.centres, far.radii}, gc::kIdentityRotation), std::invalid_argument);
}

TEST(TruncatedOverlap, ErrorDecreasesWithRetainedModes) {
  // Two clumps; overlap at several relative placements.
  const gt::Scene a{{0.0, 0.0, 0.0, 0.12, 0.0, 0.0, 0.05, 0.1, 0.0}, {0.1, 0.08, 0.07}};
  const gt::Scene b{{0.0, 0.0, 0.0, 0.0, 0.0, 0.11, 0.0, 0.09, 0.05}, {0.09, 0.06, 0.06}};
  const gc::BallSet ba{a.centres, a.radii}, bb{b.centres, b.radii};
  const auto P = gc::TruncatedOverlap::safe_period(ba, bb, {0.2, 0.2, 0.2});
  gc::TruncatedOverlapOptions opt;
  opt.max_mode = {32, 32, 32};
  const gc::TruncatedOverlap q(ba, bb, P, opt);
  std::mt19937 rng(34);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  std::vector<std::array<double, 3>> ts;
  std::vector<double> exact;
  for (int i = 0; i < 40; ++i) {
    ts.push_back({u(rng), u(rng), u(rng)});
    exact.push_back(exact_overlap(a, b, gc::kIdentityRotation, ts.back(), {1e9, 1e9, 1e9},
                                  {false, false, false}));
  }
  double vmax = *std::max_element(exact.begin(), exact.end());
  ASSERT_GT(vmax, 0.0);
  std::vector<double> err;
  const std::vector<std::size_t> mp = {64, 512, 4096, 32768, q.num_modes()};
  for (std::size_t m : mp) {
    double e = 0.0;
    for (std::size_t i = 0; i < ts.size(); ++i) e += std::pow(q.overlap(ts[i], m) - exact[i], 2);
    err.push_back(std::sqrt(e / ts.size()) / vmax);
    std::printf("truncated query m' = %zu: rms error / max overlap = %.3g\n", m, err.back());
  }
  for (std::size_t i = 1; i < err.size(); ++i) EXPECT_LT(err[i], err[i - 1]) << mp[i];
  EXPECT_LT(err.back(), 0.01);
  // Far apart: no overlap, and the full-spectrum query says so.
  EXPECT_NEAR(q.overlap({0.0, 0.0, 0.0}, q.num_modes()),
              exact_overlap(a, b, gc::kIdentityRotation, {0, 0, 0}, {1e9, 1e9, 1e9}, {false, false, false}),
              0.01 * vmax);
}

namespace {

// A random half spectrum of a real field: m0 = 0 Hermitian in (m1, m2).
gc::HalfSpectrum random_half_spectrum(std::array<int, 3> K, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> v(-1.0, 1.0);
  gc::HalfSpectrum h(K);
  for (int m2 = -K[2]; m2 <= K[2]; ++m2)
    for (int m1 = -K[1]; m1 <= K[1]; ++m1)
      for (int m0 = 0; m0 <= K[0]; ++m0) h(m0, m1, m2) = {v(rng), v(rng)};
  for (int m2 = -K[2]; m2 <= K[2]; ++m2)
    for (int m1 = -K[1]; m1 <= K[1]; ++m1) {
      if (m2 < 0 || (m2 == 0 && m1 < 0)) h(0, m1, m2) = std::conj(h(0, -m1, -m2));
      if (m1 == 0 && m2 == 0) h(0, 0, 0) = {h(0, 0, 0).real(), 0.0};
    }
  return h;
}

}  // namespace

// The field at the nodes against the sum over every mode, including grids
// smaller than the spectrum (modes past the Nyquist fold onto their aliases)
// and grids of one or two nodes per axis.
TEST(SynthesizeOnGrid, MatchesTheSumOverModes) {
  std::mt19937_64 rng(17);
  const std::array<int, 3> K{3, 2, 4};
  const gc::HalfSpectrum h = random_half_spectrum(K, rng);
  for (const std::array<int, 3> T : {std::array<int, 3>{1, 2, 3}, std::array<int, 3>{5, 4, 7},
                                     std::array<int, 3>{8, 6, 10}, std::array<int, 3>{12, 9, 16}})
    for (int threads : {1, 2}) {
      const std::vector<double> f = gc::synthesize_on_grid(h, T, threads);
      ASSERT_EQ(f.size(), static_cast<std::size_t>(T[0]) * T[1] * T[2]);
      double worst = 0.0;
      for (int i2 = 0; i2 < T[2]; ++i2)
        for (int i1 = 0; i1 < T[1]; ++i1)
          for (int i0 = 0; i0 < T[0]; ++i0) {
            std::complex<double> sum{0.0, 0.0};
            for (int m2 = -K[2]; m2 <= K[2]; ++m2)
              for (int m1 = -K[1]; m1 <= K[1]; ++m1)
                for (int m0 = -K[0]; m0 <= K[0]; ++m0)
                  sum += h.at(m0, m1, m2) *
                         std::polar(1.0, 2 * kPi * (static_cast<double>(m0) * i0 / T[0] +
                                                    static_cast<double>(m1) * i1 / T[1] +
                                                    static_cast<double>(m2) * i2 / T[2]));
            EXPECT_LT(std::abs(sum.imag()), 1e-11);
            worst = std::max(worst, std::abs(f[(static_cast<std::size_t>(i2) * T[1] + i1) * T[0] + i0] - sum.real()));
          }
      EXPECT_LT(worst, 1e-11) << "T = " << T[0] << " x " << T[1] << " x " << T[2] << ", " << threads << " threads";
      // Only the first nodes per axis: the same values.
      const std::array<int, 3> keep{std::max(1, T[0] - 1), std::max(1, T[1] / 2), T[2]};
      const std::vector<double> part = gc::synthesize_on_grid(h, T, threads, keep);
      ASSERT_EQ(part.size(), static_cast<std::size_t>(keep[0]) * keep[1] * keep[2]);
      for (int i2 = 0; i2 < keep[2]; ++i2)
        for (int i1 = 0; i1 < keep[1]; ++i1)
          for (int i0 = 0; i0 < keep[0]; ++i0)
            ASSERT_EQ(part[(static_cast<std::size_t>(i2) * keep[1] + i1) * keep[0] + i0],
                      f[(static_cast<std::size_t>(i2) * T[1] + i1) * T[0] + i0]);
    }
  EXPECT_THROW(gc::synthesize_on_grid(h, {4, 4, 4}, 1, {5, 4, 4}), std::invalid_argument);
  EXPECT_THROW(gc::synthesize_on_grid(h, {4, 4, 4}, 1, {4, -1, 4}), std::invalid_argument);
}
