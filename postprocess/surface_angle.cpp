#include "postprocess/surface_angle.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <system_error>

namespace grains::postprocess {

namespace fs = std::filesystem;

namespace {

const char* axis_name(int axis) { return axis == 0 ? "x" : axis == 1 ? "y" : "z"; }

// Half-height of particle i along z: how far its top lies above its centre.
double half_height(const Frame& f, std::size_t i) {
  if (!f.has_ellipsoids()) return f.radius[i];
  const Vec3& a = f.semi_axes[i];
  if (!f.has_orientation()) return a.z();
  const Eigen::Matrix3d m = f.orientation[i].toRotationMatrix();  // body -> world
  return std::sqrt(std::pow(m(2, 0) * a.x(), 2) + std::pow(m(2, 1) * a.y(), 2) + std::pow(m(2, 2) * a.z(), 2));
}

void check_options(const Frame& f, const SurfaceAngleOptions& o) {
  if (o.axis == 2)
    throw std::invalid_argument(
        "the drum axis cannot be z: gravity is along -z and the free surface is read in a vertical plane (axis x or "
        "y)");
  if (o.axis != 0 && o.axis != 1) throw std::invalid_argument("the drum axis must be x (0) or y (1)");
  if (!o.centre.allFinite()) throw std::invalid_argument("the drum centre must be finite");
  if (!std::isfinite(o.column) || o.column < 0)
    throw std::invalid_argument("the column width must be a positive length (0 for 2 mean diameters)");
  if (!std::isfinite(o.radius) || o.radius < 0)
    throw std::invalid_argument("the drum radius must be a positive length (0 for the particles' extent)");
  if (!(o.span > 0 && o.span <= 1))
    throw std::invalid_argument("the span must lie in (0, 1] (a fraction of the radius)");
  if (!std::isfinite(o.near_ends) || o.near_ends < 0)
    throw std::invalid_argument("the end-wall band must be a positive length (0 for the whole bed)");
  if (o.min_columns < 2) throw std::invalid_argument("a line needs at least 2 columns");
  if (f.radius.size() != f.x.size())
    throw std::invalid_argument("the frame has " + std::to_string(f.x.size()) + " particles but " +
                                std::to_string(f.radius.size()) + " radii");
}

}  // namespace

SurfaceAngle surface_angle(const Frame& f, const SurfaceAngleOptions& opt) {
  check_options(f, opt);
  const std::string when = "frame at t = " + [&] {
    std::ostringstream o;
    o << f.time;
    return o.str();
  }() + " s";
  if (f.size() == 0) throw SurfaceAngleRefused(when + ": no particles");
  const int iu = surface_u_axis(opt.axis);
  const double uc = opt.centre[iu], vc = opt.centre.z();

  SurfaceAngle r;
  r.time = f.time;
  r.column = opt.column > 0 ? opt.column : 2 * f.mean_diameter();
  r.radius = opt.radius;
  if (r.radius <= 0)
    for (std::size_t i = 0; i < f.size(); ++i)
      r.radius = std::max(r.radius, std::hypot(f.x[i][iu] - uc, f.x[i].z() - vc) + f.bounding_radius(i));
  if (!(r.column > 0)) throw SurfaceAngleRefused(when + ": the particles have no size, so no column width (give one)");
  if (!(r.radius > 0))
    throw SurfaceAngleRefused(when + ": the particles have no extent about the axis (give the radius)");

  // Columns k = floor((u - u_c) / w) over |u - u_c| <= span R.
  const double half = opt.span * r.radius;
  if (2 * half / r.column > 1e6) {
    std::ostringstream o;
    o << "a column width of " << r.column << " m makes more than a million columns across " << 2 * half << " m";
    throw std::invalid_argument(o.str());
  }
  const long k_lo = static_cast<long>(std::floor(-half / r.column)),
             k_hi = static_cast<long>(std::floor(half / r.column));
  const std::size_t n_cols = static_cast<std::size_t>(k_hi - k_lo + 1);
  const double none = -std::numeric_limits<double>::infinity();
  std::vector<double> top(n_cols, none), at(n_cols, 0);
  // The bed's ends along the axis, for the end-wall bands.
  double a_lo = std::numeric_limits<double>::infinity(), a_hi = -a_lo;
  if (opt.near_ends > 0)
    for (std::size_t i = 0; i < f.size(); ++i) {
      const double a = f.x[i][opt.axis], b = f.bounding_radius(i);
      a_lo = std::min(a_lo, a - b), a_hi = std::max(a_hi, a + b);
    }
  for (std::size_t i = 0; i < f.size(); ++i) {
    const double du = f.x[i][iu] - uc;
    if (std::abs(du) > half) continue;
    if (opt.near_ends > 0 && f.x[i][opt.axis] - a_lo > opt.near_ends && a_hi - f.x[i][opt.axis] > opt.near_ends)
      continue;
    const long k = std::clamp(static_cast<long>(std::floor(du / r.column)), k_lo, k_hi);
    const auto c = static_cast<std::size_t>(k - k_lo);
    const double h = f.x[i].z() + half_height(f, i);
    if (h > top[c]) top[c] = h, at[c] = f.x[i][iu];
  }
  for (std::size_t c = 0; c < n_cols; ++c)
    if (top[c] > none) r.u.push_back(at[c]), r.top.push_back(top[c]);
  r.columns = r.u.size();
  if (r.columns < opt.min_columns) {
    std::ostringstream o;
    o << when << ": only " << r.columns << " column(s) of width " << r.column << " m hold particles within |"
      << axis_name(iu) << " - " << uc << "| <= " << opt.span << " x " << r.radius << " m; the fit needs at least "
      << opt.min_columns << " (narrow the columns, widen the span, or check the axis and the centre)";
    throw SurfaceAngleRefused(o.str());
  }

  // Least squares v = a u + b about the means (better conditioned).
  const double n = static_cast<double>(r.columns);
  double mu = 0, mv = 0;
  for (std::size_t c = 0; c < r.columns; ++c) mu += r.u[c], mv += r.top[c];
  mu /= n, mv /= n;
  double suu = 0, suv = 0;
  for (std::size_t c = 0; c < r.columns; ++c)
    suu += (r.u[c] - mu) * (r.u[c] - mu), suv += (r.u[c] - mu) * (r.top[c] - mv);
  r.slope = suv / suu;  // suu > 0: the tops lie in distinct columns
  r.intercept = mv - r.slope * mu;
  double ss = 0;
  for (std::size_t c = 0; c < r.columns; ++c) ss += std::pow(r.top[c] - (r.slope * r.u[c] + r.intercept), 2);
  r.rms_residual = std::sqrt(ss / n);
  r.angle_deg = std::atan(std::abs(r.slope)) * 180 / M_PI;
  return r;
}

std::optional<Vec3> drum_axis_point(const WallSet& walls, int axis) {
  if (axis < 0 || axis > 2) throw std::invalid_argument("the drum axis must be x, y or z");
  std::vector<std::pair<Vec3, std::string>> found;
  for (std::size_t w = 0; w < walls.of<sim::MeshWall>().size(); ++w) {
    const auto& m = walls.of<sim::MeshWall>()[w];
    if (!m.surface || m.surface->vertices().empty()) continue;
    Eigen::AlignedBox3d box;
    for (const auto& v : m.surface->vertices()) box.extend(v);
    found.emplace_back(box.center(), "mesh wall " + std::to_string(w));
  }
  const Vec3 e = Vec3::Unit(axis);
  for (std::size_t w = 0; w < walls.of<sim::CylinderWall>().size(); ++w) {
    const auto& s = walls.of<sim::CylinderWall>()[w].surface;
    if (s.axis.normalized().cross(e).norm() < 1e-6) found.emplace_back(s.base, "cylinder wall " + std::to_string(w));
  }
  if (found.empty()) return std::nullopt;
  // Only the position in the plane normal to the axis matters.
  for (std::size_t k = 1; k < found.size(); ++k) {
    Vec3 d = found[k].first - found[0].first;
    d[axis] = 0;
    const double scale = std::max({1e-3, found[0].first.norm(), found[k].first.norm()});
    if (d.norm() > 1e-6 * scale)
      throw std::invalid_argument("the run's walls give more than one drum axis (" + found[0].second + " and " +
                                  found[k].second + " lie on different axes)");
  }
  return found[0].first;
}

ReposeSummary summarize_repose(const std::vector<SurfaceAngle>& frames) {
  ReposeSummary s;
  s.frames = frames.size();
  if (frames.empty()) return s;
  const double n = static_cast<double>(frames.size());
  for (const auto& f : frames) s.mean_deg += f.angle_deg;
  s.mean_deg /= n;
  if (frames.size() > 1) {
    double ss = 0;
    for (const auto& f : frames) ss += (f.angle_deg - s.mean_deg) * (f.angle_deg - s.mean_deg);
    s.std_deg = std::sqrt(ss / (n - 1));
  }
  s.standard_error_deg = s.std_deg / std::sqrt(n);
  s.from_s = frames.front().time, s.to_s = frames.front().time;
  for (const auto& f : frames) s.from_s = std::min(s.from_s, f.time), s.to_s = std::max(s.to_s, f.time);
  return s;
}

std::vector<fs::path> write_repose(const std::vector<SurfaceAngle>& frames, const ReposeSummary& s,
                                   const SurfaceAngleOptions& opt,
                                   const std::vector<std::pair<std::string, std::string>>& extra, const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error("cannot create '" + dir.string() + "': " + ec.message());
  auto open = [](const fs::path& p) {
    std::ofstream o(p);
    if (!o) throw std::runtime_error("cannot write '" + p.string() + "'");
    o << std::setprecision(10);
    return o;
  };
  const std::vector<fs::path> files{dir / "repose.csv", dir / "repose.json"};
  {
    auto o = open(files[0]);
    o << "time_s,angle_deg,slope,columns,rms_residual_m,radius_m\n";
    for (const auto& f : frames)
      o << f.time << "," << f.angle_deg << "," << f.slope << "," << f.columns << "," << f.rms_residual << ","
        << f.radius << "\n";
    if (!o) throw std::runtime_error("cannot write '" + files[0].string() + "'");
  }
  {
    double column = opt.column, radius = opt.radius;
    if (!frames.empty() && column <= 0) column = frames.front().column;
    if (!frames.empty() && radius <= 0) {  // per frame: their mean
      radius = 0;
      for (const auto& f : frames) radius += f.radius;
      radius /= static_cast<double>(frames.size());
    }
    auto o = open(files[1]);
    o << "{\n  \"frames\": " << s.frames << ",\n  \"mean_deg\": " << s.mean_deg << ",\n  \"std_deg\": " << s.std_deg
      << ",\n  \"standard_error_deg\": " << s.standard_error_deg << ",\n  \"from_s\": " << s.from_s
      << ",\n  \"to_s\": " << s.to_s << ",\n  \"axis\": \"" << axis_name(opt.axis) << "\",\n  \"column_m\": " << column
      << ",\n  \"span\": " << opt.span
      << ",\n  \"near_ends_m\": " << opt.near_ends << ",\n  \"radius_m\": " << radius << ",\n  \"centre\": [" << opt.centre.x()
      << ", " << opt.centre.y() << ", " << opt.centre.z() << "]";
    for (const auto& [k, v] : extra) o << ",\n  \"" << k << "\": " << v;
    o << "\n}\n";
    if (!o) throw std::runtime_error("cannot write '" + files[1].string() + "'");
  }
  return files;
}

}  // namespace grains::postprocess
