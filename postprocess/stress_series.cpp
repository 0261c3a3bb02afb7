#include "postprocess/stress_series.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace grains::postprocess {

namespace fs = std::filesystem;

namespace {

const char* kSym[6] = {"xx", "yy", "zz", "xy", "xz", "yz"};

struct Table {
  std::map<std::string, std::size_t> col;
  std::vector<std::vector<double>> rows;
  std::size_t at(const std::string& name, const fs::path& f) const {
    const auto it = col.find(name);
    if (it == col.end()) throw std::invalid_argument(f.string() + ": no column '" + name + "'");
    return it->second;
  }
};

Table read_table(const fs::path& f) {
  std::ifstream in(f);
  if (!in) throw std::invalid_argument("cannot read " + f.string());
  Table t;
  std::string line;
  if (!std::getline(in, line)) throw std::invalid_argument(f.string() + ": empty");
  {
    std::stringstream h(line);
    std::string name;
    for (std::size_t k = 0; std::getline(h, name, ','); ++k) t.col[name] = k;
  }
  for (std::size_t n = 2; std::getline(in, line); ++n) {
    if (line.empty()) continue;
    std::vector<double> row;
    std::stringstream r(line);
    std::string cell;
    while (std::getline(r, cell, ',')) {
      char* end = nullptr;
      row.push_back(std::strtod(cell.c_str(), &end));
      if (end == cell.c_str()) throw std::invalid_argument(f.string() + ":" + std::to_string(n) + ": not a number: '" + cell + "'");
    }
    if (row.size() != t.col.size())
      throw std::invalid_argument(f.string() + ":" + std::to_string(n) + ": " + std::to_string(row.size()) +
                                  " values, the header has " + std::to_string(t.col.size()));
    t.rows.push_back(std::move(row));
  }
  return t;
}

// The run's average_after from summary.json (output.stress's), if any.
std::optional<double> average_after(const fs::path& dir) {
  std::ifstream in(dir / "summary.json");
  if (!in) return std::nullopt;
  std::stringstream s;
  s << in.rdbuf();
  std::smatch m;
  const std::string text = s.str();
  if (std::regex_search(text, m, std::regex("\"average_after_s\": *([-+0-9.eE]+)"))) return std::stod(m[1].str());
  return std::nullopt;
}

// Means of the rows (indices) with the standard error of five blocks.
StressMeans means(const Table& t, const std::vector<std::size_t>& rows, const fs::path& f) {
  StressMeans m;
  auto mean_of = [&](std::size_t c, std::size_t b0, std::size_t b1) {
    double s = 0;
    for (std::size_t k = b0; k < b1; ++k) s += t.rows[rows[k]][c];
    return s / static_cast<double>(b1 - b0);
  };
  auto err_of = [&](std::size_t c) {
    const std::size_t b = rows.size() / 5;
    if (b == 0) return std::nan("");
    double blocks[5], avg = 0;
    for (std::size_t k = 0; k < 5; ++k) avg += (blocks[k] = mean_of(c, k * b, (k + 1) * b)) / 5;
    double v = 0;
    for (double x : blocks) v += (x - avg) * (x - avg);
    return std::sqrt(v / 4 / 5);
  };
  for (std::size_t k = 0; k < 6; ++k) {
    const std::size_t c = t.at(std::string("s") + kSym[k] + "_Pa", f);
    m.stress[k] = mean_of(c, 0, rows.size());
    m.stress_err[k] = err_of(c);
    m.kinetic[k] = mean_of(t.at(std::string("k") + kSym[k] + "_Pa", f), 0, rows.size());
  }
  const char* v[3] = {"vx_mps", "vy_mps", "vz_mps"};
  for (std::size_t d = 0; d < 3; ++d) m.velocity[d] = mean_of(t.at(v[d], f), 0, rows.size());
  m.solid_fraction = mean_of(t.at("solid_fraction", f), 0, rows.size());
  m.solid_fraction_err = err_of(t.at("solid_fraction", f));
  m.grains = mean_of(t.at("grains", f), 0, rows.size());
  return m;
}

void put_array(std::ostringstream& o, const double* x, std::size_t n) {
  o << "[";
  for (std::size_t k = 0; k < n; ++k) o << (k ? ", " : "") << (std::isfinite(x[k]) ? x[k] : 0.0);
  o << "]";
}

}  // namespace

std::optional<StressSeries> read_stress_series(const fs::path& dir, std::optional<double> from) {
  const fs::path sf = dir / "stress.csv";
  if (!fs::exists(sf)) return std::nullopt;
  const Table t = read_table(sf);
  if (t.rows.empty()) throw std::invalid_argument(sf.string() + ": no rows");
  const std::size_t tc = t.at("time_s", sf);
  StressSeries s;
  s.first_time = t.rows.front()[tc];
  s.last_time = t.rows.back()[tc];
  if (!from) from = average_after(dir);
  if (!from) from = 0.5 * (s.first_time + s.last_time);
  s.from = *from;
  std::vector<std::size_t> rows;
  for (std::size_t k = 0; k < t.rows.size(); ++k)
    if (t.rows[k][tc] >= s.from) rows.push_back(k);
  if (rows.empty()) {
    std::ostringstream m;
    m << sf.string() << ": no row at or after t = " << s.from << " s (the series runs from " << s.first_time
      << " to " << s.last_time << " s)";
    throw std::invalid_argument(m.str());
  }
  s.rows = rows.size();
  s.region = means(t, rows, sf);
  const auto& a = s.region.stress;
  s.pressure = (a[0] + a[1] + a[2]) / 3;
  const double dx = a[0] - s.pressure, dy = a[1] - s.pressure, dz = a[2] - s.pressure;
  s.shear = std::sqrt(0.5 * (dx * dx + dy * dy + dz * dz) + a[3] * a[3] + a[4] * a[4] + a[5] * a[5]);
  s.friction = s.pressure != 0 ? s.shear / s.pressure : std::nan("");
  auto ratio = [](double off, double diag) { return diag != 0 ? std::abs(off) / diag : std::nan(""); };
  s.ratios = {ratio(a[3], a[1]), ratio(a[4], a[2]), ratio(a[5], a[2]),
              ratio(a[3], a[0]), ratio(a[4], a[0]), ratio(a[5], a[1])};
  const fs::path pf = dir / "profile.csv";
  if (fs::exists(pf)) {
    const Table p = read_table(pf);
    const std::size_t ptc = p.at("time_s", pf), bc = p.at("bin", pf), xc = p.at("position_m", pf);
    std::map<long, std::vector<std::size_t>> bins;
    std::map<long, double> where;
    for (std::size_t k = 0; k < p.rows.size(); ++k)
      if (p.rows[k][ptc] >= s.from) {
        const long b = std::lround(p.rows[k][bc]);
        bins[b].push_back(k);
        where[b] = p.rows[k][xc];
      }
    for (const auto& [b, r] : bins) {
      s.profile_position.push_back(where[b]);
      s.profile.push_back(means(p, r, pf));
    }
  }
  return s;
}

std::string stress_series_json(const StressSeries& s) {
  std::ostringstream o;
  o.precision(10);
  auto block = [&](const StressMeans& m) {
    o << "{\"stress_Pa\": ";
    put_array(o, m.stress.data(), 6);
    o << ", \"stress_err_Pa\": ";
    put_array(o, m.stress_err.data(), 6);
    o << ", \"kinetic_stress_Pa\": ";
    put_array(o, m.kinetic.data(), 6);
    o << ", \"velocity_mps\": ";
    put_array(o, m.velocity.data(), 3);
    o << ", \"solid_fraction\": " << m.solid_fraction << ", \"solid_fraction_err\": "
      << (std::isfinite(m.solid_fraction_err) ? m.solid_fraction_err : 0.0) << ", \"grains\": " << m.grains << "}";
  };
  o << "{\n \"components\": [\"xx\", \"yy\", \"zz\", \"xy\", \"xz\", \"yz\"],\n \"from_s\": " << s.from
    << ",\n \"rows\": " << s.rows << ",\n \"series_s\": [" << s.first_time << ", " << s.last_time
    << "],\n \"region\": ";
  block(s.region);
  o << ",\n \"pressure_Pa\": " << s.pressure << ",\n \"shear_stress_Pa\": " << s.shear
    << ",\n \"friction\": " << s.friction << ",\n \"ratios\": {\"xy/yy\": " << s.ratios[0]
    << ", \"xz/zz\": " << s.ratios[1] << ", \"yz/zz\": " << s.ratios[2] << ", \"xy/xx\": " << s.ratios[3]
    << ", \"xz/xx\": " << s.ratios[4] << ", \"yz/yy\": " << s.ratios[5] << "},\n \"profile\": [";
  for (std::size_t b = 0; b < s.profile.size(); ++b) {
    o << (b ? ",\n  " : "\n  ") << "{\"position_m\": " << s.profile_position[b] << ", \"means\": ";
    block(s.profile[b]);
    o << "}";
  }
  o << "]\n}\n";
  return o.str();
}

std::string stress_series_summary(const StressSeries& s) {
  std::ostringstream o;
  o.precision(4);
  const auto& a = s.region.stress;
  o << "stress series: " << s.rows << " rows from t = " << s.from << " s; solid fraction "
    << s.region.solid_fraction << "; p = " << s.pressure << " Pa, sqrt(J2)/p = " << s.friction << "\n"
    << "  sigma (Pa): xx " << a[0] << ", yy " << a[1] << ", zz " << a[2] << ", xy " << a[3] << ", xz " << a[4]
    << ", yz " << a[5] << "; |xy|/yy " << s.ratios[0] << ", |xz|/zz " << s.ratios[1] << "\n";
  if (!s.profile.empty()) o << "  profile: " << s.profile.size() << " bins\n";
  return o.str();
}

}  // namespace grains::postprocess
