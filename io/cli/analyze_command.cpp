#include "io/cli/analyze_command.hpp"
#include "io/cli/arguments.hpp"

#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "postprocess/analysis.hpp"
#include "postprocess/plots.hpp"
#include "postprocess/render.hpp"
#include "postprocess/stress_series.hpp"

namespace grains::io {

namespace fs = std::filesystem;
namespace pp = grains::postprocess;

namespace {

const char* kAnalyzeUsage =
    "usage: grains analyze OUTDIR [--frame N | --time T] [--region xmin,ymin,zmin,xmax,ymax,zmax]\n"
    "                      [--margin D] [--axis x|y|z] [--rattler-contacts K] [--rattlers once|iterative]\n"
    "                      [--samples M] [--no-walls] [--no-plots] [--from T] [-o DIR]\n"
    "  OUTDIR   a folder written by 'grains run' (holds particles.pvd, or output.stress's stress.csv)\n"
    "  --frame  frame number (0 = first; negative counts from the end; default -1, the last)\n"
    "  --time   the frame closest to this time (s)\n"
    "  --region the analysis box in metres (default: automatic bulk region)\n"
    "  --margin distance of the automatic region from walls and free surface, in mean diameters (default 2)\n"
    "  --axis   axis of the packing-fraction profile (default z)\n"
    "  --rattler-contacts  rattler: fewer contacts than this (default 4)\n"
    "  --rattlers once (default) or iterative (repeat after removing rattlers' contacts)\n"
    "  --no-walls particle contacts only (default: contacts with the frame's walls count too)\n"
    "  --samples Monte Carlo points per particle for ellipsoids and clumps (default 1000)\n"
    "  --from   the stress series (stress.csv, profile.csv of output.stress) is averaged from this time, s\n"
    "           (default: the run's output.stress.average_after, else the series' second half); written\n"
    "           to stress_series.json: means, block errors, p, sqrt(J2)/p, shear-to-normal ratios, profiles\n"
    "  -o DIR   where to write analysis.json, the CSV files and the PNG plots (default OUTDIR/analysis)\n";

const char* kRenderUsage =
    "usage: grains render OUTDIR [--frame N] [--color FIELD] [--view iso|x|y|z] [--size WxH] [--no-walls] -o PNG\n"
    "  --color  point field: radius (default), velocity, force, coordination, material, id, angular_velocity,\n"
    "           or one component, e.g. velocity:z\n";

using cli_args::parse_long;
using cli_args::parse_number;

bool parse_region(const std::string& s, pp::Box& b) {
  std::vector<double> v;
  if (!cli_args::parse_numbers(s, 6, v)) return false;
  b.lo = pp::Vec3(v[0], v[1], v[2]);
  b.hi = pp::Vec3(v[3], v[4], v[5]);
  return (b.hi.array() > b.lo.array()).all();
}

int axis_of(const std::string& s) {
  if (s == "x" || s == "0") return 0;
  if (s == "y" || s == "1") return 1;
  if (s == "z" || s == "2") return 2;
  return -1;
}

}  // namespace

int run_analyze_command(const std::vector<std::string>& a, std::ostream& out, std::ostream& err) {
  std::string dir, out_dir;
  long frame = -1;
  std::optional<double> time;
  pp::AnalysisOptions opt;
  std::optional<double> from;  // the stress series' averaging window
  bool plots = true;
  auto bad = [&](const std::string& msg) {
    err << "grains analyze: " << msg << "\n" << kAnalyzeUsage;
    return 2;
  };
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string& s = a[i];
    const bool has_value = i + 1 < a.size();
    auto value = [&]() -> const std::string& { return a[++i]; };
    if (s == "-h" || s == "--help") {
      out << kAnalyzeUsage;
      return 0;
    } else if (s == "--frame") {
      if (!has_value || !parse_long(value(), frame)) return bad("--frame needs an integer");
    } else if (s == "--time") {
      double t;
      if (!has_value || !parse_number(value(), t)) return bad("--time needs a number of seconds");
      time = t;
    } else if (s == "--region") {
      pp::Box b;
      if (!has_value || !parse_region(value(), b))
        return bad("--region needs six numbers xmin,ymin,zmin,xmax,ymax,zmax with min < max");
      opt.region = b;
    } else if (s == "--margin") {
      if (!has_value || !parse_number(value(), opt.margin_diameters) || opt.margin_diameters < 0)
        return bad("--margin needs a non-negative number of diameters");
    } else if (s == "--axis") {
      if (!has_value || (opt.profile_axis = axis_of(value())) < 0) return bad("--axis must be x, y or z");
    } else if (s == "--rattler-contacts") {
      long k;
      if (!has_value || !parse_long(value(), k) || k < 0 || k > 64) return bad("--rattler-contacts needs 0..64");
      opt.rattler_contacts = static_cast<int>(k);
    } else if (s == "--rattlers") {
      if (!has_value) return bad("--rattlers needs once or iterative");
      const std::string v = value();
      if (v == "once") opt.rattler_rule = pp::RattlerRule::once;
      else if (v == "iterative") opt.rattler_rule = pp::RattlerRule::iterative;
      else return bad("--rattlers must be once or iterative");
    } else if (s == "--no-walls") {
      opt.wall_contacts = false;
    } else if (s == "--samples") {
      long k;
      if (!has_value || !parse_long(value(), k) || k < 10) return bad("--samples needs an integer >= 10");
      opt.sampling.samples_per_particle = static_cast<std::size_t>(k);
    } else if (s == "--from") {
      double t;
      if (!has_value || !parse_number(value(), t)) return bad("--from needs a number of seconds");
      from = t;
    } else if (s == "--no-plots") {
      plots = false;
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
  const bool frames = fs::exists(fs::path(dir) / "particles.pvd");
  const bool series = fs::exists(fs::path(dir) / "stress.csv");
  if (!frames && !series)
    return err << "grains analyze: '" << dir
               << "' has neither particles.pvd nor stress.csv (not an output folder of 'grains run')\n",
           2;
  const fs::path dest = out_dir.empty() ? fs::path(dir) / "analysis" : fs::path(out_dir);
  if (series) {
    // The stress series of output.stress: means, errors, invariants, profiles.
    try {
      const auto ss = pp::read_stress_series(dir, from);
      fs::create_directories(dest);
      std::ofstream j(dest / "stress_series.json");
      j << pp::stress_series_json(*ss);
      if (!j) throw std::runtime_error("cannot write " + (dest / "stress_series.json").string());
      out << pp::stress_series_summary(*ss) << "wrote stress_series.json to " << dest.string() << "\n";
    } catch (const std::invalid_argument& e) {
      return err << "grains analyze: " << e.what() << "\n", 2;
    } catch (const std::exception& e) {
      return err << "grains analyze: " << e.what() << "\n", 1;
    }
    if (!frames) return 0;
  }
  pp::Frame f;
  try {
    f = time ? pp::read_frame_at_time(dir, *time) : pp::read_frame(dir, frame);
  } catch (const std::exception& e) {
    return err << "grains analyze: " << e.what() << "\n", 2;
  }
  try {
    std::optional<pp::WallSet> walls;
    if (const auto wf = pp::walls_file(dir, f.index); !wf.empty() && opt.wall_contacts) walls = pp::read_walls(wf);
    const auto r = pp::analyze_frame(f, opt, walls ? &*walls : nullptr);
    const auto files = pp::write_analysis(r, dest);
    out << pp::analysis_summary(r);
    out << "wrote";
    for (const auto& p : files) out << " " << p.filename().string();
    out << " to " << dest.string() << "\n";
    if (plots) {
      const std::string why = pp::make_plots(dest);
      if (why.empty())
        out << "plots: " << (dest / "*.png").string() << "\n";
      else
        err << "grains analyze: no plots: " << why << "\n";
    }
  } catch (const std::invalid_argument& e) {
    return err << "grains analyze: " << e.what() << "\n", 2;
  } catch (const std::exception& e) {
    return err << "grains analyze: " << e.what() << "\n", 1;
  }
  return 0;
}

int run_render_command(const std::vector<std::string>& a, std::ostream& out, std::ostream& err) {
  std::string dir, png;
  long frame = -1;
  pp::RenderOptions opt;
  auto bad = [&](const std::string& msg) {
    err << "grains render: " << msg << "\n" << kRenderUsage;
    return 2;
  };
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string& s = a[i];
    const bool has_value = i + 1 < a.size();
    auto value = [&]() -> const std::string& { return a[++i]; };
    if (s == "-h" || s == "--help") {
      out << kRenderUsage;
      return 0;
    } else if (s == "--frame") {
      if (!has_value || !parse_long(value(), frame)) return bad("--frame needs an integer");
    } else if (s == "--color" || s == "--colour") {
      if (!has_value) return bad("--color needs a field name");
      opt.color = value();
    } else if (s == "--view") {
      if (!has_value) return bad("--view needs iso, x, y or z");
      opt.view = value();
      if (opt.view != "iso" && opt.view != "x" && opt.view != "y" && opt.view != "z")
        return bad("--view must be iso, x, y or z");
    } else if (s == "--size") {
      if (!has_value) return bad("--size needs WxH");
      const std::string v = value();
      const auto x = v.find('x');
      long w = 0, h = 0;
      if (x == std::string::npos || !parse_long(v.substr(0, x), w) || !parse_long(v.substr(x + 1), h) || w < 16 ||
          h < 16 || w > 8192 || h > 8192)
        return bad("--size needs WxH with 16..8192 pixels each, e.g. 1200x900");
      opt.width = static_cast<int>(w);
      opt.height = static_cast<int>(h);
    } else if (s == "--no-walls") {
      opt.walls = false;
    } else if (s == "-o" || s == "--out") {
      if (!has_value) return bad("-o needs a PNG file name");
      png = value();
    } else if (!s.empty() && s[0] == '-' && s.size() > 1) {
      return bad("unknown option '" + s + "'");
    } else if (dir.empty()) {
      dir = s;
    } else {
      return bad("unexpected argument '" + s + "' (one output folder only)");
    }
  }
  if (dir.empty()) return bad("missing the output folder of a run");
  if (png.empty()) return bad("missing -o snapshot.png");
  if (!fs::exists(fs::path(dir) / "particles.pvd"))
    return err << "grains render: '" << dir << "' has no particles.pvd (not an output folder of 'grains run')\n", 2;
  try {
    pp::render_frame(dir, frame, opt, png);
  } catch (const std::exception& e) {
    return err << "grains render: " << e.what() << "\n", 1;
  }
  out << "wrote " << png << "\n";
  return 0;
}

}  // namespace grains::io
