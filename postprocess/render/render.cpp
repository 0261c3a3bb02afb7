#include "postprocess/render.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include <vtkActor.h>
#include <vtkAutoInit.h>
#include <vtkBoxClipDataSet.h>
#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkDataSetMapper.h>
#include <vtkDoubleArray.h>
#include <vtkGlyph3DMapper.h>
#include <vtkImageData.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkSphereSource.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkWindowToImageFilter.h>
#include <vtkXMLPUnstructuredGridReader.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include "postprocess/frame.hpp"
#include "postprocess/render/headless_display.hpp"

VTK_MODULE_INIT(vtkRenderingOpenGL2);
VTK_MODULE_INIT(vtkRenderingFreeType);

namespace grains::postprocess {

namespace fs = std::filesystem;

namespace {

// The colour field as one scalar per point: a scalar array as is, a vector
// array by magnitude, or a component "name:x|y|z".
vtkNew<vtkDoubleArray> colour_values(vtkPointData* pd, const std::string& spec) {
  std::string name = spec;
  int comp = -1;
  if (const auto c = spec.rfind(':'); c != std::string::npos) {
    name = spec.substr(0, c);
    const std::string s = spec.substr(c + 1);
    if (s == "x" || s == "0") comp = 0;
    else if (s == "y" || s == "1") comp = 1;
    else if (s == "z" || s == "2") comp = 2;
    else if (s == "w" || s == "3") comp = 3;
    else if (s != "mag") throw std::runtime_error("colour field '" + spec + "': component must be x, y, z or mag");
  }
  vtkDataArray* a = pd->GetArray(name.c_str());
  if (!a) {
    std::string known;
    for (int k = 0; k < pd->GetNumberOfArrays(); ++k) known += std::string(" ") + pd->GetArrayName(k);
    throw std::runtime_error("no point field '" + name + "' in this frame; fields:" + known);
  }
  if (comp >= a->GetNumberOfComponents())
    throw std::runtime_error("colour field '" + spec + "': '" + name + "' has " +
                             std::to_string(a->GetNumberOfComponents()) + " components");
  vtkNew<vtkDoubleArray> v;
  v->SetName(spec.c_str());
  v->SetNumberOfTuples(a->GetNumberOfTuples());
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i) {
    double val = 0;
    if (comp >= 0) {
      val = a->GetComponent(i, comp);
    } else if (a->GetNumberOfComponents() == 1) {
      val = a->GetComponent(i, 0);
    } else {
      for (int k = 0; k < a->GetNumberOfComponents(); ++k) val += a->GetComponent(i, k) * a->GetComponent(i, k);
      val = std::sqrt(val);
    }
    v->SetValue(i, val);
  }
  return v;
}

}  // namespace

void render_frame(const fs::path& out_dir, long index, const RenderOptions& o, const fs::path& png) {
  const auto frames = list_frames(out_dir);
  if (frames.empty()) throw std::runtime_error("'" + (out_dir / "particles.pvd").string() + "' lists no frames");
  const long n = static_cast<long>(frames.size());
  const long k = index < 0 ? n + index : index;
  if (k < 0 || k >= n)
    throw std::runtime_error("frame " + std::to_string(index) + " does not exist: the run has " + std::to_string(n) +
                             " frames (0.." + std::to_string(n - 1) + ")");
  const fs::path file = frames[static_cast<std::size_t>(k)].file;
  if (o.width < 16 || o.height < 16 || o.width > 8192 || o.height > 8192)
    throw std::runtime_error("image size must be between 16 and 8192 pixels");

  // Particles: a poly-data of centres carrying the glyph scale and orientation.
  vtkNew<vtkXMLUnstructuredGridReader> serial;
  vtkNew<vtkXMLPUnstructuredGridReader> parallel;
  vtkXMLReader* reader = file.extension() == ".pvtu" ? static_cast<vtkXMLReader*>(parallel) : serial;
  if (!fs::exists(file) || !reader->CanReadFile(file.c_str()))
    throw std::runtime_error("cannot read particle file '" + file.string() + "'");
  reader->SetFileName(file.c_str());
  reader->Update();
  auto* grid = vtkUnstructuredGrid::SafeDownCast(reader->GetOutputDataObject(0));
  if (!grid || grid->GetNumberOfPoints() == 0) throw std::runtime_error("'" + file.string() + "' has no particles");
  auto* pd = grid->GetPointData();
  vtkDataArray* radius = pd->GetArray("radius");
  if (!radius) throw std::runtime_error("'" + file.string() + "' has no radius array");
  vtkDataArray* axes = pd->GetArray("semi_axes");
  vtkDataArray* quat = pd->GetArray("orientation");
  if (axes && axes->GetNumberOfComponents() != 3) axes = nullptr;
  if (quat && quat->GetNumberOfComponents() != 4) quat = nullptr;
  const vtkIdType np = grid->GetNumberOfPoints();
  vtkNew<vtkDoubleArray> scale, orient;
  scale->SetName("glyph_scale");
  scale->SetNumberOfComponents(3);
  scale->SetNumberOfTuples(np);
  orient->SetName("glyph_orientation");
  orient->SetNumberOfComponents(4);
  orient->SetNumberOfTuples(np);
  for (vtkIdType i = 0; i < np; ++i) {
    double s[3], q[4] = {1, 0, 0, 0};
    if (axes) {
      axes->GetTuple(i, s);
    } else {
      s[0] = s[1] = s[2] = radius->GetComponent(i, 0);
    }
    if (quat && axes) quat->GetTuple(i, q);  // w, x, y, z
    scale->SetTuple(i, s);
    orient->SetTuple(i, q);
  }
  vtkNew<vtkPolyData> centres;
  centres->SetPoints(grid->GetPoints());
  auto colour = colour_values(pd, o.color);
  centres->GetPointData()->AddArray(scale);
  centres->GetPointData()->AddArray(orient);
  centres->GetPointData()->AddArray(colour);

  vtkNew<vtkSphereSource> ball;
  ball->SetRadius(1.0);
  const int res = np > 200000 ? 8 : np > 20000 ? 12 : 20;
  ball->SetThetaResolution(res);
  ball->SetPhiResolution(res);
  vtkNew<vtkLookupTable> lut;
  double range[2];
  colour->GetRange(range);
  if (range[1] <= range[0]) range[1] = range[0] + (range[0] != 0 ? 1e-6 * std::abs(range[0]) : 1.0);
  lut->SetHueRange(0.667, 0.0);  // blue (low) to red (high)
  lut->SetTableRange(range);
  lut->Build();
  vtkNew<vtkGlyph3DMapper> glyphs;
  glyphs->SetInputData(centres);
  glyphs->SetSourceConnection(ball->GetOutputPort());
  glyphs->SetScaleArray("glyph_scale");
  glyphs->SetScaleModeToScaleByVectorComponents();
  glyphs->SetScaleFactor(1.0);
  glyphs->ScalingOn();
  glyphs->SetOrientationArray("glyph_orientation");
  glyphs->SetOrientationModeToQuaternion();
  glyphs->OrientOn();
  glyphs->SetScalarModeToUsePointFieldData();
  glyphs->SelectColorArray(o.color.c_str());
  glyphs->SetLookupTable(lut);
  glyphs->SetScalarRange(range);
  glyphs->UseLookupTableScalarRangeOn();
  glyphs->ScalarVisibilityOn();
  vtkNew<vtkActor> particles;
  particles->SetMapper(glyphs);
  particles->GetProperty()->SetSpecular(0.3);
  particles->GetProperty()->SetSpecularPower(20);

  // Bounds of the particles themselves (walls are much larger quads).
  double b[6] = {1e300, -1e300, 1e300, -1e300, 1e300, -1e300};
  for (vtkIdType i = 0; i < np; ++i) {
    double p[3], s[3];
    grid->GetPoint(i, p);
    scale->GetTuple(i, s);
    const double r = std::max({s[0], s[1], s[2]});
    for (int d = 0; d < 3; ++d) {
      b[2 * d] = std::min(b[2 * d], p[d] - r);
      b[2 * d + 1] = std::max(b[2 * d + 1], p[d] + r);
    }
  }

  vtkNew<vtkRenderer> ren;
  ren->SetBackground(0.93, 0.94, 0.96);
  ren->AddActor(particles);
  vtkNew<vtkXMLPolyDataReader> wall_reader;
  vtkNew<vtkDataSetMapper> wall_mapper;
  vtkNew<vtkBoxClipDataSet> wall_clip;
  vtkNew<vtkActor> walls;
  if (o.walls) {
    const fs::path wf = walls_file(out_dir, static_cast<std::size_t>(k));
    if (!wf.empty() && fs::exists(wf)) {
      wall_reader->SetFileName(wf.c_str());
      wall_reader->Update();
      // Plane walls are written as quads as wide as the domain's diagonal:
      // keep only the part near the particles.
      const double pad = 0.08 * std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
                                          (b[5] - b[4]) * (b[5] - b[4]));
      wall_clip->SetInputConnection(wall_reader->GetOutputPort());
      wall_clip->SetBoxClip(b[0] - pad, b[1] + pad, b[2] - pad, b[3] + pad, b[4] - pad, b[5] + pad);
      wall_mapper->SetInputConnection(wall_clip->GetOutputPort());
      wall_mapper->ScalarVisibilityOff();
      walls->SetMapper(wall_mapper);
      walls->GetProperty()->SetColor(0.55, 0.6, 0.7);
      walls->GetProperty()->SetOpacity(std::clamp(o.wall_opacity, 0.0, 1.0));
      ren->AddActor(walls);
    }
  }
  vtkNew<vtkScalarBarActor> bar;
  bar->SetLookupTable(lut);
  bar->SetTitle(o.color.c_str());
  bar->SetNumberOfLabels(5);
  bar->SetWidth(0.08);
  bar->SetHeight(0.6);
  bar->SetPosition(0.9, 0.2);
  for (auto* tp : {bar->GetTitleTextProperty(), bar->GetLabelTextProperty()}) {
    tp->SetColor(0.1, 0.1, 0.1);
    tp->ShadowOff();
    tp->ItalicOff();
  }
  ren->AddActor2D(bar);

  // Camera on the particles' bounding box.
  const double c[3] = {0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5])};
  double dir[3] = {1.0, -1.6, 0.9}, up[3] = {0, 0, 1};
  if (o.view == "x") dir[0] = 1, dir[1] = 0, dir[2] = 0;
  else if (o.view == "y") dir[0] = 0, dir[1] = -1, dir[2] = 0;
  else if (o.view == "z") dir[0] = 0, dir[1] = 0, dir[2] = 1, up[0] = 0, up[1] = 1, up[2] = 0;
  else if (o.view != "iso") throw std::runtime_error("view must be iso, x, y or z, not '" + o.view + "'");
  auto* cam = ren->GetActiveCamera();
  cam->SetFocalPoint(c);
  cam->SetPosition(c[0] + dir[0], c[1] + dir[1], c[2] + dir[2]);
  cam->SetViewUp(up);
  ren->ResetCamera(b);
  ren->ResetCameraClippingRange(b);

  HeadlessDisplay display;
  vtkNew<vtkRenderWindow> win;
  win->SetOffScreenRendering(1);
  win->SetSize(o.width, o.height);
  win->SetMultiSamples(0);
  win->AddRenderer(ren);
  ren->SetUseDepthPeeling(1);
  ren->SetMaximumNumberOfPeels(8);
  win->SetAlphaBitPlanes(1);
  win->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(win);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  std::error_code ec;
  if (png.has_parent_path()) fs::create_directories(png.parent_path(), ec);
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(png.c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  win->Finalize();
  if (!fs::exists(png) || fs::file_size(png) == 0) throw std::runtime_error("could not write '" + png.string() + "'");
}

ImageStats png_statistics(const fs::path& png) {
  vtkNew<vtkPNGReader> r;
  if (!fs::exists(png) || !r->CanReadFile(png.c_str())) throw std::runtime_error("'" + png.string() + "' is not a PNG");
  r->SetFileName(png.c_str());
  r->Update();
  auto* img = r->GetOutput();
  ImageStats s;
  int dims[3];
  img->GetDimensions(dims);
  s.width = dims[0];
  s.height = dims[1];
  auto* a = img->GetPointData()->GetScalars();
  if (!a) return s;
  const int nc = a->GetNumberOfComponents();
  const int use = std::min(nc, 3);
  double sum = 0, sum2 = 0;
  std::size_t count = 0;
  std::set<std::uint32_t> colours;
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i) {
    std::uint32_t key = 0;
    for (int c = 0; c < use; ++c) {
      const double v = a->GetComponent(i, c);
      sum += v;
      sum2 += v * v;
      ++count;
      key = key * 256 + static_cast<std::uint32_t>(v);
    }
    if (colours.size() < 100000) colours.insert(key);
  }
  if (count) {
    s.mean = sum / static_cast<double>(count);
    s.variance = sum2 / static_cast<double>(count) - s.mean * s.mean;
  }
  s.distinct_colours = colours.size();
  return s;
}

}  // namespace grains::postprocess
