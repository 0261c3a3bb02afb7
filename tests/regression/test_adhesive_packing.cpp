// Packing regression of adhesive spheres, CI size (label `regression`,
// about a minute): JKR micro-spheres deposited one by one onto a plate
// (cases/adhesive_deposition, 2,000 grains in a 10 d x 10 d periodic box)
// at adhesion parameters Ad = w / (2 rho U0^2 R) = 0.1, 1 and 10, the random
// loose, the onset of the adhesive and the adhesive regime of Liu, Li &
// Chen (arXiv:1511.02315). References, bands and sources:
// tests/regression/packing_references.yaml (adhesive_*); the full sweep is
// PackingLong.AdhesiveDepositionSweep (test_packing_long.cpp).
#include "tests/regression/packing_support.hpp"

namespace grains::test::packing {
namespace {

TEST(Packing, AdhesiveDepositionSweep) {
  const Reference rlp = reference("adhesive_rlp_phi"), alp = reference("adhesive_alp_phi"),
                  alpz = reference("adhesive_alp_z"), fall = reference("adhesive_phi_fall");
  const std::vector<double> ads = {0.1, 1, 10};
  DepositConfig c;  // 2,000 grains, 15 d x 15 d, seed 1
  std::vector<double> phi, z;
  for (double ad : ads) {
    const DepositResult r = deposit_adhesive(ad, c);
    // Without gravity a grain that rebounds (low Ad) leaves through the top.
    EXPECT_GE(r.n, static_cast<std::size_t>(0.98 * c.count)) << "grains lost or not inserted at Ad = " << ad;
    EXPECT_LE(r.n, static_cast<std::size_t>(c.count));
    // At rest: the structure no longer changes (grains landing on it would
    // move phi by ~0.01 and Z by ~0.1). What still moves is a rocking of the
    // network on its contacts, about 5 mm/s rms whatever U0 (measured; the
    // EPSD rolling spring has no dashpot), printed with the result.
    EXPECT_LT(std::abs(r.phi_change), 0.002) << "the deposit is still changing at Ad = " << ad;
    EXPECT_LT(std::abs(r.z_change), 0.02) << "the deposit is still changing at Ad = " << ad;
    EXPECT_GT(r.bulk_height, 10 * 1e-5) << "bulk region too thin at Ad = " << ad;
    phi.push_back(r.phi);
    z.push_back(r.z);
  }
  record("adhesive_ci", Record()
                            .str("case", "adhesive deposition, 2,000 grains in 10 d x 10 d, one seed")
                            .nums("ad", ads)
                            .nums("phi", phi)
                            .nums("z", z)
                            .num("sigma_run", kDepositSigma));
  expect_in_band(rlp, phi[0], "Ad = 0.1");
  expect_in_band(alp, phi[2], "Ad = 10");
  expect_in_band(alpz, z[2], "Z at Ad = 10");
  // Looser and fewer contacts at every step up in adhesion, far beyond the
  // seed-to-seed noise (kDepositSigma).
  const double sd_diff = std::sqrt(2.0) * kDepositSigma;
  for (std::size_t k = 0; k + 1 < ads.size(); ++k) {
    EXPECT_GT(phi[k] - phi[k + 1], 3 * sd_diff) << "phi does not fall from Ad = " << ads[k] << " to " << ads[k + 1];
    EXPECT_GT(z[k], z[k + 1]) << "Z does not fall from Ad = " << ads[k] << " to " << ads[k + 1];
  }
  expect_in_band(fall, phi.front() - phi.back(), "phi(0.1) - phi(10)");
}

}  // namespace
}  // namespace grains::test::packing
