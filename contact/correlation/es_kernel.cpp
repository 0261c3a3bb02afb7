#include "contact/correlation/es_kernel.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "contact/correlation/gauss_legendre.hpp"

namespace grains::correlation {

namespace {

int width_for(double eps, double sigma) {
  // One node of headroom at sigma = 2; two below it, where the measured
  // error sits further above the asymptotic rate (docs/nfft.md).
  const double rate = std::numbers::pi * std::sqrt(1.0 - 1.0 / sigma);
  return static_cast<int>(std::ceil(std::log(1.0 / eps) / rate)) + (sigma < 2.0 ? 2 : 1);
}

}  // namespace

bool kernel_feasible(double eps, double sigma) {
  return sigma > 1.0 && eps > 0.0 && width_for(eps, sigma) <= kMaxKernelWidth;
}

KernelSpec choose_kernel(double eps, double sigma) {
  if (!(sigma > 1.0)) throw std::invalid_argument("choose_kernel: upsampling factor must exceed 1");
  if (!(eps >= 1e-14 && eps <= 1e-1))
    throw std::invalid_argument("choose_kernel: tolerance " + std::to_string(eps) +
                                " outside [1e-14, 1e-1]");
  KernelSpec s;
  s.sigma = sigma;
  s.width = std::max(2, width_for(eps, sigma));
  if (s.width > kMaxKernelWidth)
    throw std::invalid_argument("choose_kernel: tolerance " + std::to_string(eps) +
                                " needs a kernel wider than 16 at upsampling " +
                                std::to_string(sigma) + "; use upsampling 2");
  s.beta = 0.98 * std::numbers::pi * (1.0 - 0.5 / sigma) * s.width;
  return s;
}

double es_kernel(double z, double beta) {
  if (std::abs(z) >= 1.0) return 0.0;
  return std::exp(beta * (std::sqrt(1.0 - z * z) - 1.0));
}

std::vector<double> kernel_fourier_series(const KernelSpec& spec, int n, int kmax) {
  // psi_hat(k) = (w/2) int_{-1}^{1} phi(z) cos(2 pi k (w/2) z / n) dz
  //            = w int_0^1 phi(z) cos(pi k w z / n) dz.
  const int q = 2 * spec.width + 24;
  const QuadratureRule rule = gauss_legendre(q);
  std::vector<double> zq, wq;  // nodes mapped to [0, 1]
  for (int j = 0; j < q; ++j) {
    zq.push_back(0.5 * (rule.nodes[j] + 1.0));
    wq.push_back(0.5 * rule.weights[j] * es_kernel(0.5 * (rule.nodes[j] + 1.0), spec.beta));
  }
  std::vector<double> out(kmax + 1);
  const double a = std::numbers::pi * spec.width / n;
  for (int k = 0; k <= kmax; ++k) {
    double s = 0.0;
    for (int j = 0; j < q; ++j) s += wq[j] * std::cos(a * k * zq[j]);
    out[k] = spec.width * s;
  }
  return out;
}

KernelPolynomial fit_kernel_polynomial(const KernelSpec& spec) {
  KernelPolynomial kp;
  kp.spec = spec;
  kp.degree = std::min(kMaxKernelDegree, spec.width + 1);
  const int d = kp.degree;
  const int m = d + 1;
  const int w = spec.width;
  // Interpolate at m Chebyshev nodes x_j in [-1, 1]: solve the Vandermonde
  // system in long double (degree <= 19, condition ~ 1e8, fine in 64-bit mantissa).
  std::vector<long double> xs(m);
  for (int j = 0; j < m; ++j) xs[j] = std::cos(std::numbers::pi_v<long double> * (j + 0.5L) / m);
  for (int i = 0; i < w; ++i) {
    std::vector<long double> a(m * m), b(m);
    for (int j = 0; j < m; ++j) {
      const long double v = 0.5L * (xs[j] + 1.0L);
      const long double t = v - 0.5L * w + i;  // offset of node i from the point
      const long double z = 2.0L * t / w;
      b[j] = std::abs(z) >= 1.0L ? 0.0L : std::exp(spec.beta * (std::sqrt(1.0L - z * z) - 1.0L));
      long double p = 1.0L;
      for (int c = 0; c < m; ++c) {
        a[j * m + c] = p;
        p *= xs[j];
      }
    }
    // Gaussian elimination with partial pivoting.
    for (int c = 0; c < m; ++c) {
      int piv = c;
      for (int r = c + 1; r < m; ++r)
        if (std::abs(a[r * m + c]) > std::abs(a[piv * m + c])) piv = r;
      if (piv != c) {
        for (int k = 0; k < m; ++k) std::swap(a[c * m + k], a[piv * m + k]);
        std::swap(b[c], b[piv]);
      }
      for (int r = c + 1; r < m; ++r) {
        const long double f = a[r * m + c] / a[c * m + c];
        for (int k = c; k < m; ++k) a[r * m + k] -= f * a[c * m + k];
        b[r] -= f * b[c];
      }
    }
    for (int c = m - 1; c >= 0; --c) {
      long double s = b[c];
      for (int k = c + 1; k < m; ++k) s -= a[c * m + k] * b[k];
      b[c] = s / a[c * m + c];
    }
    for (int p = 0; p < m; ++p) kp.coeff[p * kMaxKernelWidth + i] = static_cast<double>(b[p]);
  }
  return kp;
}

void eval_kernel_polynomial(const KernelPolynomial& kp, double v, double* out) {
  const double x = 2.0 * v - 1.0;
  const int w = kp.spec.width;
  for (int i = 0; i < w; ++i) out[i] = kp.coeff[kp.degree * kMaxKernelWidth + i];
  for (int p = kp.degree - 1; p >= 0; --p)
    for (int i = 0; i < w; ++i) out[i] = out[i] * x + kp.coeff[p * kMaxKernelWidth + i];
}

}  // namespace grains::correlation
