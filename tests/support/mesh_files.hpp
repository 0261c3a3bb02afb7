#pragma once
// Triangle meshes written for tests: flat triangulated rectangles, boxes and
// folded sheets as OFF files, and the same as in-memory vertex/face lists.
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace grains::test {

struct Tri {
  std::vector<Eigen::Vector3d> v;
  std::vector<std::array<int, 3>> f;
  /// Appends another mesh (its vertices are not welded to ours).
  void add(const Tri& o) {
    const int n = static_cast<int>(v.size());
    v.insert(v.end(), o.v.begin(), o.v.end());
    for (auto t : o.f) f.push_back({t[0] + n, t[1] + n, t[2] + n});
  }
  /// Merges vertices with equal coordinates (as the STL reader does).
  Tri& weld() {
    std::vector<Eigen::Vector3d> u;
    std::vector<int> map(v.size());
    for (std::size_t k = 0; k < v.size(); ++k) {
      int found = -1;
      for (std::size_t j = 0; j < u.size() && found < 0; ++j)
        if (u[j] == v[k]) found = static_cast<int>(j);
      if (found < 0) found = static_cast<int>(u.size()), u.push_back(v[k]);
      map[k] = found;
    }
    for (auto& t : f)
      for (auto& c : t) c = map[static_cast<std::size_t>(c)];
    v = u;
    return *this;
  }
};

/// The rectangle o + s u + t w (s, t in [0, 1]) as nu x nw cells of two
/// triangles each, the diagonals alternating, counter-clockwise about u x w.
inline Tri grid(const Eigen::Vector3d& o, const Eigen::Vector3d& u, const Eigen::Vector3d& w, int nu, int nw) {
  Tri m;
  for (int j = 0; j <= nw; ++j)
    for (int i = 0; i <= nu; ++i) m.v.push_back(o + u * (double(i) / nu) + w * (double(j) / nw));
  auto id = [&](int i, int j) { return j * (nu + 1) + i; };
  for (int j = 0; j < nw; ++j)
    for (int i = 0; i < nu; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {
        m.f.push_back({a, b, c});
        m.f.push_back({a, c, d});
      } else {
        m.f.push_back({a, b, d});
        m.f.push_back({b, c, d});
      }
    }
  return m;
}

/// The five faces of an open box [lo, hi] (no lid), two triangles each,
/// facing inwards.
inline Tri open_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const Eigen::Vector3d d = hi - lo;
  const Eigen::Vector3d X(d.x(), 0, 0), Y(0, d.y(), 0), Z(0, 0, d.z());
  Tri m;
  m.add(grid(lo, X, Y, 1, 1));                 // floor, normal +z
  m.add(grid(lo, Z, X, 1, 1));                 // y = lo, normal +y
  m.add(grid(lo + Y, X, Z, 1, 1));             // y = hi, normal -y
  m.add(grid(lo, Y, Z, 1, 1));                 // x = lo, normal +x
  m.add(grid(lo + X, Z, Y, 1, 1));             // x = hi, normal -x
  return m;
}

/// A closed drum: a cylinder of radius r about the y axis through `centre`,
/// from y = centre.y - length/2 to + length/2, its side in `segments` x
/// `rings` quads of two triangles, its ends as fans; welded.
inline Tri drum(const Eigen::Vector3d& centre, double r, double length, int segments, int rings) {
  Tri m;
  auto at = [&](int k, double y) {
    const double t = 2 * M_PI * k / segments;
    return Eigen::Vector3d(centre.x() + r * std::cos(t), centre.y() + y, centre.z() + r * std::sin(t));
  };
  for (int j = 0; j <= rings; ++j)
    for (int k = 0; k < segments; ++k) m.v.push_back(at(k, -0.5 * length + length * j / rings));
  auto id = [&](int k, int j) { return j * segments + (k % segments); };
  for (int j = 0; j < rings; ++j)
    for (int k = 0; k < segments; ++k) {
      m.f.push_back({id(k, j), id(k + 1, j), id(k + 1, j + 1)});
      m.f.push_back({id(k, j), id(k + 1, j + 1), id(k, j + 1)});
    }
  const int c0 = static_cast<int>(m.v.size());
  m.v.push_back(centre - Eigen::Vector3d(0, 0.5 * length, 0));
  m.v.push_back(centre + Eigen::Vector3d(0, 0.5 * length, 0));
  for (int k = 0; k < segments; ++k) {
    m.f.push_back({c0, id(k + 1, 0), id(k, 0)});
    m.f.push_back({c0 + 1, id(k, rings), id(k + 1, rings)});
  }
  return m;
}

/// An open conical hopper about the z axis (cases/hopper_discharge/make_hopper.py):
/// the cone from the orifice (radius r0 at z = 0) to radius R at half-angle
/// theta from the vertical (90 degrees: a flat bottom), then a bin of
/// height H; `segments` around.
inline Tri hopper(double theta_deg, double r0, double R, double H, int segments) {
  const double hc = theta_deg >= 90 ? 0.0 : (R - r0) / std::tan(theta_deg * M_PI / 180);
  const double rr[4] = {r0, R, R, R}, zz[4] = {0, hc, hc + H / 2, hc + H};
  Tri m;
  for (int j = 0; j < 4; ++j)
    for (int k = 0; k < segments; ++k) {
      const double t = 2 * M_PI * k / segments;
      m.v.emplace_back(rr[j] * std::cos(t), rr[j] * std::sin(t), zz[j]);
    }
  auto id = [&](int k, int j) { return j * segments + (k % segments); };
  for (int j = 0; j < 3; ++j)
    for (int k = 0; k < segments; ++k) {
      m.f.push_back({id(k, j), id(k + 1, j + 1), id(k + 1, j)});
      m.f.push_back({id(k, j), id(k, j + 1), id(k + 1, j + 1)});
    }
  return m;
}

inline void write_off(const std::filesystem::path& path, const Tri& m) {
  std::ofstream o(path);
  o.precision(17);
  o << "OFF\n" << m.v.size() << " " << m.f.size() << " 0\n";
  for (const auto& p : m.v) o << p.x() << " " << p.y() << " " << p.z() << "\n";
  for (const auto& t : m.f) o << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
}

}  // namespace grains::test
