#include "postprocess/walls.hpp"

#include <cmath>
#include <map>
#include <stdexcept>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include "contact/plane.hpp"

namespace grains::postprocess {

WallSet read_walls(const std::filesystem::path& vtp) {
  vtkNew<vtkXMLPolyDataReader> r;
  if (!std::filesystem::exists(vtp) || !r->CanReadFile(vtp.c_str()))
    throw std::runtime_error("cannot read walls file '" + vtp.string() + "'");
  r->SetFileName(vtp.c_str());
  r->Update();
  vtkPolyData* poly = r->GetOutput();
  WallSet w;
  if (!poly || poly->GetNumberOfCells() == 0) return w;
  vtkDataArray* id = poly->GetCellData()->GetArray("wall");
  vtkDataArray* type = poly->GetCellData()->GetArray("wall_type");
  std::map<long, std::vector<vtkIdType>> groups;  // wall -> its cells
  for (vtkIdType c = 0; c < poly->GetNumberOfCells(); ++c)
    groups[id ? static_cast<long>(id->GetComponent(c, 0)) : static_cast<long>(c)].push_back(c);
  vtkNew<vtkIdList> pts;
  auto point = [&](vtkIdType p) {
    Vec3 v;
    poly->GetPoint(p, v.data());
    return v;
  };
  for (const auto& [wall, cells] : groups) {
    if (cells.size() == 1) {
      poly->GetCellPoints(cells[0], pts);
      if (pts->GetNumberOfIds() < 3) continue;
      const Vec3 a = point(pts->GetId(0)), b = point(pts->GetId(1)), c = point(pts->GetId(2));
      const Vec3 n = (b - a).cross(c - a);
      if (n.norm() == 0) continue;
      w.planes.push_back({a, n.normalized()});
      continue;
    }
    if (type && static_cast<int>(type->GetComponent(cells[0], 0)) == 2) {
      // A finite plane: quads (inner k, inner k+1, outer k+1, outer k).
      std::vector<Vec3> inner, outer;
      for (vtkIdType c : cells) {
        poly->GetCellPoints(c, pts);
        if (pts->GetNumberOfIds() != 4) continue;
        inner.push_back(point(pts->GetId(0)));
        outer.push_back(point(pts->GetId(3)));
      }
      if (outer.size() < 3) continue;
      AnnulusWall a;
      for (const auto& p : outer) a.centre += p;
      a.centre /= static_cast<double>(outer.size());
      const Vec3 n = (outer[1] - outer[0]).cross(outer[outer.size() / 2] - outer[0]);
      if (n.norm() == 0) continue;
      a.normal = n.normalized();
      for (std::size_t k = 0; k < outer.size(); ++k) {
        a.r_in += (inner[k] - a.centre).norm();
        a.r_out += (outer[k] - a.centre).norm();
      }
      a.r_in /= static_cast<double>(inner.size());
      a.r_out /= static_cast<double>(outer.size());
      w.annuli.push_back(a);
      continue;
    }
    // A cylinder: quads (bottom k, bottom k+1, top k+1, top k).
    Vec3 bottom(0, 0, 0), top(0, 0, 0);
    std::vector<Vec3> ring;
    for (vtkIdType c : cells) {
      poly->GetCellPoints(c, pts);
      if (pts->GetNumberOfIds() != 4) continue;
      const Vec3 b0 = point(pts->GetId(0)), t0 = point(pts->GetId(3));
      bottom += b0;
      top += t0;
      ring.push_back(b0);
    }
    if (ring.size() < 3) continue;
    bottom /= static_cast<double>(ring.size());
    top /= static_cast<double>(ring.size());
    CylinderWall cy;
    cy.base = bottom;
    cy.length = (top - bottom).norm();
    if (cy.length == 0) continue;
    cy.axis = (top - bottom) / cy.length;
    for (const auto& p : ring) {
      const Vec3 d = p - bottom;
      cy.radius += (d - cy.axis * cy.axis.dot(d)).norm();
    }
    cy.radius /= static_cast<double>(ring.size());
    w.cylinders.push_back(cy);
  }
  return w;
}

std::vector<int> wall_contacts(const Frame& f, const WallSet& w, double gap) {
  std::vector<int> z(f.size(), 0);
  const bool ell = f.has_ellipsoids();
  auto reach = [&](std::size_t i, const Vec3& n) {
    if (!ell) return f.radius[i];
    const Vec3 m = (f.has_orientation() ? f.orientation[i].conjugate() * n : n);  // body frame
    return m.cwiseProduct(f.semi_axes[i]).norm();  // support function sqrt(n^T Q n)
  };
  for (std::size_t i = 0; i < f.size(); ++i) {
    for (const auto& p : w.planes)
      if (std::abs(p.normal.dot(f.x[i] - p.point)) < reach(i, p.normal) + gap) ++z[i];
    for (const auto& a : w.annuli) {
      // Distance to the nearest point of the annulus (contact/plane.hpp).
      const Vec3 d = f.x[i] - contact::annulus_nearest(f.x[i], {a.centre, a.normal, a.r_in, a.r_out});
      const double dist = d.norm();
      if (dist < reach(i, dist > 0 ? Vec3(d / dist) : a.normal) + gap) ++z[i];
    }
    for (const auto& c : w.cylinders) {
      const Vec3 d = f.x[i] - c.base;
      const double t = c.axis.dot(d);
      if (t < 0 || t > c.length) continue;
      const Vec3 radial = d - c.axis * t;
      const double rho = radial.norm();
      if (rho == 0) continue;
      if (std::abs(rho - c.radius) < reach(i, radial / rho) + gap) ++z[i];
    }
  }
  return z;
}

}  // namespace grains::postprocess
