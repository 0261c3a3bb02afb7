// The free-surface angle of a drum bed (postprocess/surface_angle.hpp) on
// synthetic beds of known angle, and `grains repose` on a folder of frames.
#include <gtest/gtest.h>
#include <unistd.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "io/cli/repose_command.hpp"
#include "postprocess/surface_angle.hpp"

namespace grains::postprocess {
namespace {

namespace fs = std::filesystem;

constexpr double kR = 0.0015;   // particle radius, m
constexpr double kDrum = 0.05;  // drum radius, m

// Spheres of radius kR on a square lattice (spacing 2 kR, shifted by `shift`
// spacings) in the plane normal to `axis`, inside a disc of radius kDrum about
// `centre`, below the line through the centre rising at `angle_deg` towards
// +u; `layers` copies along the axis.
Frame drum_bed(double angle_deg, int axis = 1, const Vec3& centre = Vec3::Zero(), double shift = 0, int layers = 3) {
  const int iu = axis == 0 ? 1 : 0;
  const double a = 2 * kR, slope = std::tan(angle_deg * M_PI / 180);
  const int n = static_cast<int>(kDrum / a) + 2;
  Frame f;
  for (int i = -n; i <= n; ++i)
    for (int k = -n; k <= n; ++k) {
      const double du = (i + shift) * a, dv = (k + shift) * a;
      if (std::hypot(du, dv) + kR > kDrum || dv + kR > slope * du) continue;
      for (int l = 0; l < layers; ++l) {
        Vec3 x = centre;
        x[iu] += du;
        x.z() += dv;
        x[axis] += l * a;
        f.x.push_back(x);
        f.radius.push_back(kR);
      }
    }
  return f;
}

TEST(SurfaceAngle, RecoversTheAngleOfATiltedBed) {
  for (const double angle : {22.0, 35.0, -30.0})
    for (const double shift : {0.0, 0.37}) {
      SCOPED_TRACE("angle " + std::to_string(angle) + " deg, lattice shift " + std::to_string(shift));
      const Frame f = drum_bed(angle, 1, Vec3::Zero(), shift);
      const auto r = surface_angle(f, {});
      EXPECT_NEAR(r.angle_deg, std::abs(angle), 0.7);
      EXPECT_EQ(r.slope > 0, angle > 0);     // which side is higher
      EXPECT_NEAR(r.column, 4 * kR, 1e-12);  // 2 mean diameters
      EXPECT_NEAR(r.radius, kDrum, 2 * kR);  // the far edge of the outermost particle
      // |u| <= 0.6 R, columns 6 mm wide: 10 or 11 of them.
      EXPECT_GE(r.columns, 10u);
      EXPECT_LE(r.columns, 11u);
      EXPECT_EQ(r.u.size(), r.columns);
      // The lattice's tops lie within a lattice spacing below the line.
      EXPECT_GT(r.rms_residual, 0.0);
      EXPECT_LT(r.rms_residual, 2 * kR);
      for (std::size_t c = 0; c < r.columns; ++c) {
        const double line = std::tan(angle * M_PI / 180) * r.u[c];
        EXPECT_LE(r.top[c], line + 1e-12);
        EXPECT_GT(r.top[c], line - 2 * kR - std::abs(std::tan(angle * M_PI / 180)) * 2 * kR);
      }
    }
}

TEST(SurfaceAngle, AxisXAndAnOffCentreDrumGiveTheSameAngle) {
  const Vec3 centre(0.013, -0.4, 0.21);
  const auto ref = surface_angle(drum_bed(35, 1, Vec3::Zero(), 0.37), {});
  for (const int axis : {0, 1}) {
    SurfaceAngleOptions o;
    o.axis = axis;
    o.centre = centre;
    const auto r = surface_angle(drum_bed(35, axis, centre, 0.37), o);
    EXPECT_NEAR(r.angle_deg, ref.angle_deg, 1e-9);
    EXPECT_NEAR(r.rms_residual, ref.rms_residual, 1e-9);
    EXPECT_EQ(r.columns, ref.columns);
    // The line passes through the centre: its intercept is in world coordinates.
    EXPECT_NEAR(r.intercept + r.slope * centre[surface_u_axis(axis)], centre.z() + ref.intercept, 1e-9);
  }
}

TEST(SurfaceAngle, OnlyTheTopOfEachColumnCounts) {
  const Frame bed = drum_bed(22);
  SurfaceAngleOptions o;
  o.column = 4 * kR;  // fixed: the extra particles below would change the mean diameter
  o.radius = kDrum;
  const auto ref = surface_angle(bed, o);
  // A lower layer of large and small particles, well below the surface,
  // spread over all the columns (overlapping the bed: only their tops matter).
  Frame more = bed;
  for (int i = 0; i < 200; ++i) {
    const double u = -0.028 + 0.056 * i / 199.0;
    const double line = std::tan(22 * M_PI / 180) * u;
    const double rr = i % 2 ? 0.5 * kR : 3 * kR;
    more.x.emplace_back(u, 0.001 * (i % 5), line - 4 * kR - rr - 0.004 * (i % 3));
    more.radius.push_back(rr);
  }
  const auto r = surface_angle(more, o);
  EXPECT_EQ(r.columns, ref.columns);
  EXPECT_EQ(r.slope, ref.slope);
  EXPECT_EQ(r.rms_residual, ref.rms_residual);
  EXPECT_EQ(r.u, ref.u);
  EXPECT_EQ(r.top, ref.top);
  // A particle above the surface is a column's top: it changes the fit.
  Frame above = bed;
  above.x.emplace_back(0.02, 0, std::tan(22 * M_PI / 180) * 0.02 + 5 * kR);
  above.radius.push_back(kR);
  const auto changed = surface_angle(above, o);
  EXPECT_EQ(changed.columns, ref.columns);
  EXPECT_NE(changed.slope, ref.slope);
  EXPECT_GT(changed.angle_deg, ref.angle_deg);
}

TEST(SurfaceAngle, EllipsoidTopsAreTheirExtentAlongZ) {
  // Five ellipsoids on the line z = 0.2 u, lying on their side (body z along
  // world y): each top lies its semi-axis b above the centre.
  Frame f;
  const Vec3 semi(0.001, 0.002, 0.003);
  for (int i = -2; i <= 2; ++i) {
    f.x.emplace_back(0.01 * i + 0.003, 0, 0.2 * (0.01 * i + 0.003));
    f.radius.push_back(semi.maxCoeff());
    f.semi_axes.push_back(semi);
    f.orientation.emplace_back(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()));
  }
  SurfaceAngleOptions o;
  o.column = 0.01;
  o.radius = 0.04;
  o.span = 0.75;
  const auto r = surface_angle(f, o);
  ASSERT_EQ(r.columns, 5u);
  for (std::size_t c = 0; c < 5; ++c) EXPECT_NEAR(r.top[c], 0.2 * r.u[c] + semi.y(), 1e-12);
  EXPECT_NEAR(r.slope, 0.2, 1e-12);
  EXPECT_NEAR(r.angle_deg, std::atan(0.2) * 180 / M_PI, 1e-9);
  EXPECT_NEAR(r.rms_residual, 0, 1e-12);
}

TEST(SurfaceAngle, RefusesFewerThanFourColumns) {
  // Lattice columns at u = -10.89, -7.89, -4.89, -1.89, 1.11, 4.11, 7.11, 10.11 mm.
  const Frame bed = drum_bed(30, 1, Vec3::Zero(), 0.37);
  SurfaceAngleOptions o;
  o.radius = kDrum;
  o.span = 0.15;  // |u| <= 7.5 mm: particles in the columns [-6, 0), [0, 6), [6, 12) mm only
  try {
    surface_angle(bed, o);
    FAIL() << "a frame with 3 columns was measured";
  } catch (const SurfaceAngleRefused& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("only 3 column(s)"), std::string::npos) << what;
    EXPECT_NE(what.find("at least 4"), std::string::npos) << what;
  }
  o.span = 0.25;  // |u| <= 12.5 mm: [-12, -6) too, four columns, measured
  EXPECT_EQ(surface_angle(bed, o).columns, 4u);
  EXPECT_THROW(surface_angle(Frame{}, {}), SurfaceAngleRefused);
}

TEST(SurfaceAngle, NearEndsMeasuresOnlyTheBandsNextToTheEndWalls) {
  // A bed 3 layers long at 40 degrees, 4 layers at 20 degrees beyond it
  // along the axis (the middle of a long drum), and 3 more at 40 (the far
  // end): the ends alone give 40 degrees, the whole bed's column tops mix.
  Frame f;
  const double a = 2 * kR;
  const auto append = [&](double angle, double y0, int layers) {
    Frame b = drum_bed(angle, 1, Vec3(0, y0, 0), 0, layers);
    f.x.insert(f.x.end(), b.x.begin(), b.x.end());
    f.radius.insert(f.radius.end(), b.radius.begin(), b.radius.end());
  };
  append(40, 0, 3);
  append(20, 3 * a, 4);
  append(40, 7 * a, 3);
  SurfaceAngleOptions o;
  o.near_ends = 2.5 * a;  // the first and the last three layers' centres lie within 2 spacings + kR of the ends
  const auto ends = surface_angle(f, o);
  EXPECT_NEAR(ends.angle_deg, surface_angle(drum_bed(40), {}).angle_deg, 1e-12);
  o.near_ends = 0;
  EXPECT_GT(std::abs(surface_angle(f, o).angle_deg - ends.angle_deg), 1.0);
  o.near_ends = 0.5 * kR;  // no centre that close to an end: no columns
  EXPECT_THROW(surface_angle(f, o), SurfaceAngleRefused);
  o.near_ends = -1;
  EXPECT_THROW(surface_angle(f, o), std::invalid_argument);
}

TEST(SurfaceAngle, RefusesBadOptions) {
  const Frame bed = drum_bed(30);
  SurfaceAngleOptions o;
  o.axis = 2;  // gravity is along -z
  EXPECT_THROW(surface_angle(bed, o), std::invalid_argument);
  o = {};
  o.span = 1.5;
  EXPECT_THROW(surface_angle(bed, o), std::invalid_argument);
  o = {};
  o.column = -1;
  EXPECT_THROW(surface_angle(bed, o), std::invalid_argument);
}

TEST(SurfaceAngle, SummaryOfASeries) {
  std::vector<SurfaceAngle> s(3);
  const double angle[] = {30, 33, 36}, time[] = {1, 1.5, 2};
  for (int k = 0; k < 3; ++k) s[k].angle_deg = angle[k], s[k].time = time[k];
  const auto m = summarize_repose(s);
  EXPECT_EQ(m.frames, 3u);
  EXPECT_DOUBLE_EQ(m.mean_deg, 33);
  EXPECT_DOUBLE_EQ(m.std_deg, 3);
  EXPECT_DOUBLE_EQ(m.standard_error_deg, 3 / std::sqrt(3.0));
  EXPECT_DOUBLE_EQ(m.from_s, 1);
  EXPECT_DOUBLE_EQ(m.to_s, 2);
}

// ---- grains repose on files ----

void write_vtu(const Frame& f, const fs::path& file) {
  vtkNew<vtkPoints> pts;
  vtkNew<vtkDoubleArray> radius;
  radius->SetName("radius");
  for (std::size_t i = 0; i < f.size(); ++i) {
    pts->InsertNextPoint(f.x[i].data());
    radius->InsertNextValue(f.radius[i]);
  }
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(pts);
  grid->GetPointData()->AddArray(radius);
  vtkNew<vtkXMLUnstructuredGridWriter> w;
  w->SetFileName(file.c_str());
  w->SetInputData(grid);
  ASSERT_EQ(w->Write(), 1) << file;
}

struct TempDir {
  fs::path path;
  TempDir() {
    std::string t = (fs::temp_directory_path() / "grains_repose_XXXXXX").string();
    path = mkdtemp(t.data());
  }
  ~TempDir() { fs::remove_all(path); }
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(ReposeCommand, MeasuresTheFramesInTheWindow) {
  TempDir tmp;
  const fs::path run = tmp.path / "run";
  fs::create_directories(run / "frames");
  const double angles[] = {-30, -32, -34}, times[] = {0, 0.5, 1};
  std::ofstream pvd(run / "particles.pvd");
  pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (int k = 0; k < 3; ++k) {
    const std::string name = "frames/particles_00000" + std::to_string(k) + ".vtu";
    write_vtu(drum_bed(angles[k], 1, Vec3::Zero(), 0.37, 1), run / name);
    pvd << "<DataSet timestep=\"" << times[k] << "\" file=\"" << name << "\"/>\n";
  }
  pvd << "</Collection>\n</VTKFile>\n";
  pvd.close();

  std::ostringstream out, err;
  ASSERT_EQ(io::run_repose_command({run.string(), "--from", "0.25"}, out, err), 0) << err.str();
  EXPECT_NE(out.str().find("(2 frames"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("higher on the -x side"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("±"), std::string::npos) << out.str();
  // repose.csv: a header and the frames at 0.5 and 1 s.
  std::istringstream csv(slurp(run / "repose.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line.rfind("time_s,angle_deg,slope,columns,rms_residual_m", 0), 0u) << line;
  std::vector<std::vector<double>> rows;
  while (std::getline(csv, line)) {
    std::vector<double> v;
    std::stringstream ls(line);
    std::string cell;
    while (std::getline(ls, cell, ',')) v.push_back(std::stod(cell));
    rows.push_back(v);
  }
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_DOUBLE_EQ(rows[0][0], 0.5);
  EXPECT_DOUBLE_EQ(rows[1][0], 1.0);
  EXPECT_NEAR(rows[0][1], 32, 0.7);
  EXPECT_NEAR(rows[1][1], 34, 0.7);
  EXPECT_LT(rows[0][2], 0);
  const std::string json = slurp(run / "repose.json");
  EXPECT_NE(json.find("\"frames\": 2,"), std::string::npos) << json;
  EXPECT_NE(json.find("\"axis\": \"y\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"column_m\": 0.006,"), std::string::npos) << json;
  EXPECT_NE(json.find("\"span\": 0.6,"), std::string::npos) << json;
  EXPECT_NE(json.find("\"from_s\": 0.5,"), std::string::npos) << json;
  EXPECT_NE(json.find("\"to_s\": 1,"), std::string::npos) << json;
  EXPECT_NE(json.find("\"centre_source\": \"the origin"), std::string::npos) << json;
  for (const char* key : {"\"mean_deg\": ", "\"std_deg\": ", "\"standard_error_deg\": "})
    EXPECT_NE(json.find(key), std::string::npos) << key;
  const double mean = std::stod(json.substr(json.find("\"mean_deg\": ") + 12));
  EXPECT_NEAR(mean, (rows[0][1] + rows[1][1]) / 2, 1e-8);
  const double sd = std::stod(json.substr(json.find("\"std_deg\": ") + 11));
  EXPECT_NEAR(sd, std::abs(rows[0][1] - rows[1][1]) / std::sqrt(2.0), 1e-8);

  // -o elsewhere, a window of one frame.
  std::ostringstream out2, err2;
  ASSERT_EQ(io::run_repose_command({run.string(), "--to", "0.1", "-o", (tmp.path / "elsewhere").string()}, out2, err2),
            0)
      << err2.str();
  EXPECT_TRUE(fs::exists(tmp.path / "elsewhere" / "repose.json"));
  EXPECT_NE(slurp(tmp.path / "elsewhere" / "repose.json").find("\"frames\": 1,"), std::string::npos);

  // --near-ends: the frames are one layer long, so a band of a radius keeps
  // every grain (the same angles) and is written to repose.json.
  std::ostringstream out4, err4;
  ASSERT_EQ(io::run_repose_command({run.string(), "--near-ends", "0.0015", "-o", (tmp.path / "ends").string()}, out4,
                                   err4),
            0)
      << err4.str();
  const std::string ends = slurp(tmp.path / "ends" / "repose.json");
  EXPECT_NE(ends.find("\"near_ends_m\": 0.0015,"), std::string::npos) << ends;
  EXPECT_NEAR(std::stod(ends.substr(ends.find("\"mean_deg\": ") + 12)), 32, 1.5);

  // Too narrow a span: every frame refused, said why, exit 1.
  std::ostringstream out3, err3;
  EXPECT_EQ(io::run_repose_command({run.string(), "--span", "0.1"}, out3, err3), 1);
  EXPECT_NE(err3.str().find("column"), std::string::npos) << err3.str();

  // Bad arguments: one line, exit 2.
  for (const std::vector<std::string>& bad : {std::vector<std::string>{run.string(), "--axis", "z"},
                                              {run.string(), "--span", "2"},
                                              {run.string(), "--near-ends", "0"},
                                              {run.string(), "--centre", "1,2"},
                                              {run.string(), "--from", "2", "--to", "1"},
                                              {run.string(), "--bogus"},
                                              {},
                                              {(tmp.path / "nothing").string()},
                                              {run.string(), "--from", "5"}}) {
    std::ostringstream o, e;
    EXPECT_EQ(io::run_repose_command(bad, o, e), 2) << e.str();
    const std::string msg = e.str();
    EXPECT_EQ(std::count(msg.begin(), msg.end(), '\n'), 1) << msg;
    EXPECT_TRUE(o.str().empty());
  }
}

}  // namespace
}  // namespace grains::postprocess
