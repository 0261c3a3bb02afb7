#pragma once
// A triangle mesh as loaded from a file: shared vertices, faces as index
// triples (counter-clockwise seen from outside once validated), the source
// name for messages, and warnings collected while loading or repairing.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <string>
#include <vector>

namespace grains::mesh {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> faces;
  std::string source;                 // file path (or a label) used in messages
  std::vector<std::string> warnings;  // repairs done on the way (e.g. flipped faces)

  Eigen::Vector3d bbox_min() const;
  Eigen::Vector3d bbox_max() const;
  // Volume enclosed by the faces, by the divergence theorem: positive for a
  // closed outward-oriented mesh, negative for an inward-oriented one.
  double signed_volume() const;
  double surface_area() const;
};

// Exact mass properties of the solid bounded by a closed, oriented mesh
// (polyhedral integration over the tetrahedra spanned with the origin).
struct PolyhedronMoments {
  double volume = 0.0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  // Inertia tensor per unit density about the centroid.
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};
PolyhedronMoments polyhedron_moments(const TriangleMesh& mesh);

}  // namespace grains::mesh
