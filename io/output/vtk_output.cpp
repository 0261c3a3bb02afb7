#include "io/output/vtk_output.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkLongLongArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include "io/output/paraview_state.hpp"
#include "sim/parallel/comm.hpp"

#include "contact/sphere.hpp"
#include "sim/neighbor/pair_geometry.hpp"

namespace grains::io {

namespace fs = std::filesystem;
using sim::Vec3;

std::vector<int> coordination_numbers(const sim::Scene& s) {
  const auto& p = s.particles;
  const auto& nl = s.neighbors;
  std::vector<int> z(p.n_owned(), 0);
  const std::size_t rows = nl.row_start.empty() ? 0 : nl.row_start.size() - 1;
  // Rows cover ghosts too (under MPI or with periodic images): count each
  // contact for whichever of its particles this rank owns.
  for (std::size_t i = 0; i < rows; ++i)
    for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
      const auto j = nl.partner[k];
      const double rs = p.radius[i] + p.radius[j];
      if ((p.x[i] - p.x[j]).squaredNorm() >= rs * rs) continue;
      bool touching = true;
      if (p.shape[i] != sim::kSphere || p.shape[j] != sim::kSphere) {
        double lambda = -1;
        contact::ContactGeometry g;
        touching = sim::shape_pair_geometry(p, i, j, lambda, g);
      }
      if (touching) {
        if (i < z.size()) ++z[i];
        if (j < z.size()) ++z[j];
      }
    }
  return z;
}

VtkOutput::VtkOutput(fs::path dir, std::int64_t every_steps) : dir_(std::move(dir)), every_(every_steps) {}

std::string VtkOutput::name() const {
  return "output.vtk(" + (every_ > 0 ? "every " + std::to_string(every_) + " steps" : std::string("first+last")) + ")";
}

void VtkOutput::run(sim::Scene& s) {
  if (reads_state(s)) write_frame(s);  // its cadence
}

void VtkOutput::finish(sim::Scene& s) {
  if (last_step_ != s.clock.step) write_frame(s);
}

namespace {
std::string piece_name(const std::string& stem, int rank);
void write_pvtu(const fs::path& file, const std::string& layout, const std::string& stem, int pieces);
}  // namespace

void VtkOutput::write_frame(const sim::Scene& s) {
  // Under MPI every rank writes its piece of the frame and rank 0 the .pvtu
  // index, the walls and the .pvd series. A failure on any rank stops all
  // ranks with the same message (no rank is left waiting).
  const auto& comm = sim::Comm::world();
  const bool par = comm.parallel();
  std::string err;
  try {
    if (times_.empty()) {
      std::error_code ec;
      fs::create_directories(dir_ / "frames", ec);
      if (ec) throw std::runtime_error("cannot create output folder '" + (dir_ / "frames").string() + "': " + ec.message());
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, "%06zu", times_.size());
    const fs::path frames = dir_ / "frames";
    const bool clumps = s.particles.fields().has(sim::Field::Body);
    if (!par) {
      write_particles(s, frames / (std::string("particles_") + buf + ".vtu"));
      if (clumps) write_bodies(s, frames / (std::string("bodies_") + buf + ".vtu"));
    } else {
      const std::string ps = std::string("particles_") + buf, bs = std::string("bodies_") + buf;
      const auto layout = write_particles(s, frames / piece_name(ps, comm.rank()));
      if (comm.root()) write_pvtu(frames / (ps + ".pvtu"), layout, ps, comm.size());
      if (clumps) {
        const auto bl = write_bodies(s, frames / piece_name(bs, comm.rank()));
        if (comm.root()) write_pvtu(frames / (bs + ".pvtu"), bl, bs, comm.size());
      }
    }
    if (comm.root() && s.walls.count() > 0) write_walls(s, frames / (std::string("walls_") + buf + ".vtp"));
    times_.push_back(s.clock.time);
    steps_.push_back(s.clock.step);
    last_step_ = s.clock.step;
    write_series(s);
  } catch (const std::exception& e) {
    err = e.what();
  }
  if (comm.agree_error(err)) throw std::runtime_error(err);
}

void VtkOutput::write_series(const sim::Scene& s) const {
  if (!sim::Comm::world().root()) return;
  const char* ext = sim::Comm::world().parallel() ? ".pvtu" : ".vtu";
  write_pvd("particles.pvd", "particles_", ext);
  if (!state_written_) {  // once per run: the ParaView state beside the series
    write_paraview_state(dir_);
    state_written_ = true;
  }
  if (s.walls.count() > 0) write_pvd("walls.pvd", "walls_", ".vtp");
  if (s.particles.fields().has(sim::Field::Body)) write_pvd("bodies.pvd", "bodies_", ext);
}

void VtkOutput::resume(const sim::Scene& s, std::vector<double> times, std::vector<std::int64_t> steps) {
  times_ = std::move(times);
  steps_ = std::move(steps);
  if (!times_.empty()) {
    // Continued in another output folder (one without the series, nor its
    // last frame): the series starts afresh here, so that it names no file
    // the folder lacks. In the run's own folder it goes on, frames lost to a
    // failed output included (they are written again as the run reaches them).
    char buf[32];
    std::snprintf(buf, sizeof buf, "%06zu", times_.size() - 1);
    const fs::path last = dir_ / "frames" / (std::string("particles_") + buf);
    std::error_code ec;
    if (!fs::exists(dir_ / "particles.pvd", ec) && !fs::exists(last.string() + ".vtu", ec) &&
        !fs::exists(last.string() + ".pvtu", ec))
      times_.clear(), steps_.clear();
  }
  last_step_ = steps_.empty() ? -1 : steps_.back();
  std::error_code ec;
  fs::create_directories(dir_ / "frames", ec);
  if (ec) throw std::runtime_error("cannot create output folder '" + (dir_ / "frames").string() + "': " + ec.message());
  if (last_step_ != s.clock.step && every_ > 0 && s.clock.step % every_ == 0) {
    write_frame(s);
  } else if (!times_.empty()) {
    write_series(s);
  }
}

namespace {

std::string piece_name(const std::string& stem, int rank) {
  char b[32];
  std::snprintf(b, sizeof b, "_r%04d.vtu", rank);
  return stem + b;
}

vtkNew<vtkDoubleArray> vec_array(const char* name, const std::vector<Vec3>& v, std::size_t n) {
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(3);
  a->SetNumberOfTuples(static_cast<vtkIdType>(n));
  for (std::size_t i = 0; i < n; ++i) a->SetTuple(static_cast<vtkIdType>(i), v[i].data());
  return a;
}

template <class W>
void write_or_throw(W* w, const fs::path& file) {
  const fs::path tmp = file.string() + ".tmp";
  w->SetFileName(tmp.c_str());
  w->SetDataModeToAppended();
  w->SetCompressorTypeToZLib();
  if (w->Write() != 1) throw std::runtime_error("could not write '" + file.string() + "' (disk full or not writable?)");
  std::error_code ec;
  fs::rename(tmp, file, ec);
  if (ec) throw std::runtime_error("could not write '" + file.string() + "': " + ec.message());
}

// The array layout of a piece, as the <PPointData>/<PPoints> of a .pvtu.
std::string piece_layout(vtkUnstructuredGrid* g) {
  auto xml_type = [](vtkDataArray* a) -> std::string {
    switch (a->GetDataType()) {
      case VTK_DOUBLE: return "Float64";
      case VTK_FLOAT: return "Float32";
      case VTK_INT: return "Int32";
      case VTK_LONG_LONG: return "Int64";
      case VTK_UNSIGNED_CHAR: return "UInt8";
      default: return "Float64";
    }
  };
  std::ostringstream o;
  auto* pd = g->GetPointData();
  o << "    <PPointData";
  if (pd->GetScalars()) o << " Scalars=\"" << pd->GetScalars()->GetName() << "\"";
  o << ">\n";
  for (int k = 0; k < pd->GetNumberOfArrays(); ++k) {
    auto* a = pd->GetArray(k);
    o << "      <PDataArray type=\"" << xml_type(a) << "\" Name=\"" << a->GetName() << "\" NumberOfComponents=\""
      << a->GetNumberOfComponents() << "\"/>\n";
  }
  o << "    </PPointData>\n    <PPoints>\n      <PDataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\"/>\n"
       "    </PPoints>\n";
  return o.str();
}

// Writes the .pvtu index of a frame written as one piece per rank.
void write_pvtu(const fs::path& file, const std::string& layout, const std::string& stem, int pieces) {
  const fs::path tmp = file.string() + ".tmp";
  {
    std::ofstream o(tmp);
    o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "  <PUnstructuredGrid GhostLevel=\"0\">\n"
      << layout;
    for (int r = 0; r < pieces; ++r) o << "    <Piece Source=\"" << piece_name(stem, r) << "\"/>\n";
    o << "  </PUnstructuredGrid>\n</VTKFile>\n";
    o.flush();
    if (!o) throw std::runtime_error("could not write '" + file.string() + "' (disk full or not writable?)");
  }
  std::error_code ec;
  fs::rename(tmp, file, ec);
  if (ec) throw std::runtime_error("could not write '" + file.string() + "': " + ec.message());
}

}  // namespace

std::string VtkOutput::write_particles(const sim::Scene& s, const fs::path& file) const {
  const auto& p = s.particles;
  const std::size_t n = p.n_owned();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(static_cast<vtkIdType>(n));
  for (std::size_t i = 0; i < n; ++i) pts->SetPoint(static_cast<vtkIdType>(i), p.x[i].data());
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(pts);
  grid->Allocate(static_cast<vtkIdType>(n));
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(n); ++i) grid->InsertNextCell(VTK_VERTEX, 1, &i);
  auto* pd = grid->GetPointData();
  vtkNew<vtkLongLongArray> id;
  id->SetName("id");
  vtkNew<vtkDoubleArray> radius;
  radius->SetName("radius");
  vtkNew<vtkIntArray> mat, coord;
  mat->SetName("material");
  coord->SetName("coordination");
  const auto z = coordination_numbers(s);
  for (std::size_t i = 0; i < n; ++i) {
    id->InsertNextValue(p.id[i]);
    radius->InsertNextValue(p.radius[i]);
    mat->InsertNextValue(p.material[i]);
    coord->InsertNextValue(z[i]);
  }
  pd->AddArray(id);
  pd->AddArray(radius);
  pd->AddArray(mat);
  pd->AddArray(coord);
  pd->AddArray(vec_array("velocity", p.v, n));
  pd->AddArray(vec_array("force", p.f, n));
  if (p.fields().has(sim::Field::AngularVelocity)) pd->AddArray(vec_array("angular_velocity", p.omega, n));
  if (s.neighbors.frozen()) {  // scenes with frozen sets: 1 for a held grain (particles[].frozen)
    vtkNew<vtkUnsignedCharArray> frozen;
    frozen->SetName("frozen");
    for (std::size_t i = 0; i < n; ++i) frozen->InsertNextValue(p.inv_mass[i] == 0 ? 1 : 0);
    pd->AddArray(frozen);
  }
  if (p.fields().has(sim::Field::Orientation) && p.fields().has(sim::Field::SemiAxes)) {
    // Orientation as a quaternion (w, x, y, z), the semi-axes, and the shape
    // tensor R diag(a, b, c) R^T that ParaView's Tensor Glyph draws as the ellipsoid.
    vtkNew<vtkDoubleArray> q, t;
    q->SetName("orientation");
    q->SetNumberOfComponents(4);
    t->SetName("shape_tensor");
    t->SetNumberOfComponents(9);
    for (std::size_t i = 0; i < n; ++i) {
      const auto& o = p.orientation[i];
      const double qv[4] = {o.w(), o.x(), o.y(), o.z()};
      q->InsertNextTuple(qv);
      const Eigen::Matrix3d R = o.toRotationMatrix();
      const Eigen::Matrix3d T = R * p.semi_axes[i].asDiagonal() * R.transpose();
      t->InsertNextTuple(T.data());
    }
    pd->AddArray(q);
    pd->AddArray(vec_array("semi_axes", p.semi_axes, n));
    pd->AddArray(t);
  }
  if (p.fields().has(sim::Field::Body)) {  // clump balls: the body they belong to (-1: free particle)
    vtkNew<vtkLongLongArray> body;
    body->SetName("body");
    for (std::size_t i = 0; i < n; ++i) body->InsertNextValue(p.body[i]);
    pd->AddArray(body);
  }
  pd->SetActiveScalars("radius");
  vtkNew<vtkXMLUnstructuredGridWriter> w;
  w->SetInputData(grid);
  write_or_throw(w.Get(), file);
  return piece_layout(grid);
}

std::string VtkOutput::write_bodies(const sim::Scene& s, const fs::path& file) const {
  const auto& b = s.bodies;
  const std::size_t n = b.size();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(static_cast<vtkIdType>(n));
  for (std::size_t k = 0; k < n; ++k) pts->SetPoint(static_cast<vtkIdType>(k), b.x[k].data());
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(pts);
  grid->Allocate(static_cast<vtkIdType>(n));
  for (vtkIdType k = 0; k < static_cast<vtkIdType>(n); ++k) grid->InsertNextCell(VTK_VERTEX, 1, &k);
  auto* pd = grid->GetPointData();
  vtkNew<vtkLongLongArray> id;
  id->SetName("body");
  vtkNew<vtkDoubleArray> mass, q;
  mass->SetName("mass");
  q->SetName("orientation");  // w, x, y, z
  q->SetNumberOfComponents(4);
  std::vector<Vec3> axes[3];
  for (std::size_t k = 0; k < n; ++k) {
    id->InsertNextValue(b.id[k]);
    mass->InsertNextValue(b.mass[k]);
    const auto& o = b.orientation[k];
    const double qv[4] = {o.w(), o.x(), o.y(), o.z()};
    q->InsertNextTuple(qv);
    const Eigen::Matrix3d R = o.toRotationMatrix();
    for (int a = 0; a < 3; ++a) axes[a].push_back(R.col(a));
  }
  pd->AddArray(id);
  pd->AddArray(mass);
  pd->AddArray(q);
  pd->AddArray(vec_array("velocity", b.v, n));
  pd->AddArray(vec_array("angular_velocity", b.omega, n));
  pd->AddArray(vec_array("inertia", b.inertia, n));
  // Principal axes in the world frame (unit vectors; axis_1 has the smallest moment).
  pd->AddArray(vec_array("axis_1", axes[0], n));
  pd->AddArray(vec_array("axis_2", axes[1], n));
  pd->AddArray(vec_array("axis_3", axes[2], n));
  vtkNew<vtkXMLUnstructuredGridWriter> w;
  w->SetInputData(grid);
  write_or_throw(w.Get(), file);
  return piece_layout(grid);
}

// Every wall's cells (its kind's cells(), sim/walls/wall_kind.hpp), with
// cell arrays `wall` (the walls' index across kinds) and `wall_kind` (the
// kind's index in sim/walls/wall_kinds.hpp), and for each wall a field-data
// array `wall_<index>_<kind>` holding its kind's record(), from which
// `grains analyze` rebuilds it (postprocess/walls.hpp).
void VtkOutput::write_walls(const sim::Scene& s, const fs::path& file) const {
  vtkNew<vtkPoints> pts;
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIntArray> wall_id, wall_kind;
  wall_id->SetName("wall");
  wall_kind->SetName("wall_kind");
  vtkNew<vtkPolyData> poly;
  const Vec3 c = 0.5 * (s.domain.lo + s.domain.hi);
  const double half = 0.5 * (s.domain.hi - s.domain.lo).norm();
  int kind = 0;
  std::size_t first_wall = 0;
  sim::for_each_type(sim::WallKinds{}, [&]<class K>() {
    const auto& walls = s.walls.of<K>();
    for (std::size_t k = 0; k < walls.size(); ++k) {
      const std::size_t w = first_wall + k;
      sim::WallSurface surf;
      walls[k].cells(surf, c, half);
      const vtkIdType first = pts->GetNumberOfPoints();
      for (const auto& p : surf.points) pts->InsertNextPoint(p.data());
      for (const auto& q : surf.quads) {
        const vtkIdType ids[4] = {first + q[0], first + q[1], first + q[2], first + q[3]};
        polys->InsertNextCell(4, ids);
        wall_id->InsertNextValue(static_cast<int>(w));
        wall_kind->InsertNextValue(kind);
      }
      for (const auto& t : surf.triangles) {
        const vtkIdType ids[3] = {first + t[0], first + t[1], first + t[2]};
        polys->InsertNextCell(3, ids);
        wall_id->InsertNextValue(static_cast<int>(w));
        wall_kind->InsertNextValue(kind);
      }
      const auto rec = walls[k].record();
      vtkNew<vtkDoubleArray> r;
      r->SetName(("wall_" + std::to_string(w) + "_" + K::kind).c_str());
      for (double v : rec) r->InsertNextValue(v);
      poly->GetFieldData()->AddArray(r);
    }
    first_wall += walls.size();
    ++kind;
  });
  poly->SetPoints(pts);
  poly->SetPolys(polys);
  poly->GetCellData()->AddArray(wall_id);
  poly->GetCellData()->AddArray(wall_kind);
  vtkNew<vtkXMLPolyDataWriter> wr;
  wr->SetInputData(poly);
  write_or_throw(wr.Get(), file);
}

void VtkOutput::write_pvd(const std::string& name, const std::string& prefix, const std::string& ext) const {
  const fs::path file = dir_ / name;
  const fs::path tmp = file.string() + ".tmp";
  {
    std::ofstream o(tmp);
    o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "  <Collection>\n";
    o.precision(12);
    for (std::size_t k = 0; k < times_.size(); ++k) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%06zu", k);
      o << "    <DataSet timestep=\"" << times_[k] << "\" group=\"\" part=\"0\" file=\"frames/" << prefix << buf << ext
        << "\"/>\n";
    }
    o << "  </Collection>\n</VTKFile>\n";
    o.flush();
    if (!o) throw std::runtime_error("could not write '" + file.string() + "' (disk full or not writable?)");
  }
  std::error_code ec;
  fs::rename(tmp, file, ec);
  if (ec) throw std::runtime_error("could not write '" + file.string() + "': " + ec.message());
}

}  // namespace grains::io
