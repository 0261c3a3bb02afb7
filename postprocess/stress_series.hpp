#pragma once
// `grains analyze` on a run's stress series (output.stress: stress.csv, and
// profile.csv with profiles): the means from a time on, with the standard
// error of five consecutive blocks, and the invariants a granular rheology
// reads -- the pressure p = tr(sigma)/3, the shear stress tau = sqrt(J2) and
// the friction tau/p, plus each off-diagonal component over each diagonal
// one (sigma_xy/sigma_yy in a shear cell with gradient y; sigma_xz/sigma_zz
// on a chute). Compressive stresses are positive, as output.stress writes them.
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace grains::postprocess {

struct StressMeans {
  std::array<double, 6> stress{}, stress_err{};  // xx, yy, zz, xy, xz, yz (contact + kinetic), Pa
  std::array<double, 6> kinetic{};               // the kinetic part, Pa
  std::array<double, 3> velocity{};              // mean velocity, m/s
  double solid_fraction = 0, solid_fraction_err = 0;
  double grains = 0;                             // mean count of centres
};

struct StressSeries {
  double from = 0;        // s: the rows averaged are those with time >= from
  std::size_t rows = 0;   // of stress.csv averaged
  double first_time = 0, last_time = 0;
  StressMeans region;     // the whole region of output.stress
  double pressure = 0, shear = 0, friction = 0;  // p, sqrt(J2), sqrt(J2)/p
  std::array<double, 6> ratios{};  // |s_xy|/s_yy, |s_xz|/s_zz, |s_yz|/s_zz, |s_xy|/s_xx, |s_xz|/s_xx, |s_yz|/s_yy
  std::vector<double> profile_position;  // bin centres, m (empty without profile.csv)
  std::vector<StressMeans> profile;      // per bin, over the same rows
};

/// Reads OUTDIR/stress.csv (and profile.csv when present) and averages the
/// rows from `from` on; without `from`, from the run's average_after when
/// summary.json gives one, else over the second half of the series. Empty
/// (nullopt) when the run wrote no stress.csv; std::invalid_argument for a
/// malformed file or no row in the window.
std::optional<StressSeries> read_stress_series(const std::filesystem::path& dir, std::optional<double> from);

/// stress_series.json text.
std::string stress_series_json(const StressSeries& s);
/// A few lines for the terminal.
std::string stress_series_summary(const StressSeries& s);

}  // namespace grains::postprocess
