// compare_frames: checks that two runs agree particle by particle.
//
//   compare_frames A_OUT B_OUT [--tol METRES] [--frames all|last]
//       positions and velocities of every particle (matched by id) in the
//       frames both runs wrote; --tol 0 (default) demands bitwise equality.
//       Exit 0 when they agree, 1 when not (with the worst particle named).
//   compare_frames --track ID OUT
//       prints "time x y z fx fy fz" of particle ID for every frame.
//   compare_frames --wall-cells A.vtp B.vtp
//       the wall surfaces of two walls_NNNNNN.vtp files: the same points
//       (bitwise) and the same cells; exit 0 when they are.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <string>

#include <vtkCellArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include "postprocess/frame.hpp"

namespace pp = grains::postprocess;

namespace {

std::map<std::int64_t, std::size_t> by_id(const pp::Frame& f) {
  std::map<std::int64_t, std::size_t> m;
  for (std::size_t i = 0; i < f.size(); ++i) m[f.id[i]] = i;
  return m;
}

int track(std::int64_t id, const std::string& out) {
  const auto frames = pp::list_frames(out);
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const auto f = pp::read_frame(out, static_cast<long>(k));
    const auto m = by_id(f);
    const auto it = m.find(id);
    if (it == m.end()) continue;
    const auto i = it->second;
    std::printf("%.9g %.12g %.12g %.12g %.9g %.9g %.9g\n", f.time, f.x[i].x(), f.x[i].y(), f.x[i].z(), f.force[i].x(),
                f.force[i].y(), f.force[i].z());
  }
  return 0;
}

}  // namespace

int wall_cells(const std::string& a, const std::string& b) {
  vtkNew<vtkXMLPolyDataReader> ra, rb;
  ra->SetFileName(a.c_str());
  rb->SetFileName(b.c_str());
  ra->Update();
  rb->Update();
  vtkPolyData* A = ra->GetOutput();
  vtkPolyData* B = rb->GetOutput();
  if (!A || !B || A->GetNumberOfPoints() != B->GetNumberOfPoints() || A->GetNumberOfCells() != B->GetNumberOfCells()) {
    std::cerr << a << " and " << b << ": different point or cell counts\n";
    return 1;
  }
  for (vtkIdType k = 0; k < A->GetNumberOfPoints(); ++k) {
    double x[3], y[3];
    A->GetPoint(k, x);
    B->GetPoint(k, y);
    if (x[0] != y[0] || x[1] != y[1] || x[2] != y[2]) {
      std::cerr << a << " and " << b << ": point " << k << " differs\n";
      return 1;
    }
  }
  vtkNew<vtkIdList> ia, ib;
  for (vtkIdType c = 0; c < A->GetNumberOfCells(); ++c) {
    A->GetCellPoints(c, ia);
    B->GetCellPoints(c, ib);
    bool same = ia->GetNumberOfIds() == ib->GetNumberOfIds();
    for (vtkIdType k = 0; same && k < ia->GetNumberOfIds(); ++k) same = ia->GetId(k) == ib->GetId(k);
    if (!same) {
      std::cerr << a << " and " << b << ": cell " << c << " differs\n";
      return 1;
    }
  }
  return 0;
}

int main(int argc, char** argv) {
  std::vector<std::string> a(argv + 1, argv + argc);
  try {
    if (a.size() == 3 && a[0] == "--track") return track(std::stoll(a[1]), a[2]);
    if (a.size() == 3 && a[0] == "--wall-cells") return wall_cells(a[1], a[2]);
    if (a.size() < 2) {
      std::cerr << "usage: compare_frames A_OUT B_OUT [--tol METRES] [--frames all|last]\n"
                   "       compare_frames --track ID OUT\n";
      return 2;
    }
    double tol = 0;
    bool all = true;
    for (std::size_t k = 2; k + 1 < a.size(); k += 2) {
      if (a[k] == "--tol") tol = std::stod(a[k + 1]);
      else if (a[k] == "--frames") all = a[k + 1] == "all";
    }
    const auto fa = pp::list_frames(a[0]), fb = pp::list_frames(a[1]);
    if (all && fa.size() != fb.size()) {
      std::cerr << "different frame counts: " << fa.size() << " vs " << fb.size() << "\n";
      return 1;
    }
    double worst = 0;
    std::size_t compared = 0;
    for (std::size_t k = all ? 0 : fa.size() - 1; k < fa.size(); ++k) {
      const auto A = pp::read_frame(a[0], all ? static_cast<long>(k) : -1L);
      const auto B = pp::read_frame(a[1], all ? static_cast<long>(k) : -1L);
      if (A.time != B.time) {
        std::cerr << "frame " << k << ": times differ: " << A.time << " vs " << B.time << " s\n";
        return 1;
      }
      if (A.size() != B.size()) {
        std::cerr << "frame " << k << ": " << A.size() << " vs " << B.size() << " particles\n";
        return 1;
      }
      const auto mb = by_id(B);
      for (std::size_t i = 0; i < A.size(); ++i) {
        const auto it = mb.find(A.id[i]);
        if (it == mb.end()) {
          std::cerr << "frame " << k << ": particle id " << A.id[i] << " missing from " << a[1] << "\n";
          return 1;
        }
        const auto j = it->second;
        const double dx = (A.x[i] - B.x[j]).cwiseAbs().maxCoeff();
        const double dv = (A.velocity[i] - B.velocity[j]).cwiseAbs().maxCoeff();
        const bool bad = tol == 0 ? (A.x[i] != B.x[j] || A.velocity[i] != B.velocity[j]) : dx > tol;
        worst = std::max(worst, dx);
        if (bad) {
          std::cerr << "frame " << k << " (t = " << A.time << " s): particle id " << A.id[i] << " differs: |dx| = " << dx
                    << " m, |dv| = " << dv << " m/s (tolerance " << tol << " m)\n";
          return 1;
        }
        ++compared;
      }
    }
    std::cout << "agree: " << compared << " particle states in " << (all ? fa.size() : 1) << " frame(s), largest |dx| "
              << worst << " m" << (tol == 0 ? " (bitwise)" : "") << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "compare_frames: " << e.what() << "\n";
    return 2;
  }
}
