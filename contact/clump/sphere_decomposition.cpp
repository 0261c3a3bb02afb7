#include "contact/clump/sphere_decomposition.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace grains::clump {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Our reading of the skeletal density (see the header): r (1 + m), with m the
// 26-neighbour mean of max(0, 1 - |grad r|), |grad r| by central differences.
std::vector<double> skeletal_key(const DistanceGrid& g, const std::vector<size_t>& nodes) {
  const int n = g.n;
  auto phi = [&](int i, int j, int k) {
    i = std::clamp(i, 0, n - 1);
    j = std::clamp(j, 0, n - 1);
    k = std::clamp(k, 0, n - 1);
    return double(g.phi[g.index(i, j, k)]);
  };
  auto medial = [&](int i, int j, int k) {
    const double gx = phi(i + 1, j, k) - phi(i - 1, j, k);
    const double gy = phi(i, j + 1, k) - phi(i, j - 1, k);
    const double gz = phi(i, j, k + 1) - phi(i, j, k - 1);
    return std::max(0.0, 1.0 - std::sqrt(gx * gx + gy * gy + gz * gz) / (2.0 * g.h));
  };
  std::vector<double> key(nodes.size());
  for (size_t a = 0; a < nodes.size(); ++a) {
    const size_t idx = nodes[a];
    const int i = int(idx % n), j = int((idx / n) % n), k = int(idx / (size_t(n) * n));
    double m = 0.0;
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) m += medial(i + di, j + dj, k + dk);
    key[a] = -g.phi[idx] * (1.0 + m / 27.0);
  }
  return key;
}

}  // namespace

SphereDecomposition decompose(const DistanceGrid& g, const DecompositionOptions& opt) {
  if (!(opt.mu >= 0.0 && opt.mu <= 1.0)) {
    throw std::invalid_argument("protrusion factor mu = " + std::to_string(opt.mu) + " is outside [0, 1]");
  }
  SphereDecomposition out;
  out.grid = g.n;
  out.mu = opt.mu;
  out.key = opt.key;
  out.half_edge = 0.5 * g.h * g.n;
  out.epsilon = std::sqrt(3.0) * out.half_edge / g.n;
  const int n = g.n;
  const size_t m = size_t(n) * n * n;

  // X = nodes inside the solid (r >= 0), with their distance r.
  auto t0 = Clock::now();
  std::vector<size_t> node;  // grid index of each element of X
  std::vector<int> x_of(m, -1);
  for (size_t idx = 0; idx < m; ++idx) {
    if (g.phi[idx] <= 0.0) {
      x_of[idx] = static_cast<int>(node.size());
      node.push_back(idx);
    }
  }
  const size_t nx = node.size();
  out.nodes_inside = nx;
  if (nx == 0) {
    throw std::invalid_argument("no grid node lies inside the mesh at " + std::to_string(n) +
                                "^3 nodes; use a finer --grid");
  }
  std::vector<double> r(nx);
  for (size_t a = 0; a < nx; ++a) r[a] = -double(g.phi[node[a]]);
  const std::vector<double> key = opt.key == GreedyKey::distance ? r : skeletal_key(g, node);
  std::vector<int> order(nx);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key[a] > key[b]; });

  // Step 1.
  std::vector<char> covered(nx, 0), popped(nx, 0);
  size_t n_covered = 0;
  std::vector<int> center_node;  // element of X at each ball centre
  auto place = [&](int a) {
    const double ra = r[a];
    center_node.push_back(a);
    const size_t idx = node[a];
    const int i = int(idx % n), j = int((idx / n) % n), k = int(idx / (size_t(n) * n));
    const int w = static_cast<int>(std::floor(ra / g.h + 1e-9));
    for (int kk = std::max(0, k - w); kk <= std::min(n - 1, k + w); ++kk) {
      for (int jj = std::max(0, j - w); jj <= std::min(n - 1, j + w); ++jj) {
        for (int ii = std::max(0, i - w); ii <= std::min(n - 1, i + w); ++ii) {
          const int b = x_of[g.index(ii, jj, kk)];
          if (b < 0) continue;
          const double d = g.h * std::sqrt(double((ii - i) * (ii - i) + (jj - j) * (jj - j) + (kk - k) * (kk - k)));
          if (d > ra) continue;
          if (!covered[b]) {
            covered[b] = 1;
            ++n_covered;
          }
          if (d - std::abs(ra - r[b]) <= opt.mu * r[b]) popped[b] = 1;
        }
      }
    }
    covered[a] = popped[a] = 1;  // a ball of radius 0 still covers its own node
  };
  for (size_t s = 0; s < nx && n_covered < nx; ++s) {
    const int a = order[s];
    if (!popped[a]) place(a);
  }
  // Only reachable with a non-distance key: popped nodes left uncovered.
  for (size_t s = 0; s < nx && n_covered < nx; ++s) {
    const int a = order[s];
    if (!covered[a]) place(a);
  }
  out.a1.reserve(center_node.size());
  for (int a : center_node) out.a1.push_back({g.node(int(node[a] % n), int((node[a] / n) % n), int(node[a] / (size_t(n) * n))), r[a]});
  out.seconds_greedy = seconds_since(t0);

  // Steps 2-3: engulfed[i] when B(x_i, r_i) lies in B(x_j, r_j + eps), j != i.
  t0 = Clock::now();
  const size_t nb = out.a1.size();
  std::vector<int> ball_at_x(nx, -1);
  for (size_t b = 0; b < nb; ++b) ball_at_x[center_node[b]] = static_cast<int>(b);
  const double eps = out.epsilon;
  auto for_engulfed_by = [&](size_t jb, auto&& visit) {
    const int a = center_node[jb];
    const size_t idx = node[a];
    const int i = int(idx % n), j = int((idx / n) % n), k = int(idx / (size_t(n) * n));
    const double R = out.a1[jb].radius + eps;
    const int w = static_cast<int>(std::floor(R / g.h + 1e-9));
    for (int kk = std::max(0, k - w); kk <= std::min(n - 1, k + w); ++kk) {
      for (int jj = std::max(0, j - w); jj <= std::min(n - 1, j + w); ++jj) {
        for (int ii = std::max(0, i - w); ii <= std::min(n - 1, i + w); ++ii) {
          const int x = x_of[g.index(ii, jj, kk)];
          if (x < 0 || ball_at_x[x] < 0 || size_t(ball_at_x[x]) == jb) continue;
          const int ib = ball_at_x[x];
          const double d = g.h * std::sqrt(double((ii - i) * (ii - i) + (jj - j) * (jj - j) + (kk - k) * (kk - k)));
          if (d <= R - out.a1[ib].radius) visit(ib);
        }
      }
    }
  };
  std::vector<char> dropped(nb, 0);
  for (size_t jb = 0; jb < nb; ++jb) for_engulfed_by(jb, [&](int ib) { dropped[ib] = 1; });
  std::vector<char> held(nb, 0);  // engulfed by a ball that is kept
  for (size_t jb = 0; jb < nb; ++jb) {
    if (!dropped[jb]) for_engulfed_by(jb, [&](int ib) { held[ib] = 1; });
  }
  for (size_t b = 0; b < nb; ++b) {
    if (dropped[b] && !held[b]) {
      dropped[b] = 0;
      ++out.restored;
    }
    if (!dropped[b]) out.a3.push_back({out.a1[b].center, out.a1[b].radius + eps});
  }
  out.seconds_reduction = seconds_since(t0);
  return out;
}

SphereDecomposition decompose(const mesh::TriangleMesh& mesh, const DecompositionOptions& opt) {
  if (opt.grid < 2) {
    throw std::invalid_argument("grid resolution N = " + std::to_string(opt.grid) + " is too small; use N >= 2");
  }
  const auto t0 = Clock::now();
  const DistanceGrid g = compute_distance_grid(mesh, opt.grid);
  const double t_dist = seconds_since(t0);
  SphereDecomposition d = decompose(g, opt);
  d.seconds_distance = t_dist;
  return d;
}

}  // namespace grains::clump
