#include "io/mesh/mesh_error.hpp"

namespace grains::mesh {

const char* to_string(MeshErrorKind kind) {
  switch (kind) {
    case MeshErrorKind::cannot_open: return "cannot_open";
    case MeshErrorKind::unknown_format: return "unknown_format";
    case MeshErrorKind::empty: return "empty";
    case MeshErrorKind::parse: return "parse";
    case MeshErrorKind::truncated: return "truncated";
    case MeshErrorKind::non_finite: return "non_finite";
    case MeshErrorKind::degenerate_face: return "degenerate_face";
    case MeshErrorKind::not_closed: return "not_closed";
    case MeshErrorKind::non_manifold: return "non_manifold";
    case MeshErrorKind::non_orientable: return "non_orientable";
    case MeshErrorKind::bad_orientation: return "bad_orientation";
  }
  return "unknown";
}

}  // namespace grains::mesh
