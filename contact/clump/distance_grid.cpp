#include "contact/clump/distance_grid.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact/clump/vdb/vdb_module.hpp"
#include "contact/module_loader.hpp"

namespace grains::clump {

namespace {

// OpenVDB is loaded the first time a grid is computed (vdb_module.hpp,
// contact/module_loader.hpp): from $GRAINS_VDB_MODULE if set (and only
// there), else where the build put it, else beside the running program, else
// by the loader's search path.
GrainsVdbSignedDistance vdb_signed_distance() {
#ifdef GRAINS_VDB_MODULE_PATH
  const char* build_path = GRAINS_VDB_MODULE_PATH;
#else
  const char* build_path = nullptr;
#endif
  return reinterpret_cast<GrainsVdbSignedDistance>(module_symbol(
      {"GRAINS_VDB_MODULE", build_path, "libgrains_vdb.so", kGrainsVdbSymbol, "the sphere decomposition of a mesh",
       "OpenVDB"}));
}

}  // namespace

double half_cube_edge(const mesh::TriangleMesh& mesh) {
  return 0.5 * (mesh.bbox_max() - mesh.bbox_min()).maxCoeff();
}

double DistanceGrid::interpolate(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d u = (p - origin) / h;
  const Eigen::Vector3d uc = u.cwiseMax(0.0).cwiseMin(double(n - 1));
  const double outside = h * (u - uc).norm();
  int i0[3];
  double w[3];
  for (int d = 0; d < 3; ++d) {
    i0[d] = std::min(static_cast<int>(std::floor(uc[d])), n - 2);
    w[d] = uc[d] - i0[d];
  }
  double v = 0.0;
  for (int c = 0; c < 8; ++c) {
    const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
    const double wt = (di ? w[0] : 1 - w[0]) * (dj ? w[1] : 1 - w[1]) * (dk ? w[2] : 1 - w[2]);
    v += wt * phi[index(i0[0] + di, i0[1] + dj, i0[2] + dk)];
  }
  return v + outside;
}

double DistanceGrid::distance_to_inside_node(const Eigen::Vector3d& p) const {
  // Search growing cubes of nodes around p; once a node at distance d is
  // found in the cube of half-width w cells, nodes outside it are farther
  // than (w - 0.5) h, so the search can stop when d <= (w - 0.5) h.
  const Eigen::Vector3d u = (p - origin) / h;
  int c[3];
  for (int d = 0; d < 3; ++d) c[d] = std::clamp(static_cast<int>(std::lround(u[d])), 0, n - 1);
  double best2 = std::numeric_limits<double>::infinity();
  for (int w = 1; w <= n; ++w) {
    for (int k = std::max(0, c[2] - w); k <= std::min(n - 1, c[2] + w); ++k)
      for (int j = std::max(0, c[1] - w); j <= std::min(n - 1, c[1] + w); ++j)
        for (int i = std::max(0, c[0] - w); i <= std::min(n - 1, c[0] + w); ++i) {
          // Only the shell of the cube is new (inner part seen at w - 1).
          if (w > 1 && std::abs(i - c[0]) < w && std::abs(j - c[1]) < w && std::abs(k - c[2]) < w) continue;
          if (phi[index(i, j, k)] <= 0.0) best2 = std::min(best2, (node(i, j, k) - p).squaredNorm());
        }
    const double reach = (w - 0.5) * h;
    if (best2 <= reach * reach) break;
  }
  return std::sqrt(best2);
}

DistanceGrid compute_distance_grid(const mesh::TriangleMesh& mesh, int n, const MeshDistance* exact) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  if (n < 2) throw std::invalid_argument("distance grid needs at least 2 nodes per axis, got " + std::to_string(n));
  const auto signed_distance = vdb_signed_distance();

  DistanceGrid g;
  g.n = n;
  const double L = half_cube_edge(mesh);
  g.h = 2.0 * L / n;
  const Eigen::Vector3d centre = 0.5 * (mesh.bbox_min() + mesh.bbox_max());
  g.origin = centre - Eigen::Vector3d::Constant(L - 0.5 * g.h);

  // Index space of the VDB grid = our node indices: world = origin + h * ijk.
  // The mesh is shifted by -origin before the single-precision conversion so
  // that large offsets do not cost digits.
  std::vector<float> points;
  points.reserve(3 * mesh.vertices.size());
  for (const auto& v : mesh.vertices) {
    const Eigen::Vector3d q = v - g.origin;
    points.insert(points.end(), {float(q.x()), float(q.y()), float(q.z())});
  }
  // OpenVDB's sign comes from a flood fill of the exterior, independent of
  // the winding; it needs a closed surface.
  std::vector<unsigned> tris;
  tris.reserve(3 * mesh.faces.size());
  for (const auto& f : mesh.faces)
    tris.insert(tris.end(), {static_cast<unsigned>(f[0]), static_cast<unsigned>(f[1]), static_cast<unsigned>(f[2])});
  const float ex_band = 3.0f;
  const float in_band = static_cast<float>(n) * 2.0f;  // covers the whole interior
  g.phi.assign(size_t(n) * n * n, 0.0);
  char err[512] = "";
  if (signed_distance(points.data(), mesh.vertices.size(), tris.data(), mesh.faces.size(), g.h, n, ex_band, in_band,
                      g.phi.data(), err, sizeof err) != 0)
    throw std::runtime_error(err);
  const auto t1 = Clock::now();
  g.seconds_vdb = std::chrono::duration<double>(t1 - t0).count();

  // Exact pass over the nodes inside and near the surface.
  std::unique_ptr<MeshDistance> own;
  if (!exact) {
    own = std::make_unique<MeshDistance>(mesh);
    exact = own.get();
  }
  const double near = 2.5 * g.h;
  size_t count = 0, sign_errors = 0;
  double max_err = 0.0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : count, sign_errors) reduction(max : max_err)
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        double& v = g.phi[g.index(i, j, k)];
        if (v >= near) continue;
        const Eigen::Vector3d x = g.node(i, j, k);
        double e = exact->signed_distance(x, std::abs(v) + g.h);
        if ((e <= 0.0) != (v <= 0.0)) {
          // The two signs disagree: let the winding number decide.
          const bool inside = exact->winding_number_fast(x) > 0.5;
          if (inside != (v <= 0.0)) ++sign_errors;
          e = inside ? -std::abs(e) : std::abs(e);
        }
        max_err = std::max(max_err, std::abs(e - v));
        v = e;
        ++count;
      }
    }
  }
  g.nodes_exact = count;
  g.vdb_sign_errors = sign_errors;
  g.max_vdb_error = max_err;
  g.seconds_exact = std::chrono::duration<double>(Clock::now() - t1).count();
  return g;
}

}  // namespace grains::clump
