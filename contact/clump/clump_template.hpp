#pragma once
// A clump template: the balls of a sphere decomposition in the body frame
// (principal axes at the centre of mass) with the mass properties of the
// union of the balls, and the metadata of how it was made.
//
// Mass properties are those of the union of the (overlapping) balls, the
// solid the simulated clump really is, integrated once over the union
// (ball_union.hpp), never as a sum of ball masses or inertias. The exact
// polyhedral volume of the mesh is kept in the metadata for the volume error.

#include "contact/clump/sphere_decomposition.hpp"
#include "contact/mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace grains::clump {

struct ClumpMetadata {
  std::string source;       // mesh file
  std::string method = "Behandish-Ilies 2016 Algorithm 1 (greedy SDF-guided spherical decomposition)";
  int grid = 0;             // N, m = N^3
  double mu = 0.0;
  std::string greedy_key = "distance";
  double epsilon = 0.0;     // Hausdorff bound sqrt(3) L / m^(1/3)
  size_t n1 = 0, n3 = 0;    // |A1| = |A2|, |A3|
  int restored = 0;
  double hausdorff = -1.0;  // measured d_H(U, S); < 0 if not measured
  double hausdorff_mesh_to_union = -1.0;
  double hausdorff_union_to_mesh = -1.0;
  double mesh_volume = 0.0;   // exact, polyhedral
  double volume_error = 0.0;  // (V_union - V_mesh) / V_mesh
  double node_cover_radius = -1.0;  // measured sup_{s in S} d(s, X), see hausdorff.hpp
  double seconds_decomposition = 0.0;  // distance grid + steps 1-3
  double seconds_distance_vdb = 0.0, seconds_distance_exact = 0.0;
  double seconds_greedy = 0.0, seconds_reduction = 0.0;
  double seconds_mass = 0.0;
  double seconds_measurement = 0.0;
  size_t n3_seed_rule() const { return n3 - static_cast<size_t>(restored); }
};

struct ClumpTemplate {
  std::vector<Ball> balls;  // body frame: x_mesh = centre_of_mass + axes * x_body
  double density = 0.0;     // kg/m^3
  double volume = 0.0;      // of the union of balls, m^3
  double volume_bound = 0.0;  // strict bound on |volume error| of the integration
  double mass = 0.0;          // density * volume, kg
  Eigen::Vector3d inertia = Eigen::Vector3d::Zero();  // principal moments, ascending, kg m^2
  Eigen::Vector3d centre_of_mass = Eigen::Vector3d::Zero();  // in the mesh frame
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();        // columns: body axes in the mesh frame, det = +1
  ClumpMetadata meta;
};

// Mass properties of the union of `balls` (mesh frame) and the move to the
// principal-axes body frame. `finest`: edge of the smallest integration cube.
ClumpTemplate make_clump_template(const std::vector<Ball>& balls, double density, double finest);

struct ClumpOptions {
  DecompositionOptions decomposition;
  double density = 1000.0;
  bool measure = true;             // measure Hausdorff distance (costs about as much as the decomposition)
  double sample_spacing_cells = 0.5;    // Hausdorff sample spacing, in grid cells h
  double integration_cells = 0.25;      // finest integration cube, in grid cells h
};

// Decompose a validated mesh, measure it, and build the template.
ClumpTemplate build_clump(const mesh::TriangleMesh& mesh, const ClumpOptions& options);

}  // namespace grains::clump
