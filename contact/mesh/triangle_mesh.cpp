#include "contact/mesh/triangle_mesh.hpp"

#include <limits>

namespace grains::mesh {

Eigen::Vector3d TriangleMesh::bbox_min() const {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  for (const auto& v : vertices) lo = lo.cwiseMin(v);
  return lo;
}

Eigen::Vector3d TriangleMesh::bbox_max() const {
  Eigen::Vector3d hi = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
  for (const auto& v : vertices) hi = hi.cwiseMax(v);
  return hi;
}

double TriangleMesh::signed_volume() const {
  return polyhedron_moments(*this).volume;
}

double TriangleMesh::surface_area() const {
  double a = 0.0;
  for (const auto& f : faces) {
    a += 0.5 * (vertices[f[1]] - vertices[f[0]]).cross(vertices[f[2]] - vertices[f[0]]).norm();
  }
  return a;
}

PolyhedronMoments polyhedron_moments(const TriangleMesh& mesh) {
  // Shift to the bounding-box centre first so that large offsets do not cost
  // digits; each face spans a tetrahedron with the (shifted) origin.
  PolyhedronMoments m;
  if (mesh.vertices.empty()) return m;
  const Eigen::Vector3d shift = 0.5 * (mesh.bbox_min() + mesh.bbox_max());
  double vol = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  // integral of x x^T
  for (const auto& f : mesh.faces) {
    const Eigen::Vector3d a = mesh.vertices[f[0]] - shift;
    const Eigen::Vector3d b = mesh.vertices[f[1]] - shift;
    const Eigen::Vector3d c = mesh.vertices[f[2]] - shift;
    const double v = a.dot(b.cross(c)) / 6.0;
    const Eigen::Vector3d s = a + b + c;  // the origin vertex adds nothing
    vol += v;
    first += v * s / 4.0;
    // For a tetrahedron with vertices v0..v3: integral of x x^T is
    // V/20 (sum_k v_k v_k^T + s s^T), s = sum_k v_k.
    second += v / 20.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  m.volume = vol;
  if (vol == 0.0) return m;
  const Eigen::Vector3d com = first / vol;
  const Eigen::Matrix3d second_c = second - vol * com * com.transpose();
  m.centroid = com + shift;
  m.inertia = second_c.trace() * Eigen::Matrix3d::Identity() - second_c;
  return m;
}

}  // namespace grains::mesh
