#pragma once
// Dynamic angle of repose of the free surface of a bed in a rotating drum
// (`grains repose`).
//
// Geometry: the drum turns about a coordinate axis (x or y; `axis`) through
// `centre`; gravity is along -z, so an axis along z is refused. Each particle
// centre is projected onto the plane normal to the axis: v = z, and u = the
// other horizontal coordinate (u = x for a drum about y, u = y for a drum
// about x); u_c, v_c are the centre's.
//
// Surface: u is cut into columns of width w (`column`; default 2 mean
// particle diameters) starting at u_c, over the central part
// |u - u_c| <= f R (`span` f, default 0.6; R the drum radius, `radius`, by
// default the largest distance of a particle's far edge from the axis), away
// from the drum wall where the surface bends. A column's top is its highest
// particle: the point (u_i, v_i + h_i), h_i the particle's half-height along
// z (its radius for a sphere or a clump ball; the extent of the rotated
// ellipsoid along z for an ellipsoid). Only that particle of each column
// counts: the particles beneath it do not change the result.
//
// Near the end walls (`near_ends` e > 0): only the particles whose centres
// lie within e of either end of the bed along the axis (the frame's smallest
// and largest particle extent along it: a grain that has left the drum moves
// them) make the columns: the surface an
// experiment films through a transparent end plate, steeper than the
// middle's where the end walls' friction holds the bed up.
//
// Angle: a straight line v = a u + b is fitted to the columns' tops by least
// squares; the angle is atan(|a|) in degrees, `slope` a keeps the sign (a > 0:
// the surface is higher on the +u side), `rms_residual` is
// sqrt(mean of the squared vertical residuals) of the tops about that line.
// A frame with fewer than 4 columns holding particles is refused
// (SurfaceAngleRefused): a line through fewer tops says little about the
// surface (the span or the columns are too narrow, or the drum is near
// empty).
#include <cstddef>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "postprocess/frame.hpp"
#include "postprocess/walls.hpp"

namespace grains::postprocess {

struct SurfaceAngleOptions {
  int axis = 1;                 // drum axis: 0 (x) or 1 (y)
  Vec3 centre{0, 0, 0};         // a point on the axis, m
  double column = 0;            // column width, m; 0: 2 mean diameters of the frame
  double radius = 0;            // drum radius R, m; 0: largest far edge of a particle from the axis
  double span = 0.6;            // columns over |u - u_c| <= span R, 0 < span <= 1
  double near_ends = 0;         // > 0: only particles whose centres lie within this distance (m) of either end
                                // of the bed along the axis (what a camera sees through a glass end plate)
  std::size_t min_columns = 4;  // fewer columns with particles: the frame is refused
};

/// A frame refused for a reason of its content (too few columns), not of the
/// options (those throw std::invalid_argument).
class SurfaceAngleRefused : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct SurfaceAngle {
  double time = 0;
  double angle_deg = 0;        // atan(|slope|)
  double slope = 0;            // dv/du of the fitted line; > 0: higher on the +u side
  double intercept = 0;        // v of the line at u = 0, m
  double rms_residual = 0;     // m
  std::size_t columns = 0;     // columns with particles (points of the fit)
  double column = 0;           // column width used, m
  double radius = 0;           // drum radius used, m
  std::vector<double> u, top;  // the columns' tops, m
};

/// The in-plane horizontal coordinate u of a drum about `axis` (0 -> y, 1 -> x).
inline int surface_u_axis(int axis) { return axis == 0 ? 1 : 0; }

/// Checks the options (std::invalid_argument naming the option) and measures
/// the frame's free surface as described above.
SurfaceAngle surface_angle(const Frame& f, const SurfaceAngleOptions& opt);

/// The drum's axis point as the run's walls give it: the bounding-box centre
/// of a mesh wall (its axis_point default; take the walls of the first frame,
/// before the drum turns) or the base of a cylinder wall parallel to `axis`.
/// nullopt when there is no such wall; std::invalid_argument when several
/// candidates disagree (the caller must be told the centre).
std::optional<Vec3> drum_axis_point(const WallSet& walls, int axis);

/// Statistics of the angles of a series of frames.
struct ReposeSummary {
  std::size_t frames = 0;
  double mean_deg = 0;
  double std_deg = 0;             // sample standard deviation (n - 1); 0 for one frame
  double standard_error_deg = 0;  // std / sqrt(n): frames a rotation apart are correlated, so a lower bound
  double from_s = 0, to_s = 0;    // times of the first and the last frame measured
};
ReposeSummary summarize_repose(const std::vector<SurfaceAngle>& frames);

/// Writes DIR/repose.csv (time_s, angle_deg, slope, columns, rms_residual_m,
/// radius_m; one row per frame) and DIR/repose.json (the summary and the
/// options; `extra` holds further "key": value pairs, already JSON, written
/// as they are). Returns the two paths; std::runtime_error when a file
/// cannot be written.
std::vector<std::filesystem::path> write_repose(const std::vector<SurfaceAngle>& frames, const ReposeSummary& s,
                                                const SurfaceAngleOptions& opt,
                                                const std::vector<std::pair<std::string, std::string>>& extra,
                                                const std::filesystem::path& dir);

}  // namespace grains::postprocess
