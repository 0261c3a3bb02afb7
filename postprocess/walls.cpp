#include "postprocess/walls.hpp"

#include <map>
#include <stdexcept>
#include <string>

#include <array>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include "contact/ellipsoid/ellipsoid.hpp"

namespace grains::postprocess {

WallSet read_walls(const std::filesystem::path& vtp) {
  vtkNew<vtkXMLPolyDataReader> r;
  if (!std::filesystem::exists(vtp) || !r->CanReadFile(vtp.c_str()))
    throw std::runtime_error("cannot read walls file '" + vtp.string() + "'");
  r->SetFileName(vtp.c_str());
  r->Update();
  vtkPolyData* poly = r->GetOutput();
  WallSet w;
  if (!poly || !poly->GetFieldData()) return w;
  // wall_<index>_<kind>, in the order of the index.
  std::map<long, std::pair<std::string, std::vector<double>>> records;
  vtkFieldData* fd = poly->GetFieldData();
  for (int a = 0; a < fd->GetNumberOfArrays(); ++a) {
    vtkDataArray* arr = fd->GetArray(a);
    if (!arr || !arr->GetName()) continue;
    const std::string name = arr->GetName();
    if (name.rfind("wall_", 0) != 0) continue;
    const auto us = name.find('_', 5);
    if (us == std::string::npos) continue;
    std::vector<double> v(static_cast<std::size_t>(arr->GetNumberOfTuples()));
    for (std::size_t k = 0; k < v.size(); ++k) v[k] = arr->GetComponent(static_cast<vtkIdType>(k), 0);
    records[std::stol(name.substr(5, us - 5))] = {name.substr(us + 1), std::move(v)};
  }
  // The triangles of wall `index` as written (posed), for kinds rebuilt from their cells.
  auto cells_of = [&](long index) {
    sim::WallSurface s;
    vtkDataArray* ids = poly->GetCellData() ? poly->GetCellData()->GetArray("wall") : nullptr;
    if (!ids) return s;
    std::map<vtkIdType, int> point;
    for (vtkIdType c = 0; c < poly->GetNumberOfCells(); ++c) {
      if (static_cast<long>(ids->GetComponent(c, 0)) != index) continue;
      vtkIdType n = 0;
      const vtkIdType* pts = nullptr;
      poly->GetCellPoints(c, n, pts);
      if (n != 3) continue;
      std::array<int, 3> t{};
      for (int k = 0; k < 3; ++k) {
        auto [it, fresh] = point.try_emplace(pts[k], static_cast<int>(s.points.size()));
        if (fresh) {
          double x[3];
          poly->GetPoint(pts[k], x);
          s.points.emplace_back(x[0], x[1], x[2]);
        }
        t[static_cast<std::size_t>(k)] = it->second;
      }
      s.triangles.push_back(t);
    }
    return s;
  };
  for (const auto& [index, rec] : records) {
    bool known = false;
    sim::for_each_type(sim::WallKinds{}, [&]<class K>() {
      if (rec.first != K::kind) return;
      known = true;
      K wall;
      bool ok;
      if constexpr (requires(const sim::WallSurface& c) { K::from_record(rec.second, c, wall); })
        ok = K::from_record(rec.second, cells_of(index), wall);
      else
        ok = K::from_record(rec.second, wall);
      if (!ok)
        throw std::runtime_error(vtp.string() + ": wall " + std::to_string(index) + " (" + rec.first +
                                 "): malformed record of " + std::to_string(rec.second.size()) + " numbers");
      w.add(wall);
    });
    if (!known)
      throw std::runtime_error(vtp.string() + ": wall " + std::to_string(index) + " is of kind '" + rec.first +
                               "', which this grains does not know");
  }
  return w;
}

std::vector<int> wall_contacts(const Frame& f, const WallSet& w, double gap) {
  std::vector<int> z(f.size(), 0);
  const bool ell = f.has_ellipsoids();
  for (std::size_t i = 0; i < f.size(); ++i) {
    contact::Ellipsoid e;
    if (ell) {
      e.centre = f.x[i];
      e.semi_axes = f.semi_axes[i] + Vec3::Constant(gap);
      if (f.has_orientation()) e.orientation = f.orientation[i];
    }
    w.for_each([&](const auto& wall, std::size_t) {
      if (ell ? wall.touches(e) : wall.touches(f.x[i], f.radius[i] + gap)) ++z[i];
    });
  }
  return z;
}

}  // namespace grains::postprocess
