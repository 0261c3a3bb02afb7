// `grains analyze` on output.stress's series (postprocess/stress_series.hpp):
// written series with known values, read back through the command.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "io/cli/analyze_command.hpp"
#include "postprocess/stress_series.hpp"
#include "tests/support/temp_dir.hpp"

namespace grains::test {
namespace {

namespace pp = grains::postprocess;

const char* kHeader =
    "step,time_s,volume_m3,grains,solid_fraction,vx_mps,vy_mps,vz_mps,sxx_Pa,syy_Pa,szz_Pa,sxy_Pa,sxz_Pa,syz_Pa,"
    "kxx_Pa,kyy_Pa,kzz_Pa,kxy_Pa,kxz_Pa,kyz_Pa,pressure_Pa";

// Rows at t = 0.1 k (k = 0..19): before t = 1, sigma_xy = -100 and phi 0.3
// (a transient); from t = 1 on sigma = diag(120, 100, 80) + xy -40 (k even)
// or -60 (k odd), phi 0.58 or 0.60.
void write_series(const std::filesystem::path& dir, const std::string& summary_after = "") {
  std::ofstream f(dir / "stress.csv");
  f << kHeader << "\n";
  for (int k = 0; k < 20; ++k) {
    const double t = 0.1 * k;
    const bool late = k >= 10;
    const double sxy = late ? (k % 2 ? -60 : -40) : -100, phi = late ? (k % 2 ? 0.60 : 0.58) : 0.3;
    f << k * 10 << "," << t << ",1e-6,100," << phi << ",0.1,0,0,120,100,80," << sxy << ",0,0,1,2,3,0,0,0,100\n";
  }
  if (!summary_after.empty())
    std::ofstream(dir / "summary.json") << "{\"stage_details\": {\"output: output.stress(every 10 steps)\": "
                                           "{\"stress\": {\"file\": \"stress.csv\", \"average_after_s\": "
                                        << summary_after << "}}}}\n";
}

TEST(StressSeries, MeansErrorsAndInvariantsOverTheWindow) {
  TempDir tmp("stress_series");
  write_series(tmp.path);
  const auto s = pp::read_stress_series(tmp.path, 1.0);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->rows, 10u);
  EXPECT_NEAR(s->region.stress[3], -50, 1e-12);
  EXPECT_NEAR(s->region.solid_fraction, 0.59, 1e-12);
  // Five blocks of two rows each have the same mean: no spread.
  EXPECT_NEAR(s->region.stress_err[3], 0, 1e-12);
  EXPECT_NEAR(s->pressure, 100, 1e-12);
  // J2 = (20^2 + 0 + 20^2)/2 + 50^2 = 2900.
  EXPECT_NEAR(s->shear, std::sqrt(2900.0), 1e-12);
  EXPECT_NEAR(s->friction, std::sqrt(2900.0) / 100, 1e-12);
  EXPECT_NEAR(s->ratios[0], 0.5, 1e-12) << "|s_xy| / s_yy";
  EXPECT_NEAR(s->region.kinetic[2], 3, 1e-12);
  EXPECT_TRUE(s->profile.empty());
  // Profiles: two bins, each averaged over the window's rows.
  {
    std::ofstream f(tmp.path / "profile.csv");
    f << "step,time_s,bin,position_m,grains,solid_fraction,vx_mps,vy_mps,vz_mps,sxx_Pa,syy_Pa,szz_Pa,sxy_Pa,sxz_Pa,"
         "syz_Pa,kxx_Pa,kyy_Pa,kzz_Pa,kxy_Pa,kxz_Pa,kyz_Pa\n";
    for (int k = 0; k < 20; ++k)
      for (int b = 0; b < 2; ++b)
        f << k * 10 << "," << 0.1 * k << "," << b << "," << 0.001 * (b + 0.5) << ",50,0.5," << (b ? k : -k)
          << ",0,0,1,2,3,4,5,6,0,0,0,0,0,0\n";
  }
  const auto sp = pp::read_stress_series(tmp.path, 1.0);
  ASSERT_EQ(sp->profile.size(), 2u);
  EXPECT_NEAR(sp->profile_position[1], 0.0015, 1e-15);
  EXPECT_NEAR(sp->profile[1].velocity[0], 14.5, 1e-12) << "the mean of k = 10 ... 19";
  EXPECT_NEAR(sp->profile[0].velocity[0], -14.5, 1e-12);
  // A window that starts in the transient: its rows count.
  EXPECT_NEAR(pp::read_stress_series(tmp.path, 0.5)->region.stress[3], (5 * -100 - 500) / 15.0, 1e-12);
}

TEST(StressSeries, TheWindowDefaultsToTheRunsAverageAfterElseTheSecondHalf) {
  TempDir tmp("stress_series_default");
  write_series(tmp.path);
  EXPECT_NEAR(pp::read_stress_series(tmp.path, std::nullopt)->from, 0.95, 1e-12) << "the series' second half";
  write_series(tmp.path, "1.45");
  const auto s = pp::read_stress_series(tmp.path, std::nullopt);
  EXPECT_NEAR(s->from, 1.45, 1e-12);
  EXPECT_EQ(s->rows, 5u);
}

TEST(StressSeries, AnalyzeWritesItAndBadSeriesAreLocatedErrors) {
  TempDir tmp("stress_series_cli");
  write_series(tmp.path, "1.0");
  std::ostringstream out, err;
  ASSERT_EQ(io::run_analyze_command({tmp.path.string()}, out, err), 0) << err.str();
  EXPECT_NE(out.str().find("|xy|/yy 0.5"), std::string::npos) << out.str();
  std::ifstream j(tmp.path / "analysis" / "stress_series.json");
  std::stringstream text;
  text << j.rdbuf();
  EXPECT_NE(text.str().find("\"friction\": "), std::string::npos);
  // No row in the window.
  std::ostringstream o2, e2;
  EXPECT_EQ(io::run_analyze_command({tmp.path.string(), "--from", "5"}, o2, e2), 2);
  EXPECT_NE(e2.str().find("no row at or after t = 5 s"), std::string::npos) << e2.str();
  // A malformed row: the file and line.
  std::ofstream(tmp.path / "stress.csv", std::ios::app) << "1,2,3\n";
  std::ostringstream o3, e3;
  EXPECT_EQ(io::run_analyze_command({tmp.path.string()}, o3, e3), 2);
  EXPECT_NE(e3.str().find("stress.csv:22: 3 values, the header has 21"), std::string::npos) << e3.str();
}

}  // namespace
}  // namespace grains::test
