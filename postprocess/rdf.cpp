#include "postprocess/rdf.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "postprocess/cell_grid.hpp"

namespace grains::postprocess {

namespace {
bool inside(const Vec3& p, const Box& b) {
  return (p.array() >= b.lo.array()).all() && (p.array() <= b.hi.array()).all();
}
}  // namespace

Rdf radial_distribution(const std::vector<Vec3>& x, const Box& region, double r_max, int bins) {
  if (!(r_max > 0) || bins < 1) throw std::invalid_argument("RDF needs r_max > 0 and at least one bin");
  Rdf out;
  out.bin = r_max / bins;
  out.r.resize(static_cast<std::size_t>(bins));
  out.g.assign(static_cast<std::size_t>(bins), 0.0);
  for (int k = 0; k < bins; ++k) out.r[static_cast<std::size_t>(k)] = (k + 0.5) * out.bin;
  const Box inner{region.lo + Vec3::Constant(r_max), region.hi - Vec3::Constant(r_max)};
  std::vector<double> count(static_cast<std::size_t>(bins), 0.0);
  const CellGrid grid(x, r_max);
  const double r2max = r_max * r_max;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (inside(x[i], region)) ++out.n_region;
    if (!inside(x[i], inner)) continue;
    ++out.n_reference;
    grid.for_each_near(x[i], r_max, [&](std::size_t j) {
      if (j == i) return;
      const double d2 = (x[j] - x[i]).squaredNorm();
      if (d2 >= r2max) return;
      const auto k = static_cast<std::size_t>(std::sqrt(d2) / out.bin);
      if (k < count.size()) count[k] += 1;
    });
  }
  if (out.n_reference == 0)
    throw std::invalid_argument("RDF: no particle centre lies " + std::to_string(r_max) +
                                " m inside the region; use a larger region or a smaller r_max");
  out.density = static_cast<double>(out.n_region) / region.volume();
  for (std::size_t k = 0; k < count.size(); ++k) {
    const double a = k * out.bin, b = a + out.bin;
    const double shell = 4.0 / 3.0 * M_PI * (b * b * b - a * a * a);
    out.g[k] = count[k] / (static_cast<double>(out.n_reference) * out.density * shell);
  }
  return out;
}

std::vector<double> rdf_peaks(const Rdf& g, double min_height) {
  std::vector<double> p;
  for (std::size_t k = 1; k + 1 < g.g.size(); ++k)
    if (g.g[k] > min_height && g.g[k] > g.g[k - 1] && g.g[k] >= g.g[k + 1]) p.push_back(g.r[k]);
  return p;
}

}  // namespace grains::postprocess
