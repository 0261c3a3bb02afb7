// A coarse, closed remesh of a closed triangle mesh: its signed distance
// field on a grid of voxel size (longest extent) / N (OpenVDB
// meshToSignedDistanceField), contoured at 0 (OpenVDB volumeToMesh, quads
// split into triangles), oriented outward, written as OFF and read back
// through grains' mesh validation. How cases/pour_clumps/bunny.off was made
// from the 75,408-face bunny00.off:
//
//   remesh_coarse tests/data/meshes/bunny00.off 24 0.0 cases/pour_clumps/bunny.off
//
// usage: remesh_coarse IN N ADAPTIVITY OUT.off
#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>

#include "io/mesh/mesh_reader.hpp"

int main(int argc, char** argv) {
  if (argc != 5) {
    std::cerr << "usage: remesh_coarse IN N ADAPTIVITY OUT.off\n";
    return 2;
  }
  try {
    const auto mesh = grains::mesh::load_mesh(argv[1]);
    const int n = std::stoi(argv[2]);
    const double adaptivity = std::stod(argv[3]);
    openvdb::initialize();
    const Eigen::Vector3d lo = mesh.bbox_min(), ext = mesh.bbox_max() - lo;
    const double h = ext.maxCoeff() / n;
    auto xform = openvdb::math::Transform::createLinearTransform(h);
    std::vector<openvdb::Vec3s> pts;
    for (const auto& v : mesh.vertices) pts.emplace_back(float(v.x()), float(v.y()), float(v.z()));
    std::vector<openvdb::Vec3I> tris;
    for (const auto& f : mesh.faces) tris.emplace_back(f[0], f[1], f[2]);
    const std::vector<openvdb::Vec4I> no_quads;
    auto grid = openvdb::tools::meshToSignedDistanceField<openvdb::FloatGrid>(*xform, pts, tris, no_quads, 3.0f, 3.0f);
    std::vector<openvdb::Vec3s> out_pts;
    std::vector<openvdb::Vec3I> out_tris;
    std::vector<openvdb::Vec4I> out_quads;
    openvdb::tools::volumeToMesh(*grid, out_pts, out_tris, out_quads, 0.0, adaptivity);
    std::vector<std::array<unsigned, 3>> faces;
    for (const auto& t : out_tris) faces.push_back({t[0], t[1], t[2]});
    for (const auto& q : out_quads) {
      faces.push_back({q[0], q[1], q[2]});
      faces.push_back({q[0], q[2], q[3]});
    }
    // Orientation: outward (positive signed volume).
    double vol = 0;
    for (const auto& f : faces) {
      const Eigen::Vector3d a(out_pts[f[0]].x(), out_pts[f[0]].y(), out_pts[f[0]].z());
      const Eigen::Vector3d b(out_pts[f[1]].x(), out_pts[f[1]].y(), out_pts[f[1]].z());
      const Eigen::Vector3d c(out_pts[f[2]].x(), out_pts[f[2]].y(), out_pts[f[2]].z());
      vol += a.dot(b.cross(c)) / 6;
    }
    if (vol < 0)
      for (auto& f : faces) std::swap(f[1], f[2]);
    std::ofstream o(argv[4]);
    o << "OFF\n# coarse remesh (bench/clump/remesh_coarse.cpp, N = " << n << ", adaptivity " << adaptivity
      << ") of " << argv[1] << "\n"
      << out_pts.size() << " " << faces.size() << " 0\n";
    o.precision(7);
    for (const auto& p : out_pts) o << p.x() << " " << p.y() << " " << p.z() << "\n";
    for (const auto& f : faces) o << "3 " << f[0] << " " << f[1] << " " << f[2] << "\n";
    o.close();
    const auto back = grains::mesh::load_mesh(argv[4]);
    for (const auto& w : back.warnings) std::cout << "warning: " << w << "\n";
    std::printf("%s: %zu vertices, %zu faces, volume %.5f (input %.5f)\n", argv[4], back.vertices.size(),
                back.faces.size(), back.signed_volume(), mesh.signed_volume());
  } catch (const std::exception& e) {
    std::cerr << "remesh_coarse: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
