#include "contact/clump/clump_yaml.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>

namespace grains::clump {
namespace {

void emit_vec(YAML::Emitter& e, const Eigen::Vector3d& v) {
  e << YAML::Flow << YAML::BeginSeq << v.x() << v.y() << v.z() << YAML::EndSeq;
}

}  // namespace

void write_clump_yaml(const ClumpTemplate& c, std::ostream& out) {
  YAML::Emitter e;
  e.SetDoublePrecision(17);
  e << YAML::BeginMap;
  e << YAML::Key << "grains_clump" << YAML::Value << 1;
  e << YAML::Key << "units" << YAML::Value << "SI";
  e << YAML::Key << "density" << YAML::Value << c.density;
  e << YAML::Key << "mass" << YAML::Value << c.mass;
  e << YAML::Key << "volume" << YAML::Value << c.volume;
  e << YAML::Key << "volume_integration_bound" << YAML::Value << c.volume_bound;
  e << YAML::Key << "inertia_principal" << YAML::Value;
  emit_vec(e, c.inertia);
  e << YAML::Key << "centre_of_mass_mesh_frame" << YAML::Value;
  emit_vec(e, c.centre_of_mass);
  e << YAML::Key << "body_axes_mesh_frame" << YAML::Value << YAML::BeginSeq;
  for (int a = 0; a < 3; ++a) emit_vec(e, c.axes.col(a));
  e << YAML::EndSeq;
  const ClumpMetadata& m = c.meta;
  e << YAML::Key << "decomposition" << YAML::Value << YAML::BeginMap;
  e << YAML::Key << "source" << YAML::Value << m.source;
  e << YAML::Key << "method" << YAML::Value << m.method;
  e << YAML::Key << "grid" << YAML::Value << m.grid;
  e << YAML::Key << "m" << YAML::Value << static_cast<long long>(m.grid) * m.grid * m.grid;
  e << YAML::Key << "mu" << YAML::Value << m.mu;
  e << YAML::Key << "greedy_key" << YAML::Value << m.greedy_key;
  e << YAML::Key << "epsilon" << YAML::Value << m.epsilon;
  e << YAML::Key << "n1" << YAML::Value << m.n1;
  e << YAML::Key << "n2" << YAML::Value << m.n1;
  e << YAML::Key << "n3" << YAML::Value << m.n3;
  e << YAML::Key << "n3_seed_rule" << YAML::Value << m.n3_seed_rule();
  e << YAML::Key << "restored" << YAML::Value << m.restored;
  e << YAML::Key << "node_cover_radius" << YAML::Value << m.node_cover_radius;
  e << YAML::Key << "hausdorff" << YAML::Value << m.hausdorff;
  e << YAML::Key << "hausdorff_mesh_to_union" << YAML::Value << m.hausdorff_mesh_to_union;
  e << YAML::Key << "hausdorff_union_to_mesh" << YAML::Value << m.hausdorff_union_to_mesh;
  e << YAML::Key << "mesh_volume" << YAML::Value << m.mesh_volume;
  e << YAML::Key << "volume_error" << YAML::Value << m.volume_error;
  e << YAML::Key << "seconds_decomposition" << YAML::Value << m.seconds_decomposition;
  e << YAML::Key << "seconds_mass_properties" << YAML::Value << m.seconds_mass;
  e << YAML::Key << "seconds_measurement" << YAML::Value << m.seconds_measurement;
  e << YAML::EndMap;
  e << YAML::Key << "balls" << YAML::Value << YAML::BeginSeq;
  for (const auto& b : c.balls) {
    e << YAML::Flow << YAML::BeginSeq << b.center.x() << b.center.y() << b.center.z() << b.radius << YAML::EndSeq;
  }
  e << YAML::EndSeq << YAML::EndMap;
  out << e.c_str() << "\n";
}

void write_clump_yaml(const ClumpTemplate& c, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw ClumpFileError(path + ": cannot open clump file for writing");
  write_clump_yaml(c, out);
  if (!out) throw ClumpFileError(path + ": error while writing the clump file");
}

namespace {

const YAML::Node need(const YAML::Node& n, const char* key, const std::string& path) {
  const YAML::Node v = n[key];
  if (!v) throw ClumpFileError(path + ": missing key '" + key + "' (see contact/clump/clump_yaml.hpp for the layout)");
  return v;
}

double positive(const YAML::Node& n, const char* key, const std::string& path) {
  const double v = need(n, key, path).as<double>();
  if (!(v > 0.0) || !std::isfinite(v)) {
    throw ClumpFileError(path + ": '" + key + "' must be a positive number, got " + std::to_string(v));
  }
  return v;
}

Eigen::Vector3d vec3(const YAML::Node& n, const std::string& path, const std::string& what) {
  if (!n.IsSequence() || n.size() != 3) throw ClumpFileError(path + ": '" + what + "' must be a list of 3 numbers");
  return {n[0].as<double>(), n[1].as<double>(), n[2].as<double>()};
}

}  // namespace

ClumpTemplate load_clump_yaml(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw ClumpFileError(path + ": cannot open clump file");
  } catch (const YAML::Exception& ex) {
    throw ClumpFileError(path + ":" + std::to_string(ex.mark.line + 1) + ":" + std::to_string(ex.mark.column + 1) +
                         ": " + ex.msg);
  }
  try {
    if (!root.IsMap() || need(root, "grains_clump", path).as<int>() != 1) {
      throw ClumpFileError(path + ": not a grains clump file (expected 'grains_clump: 1')");
    }
    ClumpTemplate c;
    c.density = positive(root, "density", path);
    c.mass = positive(root, "mass", path);
    c.volume = positive(root, "volume", path);
    if (root["volume_integration_bound"]) c.volume_bound = root["volume_integration_bound"].as<double>();
    c.inertia = vec3(need(root, "inertia_principal", path), path, "inertia_principal");
    c.centre_of_mass = vec3(need(root, "centre_of_mass_mesh_frame", path), path, "centre_of_mass_mesh_frame");
    const YAML::Node axes = need(root, "body_axes_mesh_frame", path);
    if (!axes.IsSequence() || axes.size() != 3) throw ClumpFileError(path + ": 'body_axes_mesh_frame' must hold 3 axes");
    for (int a = 0; a < 3; ++a) c.axes.col(a) = vec3(axes[a], path, "body_axes_mesh_frame");
    const YAML::Node balls = need(root, "balls", path);
    if (!balls.IsSequence() || balls.size() == 0) throw ClumpFileError(path + ": 'balls' must be a non-empty list");
    for (size_t i = 0; i < balls.size(); ++i) {
      const YAML::Node b = balls[i];
      if (!b.IsSequence() || b.size() != 4) {
        throw ClumpFileError(path + ":" + std::to_string(b.Mark().line + 1) + ": ball " + std::to_string(i) +
                             " must be [x, y, z, r]");
      }
      Ball ball{{b[0].as<double>(), b[1].as<double>(), b[2].as<double>()}, b[3].as<double>()};
      if (!ball.center.allFinite() || !(ball.radius > 0.0) || !std::isfinite(ball.radius)) {
        throw ClumpFileError(path + ":" + std::to_string(b.Mark().line + 1) + ": ball " + std::to_string(i) +
                             " needs finite coordinates and a positive radius");
      }
      c.balls.push_back(ball);
    }
    if (const YAML::Node d = root["decomposition"]) {
      ClumpMetadata& m = c.meta;
      if (d["source"]) m.source = d["source"].as<std::string>();
      if (d["method"]) m.method = d["method"].as<std::string>();
      if (d["grid"]) m.grid = d["grid"].as<int>();
      if (d["mu"]) m.mu = d["mu"].as<double>();
      if (d["greedy_key"]) m.greedy_key = d["greedy_key"].as<std::string>();
      if (d["epsilon"]) m.epsilon = d["epsilon"].as<double>();
      if (d["n1"]) m.n1 = d["n1"].as<size_t>();
      if (d["n3"]) m.n3 = d["n3"].as<size_t>();
      if (d["restored"]) m.restored = d["restored"].as<int>();
      if (d["node_cover_radius"]) m.node_cover_radius = d["node_cover_radius"].as<double>();
      if (d["hausdorff"]) m.hausdorff = d["hausdorff"].as<double>();
      if (d["hausdorff_mesh_to_union"]) m.hausdorff_mesh_to_union = d["hausdorff_mesh_to_union"].as<double>();
      if (d["hausdorff_union_to_mesh"]) m.hausdorff_union_to_mesh = d["hausdorff_union_to_mesh"].as<double>();
      if (d["mesh_volume"]) m.mesh_volume = d["mesh_volume"].as<double>();
      if (d["volume_error"]) m.volume_error = d["volume_error"].as<double>();
      if (d["seconds_decomposition"]) m.seconds_decomposition = d["seconds_decomposition"].as<double>();
      if (d["seconds_measurement"]) m.seconds_measurement = d["seconds_measurement"].as<double>();
    }
    return c;
  } catch (const YAML::Exception& ex) {
    throw ClumpFileError(path + ":" + std::to_string(ex.mark.line + 1) + ":" + std::to_string(ex.mark.column + 1) +
                         ": " + ex.msg);
  }
}

}  // namespace grains::clump
