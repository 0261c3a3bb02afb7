// Compares the first point array of two VTK image-data files (.vti):
// same dimensions, and every value within `tol` times the largest value of
// the first. Prints the worst difference.
//   compare_vti A.vti B.vti TOL
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkXMLImageDataReader.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: compare_vti A.vti B.vti TOL\n");
    return 2;
  }
  vtkNew<vtkXMLImageDataReader> ra, rb;
  ra->SetFileName(argv[1]);
  rb->SetFileName(argv[2]);
  ra->Update();
  rb->Update();
  vtkImageData* a = ra->GetOutput();
  vtkImageData* b = rb->GetOutput();
  vtkDataArray* va = a->GetPointData()->GetArray(0);
  vtkDataArray* vb = b->GetPointData()->GetArray(0);
  if (!va || !vb || va->GetNumberOfTuples() != vb->GetNumberOfTuples() || va->GetNumberOfTuples() == 0) {
    std::printf("FAIL: %s and %s hold different or empty grids\n", argv[1], argv[2]);
    return 1;
  }
  double peak = 0, worst = 0;
  for (vtkIdType k = 0; k < va->GetNumberOfTuples(); ++k) peak = std::max(peak, std::abs(va->GetTuple1(k)));
  for (vtkIdType k = 0; k < va->GetNumberOfTuples(); ++k)
    worst = std::max(worst, std::abs(va->GetTuple1(k) - vb->GetTuple1(k)));
  const double tol = std::atof(argv[3]);
  std::printf("%lld values, largest %.6g, worst difference %.3g (%.3g of the largest)\n",
              static_cast<long long>(va->GetNumberOfTuples()), peak, worst, peak > 0 ? worst / peak : 0.0);
  if (!(peak > 0) || !(worst <= tol * peak)) {
    std::printf("FAIL: beyond %g of the largest value\n", tol);
    return 1;
  }
  return 0;
}
