#pragma once
// Exact distance from a point to a closed triangle mesh, with the sign of
// inside/outside, for measuring decompositions (not for the decomposition's
// grid, which comes from OpenVDB; see distance_grid.hpp).
//
// A bounding-volume hierarchy (axis-aligned boxes, median split) finds the
// closest triangle; the sign comes from the angle-weighted pseudo-normal of
// the closest feature (face, edge or vertex), which is exact for closed,
// consistently oriented, manifold meshes (Baerentzen & Aanaes, IEEE TVCG 2005).

#include "contact/mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace grains::clump {

class MeshDistance {
public:
  explicit MeshDistance(const mesh::TriangleMesh& mesh);

  // Distance to the surface: positive outside, negative inside.
  double signed_distance(const Eigen::Vector3d& p) const;
  double unsigned_distance(const Eigen::Vector3d& p) const;
  // Generalized winding number (sum of the solid angles of the faces over
  // 4 pi): 1 inside a closed outward mesh, 0 outside, robust where the
  // pseudo-normal sign is not (self-touching or sliver faces). O(faces).
  double winding_number(const Eigen::Vector3d& p) const;
  // The same by the hierarchy (Barill et al., "Fast winding numbers for
  // soups and clouds", SIGGRAPH 2018): a cluster of faces whose bounding
  // sphere is seen from farther than `beta` radii contributes the solid
  // angle of its area-weighted dipole, (c - p).A / |c - p|^3 / (4 pi);
  // nearer clusters are opened, leaves summed exactly. O(log faces) per
  // query; its error (at most 1.8e-2 at beta = 3 on the test meshes, tested) is
  // far below the 0.5 that separates inside from outside.
  double winding_number_fast(const Eigen::Vector3d& p, double beta = 3.0) const;
  // Same, searching first within `bound` of p (a good guess makes the query
  // several times faster); the result is exact whatever the guess.
  double signed_distance(const Eigen::Vector3d& p, double bound) const;

private:
  struct Hit {
    double dist2;
    int face;
    int feature;  // 0..2 vertex k, 3..5 edge (k-3, k-2), 6 face
    Eigen::Vector3d point;
  };
  struct Node {
    Eigen::Vector3d lo, hi;
    int left = -1, right = -1;  // children, or -1 for a leaf
    int begin = 0, end = 0;     // faces order_[begin, end) for a leaf
    // Far field of the node's faces: sum of area vectors (outward) and the
    // area-weighted centroid, and the radius of the box about that centroid.
    Eigen::Vector3d area_vector = Eigen::Vector3d::Zero(), centroid = Eigen::Vector3d::Zero();
    double area = 0.0, radius = 0.0;
  };
  void build_far_field(int id);
  int build(int begin, int end);
  Hit closest(const Eigen::Vector3d& p, double bound2) const;
  double sign_of(const Hit& h, const Eigen::Vector3d& p) const;

  std::vector<Eigen::Vector3d> vertices_;
  std::vector<std::array<int, 3>> faces_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
  std::vector<Eigen::Vector3d> face_normal_;                // unit
  std::vector<std::array<Eigen::Vector3d, 3>> edge_normal_;  // per face edge k = (k, k+1)
  std::vector<Eigen::Vector3d> vertex_normal_;              // angle-weighted
};

}  // namespace grains::clump
