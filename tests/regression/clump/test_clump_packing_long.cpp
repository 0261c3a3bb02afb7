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
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace grains::test
