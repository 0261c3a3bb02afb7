#pragma once
// Validation of a triangle mesh before geometry is built on it.
//
// Checks, in this order (the first failing check throws MeshError):
//   empty            no faces
//   non_finite       a vertex coordinate is NaN or infinite
//   parse            a face index out of range
//   degenerate_face  a face repeats a vertex or has area <= degenerate_area_rel * diag^2
//                    (diag = bounding-box diagonal); count and the first faces listed
//   non_manifold     an edge shared by more than two faces; count and locations
//   not_closed       boundary edges (shared by one face); count and locations
//   non_orientable   no consistent orientation exists (e.g. a Moebius-like strip)
// Orientation policy: the mesh is *repaired*, not refused, unless
// options.repair_orientation is false (then bad_orientation is thrown):
//   - faces whose winding disagrees with their neighbours are flipped so each
//     connected component is consistently oriented (the minority is flipped);
//   - a component whose enclosed signed volume is negative (inward-facing) is
//     flipped as a whole.
// Each repair adds a line to mesh.warnings. Every component is treated as a
// separate solid: meshes with internal cavities (an inner shell that should
// face inward) are not supported and would be "repaired" outward.
// Self-intersections are not detected.

#include "contact/mesh/triangle_mesh.hpp"

namespace grains::mesh {

struct ValidationOptions {
  bool repair_orientation = true;
  double degenerate_area_rel = 1e-14;
  int max_locations = 5;  // how many offending edges/faces a message lists
  /// A wall's surface, not a solid: only the syntax, finiteness and indices
  /// are checked; degenerate faces are dropped (a warning); open,
  /// non-manifold and inconsistently wound meshes are accepted as they are.
  bool wall_surface = false;
};

struct ValidationReport {
  int components = 0;
  int faces_flipped_for_consistency = 0;
  int components_flipped_inward = 0;
};

ValidationReport validate_mesh(TriangleMesh& mesh, const ValidationOptions& options = {});

}  // namespace grains::mesh
