// libgrains_vdb.so: OpenVDB's mesh-to-volume behind a C interface
// (vdb_module.hpp). Built as a module, never linked into grains itself.
#include "contact/clump/vdb/vdb_module.hpp"

#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>

#include <cstdio>
#include <exception>
#include <mutex>
#include <vector>

extern "C" __attribute__((visibility("default"))) int grains_vdb_signed_distance(
    const float* points, std::size_t n_points, const unsigned* triangles, std::size_t n_triangles, double h, int n,
    float exterior_band, float interior_band, double* phi, char* err, std::size_t err_size) {
  try {
    static std::once_flag init;
    std::call_once(init, [] { openvdb::initialize(); });
    // Index space of the VDB grid = the caller's node indices.
    auto xform = openvdb::math::Transform::createLinearTransform(h);
    std::vector<openvdb::Vec3s> pts;
    pts.reserve(n_points);
    for (std::size_t v = 0; v < n_points; ++v) pts.emplace_back(points[3 * v], points[3 * v + 1], points[3 * v + 2]);
    std::vector<openvdb::Vec3I> tris;
    tris.reserve(n_triangles);
    for (std::size_t f = 0; f < n_triangles; ++f)
      tris.emplace_back(triangles[3 * f], triangles[3 * f + 1], triangles[3 * f + 2]);
    const std::vector<openvdb::Vec4I> quads;
    auto grid = openvdb::tools::meshToSignedDistanceField<openvdb::FloatGrid>(*xform, pts, tris, quads, exterior_band,
                                                                              interior_band);
    auto acc = grid->getConstAccessor();
    const std::size_t sn = static_cast<std::size_t>(n);
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
          // OpenVDB stores distances in world units of the grid (voxel size h).
          phi[static_cast<std::size_t>(i) + sn * (static_cast<std::size_t>(j) + sn * static_cast<std::size_t>(k))] =
              acc.getValue(openvdb::Coord(i, j, k));
    return 0;
  } catch (const std::exception& e) {
    std::snprintf(err, err_size, "OpenVDB mesh-to-volume failed: %s", e.what());
  } catch (...) {
    std::snprintf(err, err_size, "OpenVDB mesh-to-volume failed (unknown exception)");
  }
  return 1;
}
