#include "postprocess/frame.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridReader.h>

namespace grains::postprocess {

namespace fs = std::filesystem;

double Frame::particle_volume(std::size_t i) const {
  if (!semi_axes.empty()) return 4.0 / 3.0 * M_PI * semi_axes[i].prod();
  return 4.0 / 3.0 * M_PI * radius[i] * radius[i] * radius[i];
}

double Frame::mean_diameter() const {
  if (x.empty()) return 0;
  double s = 0;
  for (std::size_t i = 0; i < x.size(); ++i) s += 2 * std::cbrt(particle_volume(i) / (4.0 / 3.0 * M_PI));
  return s / static_cast<double>(x.size());
}

namespace {

// Value of attribute `name` inside one XML tag, or empty.
std::string attribute(const std::string& tag, const std::string& name) {
  const std::string key = name + "=\"";
  std::size_t p = 0;
  while ((p = tag.find(key, p)) != std::string::npos) {
    if (p == 0 || std::isspace(static_cast<unsigned char>(tag[p - 1]))) {
      const std::size_t b = p + key.size(), e = tag.find('"', b);
      if (e == std::string::npos) return {};
      return tag.substr(b, e - b);
    }
    p += key.size();
  }
  return {};
}

}  // namespace

std::vector<FrameEntry> read_pvd(const fs::path& pvd) {
  std::ifstream in(pvd);
  if (!in) throw std::runtime_error("cannot open '" + pvd.string() + "' (is this a grains output folder?)");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  if (text.find("type=\"Collection\"") == std::string::npos)
    throw std::runtime_error("'" + pvd.string() + "' is not a VTK collection (.pvd) file");
  std::vector<FrameEntry> out;
  std::size_t p = 0;
  while ((p = text.find("<DataSet", p)) != std::string::npos) {
    const std::size_t e = text.find('>', p);
    if (e == std::string::npos) break;
    const std::string tag = text.substr(p, e - p);
    p = e;
    FrameEntry f;
    const std::string t = attribute(tag, "timestep"), file = attribute(tag, "file");
    if (file.empty()) throw std::runtime_error("'" + pvd.string() + "': a DataSet entry has no file attribute");
    try {
      f.time = t.empty() ? 0.0 : std::stod(t);
    } catch (const std::exception&) {
      throw std::runtime_error("'" + pvd.string() + "': bad timestep \"" + t + "\"");
    }
    f.file = fs::path(file).is_absolute() ? fs::path(file) : pvd.parent_path() / file;
    out.push_back(std::move(f));
  }
  return out;
}

std::vector<FrameEntry> list_frames(const fs::path& out_dir) { return read_pvd(out_dir / "particles.pvd"); }

namespace {

vtkDataArray* find(vtkPointData* pd, std::initializer_list<const char*> names, int components) {
  for (const char* n : names)
    if (auto* a = pd->GetArray(n); a && a->GetNumberOfComponents() == components) return a;
  return nullptr;
}

template <class T>
void scalars(vtkDataArray* a, std::size_t n, std::vector<T>& out) {
  if (!a) return;
  out.resize(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<T>(a->GetComponent(static_cast<vtkIdType>(i), 0));
}

void vectors(vtkDataArray* a, std::size_t n, std::vector<Vec3>& out) {
  if (!a) return;
  out.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    double t[3];
    a->GetTuple(static_cast<vtkIdType>(i), t);
    out[i] = Vec3(t[0], t[1], t[2]);
  }
}

}  // namespace

Frame read_frame_file(const fs::path& file) {
  if (!fs::exists(file)) throw std::runtime_error("particle file '" + file.string() + "' does not exist");
  vtkUnstructuredGrid* grid = nullptr;
  vtkNew<vtkXMLUnstructuredGridReader> serial;
  vtkNew<vtkXMLPUnstructuredGridReader> parallel;
  vtkXMLReader* reader = serial;
  if (file.extension() == ".pvtu") reader = parallel;
  if (!reader->CanReadFile(file.c_str()))
    throw std::runtime_error("'" + file.string() + "' is not a readable VTK XML unstructured grid");
  reader->SetFileName(file.c_str());
  reader->Update();
  grid = vtkUnstructuredGrid::SafeDownCast(reader->GetOutputDataObject(0));
  if (!grid || !grid->GetPoints())
    throw std::runtime_error("'" + file.string() + "' holds no particle points");
  Frame f;
  f.file = file;
  const auto n = static_cast<std::size_t>(grid->GetNumberOfPoints());
  f.x.resize(n);
  for (std::size_t i = 0; i < n; ++i) grid->GetPoint(static_cast<vtkIdType>(i), f.x[i].data());
  auto* pd = grid->GetPointData();
  auto* r = find(pd, {"radius"}, 1);
  if (!r) throw std::runtime_error("'" + file.string() + "' has no 'radius' point array");
  scalars(r, n, f.radius);
  scalars(find(pd, {"id"}, 1), n, f.id);
  if (f.id.empty())
    for (std::size_t i = 0; i < n; ++i) f.id.push_back(static_cast<std::int64_t>(i));
  scalars(find(pd, {"material"}, 1), n, f.material);
  scalars(find(pd, {"coordination"}, 1), n, f.coordination);
  scalars(find(pd, {"body", "clump"}, 1), n, f.body);
  vectors(find(pd, {"velocity"}, 3), n, f.velocity);
  vectors(find(pd, {"force"}, 3), n, f.force);
  vectors(find(pd, {"angular_velocity"}, 3), n, f.angular_velocity);
  vectors(find(pd, {"semi_axes"}, 3), n, f.semi_axes);
  if (auto* q = find(pd, {"orientation"}, 4)) {
    f.orientation.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      double t[4];
      q->GetTuple(static_cast<vtkIdType>(i), t);
      f.orientation[i] = Quat(t[0], t[1], t[2], t[3]).normalized();  // stored w, x, y, z
    }
  }
  return f;
}

Frame read_frame(const fs::path& out_dir, long index) {
  const auto frames = list_frames(out_dir);
  if (frames.empty()) throw std::runtime_error("'" + (out_dir / "particles.pvd").string() + "' lists no frames");
  const long n = static_cast<long>(frames.size());
  const long k = index < 0 ? n + index : index;
  if (k < 0 || k >= n)
    throw std::runtime_error("frame " + std::to_string(index) + " does not exist: '" + out_dir.string() + "' has " +
                             std::to_string(n) + " frames (0.." + std::to_string(n - 1) + ", or -1 for the last)");
  Frame f = read_frame_file(frames[static_cast<std::size_t>(k)].file);
  f.index = static_cast<std::size_t>(k);
  f.time = frames[static_cast<std::size_t>(k)].time;
  return f;
}

Frame read_frame_at_time(const fs::path& out_dir, double time) {
  const auto frames = list_frames(out_dir);
  if (frames.empty()) throw std::runtime_error("'" + (out_dir / "particles.pvd").string() + "' lists no frames");
  std::size_t best = 0;
  for (std::size_t k = 1; k < frames.size(); ++k)
    if (std::abs(frames[k].time - time) < std::abs(frames[best].time - time)) best = k;
  return read_frame(out_dir, static_cast<long>(best));
}

fs::path walls_file(const fs::path& out_dir, std::size_t index) {
  const fs::path pvd = out_dir / "walls.pvd";
  if (!fs::exists(pvd)) return {};
  const auto w = read_pvd(pvd);
  if (index >= w.size()) return {};
  return w[index].file;
}

}  // namespace grains::postprocess
