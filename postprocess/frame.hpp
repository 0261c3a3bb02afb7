#pragma once
// One output frame of a run, read back from the VTK XML files that
// io/output/vtk_output.cpp writes: OUTDIR/particles.pvd indexes
// OUTDIR/frames/particles_NNNNNN.vtu (or .pvtu for a parallel run), one point
// per particle with point-data arrays. Arrays that a run did not write stay
// empty here: orientation (unit quaternion w,x,y,z, body -> world) and
// semi_axes exist for ellipsoids; `body` (the clump a ball belongs to, also
// read from an array named `clump`) exists when clumps are written as their balls.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace grains::postprocess {

using Vec3 = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;

/// One entry of a .pvd collection.
struct FrameEntry {
  double time = 0;
  std::filesystem::path file;  // absolute or relative to the working directory
};

struct Frame {
  std::size_t index = 0;
  double time = 0;
  std::filesystem::path file;
  std::vector<Vec3> x;
  std::vector<double> radius;
  std::vector<std::int64_t> id;
  std::vector<int> material, coordination;
  std::vector<Vec3> velocity, force, angular_velocity;
  std::vector<Quat> orientation;      // empty unless written
  std::vector<Vec3> semi_axes;        // empty unless written (ellipsoids)
  std::vector<std::int64_t> body;     // empty unless written (clump balls)

  std::size_t size() const { return x.size(); }
  bool has_orientation() const { return !orientation.empty(); }
  bool has_ellipsoids() const { return !semi_axes.empty(); }
  /// Radius of the sphere around the centre that holds the particle.
  double bounding_radius(std::size_t i) const { return semi_axes.empty() ? radius[i] : semi_axes[i].maxCoeff(); }
  /// Volume of one particle (sphere or ellipsoid; a clump ball on its own).
  double particle_volume(std::size_t i) const;
  /// Mean particle diameter (volume-equivalent for ellipsoids).
  double mean_diameter() const;
};

/// The frames listed in a .pvd collection, in file order. Throws
/// std::runtime_error naming the file when it is missing or malformed.
std::vector<FrameEntry> read_pvd(const std::filesystem::path& pvd);

/// The particle frames of an output folder (OUTDIR/particles.pvd).
std::vector<FrameEntry> list_frames(const std::filesystem::path& out_dir);

/// Reads a particle file (.vtu or .pvtu).
Frame read_frame_file(const std::filesystem::path& file);

/// Frame number `index` of an output folder; a negative index counts from the
/// end (-1 is the last frame).
Frame read_frame(const std::filesystem::path& out_dir, long index = -1);

/// The frame of an output folder whose time is closest to `time`.
Frame read_frame_at_time(const std::filesystem::path& out_dir, double time);

/// The walls file (.vtp) that belongs to particle frame `index`, or an empty
/// path when the run has no walls.
std::filesystem::path walls_file(const std::filesystem::path& out_dir, std::size_t index);

}  // namespace grains::postprocess
