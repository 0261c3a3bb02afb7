#include "postprocess/contacts.hpp"

#include <algorithm>
#include <map>
#include <set>

#include "contact/ellipsoid/ellipsoid_contact.hpp"
#include "postprocess/cell_grid.hpp"

namespace grains::postprocess {

std::vector<Contact> find_contacts(const Frame& f, const ContactOptions& o) {
  const std::size_t n = f.size();
  std::vector<Contact> out;
  if (n == 0) return out;
  double rmax = 0;
  for (std::size_t i = 0; i < n; ++i) rmax = std::max(rmax, f.bounding_radius(i));
  const CellGrid grid(f.x, 2 * rmax + o.gap);
  const bool ell = f.has_ellipsoids() && f.has_orientation();
  std::vector<contact::SymMat3> q;
  if (ell) {
    q.resize(n);
    for (std::size_t i = 0; i < n; ++i) q[i] = contact::quadratic_form(f.semi_axes[i], f.orientation[i]);
  }
  const bool bodies = !f.body.empty();
  for (std::size_t i = 0; i < n; ++i) {
    const double bi = f.bounding_radius(i);
    grid.for_each_near(f.x[i], bi + rmax + o.gap, [&](std::size_t j) {
      if (j <= i) return;
      if (bodies && f.body[i] == f.body[j]) return;
      const Vec3 d = f.x[i] - f.x[j];
      const double reach = bi + f.bounding_radius(j) + o.gap;
      const double d2 = d.squaredNorm();
      if (d2 >= reach * reach) return;
      Contact c;
      c.i = i;
      c.j = j;
      if (!ell) {
        const double dist = std::sqrt(d2);
        c.overlap = f.radius[i] + f.radius[j] - dist;
        c.normal = dist > 0 ? Vec3(d / dist) : Vec3(0, 0, 1);
        c.point = f.x[j] + c.normal * (f.radius[j] - 0.5 * c.overlap);
        c.radius = f.radius[i] * f.radius[j] / (f.radius[i] + f.radius[j]);
      } else {
        const auto e = contact::ellipsoid_contact(f.x[i], q[i], f.x[j], q[j]);
        if (!e.pw85.converged()) return;
        c.overlap = e.geometry.overlap;
        c.normal = e.geometry.normal;
        c.point = e.geometry.point;
        c.radius = e.geometry.radius;
      }
      if (c.overlap > -o.gap) out.push_back(c);
    });
  }
  return out;
}

Units units_of(const Frame& f) {
  Units u;
  const std::size_t n = f.size();
  u.of.resize(n);
  if (f.body.empty()) {
    for (std::size_t i = 0; i < n; ++i) u.of[i] = i;
    u.count = n;
    u.centre = f.x;
    return u;
  }
  std::map<std::int64_t, std::size_t> index;
  std::vector<double> mass;
  for (std::size_t i = 0; i < n; ++i) {
    auto [it, fresh] = index.emplace(f.body[i], index.size());
    if (fresh) {
      u.centre.emplace_back(0, 0, 0);
      mass.push_back(0);
    }
    u.of[i] = it->second;
    const double v = f.particle_volume(i);
    u.centre[it->second] += v * f.x[i];
    mass[it->second] += v;
  }
  for (std::size_t k = 0; k < u.centre.size(); ++k) u.centre[k] /= mass[k];
  u.count = u.centre.size();
  return u;
}

Coordination coordination(const Frame&, const Units& u, const std::vector<Contact>& contacts, const Box& region,
                          int min_contacts, RattlerRule rule, const std::vector<int>& wall_z) {
  // Unit-level neighbour sets (clump pairs touching through several balls count once).
  std::vector<std::vector<std::size_t>> nb(u.count);
  {
    std::set<std::pair<std::size_t, std::size_t>> seen;
    for (const auto& c : contacts) {
      std::size_t a = u.of[c.i], b = u.of[c.j];
      if (a == b) continue;
      if (a > b) std::swap(a, b);
      if (!seen.emplace(a, b).second) continue;
      nb[a].push_back(b);
      nb[b].push_back(a);
    }
  }
  Coordination r;
  r.z.resize(u.count);
  std::vector<int> walls(u.count, 0);
  for (std::size_t i = 0; i < wall_z.size() && i < u.of.size(); ++i) walls[u.of[i]] += wall_z[i];
  for (std::size_t k = 0; k < u.count; ++k) r.z[k] = static_cast<int>(nb[k].size()) + walls[k];
  r.rattler.assign(u.count, 0);
  std::vector<std::size_t> queue;
  for (std::size_t k = 0; k < u.count; ++k)
    if (r.z[k] < min_contacts) {
      r.rattler[k] = 1;
      queue.push_back(k);
    }
  if (rule == RattlerRule::iterative) {
    // Removing a rattler takes one contact from each neighbour; repeat.
    std::vector<int> left = r.z;
    while (!queue.empty()) {
      const std::size_t k = queue.back();
      queue.pop_back();
      for (std::size_t m : nb[k]) {
        if (r.rattler[m]) continue;
        if (--left[m] < min_contacts) {
          r.rattler[m] = 1;
          queue.push_back(m);
        }
      }
    }
  }
  r.z_rigid.assign(u.count, 0);
  for (std::size_t k = 0; k < u.count; ++k) {
    if (r.rattler[k]) continue;
    r.z_rigid[k] = walls[k];
    for (std::size_t m : nb[k])
      if (!r.rattler[m]) ++r.z_rigid[k];
  }
  double sz = 0, szr = 0;
  std::size_t rigid = 0;
  for (std::size_t k = 0; k < u.count; ++k) {
    const Vec3& c = u.centre[k];
    if (!((c.array() >= region.lo.array()).all() && (c.array() <= region.hi.array()).all())) continue;
    ++r.n_selected;
    sz += r.z[k];
    const auto zk = static_cast<std::size_t>(r.z[k]);
    if (r.histogram.size() <= zk) r.histogram.resize(zk + 1, 0);
    ++r.histogram[zk];
    if (r.rattler[k]) {
      ++r.n_rattlers;
    } else {
      szr += r.z_rigid[k];
      ++rigid;
    }
  }
  if (r.n_selected > 0) {
    r.mean_z = sz / static_cast<double>(r.n_selected);
    r.rattler_fraction = static_cast<double>(r.n_rattlers) / static_cast<double>(r.n_selected);
  }
  if (rigid > 0) r.mean_z_without_rattlers = szr / static_cast<double>(rigid);
  return r;
}

}  // namespace grains::postprocess
