#pragma once
// Mesh file readers. `read_*` parse only (syntax, finiteness, truncation);
// `load_mesh` picks the reader by extension and then validates the mesh
// (closed, manifold, oriented, no degenerate faces; see mesh_validation.hpp).
// All failures throw MeshError; nothing aborts.

#include "io/mesh/mesh_validation.hpp"
#include "contact/mesh/triangle_mesh.hpp"

#include <string>

namespace grains::mesh {

// STL, ASCII or binary (detected from the size the binary header promises).
// Coincident vertices are welded by exact coordinate match.
TriangleMesh read_stl(const std::string& path);
// Wavefront OBJ: `v x y z` and `f a b c ...` (a may be i, i/t, i//n, i/t/n;
// negative indices count from the end); polygons are fan-triangulated.
TriangleMesh read_obj(const std::string& path);
// OFF (Object File Format): header `OFF`, counts, vertices, polygons.
TriangleMesh read_off(const std::string& path);

// Read by extension (.stl, .obj, .off, case-insensitive) without validation.
TriangleMesh read_mesh(const std::string& path);
// Read and validate; repairs (orientation) are listed in mesh.warnings.
TriangleMesh load_mesh(const std::string& path, const ValidationOptions& options = {});

}  // namespace grains::mesh
