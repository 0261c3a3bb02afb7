#include "sim/scene/shear_pressure_stage.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "sim/parallel/exchange.hpp"
#include "sim/scene/scene_config.hpp"
#include "sim/walls/wall_control_stage.hpp"

namespace grains::sim {

namespace {

Vec3 axis_vector(int a) {
  Vec3 e = Vec3::Zero();
  e[a] = 1;
  return e;
}

}  // namespace

void setup_shear_pressure(const Scene& s, const std::string& where) {
  if (!s.domain.shear.servo()) return;
  std::string why;
  if (box_cross_section(s, axis_vector(s.domain.shear.gradient), &why) == 0)
    throw SetupError(where + ": domain.shear.pressure needs the cell's volume: " + why);
}

void ShearPressure::arm(Scene& s) {
  probe_.whole = true;
  probe_.bins = 0;
  probe_.reset(omp_get_max_threads());
  probe_.next = nullptr;
  s.stress_probe = &probe_;  // first: the outputs' probes chain in front of it
  height_ = min_height_ = max_height_ = s.domain.hi[s.domain.shear.gradient] - s.domain.lo[s.domain.shear.gradient];
}

void ShearPressure::run(Scene& s) {
  Domain& d = s.domain;
  const int g = d.shear.gradient;
  const auto& p = s.particles;
  // The contact virial across the gradient, then the kinetic sums: mass,
  // momentum and sum m v^2 along the gradient (held grains take no part).
  sums_.assign(4, 0.0);
  for (const auto& row : probe_.rows) sums_[0] += row[0][static_cast<std::size_t>(g)];
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    if (!(p.inv_mass[i] > 0)) continue;
    const double v = p.v[i][g];
    sums_[1] += p.mass[i];
    sums_[2] += p.mass[i] * v;
    sums_[3] += p.mass[i] * v * v;
  }
  if (s.exchange) s.exchange->comm().sum_in_place(sums_);
  const double kinetic = sums_[1] > 0 ? sums_[3] - sums_[2] * sums_[2] / sums_[1] : 0.0;
  const double L = d.hi[g] - d.lo[g];
  const double volume = L * box_cross_section(s, axis_vector(g), nullptr);
  sigma_ = (sums_[0] + kinetic) / volume;
  const double P = d.shear.pressure;
  const double cap = d.shear.max_dilation > 0 ? d.shear.max_dilation : std::abs(d.shear.rate);
  dilation_ = std::clamp(d.shear.gain * std::abs(d.shear.rate) * (sigma_ - P) / P, -cap, cap);
  // The state after this step is at clock.time + dt (the clock moves on after the kick).
  const double factor = 1 + dilation_ * s.clock.dt;
  const double lo = d.lo[g];
  auto& x = s.particles.x;
  for (std::size_t i = 0; i < p.n_owned(); ++i) x[i][g] = lo + (x[i][g] - lo) * factor;
  d.set_gradient_length(L * factor, s.clock.time + s.clock.dt);
  height_ = L * factor;
  min_height_ = std::min(min_height_, height_);
  max_height_ = std::max(max_height_, height_);
  // The images across the gradient moved by the change, and along the flow
  // faster than the list's image speed (the start's) when the cell grew.
  s.neighbors.add_image_travel(std::abs(height_ - L) +
                               std::max(0.0, std::abs(d.shear_speed()) - s.neighbors.image_speed()) * s.clock.dt);
  if (s.exchange) s.exchange->set_domain(d);
  probe_.reset(omp_get_max_threads());
}

void ShearPressure::finish(Scene& s) {
  s.stress_probe = nullptr;  // the end of the chain: no probe stays armed
}

std::string ShearPressure::summary_json() const {
  std::ostringstream o;
  o.precision(10);
  o << "\"shear_cell\": {\"height_m\": " << height_ << ", \"min_height_m\": " << min_height_
    << ", \"max_height_m\": " << max_height_ << ", \"sigma_gradient_Pa\": " << sigma_
    << ", \"dilation_rate_per_s\": " << dilation_ << "}";
  return o.str();
}

}  // namespace grains::sim
