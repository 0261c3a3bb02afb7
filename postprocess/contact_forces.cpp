#include "postprocess/contact_forces.hpp"

#include <algorithm>
#include <cmath>

namespace grains::postprocess {

ContactForceDistribution contact_force_distribution(const Frame& f, const std::vector<Contact>& contacts,
                                                    const Box& region, double bin, double f_max) {
  ContactForceDistribution d;
  d.bin = bin;
  for (std::size_t i = 1; i < f.material.size(); ++i)
    if (f.material[i] != f.material[0]) d.single_material = false;
  std::vector<double> force;
  double rel = 0;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const auto& c = contacts[k];
    if (c.overlap <= 0) continue;
    if (!((c.point.array() >= region.lo.array()).all() && (c.point.array() <= region.hi.array()).all())) continue;
    d.selected.push_back(k);
    force.push_back(std::sqrt(c.radius) * std::pow(c.overlap, 1.5));
    d.mean_overlap += c.overlap;
    d.max_overlap = std::max(d.max_overlap, c.overlap);
    rel += c.overlap / (2 * c.radius);
  }
  d.n_contacts = force.size();
  const auto nb = static_cast<std::size_t>(std::ceil(f_max / bin));
  d.centre.resize(nb);
  d.pdf.assign(nb, 0.0);
  for (std::size_t k = 0; k < nb; ++k) d.centre[k] = (k + 0.5) * bin;
  if (force.empty()) return d;
  d.mean_overlap /= static_cast<double>(force.size());
  d.mean_relative_overlap = rel / static_cast<double>(force.size());
  double mean = 0;
  for (double v : force) mean += v;
  mean /= static_cast<double>(force.size());
  d.f_over_mean.resize(force.size());
  for (std::size_t k = 0; k < force.size(); ++k) {
    d.f_over_mean[k] = force[k] / mean;
    const auto b = static_cast<std::size_t>(d.f_over_mean[k] / bin);
    if (b < nb) d.pdf[b] += 1;
  }
  // Unit area over all contacts (those beyond f_max count in the normalisation).
  for (auto& p : d.pdf) p /= static_cast<double>(force.size()) * bin;
  return d;
}

}  // namespace grains::postprocess
