#include "contact/correlation/spreading_kernel.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>
#include <optional>
#include <tuple>
#include <stdexcept>
#include <string>
#include <utility>

#include "contact/correlation/gauss_legendre.hpp"

namespace grains::correlation {

namespace {

// The relative error a kernel may predict: a margin below eps for the
// spread of measured errors about the prediction (docs/nfft.md).
constexpr double kSafety = 0.8;

// Gauss–Legendre nodes on [0, 1] with weights times phi: the Fourier
// transform of psi is w int_0^1 phi(z) cos(pi xi w z) dz (xi = k / n).
struct KernelQuadrature {
  std::vector<double> z, wphi;
  KernelQuadrature(const KernelSpec& spec, const KernelFunction& phi) {
    const int q = 2 * spec.width + 24;
    const QuadratureRule rule = gauss_legendre(q);
    for (int j = 0; j < q; ++j) {
      const double zj = 0.5 * (rule.nodes[j] + 1.0);
      z.push_back(zj);
      wphi.push_back(0.5 * rule.weights[j] * phi(zj));
    }
  }
  // psi_hat at frequency xi (cycles per grid node).
  double transform(int width, double xi) const {
    const double a = std::numbers::pi * xi * width;
    double s = 0.0;
    for (std::size_t j = 0; j < z.size(); ++j) s += wphi[j] * std::cos(a * z[j]);
    return width * s;
  }
};

KernelSpec make_spec(int width, double f, double sigma) {
  KernelSpec s;
  s.width = width;
  s.sigma = sigma;
  s.beta = f * std::numbers::pi * (1.0 - 0.5 / sigma) * width;
  return s;
}

// The kernel of smallest width meeting eps, if any within kMaxKernelWidth.
std::optional<KernelSpec> find_kernel(double eps, double sigma, ErrorModel model) {
  static std::mutex mutex;
  static std::map<std::tuple<double, double, ErrorModel>, std::optional<KernelSpec>> cache;
  const std::lock_guard<std::mutex> lock(mutex);
  const auto key = std::make_tuple(eps, sigma, model);
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  // The aliasing error decays like exp(-pi w sqrt(1 - 1/sigma)); the search
  // starts two nodes below that rate's width, which the measured errors
  // never beat (docs/nfft.md).
  const double rate = std::numbers::pi * std::sqrt(1.0 - 1.0 / sigma);
  const int w0 = std::max(2, static_cast<int>(std::floor(std::log(1.0 / eps) / rate)) - 1);
  std::optional<KernelSpec> found;
  for (int w = w0; w <= kMaxKernelWidth && !found; ++w) {
    double best = std::numeric_limits<double>::infinity();
    KernelSpec best_spec;
    for (double f : {0.97, 0.98, 0.99, 1.0}) {
      const KernelSpec spec = make_spec(w, f, sigma);
      const double e = predicted_error(spec, model);
      if (e < best) {
        best = e;
        best_spec = spec;
      }
    }
    if (best <= kSafety * eps) found = best_spec;
  }
  cache.emplace(key, found);
  return found;
}

}  // namespace

KernelFunction::KernelFunction(const KernelSpec& spec) {
  // psi_0(c, z) = sum_k d_k sqrt(2k + 1/2) P_2k(z), where d is the eigenvector
  // of the smallest eigenvalue of the symmetric tridiagonal matrix of the
  // prolate differential operator in the normalised even Legendre basis. Its
  // coefficients fall off faster than geometrically once 2k exceeds c; K
  // terms with 2K > c + 60 leave them below rounding.
  const double c = spec.beta;
  if (!(c > 0.0 && c < 200.0)) throw std::invalid_argument("KernelFunction: bandwidth out of range");
  const int K = static_cast<int>(c / 2.0) + 32;
  Eigen::VectorXd diag(K), sub(K - 1);
  const double c2 = c * c;
  for (int k = 0; k < K; ++k) {
    const double n = 2.0 * k;
    diag[k] = n * (n + 1.0) + c2 * (2.0 * n * (n + 1.0) - 1.0) / ((2.0 * n + 3.0) * (2.0 * n - 1.0));
    if (k + 1 < K)
      sub[k] = c2 * (n + 2.0) * (n + 1.0) / ((2.0 * n + 3.0) * std::sqrt((2.0 * n + 1.0) * (2.0 * n + 5.0)));
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver;
  solver.computeFromTridiagonal(diag, sub, Eigen::ComputeEigenvectors);
  if (solver.info() != Eigen::Success) throw std::runtime_error("KernelFunction: eigensolver failed");
  coeff_.resize(K);
  for (int k = 0; k < K; ++k) coeff_[k] = solver.eigenvectors()(k, 0) * std::sqrt(2.0 * k + 0.5);
  scale_ = 1.0;
  scale_ = 1.0 / (*this)(0.0);  // also fixes the eigenvector's sign
}

double KernelFunction::operator()(double z) const {
  if (!(z >= -1.0 && z < 1.0)) return 0.0;
  // P_m by the three-term recurrence; even degrees summed.
  double p0 = 1.0, p1 = z, s = coeff_[0];
  const int top = 2 * static_cast<int>(coeff_.size()) - 2;
  for (int m = 1; m < top; ++m) {
    const double p2 = ((2.0 * m + 1.0) * z * p1 - m * p0) / (m + 1.0);
    p0 = p1;
    p1 = p2;
    if ((m + 1) % 2 == 0) s += coeff_[(m + 1) / 2] * p1;
  }
  return s * scale_;
}

bool kernel_feasible(double eps, double sigma, ErrorModel model) {
  return sigma > 1.0 && eps >= 1e-14 && eps <= 1e-1 && find_kernel(eps, sigma, model).has_value();
}

KernelSpec choose_kernel(double eps, double sigma, ErrorModel model) {
  if (!(sigma > 1.0)) throw std::invalid_argument("choose_kernel: upsampling factor must exceed 1");
  if (!(eps >= 1e-14 && eps <= 1e-1))
    throw std::invalid_argument("choose_kernel: tolerance " + std::to_string(eps) +
                                " outside [1e-14, 1e-1]");
  const std::optional<KernelSpec> spec = find_kernel(eps, sigma, model);
  if (!spec)
    throw std::invalid_argument("choose_kernel: tolerance " + std::to_string(eps) +
                                " needs a kernel wider than 16 at upsampling " +
                                std::to_string(sigma) + "; use upsampling 2");
  return *spec;
}

std::vector<double> kernel_fourier_series(const KernelSpec& spec, int n, int kmax) {
  const KernelFunction phi(spec);
  const KernelQuadrature quad(spec, phi);
  std::vector<double> out(kmax + 1);
  for (int k = 0; k <= kmax; ++k) out[k] = quad.transform(spec.width, static_cast<double>(k) / n);
  return out;
}

double predicted_error(const KernelSpec& spec, ErrorModel model) {
  const KernelFunction phi(spec);
  const KernelQuadrature quad(spec, phi);
  const int w = spec.width;
  // Frequencies |xi| = j / J of the band edge, j = 0 .. J, equally weighted:
  // the modes of a transform with N = 16 per dimension, whose edge mode
  // k = -N/2 (where the error peaks) weighs 1/16; larger N weigh it less,
  // so the prediction errs on the safe side. Offsets: midpoint rule.
  constexpr int J = 16, X = 64;
  // psi(x - l) for the X offsets and the nodes l = -w .. w.
  const int L = 2 * w + 1;
  std::vector<double> psi(static_cast<std::size_t>(X) * L);
  for (int i = 0; i < X; ++i)
    for (int l = -w; l <= w; ++l) psi[i * L + (l + w)] = phi(2.0 * ((i + 0.5) / X - l) / w);
  const double band = 0.5 / spec.sigma;
  double sum = 0.0;
  for (int j = 0; j <= J; ++j) {
    const double xi = static_cast<double>(j) / J * band;  // |e| is even in xi
    const double ph = quad.transform(w, xi);
    double mean = 0.0, worst = 0.0;
    for (int i = 0; i < X; ++i) {
      const double x = (i + 0.5) / X;
      std::complex<double> s = 0.0;
      for (int l = -w; l <= w; ++l) {
        const double p = psi[i * L + (l + w)];
        if (p != 0.0) s += p * std::polar(1.0, -2.0 * std::numbers::pi * xi * (x - l));
      }
      const double e2 = std::norm(s / ph - 1.0);
      mean += e2 / X;
      worst = std::max(worst, e2);
    }
    sum += model == ErrorModel::worst_offset ? worst : mean;
  }
  // The errors of the three dimensions add in square for offsets spread out;
  // a point at the same bad offset in all three can see them add in
  // amplitude: |e1 + e2 + e3|^2 <= 3 (|e1|^2 + |e2|^2 + |e3|^2).
  const double dims = model == ErrorModel::worst_offset ? 9.0 : 3.0;
  return std::sqrt(dims * sum / (J + 1));
}

KernelPolynomial fit_kernel_polynomial(const KernelSpec& spec) {
  KernelPolynomial kp;
  kp.spec = spec;
  kp.degree = std::min(kMaxKernelDegree, spec.width + 1);
  const int d = kp.degree;
  const int m = d + 1;
  const int w = spec.width;
  const KernelFunction phi(spec);
  // Interpolate at m Chebyshev nodes x_j in [-1, 1]: solve the Vandermonde
  // system in long double (degree <= 19, condition ~ 1e8, fine in 64-bit mantissa).
  std::vector<long double> xs(m);
  for (int j = 0; j < m; ++j) xs[j] = std::cos(std::numbers::pi_v<long double> * (j + 0.5L) / m);
  for (int i = 0; i < w; ++i) {
    std::vector<long double> a(m * m), b(m);
    for (int j = 0; j < m; ++j) {
      const long double v = 0.5L * (xs[j] + 1.0L);
      const long double t = v - 0.5L * w + i;  // offset of node i from the point
      b[j] = phi(static_cast<double>(2.0L * t / w));
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
