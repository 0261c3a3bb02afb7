#include "io/output/solid_fraction_output.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkStringArray.h>
#include <vtkXMLImageDataWriter.h>

#include "contact/correlation/solid_fraction.hpp"
#include "sim/parallel/comm.hpp"

namespace grains::io {

namespace fs = std::filesystem;

SolidFractionOutput::SolidFractionOutput(fs::path dir, SolidFractionConfig cfg, std::int64_t every_steps)
    : dir_(std::move(dir)), cfg_(cfg), every_(every_steps) {}

std::string SolidFractionOutput::name() const {
  return "output.solid_fraction(spacing " + std::to_string(cfg_.spacing) + " m, " +
         (every_ > 0 ? "every " + std::to_string(every_) + " steps" : std::string("first+last")) + ")";
}

std::vector<double> SolidFractionOutput::field(const sim::Scene& s, std::array<double, 3>& origin,
                                               std::array<int, 3>& dims) const {
  const auto& p = s.particles;
  const std::size_t n = p.n_owned();
  std::vector<double> centres(3 * n), radii(n);
  const bool ell = p.fields().has(sim::Field::SemiAxes);
  for (std::size_t i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) centres[3 * i + d] = p.x[i][d];
    radii[i] = ell && p.shape[i] == sim::kEllipsoid ? std::cbrt(p.semi_axes[i].prod()) : p.radius[i];
  }
  correlation::GridSpec g;
  for (int d = 0; d < 3; ++d) {
    const double L = s.domain.hi[d] - s.domain.lo[d];
    dims[d] = std::max(2, static_cast<int>(std::lround(L / cfg_.spacing)) + 1);
    origin[d] = s.domain.lo[d];
    g.origin[d] = origin[d];
    g.spacing[d] = L / (dims[d] - 1);
    g.dims[d] = dims[d];
    g.periodic[d] = false;
  }
  correlation::SolidFractionOptions opt;
  opt.smoothing_length = cfg_.smoothing > 0 ? cfg_.smoothing : cfg_.spacing;
  opt.tolerance = cfg_.tolerance;
  correlation::BallSet balls{centres, radii, {}};
  return correlation::solid_fraction_field(balls, g, opt);
}

void SolidFractionOutput::run(sim::Scene& s) {
  if (reads_state(s)) write_frame(s);  // its cadence
}

void SolidFractionOutput::finish(sim::Scene& s) {
  if (last_step_ != s.clock.step) write_frame(s);
}

void SolidFractionOutput::write_frame(const sim::Scene& s) {
  std::array<double, 3> origin{};
  std::array<int, 3> dims{};
  // Each rank spreads its own particles; the field is linear in them, so the
  // whole scene's field is the sum over ranks, written by rank 0 (an error
  // there is agreed, so every rank stops together).
  auto values = field(s, origin, dims);
  const auto& comm = sim::Comm::world();
  if (comm.parallel()) comm.sum_in_place(values);
  std::string err;
  if (comm.root()) {
    try {
      write_file(s, values, origin, dims);
    } catch (const std::exception& e) {
      err = e.what();
    }
  }
  if (comm.agree_error(err)) throw std::runtime_error(err);
  if (!comm.root()) {
    times_.push_back(s.clock.time);
    last_step_ = s.clock.step;
  }
}

void SolidFractionOutput::write_file(const sim::Scene& s, const std::vector<double>& values,
                                     const std::array<double, 3>& origin, const std::array<int, 3>& dims) {
  vtkNew<vtkImageData> img;
  img->SetDimensions(dims[0], dims[1], dims[2]);
  img->SetOrigin(origin.data());
  double sp[3];
  for (int d = 0; d < 3; ++d) sp[d] = (s.domain.hi[d] - s.domain.lo[d]) / (dims[d] - 1);
  img->SetSpacing(sp);
  vtkNew<vtkDoubleArray> a;
  a->SetName("solid_fraction");
  a->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  for (std::size_t k = 0; k < values.size(); ++k) a->SetValue(static_cast<vtkIdType>(k), values[k]);
  img->GetPointData()->AddArray(a);
  img->GetPointData()->SetActiveScalars("solid_fraction");
  vtkNew<vtkStringArray> note;
  note->SetName("meaning");
  note->InsertNextValue("sum of ball indicators smoothed by a Gaussian of width smoothing_length (m); ellipsoids as "
                        "equal-volume spheres");
  img->GetFieldData()->AddArray(note);
  vtkNew<vtkDoubleArray> l;
  l->SetName("smoothing_length");
  l->InsertNextValue(cfg_.smoothing > 0 ? cfg_.smoothing : cfg_.spacing);
  img->GetFieldData()->AddArray(l);

  std::error_code ec;
  fs::create_directories(dir_ / "frames", ec);
  if (ec) throw std::runtime_error("cannot create output folder '" + (dir_ / "frames").string() + "': " + ec.message());
  char buf[64];
  std::snprintf(buf, sizeof buf, "solid_fraction_%06zu.vti", times_.size());
  const fs::path file = dir_ / "frames" / buf, tmp = file.string() + ".tmp";
  vtkNew<vtkXMLImageDataWriter> w;
  w->SetInputData(img);
  w->SetFileName(tmp.c_str());
  w->SetDataModeToAppended();
  w->SetCompressorTypeToZLib();
  if (w->Write() != 1) throw std::runtime_error("could not write '" + file.string() + "' (disk full or not writable?)");
  fs::rename(tmp, file, ec);
  if (ec) throw std::runtime_error("could not write '" + file.string() + "': " + ec.message());
  times_.push_back(s.clock.time);
  last_step_ = s.clock.step;

  const fs::path pvd = dir_ / "solid_fraction.pvd", ptmp = pvd.string() + ".tmp";
  {
    std::ofstream o(ptmp);
    o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "  <Collection>\n";
    o.precision(12);
    for (std::size_t k = 0; k < times_.size(); ++k) {
      std::snprintf(buf, sizeof buf, "solid_fraction_%06zu.vti", k);
      o << "    <DataSet timestep=\"" << times_[k] << "\" group=\"\" part=\"0\" file=\"frames/" << buf << "\"/>\n";
    }
    o << "  </Collection>\n</VTKFile>\n";
    if (!o) throw std::runtime_error("could not write '" + pvd.string() + "'");
  }
  fs::rename(ptmp, pvd, ec);
  if (ec) throw std::runtime_error("could not write '" + pvd.string() + "': " + ec.message());
}

}  // namespace grains::io
