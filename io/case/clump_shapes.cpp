#include "io/case/clump_shapes.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <unistd.h>

#include "contact/clump/clump_yaml.hpp"
#include "io/mesh/mesh_reader.hpp"

namespace grains::io {

namespace fs = std::filesystem;

sim::ClumpShape normalised_clump_shape(const clump::ClumpTemplate& t, const std::string& source) {
  if (t.balls.empty()) throw std::runtime_error(source + ": the clump has no balls");
  double B = 0;
  for (const auto& b : t.balls) B = std::max(B, b.center.norm() + b.radius);
  sim::ClumpShape c;
  c.source = source;
  for (const auto& b : t.balls) {
    c.centres.push_back(b.center / B);
    c.radii.push_back(b.radius / B);
  }
  c.volume = t.volume / (B * B * B);
  c.inertia = t.inertia / (t.density * std::pow(B, 5));
  if (!(c.volume > 0) || !(c.inertia.minCoeff() > 0))
    throw std::runtime_error(source + ": the clump has no positive volume and inertia");
  return c;
}

namespace {

std::mutex g_mutex;
std::map<std::string, std::shared_ptr<const sim::ClumpShape>> g_shapes;  // in-process cache

std::uint64_t fnv1a(const std::string& bytes, std::uint64_t h = 1469598103934665603ull) {
  for (unsigned char ch : bytes) {
    h ^= ch;
    h *= 1099511628211ull;
  }
  return h;
}

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open mesh file '" + path + "'");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

fs::path clump_cache_dir() {
  if (const char* d = std::getenv("GRAINS_CACHE_DIR"); d && *d) return d;
  if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d) return fs::path(d) / "grains" / "clumps";
  if (const char* d = std::getenv("HOME"); d && *d) return fs::path(d) / ".cache" / "grains" / "clumps";
  return fs::temp_directory_path() / "grains-cache" / "clumps";
}

fs::path clump_cache_file(const std::string& mesh_path, int grid, double mu) {
  std::ostringstream key;
  key.precision(17);
  key << "grains clump cache 1|grid " << grid << "|mu " << mu << "|";
  const std::uint64_t h = fnv1a(read_all(mesh_path), fnv1a(key.str()));
  char name[64];
  std::snprintf(name, sizeof name, "clump_%016llx.yaml", static_cast<unsigned long long>(h));
  return clump_cache_dir() / name;
}

std::shared_ptr<const sim::ClumpShape> clump_shape_from_file(const std::string& path) {
  std::lock_guard<std::mutex> lock(g_mutex);
  const std::string key = "file|" + fs::absolute(path).string();
  if (auto it = g_shapes.find(key); it != g_shapes.end()) return it->second;
  auto s = std::make_shared<const sim::ClumpShape>(normalised_clump_shape(clump::load_clump_yaml(path), path));
  g_shapes[key] = s;
  return s;
}

std::shared_ptr<const sim::ClumpShape> clump_shape_from_mesh(const std::string& path, int grid, double mu) {
  const fs::path cache = clump_cache_file(path, grid, mu);
  std::lock_guard<std::mutex> lock(g_mutex);
  const std::string key = "cache|" + cache.string();
  if (auto it = g_shapes.find(key); it != g_shapes.end()) return it->second;
  clump::ClumpTemplate t;
  bool cached = false;
  std::error_code ec;
  if (fs::exists(cache, ec)) {
    try {
      t = clump::load_clump_yaml(cache.string());
      cached = true;
    } catch (const std::exception&) {
      cached = false;  // a damaged cache entry is rebuilt
    }
  }
  if (!cached) {
    const auto mesh = mesh::load_mesh(path);
    clump::ClumpOptions opt;
    opt.decomposition.grid = grid;
    opt.decomposition.mu = mu;
    opt.measure = false;
    t = clump::build_clump(mesh, opt);
    // Written atomically (temporary + rename); failure only loses the cache.
    fs::create_directories(cache.parent_path(), ec);
    const fs::path tmp = cache.string() + ".tmp" + std::to_string(::getpid());
    try {
      clump::write_clump_yaml(t, tmp.string());
      fs::rename(tmp, cache, ec);
    } catch (const std::exception&) {
    }
    fs::remove(tmp, ec);
  }
  auto s = std::make_shared<const sim::ClumpShape>(normalised_clump_shape(t, path));
  g_shapes[key] = s;
  return s;
}

}  // namespace grains::io
