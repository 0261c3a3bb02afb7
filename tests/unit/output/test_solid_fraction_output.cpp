// The solid-fraction output of a run: a .vti series ParaView opens, whose
// field integrates to the solid volume of the particles.
#include <gtest/gtest.h>

#include <filesystem>

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkXMLImageDataReader.h>

#include "tests/support/sim_helpers.hpp"

namespace grains::test {
namespace {

namespace fs = std::filesystem;

TEST(SolidFractionOutput, FieldIntegratesToTheSolidVolume) {
  const std::string yaml = R"(
domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.013]}
materials:
  - {name: m, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3}
particles:
  - {material: m, radius: {distribution: uniform, min: 0.0003, max: 0.0006}, count: 25,
     placement: {type: random_fill, region: {min: [0.003, 0.003, 0.003], max: [0.007, 0.007, 0.007]}}}
  - {material: m, radius: 0.0005, count: 3, shape: {type: ellipsoid, aspect_ratio: 2},
     placement: {type: random_fill, region: {min: [0.002, 0.002, 0.0075], max: [0.008, 0.008, 0.0100]}}}
time: {dt_rayleigh: 0.2, end: 2.0e-5}
output: {vtk: false, progress: false, solid_fraction: {spacing: 0.0004, tolerance: 1.0e-5}}
)";
  auto s = from_yaml(yaml);
  const fs::path dir = fs::temp_directory_path() / "grains_test_solid_fraction";
  run_into(s, dir);
  ASSERT_TRUE(fs::exists(dir / "solid_fraction.pvd"));
  ASSERT_TRUE(fs::exists(dir / "frames/solid_fraction_000001.vti"));  // first and last
  vtkNew<vtkXMLImageDataReader> r;
  r->SetFileName((dir / "frames/solid_fraction_000001.vti").c_str());
  r->Update();
  auto* img = r->GetOutput();
  auto* a = img->GetPointData()->GetArray("solid_fraction");
  ASSERT_NE(a, nullptr);
  double sp[3];
  img->GetSpacing(sp);
  double integral = 0;
  for (vtkIdType k = 0; k < a->GetNumberOfTuples(); ++k) integral += a->GetTuple1(k) * sp[0] * sp[1] * sp[2];
  const auto& p = s.scene.particles;
  double volume = 0;
  for (std::size_t i = 0; i < p.n_owned(); ++i)
    volume += 4.0 / 3.0 * M_PI *
              (p.shape[i] == sim::kEllipsoid ? p.semi_axes[i].prod() : p.radius[i] * p.radius[i] * p.radius[i]);
  EXPECT_NEAR(integral / volume, 1.0, 1e-3);
  // A packing fraction never exceeds 1 by more than the tolerance, nor goes negative.
  double lo = 1, hi = 0;
  for (vtkIdType k = 0; k < a->GetNumberOfTuples(); ++k) {
    lo = std::min(lo, a->GetTuple1(k));
    hi = std::max(hi, a->GetTuple1(k));
  }
  EXPECT_GT(lo, -1e-5);
  EXPECT_LT(hi, 1.0);
  EXPECT_GT(hi, 0.2);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace grains::test
