#include "io/cli/clump_command.hpp"

#include "contact/clump/clump_template.hpp"
#include "contact/clump/clump_yaml.hpp"
#include "io/mesh/mesh_error.hpp"
#include "io/mesh/mesh_reader.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace grains::io {
using namespace grains::clump;  // the decomposition and its files

const char* clump_command_usage() {
  return "usage: grains clump MESH [--grid N] [--mu MU] [-o CLUMP.yaml] [--density RHO]\n"
         "                          [--key distance|skeletal] [--no-measure]\n"
         "  MESH        closed triangle mesh (.stl ASCII or binary, .obj, .off), SI units (m)\n"
         "  --grid N    nodes per axis of the distance grid, m = N^3 (default 64; 2 <= N <= 1024)\n"
         "  --mu MU     protrusion factor in [0, 1] (default 0.25)\n"
         "  -o FILE     write the clump (balls in the body frame, mass properties, metadata) as YAML\n"
         "  --density   kg/m^3 (default 1000)\n"
         "  --key       greedy order: distance (default) or skeletal (see docs/decomposition.md)\n"
         "  --no-measure  skip the Hausdorff measurement\n";
}

namespace {

double number(const std::string& opt, const std::string& v) {
  size_t used = 0;
  double x = 0;
  try {
    x = std::stod(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != v.size() || !std::isfinite(x)) throw std::invalid_argument(opt + " needs a number, got '" + v + "'");
  return x;
}

}  // namespace

int run_clump_command(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  std::string mesh_path, out_path;
  ClumpOptions opt;
  try {
    for (size_t i = 0; i < args.size(); ++i) {
      const std::string& a = args[i];
      auto value = [&]() -> const std::string& {
        if (i + 1 >= args.size()) throw std::invalid_argument(a + " needs a value");
        return args[++i];
      };
      if (a == "-h" || a == "--help") {
        out << clump_command_usage();
        return 0;
      } else if (a == "--grid") {
        const double n = number(a, value());
        if (n != std::floor(n) || n < 2 || n > 1024) throw std::invalid_argument("--grid must be an integer in [2, 1024]");
        opt.decomposition.grid = static_cast<int>(n);
      } else if (a == "--mu") {
        opt.decomposition.mu = number(a, value());
        if (opt.decomposition.mu < 0 || opt.decomposition.mu > 1) throw std::invalid_argument("--mu must lie in [0, 1]");
      } else if (a == "-o" || a == "--output") {
        out_path = value();
      } else if (a == "--density") {
        opt.density = number(a, value());
        if (!(opt.density > 0)) throw std::invalid_argument("--density must be positive");
      } else if (a == "--key") {
        const std::string& k = value();
        if (k == "distance") opt.decomposition.key = GreedyKey::distance;
        else if (k == "skeletal") opt.decomposition.key = GreedyKey::skeletal;
        else throw std::invalid_argument("--key must be 'distance' or 'skeletal', got '" + k + "'");
      } else if (a == "--no-measure") {
        opt.measure = false;
      } else if (!a.empty() && a[0] == '-') {
        throw std::invalid_argument("unknown option '" + a + "'");
      } else if (mesh_path.empty()) {
        mesh_path = a;
      } else {
        throw std::invalid_argument("more than one mesh given ('" + mesh_path + "' and '" + a + "')");
      }
    }
    if (mesh_path.empty()) throw std::invalid_argument("no mesh file given");
  } catch (const std::invalid_argument& e) {
    err << "grains clump: " << e.what() << "\n" << clump_command_usage();
    return 2;
  }

  try {
    const auto t0 = std::chrono::steady_clock::now();
    const mesh::TriangleMesh mesh = mesh::load_mesh(mesh_path);
    for (const auto& w : mesh.warnings) err << "warning: " << w << "\n";
    const ClumpTemplate c = build_clump(mesh, opt);
    if (!out_path.empty()) write_clump_yaml(c, out_path);
    const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const ClumpMetadata& m = c.meta;
    char buf[1024];
    std::snprintf(buf, sizeof buf,
                  "mesh            %s (%zu vertices, %zu faces, volume %.6g)\n"
                  "grid            N = %d (m = %lld), mu = %.3g, key = %s\n"
                  "balls           n1 = n2 = %zu, n3 = %zu (seed's step 3 alone: %zu; %d restored)\n"
                  "bound           eps = %.6g\n",
                  mesh_path.c_str(), mesh.vertices.size(), mesh.faces.size(), m.mesh_volume, m.grid,
                  static_cast<long long>(m.grid) * m.grid * m.grid, m.mu, m.greedy_key.c_str(), m.n1, m.n3,
                  m.n3_seed_rule(), m.restored, m.epsilon);
    out << buf;
    if (m.hausdorff >= 0) {
      std::snprintf(buf, sizeof buf,
                    "hausdorff       %.6g (%.3f eps; mesh->union %.6g, union->mesh %.6g; node cover radius %.6g)\n",
                    m.hausdorff, m.hausdorff / m.epsilon, m.hausdorff_mesh_to_union, m.hausdorff_union_to_mesh,
                    m.node_cover_radius);
      out << buf;
    }
    std::snprintf(buf, sizeof buf,
                  "volume          union %.6g (+- %.2g), error %+.3f %%\n"
                  "mass            %.6g kg at density %.6g; principal inertia %.6g %.6g %.6g kg m^2\n"
                  "time            %.3f s total: decomposition %.3f s (OpenVDB %.3f, exact pass %.3f, greedy %.3f,\n"
                  "                reduction %.3f), mass properties %.3f s, measurement %.3f s\n",
                  c.volume, c.volume_bound, 100.0 * m.volume_error, c.mass, c.density, c.inertia.x(),
                  c.inertia.y(), c.inertia.z(), total, m.seconds_decomposition, m.seconds_distance_vdb,
                  m.seconds_distance_exact, m.seconds_greedy, m.seconds_reduction, m.seconds_mass,
                  m.seconds_measurement);
    out << buf;
    if (!out_path.empty()) out << "written         " << out_path << "\n";
    return 0;
  } catch (const mesh::MeshError& e) {
    err << "grains clump: " << e.what() << "\n";
  } catch (const ClumpFileError& e) {
    err << "grains clump: " << e.what() << "\n";
  } catch (const std::exception& e) {
    err << "grains clump: " << mesh_path << ": " << e.what() << "\n";
  }
  return 1;
}

}  // namespace grains::io
