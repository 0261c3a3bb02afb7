#pragma once
// Measured Hausdorff distance between the solid S bounded by a mesh and the
// union U of a clump's balls, the quantity Proposition 3 of the seed bounds:
//   d_H(U, S) = max( sup_{u in U} d(u, S), sup_{s in S} d(s, U) ).
// Both suprema are taken over dense samples:
//   - sup_{u in U} d(u, S) is reached on the exposed boundary of U: points on
//     every ball's sphere (Fibonacci lattice, spacing <= `spacing`) that lie in
//     no other ball, each measured with the exact signed mesh distance;
//   - sup_{s in S} d(s, U) is reached on the mesh surface (barycentric lattice
//     on every triangle with spacing <= `spacing`, which includes vertices and
//     edges) or in a void of U inside S, looked for at the centres of the
//     distance grid's cells that lie inside S; each measured exactly as
//     min_i (|s - c_i| - r_i) clamped at 0.
// The sampled value is a lower bound of the true one, short of it by at most
// about the sample spacing times the local slope.
//
// When a grid is given, the same samples of S also measure the covering
// radius of the node sample, delta_X = sup_{s in S} d(s, X) with X the grid
// nodes inside S. The seed's Lemma 4 takes delta_X <= eps; that fails where S
// has parts thinner than a cell (sharp tips, thin ears and legs), and then
// only d_H(U, S) <= max(eps, delta_X) holds: X lies in U, so every point of S
// is within delta_X of U, and U lies within eps of S by construction.

#include "contact/clump/ball_union.hpp"
#include "contact/clump/distance_grid.hpp"
#include "contact/clump/mesh_distance.hpp"
#include "contact/mesh/triangle_mesh.hpp"

namespace grains::clump {

struct HausdorffResult {
  double mesh_to_union = 0.0;  // sup over S of the distance to U
  double union_to_mesh = 0.0;  // sup over U of the distance to S
  double hausdorff = 0.0;      // max of the two
  Eigen::Vector3d worst = Eigen::Vector3d::Zero();  // where the max is reached
  double node_cover_radius = -1.0;  // delta_X over the samples of S (grid given), else -1
  size_t mesh_samples = 0, union_samples = 0, interior_samples = 0;
};

HausdorffResult measure_hausdorff(const mesh::TriangleMesh& mesh, const MeshDistance& distance, const BallUnion& balls,
                                  double spacing, const DistanceGrid* grid = nullptr);

}  // namespace grains::clump
