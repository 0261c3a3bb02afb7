#pragma once
// The one exception type of mesh input. Every loader and validation failure
// throws a MeshError whose message names the file, what was wrong, where, and
// what would be valid; `kind` lets callers and tests tell the cases apart.

#include <stdexcept>
#include <string>

namespace grains::mesh {

enum class MeshErrorKind {
  cannot_open,        // file missing or unreadable
  unknown_format,     // extension not .stl/.obj/.off
  empty,              // no bytes, or no faces
  parse,              // malformed text (bad token, bad index, bad header)
  truncated,          // binary STL shorter than its header promises
  non_finite,         // NaN or infinite coordinate
  degenerate_face,    // face with a repeated vertex or (near) zero area
  not_closed,         // boundary edges (edge used by one face only)
  non_manifold,       // edge used by more than two faces
  non_orientable,     // faces cannot be oriented consistently
  bad_orientation,    // inconsistent or inward orientation, when repair is off
};

const char* to_string(MeshErrorKind kind);

class MeshError : public std::runtime_error {
public:
  MeshError(MeshErrorKind kind, const std::string& message)
      : std::runtime_error(message), kind_(kind) {}
  MeshErrorKind kind() const { return kind_; }

private:
  MeshErrorKind kind_;
};

}  // namespace grains::mesh
