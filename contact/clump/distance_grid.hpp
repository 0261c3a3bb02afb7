#pragma once
// Signed distance to a closed mesh sampled on the nodes of a regular grid.
//
// Two passes. OpenVDB's mesh-to-volume gives a fast signed field over the
// whole grid; it is not exact enough to be the balls' radii: measured on our
// test meshes, its interior values overestimate the distance by up to 0.7 h
// (cow, 32^3) and its voxel sign marks some exterior nodes in concave
// creases as inside, up to 2 h deep. A ball built on such a value pokes out
// of the solid and breaks the seed's bound. So every node that OpenVDB puts
// inside or within 2.5 h outside is recomputed exactly (closest triangle by
// BVH, sign by angle-weighted pseudo-normals; mesh_distance.hpp), using the
// OpenVDB value as the search radius. Where the OpenVDB sign and the
// pseudo-normal sign disagree, the generalized winding number decides (the
// pseudo-normal sign fails on a few nodes near the cow's sliver faces).
// Nodes OpenVDB puts farther outside keep its (positive) value: they never
// become balls.
//
// Grid convention (the seed's Appendix A with cell-centred nodes): the mesh's
// bounding box is enclosed in the cube of edge 2L = its largest extent,
// centred on the box; the cube is cut into N^3 cells of edge h = 2L/N and the
// m = N^3 nodes sit at the cell centres, so every point of the cube lies
// within eps = sqrt(3) h / 2 = sqrt(3) L / m^(1/3) of a node.

#include "contact/clump/mesh_distance.hpp"
#include "contact/mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <vector>

namespace grains::clump {

struct DistanceGrid {
  int n = 0;                                     // nodes per axis (m = n^3)
  double h = 0.0;                                // node spacing
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // position of node (0,0,0)
  std::vector<double> phi;                       // signed distance, < 0 inside; index i + n (j + n k)
  size_t nodes_exact = 0;        // nodes recomputed exactly
  double max_vdb_error = 0.0;    // largest |OpenVDB - exact| over those nodes
  size_t vdb_sign_errors = 0;    // nodes where OpenVDB's sign was wrong (by the winding number)
  double seconds_vdb = 0.0, seconds_exact = 0.0;

  size_t index(int i, int j, int k) const { return size_t(i) + size_t(n) * (size_t(j) + size_t(n) * size_t(k)); }
  Eigen::Vector3d node(int i, int j, int k) const { return origin + h * Eigen::Vector3d(i, j, k); }
  // Trilinear interpolation; points outside the node lattice get the value
  // of the nearest lattice point plus their distance to it (a lower bound
  // for the true distance outside, correct in sign).
  double interpolate(const Eigen::Vector3d& p) const;
  // Distance from p to the nearest node with phi <= 0 (infinity if none).
  double distance_to_inside_node(const Eigen::Vector3d& p) const;
};

// Half edge L of the enclosing cube for the seed's grid convention.
double half_cube_edge(const mesh::TriangleMesh& mesh);

// n nodes per axis over the mesh's enclosing cube. The mesh must be closed and
// outward-oriented (validate it first: OpenVDB's sign flood fill fails on open meshes).
// `exact` may be given to reuse a MeshDistance built on the same mesh.
DistanceGrid compute_distance_grid(const mesh::TriangleMesh& mesh, int n, const MeshDistance* exact = nullptr);

}  // namespace grains::clump
