#pragma once
// How a registered kind (a wall kind, sim/walls/wall_kind.hpp) reads its own
// case-file keys without knowing the parser.
#include <memory>
#include <string>

#include "contact/contact_geometry.hpp"
#include "contact/mesh/triangle_mesh.hpp"

namespace grains::sim {

/// How a registered kind reads its own case-file keys; io's case parser
/// implements it against the kind's keys(), so every error is located and
/// every range checked. Missing keys give the declared default, else `fallback`.
class KeyReader {
 public:
  virtual ~KeyReader() = default;
  virtual bool has(const std::string& key) const = 0;
  virtual double number(const std::string& key, double fallback) = 0;
  virtual contact::Vec3 vec3(const std::string& key, const contact::Vec3& fallback) = 0;
  virtual bool boolean(const std::string& key, bool fallback) = 0;
  virtual std::string string(const std::string& key, const std::string& fallback) = 0;
  /// The triangle mesh of the file a key names (relative to the case file),
  /// read and checked as a wall surface (open and non-manifold meshes
  /// allowed; degenerate faces dropped with a warning); null after recording
  /// a located error when it cannot be read.
  virtual std::shared_ptr<const mesh::TriangleMesh> surface_mesh(const std::string& key) = 0;
  /// Records a warning at the key's location.
  virtual void warning(const std::string& key, const std::string& message) = 0;
  /// Records an error at the key's location (the map's when absent).
  virtual void error(const std::string& key, const std::string& message) = 0;
  /// A unit direction from a vector key: a zero vector is an error.
  contact::Vec3 direction(const std::string& key, const contact::Vec3& fallback) {
    contact::Vec3 v = vec3(key, fallback);
    if (v.norm() == 0) {
      error(key, key + " must not be the zero vector");
      v = fallback;
    }
    return v.normalized();
  }
};

}  // namespace grains::sim
