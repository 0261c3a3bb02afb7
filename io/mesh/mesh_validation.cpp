#include "io/mesh/mesh_validation.hpp"

#include "io/mesh/mesh_error.hpp"
#include "io/mesh/mesh_text.hpp"

#include <algorithm>
#include <cstdint>
#include <queue>
#include <unordered_map>

namespace grains::mesh {
namespace {

struct EdgeUse {
  int face;
  bool forward;  // true if the face runs the edge from the lower to the higher index
};

uint64_t edge_key(int a, int b) {
  const auto lo = static_cast<uint64_t>(std::min(a, b));
  const auto hi = static_cast<uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

std::string edge_location(const TriangleMesh& m, uint64_t key, const std::vector<EdgeUse>& uses) {
  const int a = static_cast<int>(key >> 32);
  const int b = static_cast<int>(key & 0xffffffffu);
  std::string s = "edge " + std::to_string(a) + "-" + std::to_string(b) + " at " +
                  detail::vec_to_string(0.5 * (m.vertices[a] + m.vertices[b])) + " (faces";
  for (const auto& u : uses) s += " " + std::to_string(u.face);
  return s + ")";
}

}  // namespace

ValidationReport validate_mesh(TriangleMesh& mesh, const ValidationOptions& opt) {
  const std::string& src = mesh.source.empty() ? std::string("<mesh>") : mesh.source;
  if (mesh.faces.empty()) {
    throw MeshError(MeshErrorKind::empty, src + ": mesh has no faces");
  }
  const int nv = static_cast<int>(mesh.vertices.size());
  for (int i = 0; i < nv; ++i) {
    if (!mesh.vertices[i].allFinite()) {
      throw MeshError(MeshErrorKind::non_finite, src + ": vertex " + std::to_string(i) + " has a non-finite coordinate " +
                                                     detail::vec_to_string(mesh.vertices[i]));
    }
  }
  const int nf = static_cast<int>(mesh.faces.size());
  for (int f = 0; f < nf; ++f) {
    for (int v : mesh.faces[f]) {
      if (v < 0 || v >= nv) {
        throw MeshError(MeshErrorKind::parse, src + ": face " + std::to_string(f) + " refers to vertex " +
                                                  std::to_string(v) + "; valid are 0.." + std::to_string(nv - 1));
      }
    }
  }

  // Degenerate faces.
  const double diag = (mesh.bbox_max() - mesh.bbox_min()).norm();
  const double area_tol = opt.degenerate_area_rel * diag * diag;
  std::vector<int> degenerate;
  for (int f = 0; f < nf; ++f) {
    const auto& t = mesh.faces[f];
    const bool repeated = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    const double area = 0.5 * (mesh.vertices[t[1]] - mesh.vertices[t[0]])
                                  .cross(mesh.vertices[t[2]] - mesh.vertices[t[0]])
                                  .norm();
    if (repeated || area <= area_tol) degenerate.push_back(f);
  }
  if (!degenerate.empty() && opt.wall_surface) {
    // A wall's zero-area faces touch nothing: dropped, with a warning.
    std::string msg = src + ": " + std::to_string(degenerate.size()) +
                      " degenerate face(s) (a repeated vertex or zero area) dropped; first: face " +
                      std::to_string(degenerate[0]);
    std::vector<char> drop(static_cast<std::size_t>(nf), 0);
    for (int f : degenerate) drop[static_cast<std::size_t>(f)] = 1;
    std::vector<std::array<int, 3>> kept;
    for (int f = 0; f < nf; ++f)
      if (!drop[static_cast<std::size_t>(f)]) kept.push_back(mesh.faces[static_cast<std::size_t>(f)]);
    mesh.faces = std::move(kept);
    mesh.warnings.push_back(msg);
    if (mesh.faces.empty()) throw MeshError(MeshErrorKind::empty, src + ": every face is degenerate (zero area)");
    return {};
  }
  if (opt.wall_surface) return {};  // open, non-manifold and either orientation are fine for a wall
  if (!degenerate.empty()) {
    std::string msg = src + ": " + std::to_string(degenerate.size()) +
                      " degenerate face(s) (a repeated vertex or zero area); first:";
    for (int i = 0; i < std::min<int>(opt.max_locations, degenerate.size()); ++i) {
      const auto& t = mesh.faces[degenerate[i]];
      msg += " face " + std::to_string(degenerate[i]) + " [" + std::to_string(t[0]) + " " + std::to_string(t[1]) +
             " " + std::to_string(t[2]) + "] at " + detail::vec_to_string(mesh.vertices[t[0]]) + ";";
    }
    msg += " every face needs three distinct, non-collinear vertices";
    throw MeshError(MeshErrorKind::degenerate_face, msg);
  }

  // Edge incidence.
  std::unordered_map<uint64_t, std::vector<EdgeUse>> edges;
  edges.reserve(3 * nf / 2 + 1);
  for (int f = 0; f < nf; ++f) {
    const auto& t = mesh.faces[f];
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      edges[edge_key(a, b)].push_back({f, a < b});
    }
  }
  std::vector<uint64_t> boundary, nonmanifold;
  for (const auto& [key, uses] : edges) {
    if (uses.size() == 1) boundary.push_back(key);
    if (uses.size() > 2) nonmanifold.push_back(key);
  }
  std::sort(boundary.begin(), boundary.end());
  std::sort(nonmanifold.begin(), nonmanifold.end());
  auto list = [&](const std::vector<uint64_t>& keys) {
    std::string s;
    for (int i = 0; i < std::min<int>(opt.max_locations, keys.size()); ++i) {
      s += (i ? "; " : "") + edge_location(mesh, keys[i], edges[keys[i]]);
    }
    return s;
  };
  if (!nonmanifold.empty()) {
    throw MeshError(MeshErrorKind::non_manifold,
                    src + ": mesh is not manifold: " + std::to_string(nonmanifold.size()) +
                        " edge(s) shared by more than two faces; first: " + list(nonmanifold) +
                        "; every edge of a closed solid's surface must join exactly two faces");
  }
  if (!boundary.empty()) {
    throw MeshError(MeshErrorKind::not_closed,
                    src + ": mesh is not closed: " + std::to_string(boundary.size()) +
                        " boundary edge(s) used by one face only; first: " + list(boundary) +
                        "; a grain's surface must be watertight (every edge shared by exactly two faces)");
  }

  // Orientation: breadth-first over face adjacency; two faces sharing an edge
  // are consistent when they run it in opposite directions.
  ValidationReport report;
  std::vector<int> comp(nf, -1);
  std::vector<char> flip(nf, 0);
  std::vector<std::vector<int>> members;
  for (int seed = 0; seed < nf; ++seed) {
    if (comp[seed] >= 0) continue;
    const int c = static_cast<int>(members.size());
    members.emplace_back();
    comp[seed] = c;
    std::queue<int> q;
    q.push(seed);
    while (!q.empty()) {
      const int f = q.front();
      q.pop();
      members[c].push_back(f);
      const auto& t = mesh.faces[f];
      for (int k = 0; k < 3; ++k) {
        const int a = t[k], b = t[(k + 1) % 3];
        const bool fwd_f = (a < b) != bool(flip[f]);
        for (const auto& u : edges[edge_key(a, b)]) {
          if (u.face == f) continue;
          // g must run the edge opposite to f (after flips).
          const char need = (u.forward == fwd_f) ? 1 : 0;
          if (comp[u.face] < 0) {
            comp[u.face] = c;
            flip[u.face] = need;
            q.push(u.face);
          } else if (flip[u.face] != need) {
            throw MeshError(MeshErrorKind::non_orientable,
                            src + ": mesh is not orientable: faces " + std::to_string(f) + " and " +
                                std::to_string(u.face) + " cannot be oriented consistently across " +
                                edge_location(mesh, edge_key(a, b), edges[edge_key(a, b)]));
          }
        }
      }
    }
  }
  report.components = static_cast<int>(members.size());
  for (auto& mem : members) {
    int flipped = 0;
    for (int f : mem) flipped += flip[f];
    if (2 * flipped > static_cast<int>(mem.size())) {  // flip the minority instead
      for (int f : mem) flip[f] = !flip[f];
      flipped = static_cast<int>(mem.size()) - flipped;
    }
    report.faces_flipped_for_consistency += flipped;
  }
  if (report.faces_flipped_for_consistency > 0 && !opt.repair_orientation) {
    int first = static_cast<int>(std::find(flip.begin(), flip.end(), 1) - flip.begin());
    throw MeshError(MeshErrorKind::bad_orientation,
                    src + ": inconsistent orientation: " + std::to_string(report.faces_flipped_for_consistency) +
                        " face(s) wound against their neighbours (first: face " + std::to_string(first) +
                        "); all faces must be counter-clockwise seen from outside");
  }
  for (int f = 0; f < nf; ++f) {
    if (flip[f]) std::swap(mesh.faces[f][1], mesh.faces[f][2]);
  }
  if (report.faces_flipped_for_consistency > 0) {
    mesh.warnings.push_back(src + ": " + std::to_string(report.faces_flipped_for_consistency) +
                            " face(s) were wound against their neighbours and have been flipped");
  }
  for (size_t c = 0; c < members.size(); ++c) {
    const Eigen::Vector3d o = mesh.vertices[mesh.faces[members[c][0]][0]];
    double v = 0.0;
    for (int f : members[c]) {
      const auto& t = mesh.faces[f];
      v += (mesh.vertices[t[0]] - o).dot((mesh.vertices[t[1]] - o).cross(mesh.vertices[t[2]] - o)) / 6.0;
    }
    if (v < 0.0) {
      if (!opt.repair_orientation) {
        throw MeshError(MeshErrorKind::bad_orientation,
                        src + ": inward orientation: component " + std::to_string(c) + " encloses signed volume " +
                            std::to_string(v) + " < 0; faces must be counter-clockwise seen from outside");
      }
      for (int f : members[c]) std::swap(mesh.faces[f][1], mesh.faces[f][2]);
      ++report.components_flipped_inward;
      mesh.warnings.push_back(src + ": component " + std::to_string(c) + " (" + std::to_string(members[c].size()) +
                              " faces) was inward-oriented (signed volume " + std::to_string(v) +
                              "); all its faces have been flipped");
    }
  }
  return report;
}

}  // namespace grains::mesh
