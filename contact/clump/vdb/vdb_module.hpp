#pragma once
// The one call grains makes into OpenVDB, behind a C interface so that the
// library lives in its own module (libgrains_vdb.so), loaded the first time
// a mesh is decomposed into spheres (contact/clump/distance_grid.cpp). A run
// that decomposes nothing never maps OpenVDB: its symbol and relocation
// tables alone are about 27 MB resident in every process, 27 bytes per grain
// at 10^6 grains and as much again on every MPI rank (issue 26).

#include <cstddef>

extern "C" {

/// Signed distance of a closed triangle mesh on the nodes (i, j, k),
/// 0 <= i, j, k < n, of a grid of spacing h (OpenVDB's mesh-to-volume);
/// points are in index space times h (the caller shifts the mesh to the
/// grid's origin). phi receives n^3 values, index i + n (j + n k), negative
/// inside. Returns 0, or 1 with a message in err (at most err_size bytes).
int grains_vdb_signed_distance(const float* points, std::size_t n_points, const unsigned* triangles,
                               std::size_t n_triangles, double h, int n, float exterior_band, float interior_band,
                               double* phi, char* err, std::size_t err_size);
}

/// The name the loader looks up.
inline constexpr const char* kGrainsVdbSymbol = "grains_vdb_signed_distance";
using GrainsVdbSignedDistance = decltype(&grains_vdb_signed_distance);
