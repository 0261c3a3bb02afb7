#include "contact/correlation/spreader.hpp"

#include <omp.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace grains::correlation {

namespace {

constexpr std::array<int, 3> kBin = {16, 4, 4};

// Calls f.template operator()<W>() for the runtime width w (2..16).
template <typename F>
void with_width(int w, F&& f) {
  switch (w) {
    case 2: f.template operator()<2>(); break;
    case 3: f.template operator()<3>(); break;
    case 4: f.template operator()<4>(); break;
    case 5: f.template operator()<5>(); break;
    case 6: f.template operator()<6>(); break;
    case 7: f.template operator()<7>(); break;
    case 8: f.template operator()<8>(); break;
    case 9: f.template operator()<9>(); break;
    case 10: f.template operator()<10>(); break;
    case 11: f.template operator()<11>(); break;
    case 12: f.template operator()<12>(); break;
    case 13: f.template operator()<13>(); break;
    case 14: f.template operator()<14>(); break;
    case 15: f.template operator()<15>(); break;
    case 16: f.template operator()<16>(); break;
    default: throw std::logic_error("spreader: unsupported kernel width");
  }
}

// Kernel values at the W nodes l0 .. l0+W-1 of a point at fine coordinate u.
template <int W>
inline int kernel_at(const KernelPolynomial& kp, double u, double* out) {
  constexpr int D = std::min(kMaxKernelDegree, W + 3);
  constexpr double hw = 0.5 * W;
  const int l0 = static_cast<int>(std::ceil(u - hw));
  const double x = 2.0 * (l0 - u + hw) - 1.0;
  double acc[W];
  for (int i = 0; i < W; ++i) acc[i] = kp.coeff[D * kMaxKernelWidth + i];
  for (int p = D - 1; p >= 0; --p)
    for (int i = 0; i < W; ++i) acc[i] = acc[i] * x + kp.coeff[p * kMaxKernelWidth + i];
  for (int i = 0; i < W; ++i) out[i] = acc[i];
  return l0;
}

inline int wrap(int l, int n) { return l < 0 ? l + n : (l >= n ? l - n : l); }

inline int first_node(double u, int w) { return static_cast<int>(std::ceil(u - 0.5 * w)); }

}  // namespace

Spreader::Spreader(std::array<int, 3> fine, const KernelSpec& kernel, int threads,
                   int max_subproblem)
    : fine_(fine),
      poly_(fit_kernel_polynomial(kernel)),
      threads_(threads > 0 ? threads : omp_get_max_threads()),
      max_sub_(std::max(1, max_subproblem)) {
  for (int d = 0; d < 3; ++d)
    if (fine_[d] < 2 * kernel.width)
      throw std::invalid_argument("Spreader: fine grid smaller than twice the kernel width");
}

void Spreader::set_points(std::span<const double> x, std::span<const double> y,
                          std::span<const double> z) {
  const std::size_t m = x.size();
  if (y.size() != m || z.size() != m)
    throw std::invalid_argument("Spreader::set_points: x, y, z differ in length");
  std::array<int, 3> nb;
  for (int d = 0; d < 3; ++d) nb[d] = (fine_[d] + kBin[d] - 1) / kBin[d];
  const std::size_t nbins = static_cast<std::size_t>(nb[0]) * nb[1] * nb[2];

  std::vector<double> u[3];
  for (auto& a : u) a.resize(m);
  std::vector<std::int64_t> bin(m);
  const std::span<const double> in[3] = {x, y, z};
  const double inv2pi = 0.5 / std::numbers::pi;
#pragma omp parallel for num_threads(threads_) schedule(static)
  for (std::int64_t j = 0; j < static_cast<std::int64_t>(m); ++j) {
    std::int64_t b = 0;
    for (int d = 2; d >= 0; --d) {
      const double t = in[d][j] * inv2pi;  // periods
      double v = (t - std::floor(t)) * fine_[d];
      if (v >= fine_[d]) v -= fine_[d];
      if (v < 0.0) v += fine_[d];
      if (!(v < fine_[d])) v = 0.0;  // also catches a NaN-free rounding to n
      u[d][j] = v;
      const int bd = std::min(nb[d] - 1, static_cast<int>(v / kBin[d]));
      b = b * nb[d] + bd;
    }
    bin[j] = b;
  }
  // Counting sort by bin (stable).
  std::vector<std::size_t> start(nbins + 1, 0);
  for (std::size_t j = 0; j < m; ++j) ++start[bin[j] + 1];
  for (std::size_t b = 0; b < nbins; ++b) start[b + 1] += start[b];
  order_.resize(m);
  for (std::size_t j = 0; j < m; ++j) order_[start[bin[j]]++] = static_cast<std::int64_t>(j);
  ux_.resize(m);
  uy_.resize(m);
  uz_.resize(m);
  for (std::size_t s = 0; s < m; ++s) {
    ux_[s] = u[0][order_[s]];
    uy_[s] = u[1][order_[s]];
    uz_[s] = u[2][order_[s]];
  }
  sub_begin_.clear();
  for (std::size_t s = 0; s < m; s += static_cast<std::size_t>(max_sub_)) sub_begin_.push_back(s);
  sub_begin_.push_back(m);
}

void Spreader::spread(const double* c, int nc, double* grid) const {
  if (nc != 1 && nc != 2) throw std::invalid_argument("Spreader::spread: nc must be 1 or 2");
  const std::int64_t nsub = static_cast<std::int64_t>(sub_begin_.size()) - 1;
  if (nsub <= 0) return;
  const int w = poly_.spec.width;
  const bool atomic = threads_ > 1 && nsub > 1;
  const int n0 = fine_[0], n1 = fine_[1], n2 = fine_[2];

  // Strengths in sorted order first: the random-access reads then overlap in
  // one simple loop instead of stalling the spreading arithmetic.
  std::vector<double> cs(static_cast<std::size_t>(nc) * order_.size());
  const std::int64_t m = static_cast<std::int64_t>(order_.size());
#pragma omp parallel for num_threads(threads_) schedule(static)
  for (std::int64_t q = 0; q < m; ++q)
    for (int k = 0; k < nc; ++k) cs[nc * q + k] = c[nc * order_[q] + k];

  auto body = [&]<int W, int NC>() {
#pragma omp parallel num_threads(threads_)
    {
      std::vector<double> sub;
      std::vector<int> wx;
#pragma omp for schedule(dynamic, 1)
      for (std::int64_t p = 0; p < nsub; ++p) {
        const std::size_t b = sub_begin_[p], e = sub_begin_[p + 1];
        int lo[3] = {INT_MAX, INT_MAX, INT_MAX}, hi[3] = {INT_MIN, INT_MIN, INT_MIN};
        for (std::size_t s = b; s < e; ++s) {
          const int l[3] = {first_node(ux_[s], W), first_node(uy_[s], W), first_node(uz_[s], W)};
          for (int d = 0; d < 3; ++d) {
            lo[d] = std::min(lo[d], l[d]);
            hi[d] = std::max(hi[d], l[d]);
          }
        }
        const int s0 = hi[0] - lo[0] + W, s1 = hi[1] - lo[1] + W, s2 = hi[2] - lo[2] + W;
        sub.assign(static_cast<std::size_t>(s0) * s1 * s2 * NC, 0.0);
        for (std::size_t s = b; s < e; ++s) {
          double kx[W], ky[W], kz[W];
          const int ox = kernel_at<W>(poly_, ux_[s], kx) - lo[0];
          const int oy = kernel_at<W>(poly_, uy_[s], ky) - lo[1];
          const int oz = kernel_at<W>(poly_, uz_[s], kz) - lo[2];
          const double* cv = cs.data() + NC * s;
          alignas(64) double a[W * NC];
          for (int i = 0; i < W; ++i)
            for (int q = 0; q < NC; ++q) a[i * NC + q] = cv[q] * kx[i];
          for (int dz = 0; dz < W; ++dz) {
            for (int dy = 0; dy < W; ++dy) {
              const double k = kz[dz] * ky[dy];
              double* __restrict row =
                  sub.data() + NC * ((static_cast<std::size_t>(oz + dz) * s1 + oy + dy) * s0 + ox);
#pragma omp simd
              for (int i = 0; i < W * NC; ++i) row[i] += k * a[i];
            }
          }
        }
        // Add the subgrid into the periodic fine grid.
        wx.resize(s0);
        for (int i = 0; i < s0; ++i) wx[i] = ((lo[0] + i) % n0 + n0) % n0;
        for (int zz = 0; zz < s2; ++zz) {
          const int gz = ((lo[2] + zz) % n2 + n2) % n2;
          for (int yy = 0; yy < s1; ++yy) {
            const int gy = ((lo[1] + yy) % n1 + n1) % n1;
            double* grow = grid + NC * ((static_cast<std::size_t>(gz) * n1 + gy) * n0);
            const double* srow = sub.data() + NC * ((static_cast<std::size_t>(zz) * s1 + yy) * s0);
            if (atomic) {
              for (int i = 0; i < s0; ++i)
                for (int q = 0; q < NC; ++q) {
                  const double v = srow[NC * i + q];
                  if (v != 0.0) {
#pragma omp atomic
                    grow[NC * wx[i] + q] += v;
                  }
                }
            } else {
              for (int i = 0; i < s0; ++i)
                for (int q = 0; q < NC; ++q) grow[NC * wx[i] + q] += srow[NC * i + q];
            }
          }
        }
      }
    }
  };
  with_width(w, [&]<int W>() {
    if (nc == 1)
      body.template operator()<W, 1>();
    else
      body.template operator()<W, 2>();
  });
}

void Spreader::interpolate(const double* grid, double* c) const {
  const std::int64_t m = static_cast<std::int64_t>(order_.size());
  if (m == 0) return;
  const int n0 = fine_[0], n1 = fine_[1], n2 = fine_[2];
  with_width(poly_.spec.width, [&]<int W>() {
#pragma omp parallel for num_threads(threads_) schedule(static, 4096)
    for (std::int64_t s = 0; s < m; ++s) {
      double kx[W], ky[W], kz[W];
      int ix[W], iy[W], iz[W];
      const int lx = kernel_at<W>(poly_, ux_[s], kx);
      const int ly = kernel_at<W>(poly_, uy_[s], ky);
      const int lz = kernel_at<W>(poly_, uz_[s], kz);
      for (int i = 0; i < W; ++i) {
        ix[i] = 2 * wrap(lx + i, n0);
        iy[i] = wrap(ly + i, n1);
        iz[i] = wrap(lz + i, n2);
      }
      double re = 0.0, im = 0.0;
      for (int dz = 0; dz < W; ++dz) {
        for (int dy = 0; dy < W; ++dy) {
          const double* row = grid + 2 * ((static_cast<std::size_t>(iz[dz]) * n1 + iy[dy]) * n0);
          double rr = 0.0, ri = 0.0;
          for (int i = 0; i < W; ++i) {
            rr += kx[i] * row[ix[i]];
            ri += kx[i] * row[ix[i] + 1];
          }
          const double k = kz[dz] * ky[dy];
          re += k * rr;
          im += k * ri;
        }
      }
      c[2 * order_[s]] = re;
      c[2 * order_[s] + 1] = im;
    }
  });
}

}  // namespace grains::correlation
