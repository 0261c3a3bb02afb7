#include "io/cli/repose_command.hpp"
#include "io/cli/arguments.hpp"

#include <cmath>
#include <exception>
#include <filesystem>
#include <iomanip>
#include <optional>
#include <sstream>

#include "postprocess/surface_angle.hpp"

namespace grains::io {

namespace fs = std::filesystem;
namespace pp = grains::postprocess;

const char* repose_command_usage() {
  return "usage: grains repose OUTDIR [--axis x|y] [--centre X,Y,Z] [--radius R] [--column W] [--span F]\n"
         "                            [--near-ends E] [--from T] [--to T] [-o DIR]\n"
         "  OUTDIR    a folder written by 'grains run' of a rotating drum (holds particles.pvd); gravity along -z\n"
         "  --axis    the drum's axis, x or y (default y)\n"
         "  --centre  a point on the axis, m (default: the centre of the run's mesh wall, or the axis of a\n"
         "            cylinder wall along --axis, in the first frame; the origin when there is neither)\n"
         "  --radius  drum radius, m (default: in each frame, the farthest particle edge from the axis)\n"
         "  --column  width of the columns whose tops make the surface, m (default 2 mean particle diameters)\n"
         "  --span    the columns cover |u - u_centre| <= span x radius (default 0.6; 0 < span <= 1)\n"
         "  --near-ends  only the particles within E (m) of either end of the bed along the axis: the\n"
         "            surface seen through a glass end plate, as drum experiments film it (default: all)\n"
         "  --from    first time measured, s (default 0)\n"
         "  --to      last time measured, s (default: the last frame)\n"
         "  -o DIR    where to write repose.csv and repose.json (default OUTDIR)\n"
         "  Each frame: a least-squares line through the tops of the columns (u the horizontal coordinate\n"
         "  normal to the axis); its angle atan|slope|; the mean and spread over the frames.\n";
}

namespace {

using cli_args::parse_number;

bool parse_point(const std::string& s, pp::Vec3& p) {
  std::vector<double> v;
  if (!cli_args::parse_numbers(s, 3, v)) return false;
  p = pp::Vec3(v[0], v[1], v[2]);
  return true;
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c == '\n' ? ' ' : c;
  }
  return out + "\"";
}

std::string fmt(double x, int precision = 6) {
  std::ostringstream o;
  o << std::setprecision(precision) << x;
  return o.str();
}

}  // namespace

int run_repose_command(const std::vector<std::string>& a, std::ostream& out, std::ostream& err) {
  std::string dir, out_dir;
  pp::SurfaceAngleOptions opt;
  bool centre_given = false;
  double from = 0;
  std::optional<double> to;
  auto bad = [&](const std::string& msg) {
    err << "grains repose: " << msg << " (grains repose -h for the usage)\n";
    return 2;
  };
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string& s = a[i];
    const bool has_value = i + 1 < a.size();
    auto value = [&]() -> const std::string& { return a[++i]; };
    if (s == "-h" || s == "--help") {
      out << repose_command_usage();
      return 0;
    } else if (s == "--axis") {
      if (!has_value) return bad("--axis needs x or y");
      const std::string v = value();
      if (v == "x")
        opt.axis = 0;
      else if (v == "y")
        opt.axis = 1;
      else if (v == "z")
        return bad("--axis z is refused: gravity is along -z, so the drum's axis must be horizontal (x or y)");
      else
        return bad("--axis must be x or y, got '" + v + "'");
    } else if (s == "--centre" || s == "--center") {
      if (!has_value || !parse_point(value(), opt.centre)) return bad(s + " needs three numbers X,Y,Z (m)");
      centre_given = true;
    } else if (s == "--radius") {
      if (!has_value || !parse_number(value(), opt.radius) || opt.radius <= 0)
        return bad("--radius needs a positive length (m)");
    } else if (s == "--column") {
      if (!has_value || !parse_number(value(), opt.column) || opt.column <= 0)
        return bad("--column needs a positive width (m)");
    } else if (s == "--span") {
      if (!has_value || !parse_number(value(), opt.span) || !(opt.span > 0 && opt.span <= 1))
        return bad("--span needs a fraction of the radius in (0, 1]");
    } else if (s == "--near-ends") {
      if (!has_value || !parse_number(value(), opt.near_ends) || opt.near_ends <= 0)
        return bad("--near-ends needs a positive length (m)");
    } else if (s == "--from") {
      if (!has_value || !parse_number(value(), from)) return bad("--from needs a time (s)");
    } else if (s == "--to") {
      double t;
      if (!has_value || !parse_number(value(), t)) return bad("--to needs a time (s)");
      to = t;
    } else if (s == "-o" || s == "--out") {
      if (!has_value) return bad("-o needs a folder");
      out_dir = value();
    } else if (!s.empty() && s[0] == '-' && s.size() > 1) {
      return bad("unknown option '" + s + "'");
    } else if (dir.empty()) {
      dir = s;
    } else {
      return bad("unexpected argument '" + s + "' (one output folder only)");
    }
  }
  if (dir.empty()) return bad("missing the output folder of a run");
  if (to && *to < from) return bad("--to " + fmt(*to) + " lies before --from " + fmt(from));
  if (!fs::exists(fs::path(dir) / "particles.pvd"))
    return err << "grains repose: '" << dir << "' has no particles.pvd (not an output folder of 'grains run')\n", 2;
  const fs::path dest = out_dir.empty() ? fs::path(dir) : fs::path(out_dir);

  // The frames in the time window.
  std::vector<pp::FrameEntry> all;
  try {
    all = pp::list_frames(dir);
  } catch (const std::exception& e) {
    return err << "grains repose: " << e.what() << "\n", 2;
  }
  std::vector<std::size_t> chosen;
  for (std::size_t k = 0; k < all.size(); ++k)
    if (all[k].time >= from && (!to || all[k].time <= *to)) chosen.push_back(k);
  if (chosen.empty()) {
    std::ostringstream o;
    o << "grains repose: no frame of '" << dir << "' has a time in [" << from << ", " << (to ? fmt(*to) : "end")
      << "] s";
    if (!all.empty())
      o << " (its " << all.size() << " frames span " << all.front().time << " .. " << all.back().time << " s)";
    return err << o.str() << "\n", 2;
  }

  // The drum's centre, from the walls of the run's first frame when not given.
  std::string centre_source = "--centre";
  if (!centre_given) {
    try {
      const fs::path wf = pp::walls_file(dir, 0);
      std::optional<pp::Vec3> c;
      if (!wf.empty()) c = pp::drum_axis_point(pp::read_walls(wf), opt.axis);
      if (c) {
        opt.centre = *c;
        centre_source = "the run's drum wall (" + wf.filename().string() + ")";
      } else {
        centre_source = "the origin (no mesh wall, nor a cylinder wall along the axis)";
      }
    } catch (const std::exception& e) {
      return err << "grains repose: " << e.what() << "; give the drum's centre with --centre X,Y,Z\n", 2;
    }
  }

  std::vector<pp::SurfaceAngle> angles;
  std::size_t skipped = 0;
  std::string last_refusal;
  for (const std::size_t k : chosen) {
    pp::Frame f;
    try {
      f = pp::read_frame_file(all[k].file);
    } catch (const std::exception& e) {
      return err << "grains repose: " << e.what() << "\n", 2;
    }
    f.index = k;
    f.time = all[k].time;
    // One column width for the whole series: 2 mean diameters of the first frame.
    if (opt.column <= 0 && f.size() > 0) opt.column = 2 * f.mean_diameter();
    try {
      angles.push_back(pp::surface_angle(f, opt));
    } catch (const pp::SurfaceAngleRefused& e) {
      ++skipped;
      last_refusal = e.what();
      err << "grains repose: skipped " << e.what() << "\n";
    } catch (const std::invalid_argument& e) {
      return err << "grains repose: " << e.what() << "\n", 2;
    }
  }
  if (angles.empty())
    return err << "grains repose: no frame could be measured (" << skipped << " refused; the last: " << last_refusal
               << ")\n",
           1;

  const auto sum = pp::summarize_repose(angles);
  std::size_t higher_plus = 0;
  for (const auto& s : angles) higher_plus += s.slope > 0;
  const std::string u = std::string(1, "xyz"[pp::surface_u_axis(opt.axis)]);
  // Which side of the drum the surface rises towards (the sign of the slope).
  std::string side, side_text;
  if (higher_plus == angles.size() || higher_plus == 0) {
    side = (higher_plus ? "+" : "-") + u;
    side_text = "higher on the " + side + " side";
  } else {
    auto frames = [](std::size_t n) { return std::to_string(n) + (n == 1 ? " frame" : " frames"); };
    side = "+" + u + " in " + frames(higher_plus) + ", -" + u + " in " + frames(angles.size() - higher_plus);
    side_text = "higher on the " + side;
  }
  try {
    const std::vector<std::pair<std::string, std::string>> extra{
        {"centre_source", json_string(centre_source)},
        {"radius_source",
         json_string(opt.radius > 0 ? "--radius" : "each frame: the farthest particle edge from the axis")},
        {"higher_side", json_string(side)},
        {"frames_skipped", std::to_string(skipped)},
        {"from_requested_s", fmt(from, 10)},
        {"to_requested_s", to ? fmt(*to, 10) : "null"}};
    const auto files = pp::write_repose(angles, sum, opt, extra, dest);
    std::ostringstream o;
    o << std::fixed << std::setprecision(2) << "angle of repose " << sum.mean_deg << " ± " << sum.std_deg << " deg ("
      << sum.frames << " frame" << (sum.frames == 1 ? "" : "s") << std::defaultfloat << ", t = " << sum.from_s << " .. "
      << sum.to_s << " s";
    if (skipped) o << ", " << skipped << " skipped";
    o << "; " << side_text << ") -> " << files[0].string() << ", " << files[1].filename().string();
    out << o.str() << "\n";
  } catch (const std::exception& e) {
    return err << "grains repose: " << e.what() << "\n", 1;
  }
  return 0;
}

}  // namespace grains::io
