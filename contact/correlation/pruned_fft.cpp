#include "contact/correlation/pruned_fft.hpp"

#include <omp.h>

#include <algorithm>
#include <cstddef>
#include <mutex>
#include <stdexcept>

namespace grains::correlation {

namespace {

// Fine-grid indices of the modes k = -floor(N/2) .. ceil(N/2) - 1.
std::vector<int> needed(int modes, int n) {
  std::vector<int> out;
  for (int i = 0; i < modes; ++i) out.push_back(((i - modes / 2) % n + n) % n);
  std::sort(out.begin(), out.end());
  return out;
}

constexpr int kBlock = 8;  // lines moved together by the blocked transposes

// buf[c * len + r] = base[r * stride + cols[c]] for r < len, c < ncols.
void gather(const std::complex<double>* base, std::size_t stride, int len, const std::vector<int>& cols,
            std::complex<double>* buf) {
  const int ncols = static_cast<int>(cols.size());
  for (int r0 = 0; r0 < len; r0 += kBlock) {
    const int r1 = std::min(len, r0 + kBlock);
    for (int c = 0; c < ncols; ++c) {
      const std::complex<double>* src = base + cols[c];
      std::complex<double>* dst = buf + static_cast<std::size_t>(c) * len;
      for (int r = r0; r < r1; ++r) dst[r] = src[r * stride];
    }
  }
}

// The inverse move: base[r * stride + cols[c]] = buf[c * len + r].
void scatter(const std::complex<double>* buf, std::size_t stride, int len, const std::vector<int>& cols,
             std::complex<double>* base) {
  const int ncols = static_cast<int>(cols.size());
  for (int r0 = 0; r0 < len; r0 += kBlock) {
    const int r1 = std::min(len, r0 + kBlock);
    for (int c = 0; c < ncols; ++c) {
      std::complex<double>* dst = base + cols[c];
      const std::complex<double>* src = buf + static_cast<std::size_t>(c) * len;
      for (int r = r0; r < r1; ++r) dst[r * stride] = src[r];
    }
  }
}

// howmany contiguous lines of length len, dist apart.
fftw_plan plan_lines(int len, int howmany, int dist, fftw_complex* data, int sign, unsigned flags) {
  fftw_plan p = fftw_plan_many_dft(1, &len, howmany, data, nullptr, 1, dist, data, nullptr, 1, dist, sign, flags);
  if (!p) throw std::runtime_error("FFTW could not create a plan");
  return p;
}

// The y-stage: in every plane of a complex grid (rows `pitch` cells apart),
// the lines along y of the columns xs, through each thread's buffer.
void lines_along_y(std::complex<double>* g, std::array<int, 3> n, std::size_t pitch, const std::vector<int>& xs,
                   const FftwPlan& p, std::vector<FftwBuffer>& buf, int threads) {
  const std::size_t plane = pitch * n[1];
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int z = 0; z < n[2]; ++z) {
    FftwBuffer& b = buf[omp_get_thread_num()];
    auto* bc = reinterpret_cast<std::complex<double>*>(b.data());
    gather(g + z * plane, pitch, n[1], xs, bc);
    p.execute_dft(b.as_complex(), b.as_complex());
    scatter(bc, pitch, n[1], xs, g + z * plane);
  }
}

// The z-stage: the lines along z of the columns (xs, ys).
void lines_along_z(std::complex<double>* g, std::array<int, 3> n, std::size_t pitch, const std::vector<int>& xs,
                   const std::vector<int>& ys, const FftwPlan& p, std::vector<FftwBuffer>& buf, int threads) {
  const std::size_t plane = pitch * n[1];
  const int ny = static_cast<int>(ys.size());
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int j = 0; j < ny; ++j) {
    FftwBuffer& b = buf[omp_get_thread_num()];
    auto* bc = reinterpret_cast<std::complex<double>*>(b.data());
    std::complex<double>* base = g + static_cast<std::size_t>(ys[j]) * pitch;
    gather(base, plane, n[2], xs, bc);
    p.execute_dft(b.as_complex(), b.as_complex());
    scatter(bc, plane, n[2], xs, base);
  }
}

}  // namespace

PrunedFft3d::PrunedFft3d(std::array<int, 3> fine, std::array<int, 3> modes, int pitch, fftw_complex* grid,
                         int threads, unsigned flags)
    : n_(fine), modes_(modes), pitch_(pitch), threads_(std::max(1, threads)) {
  if (pitch_ < n_[0]) throw std::invalid_argument("PrunedFft3d: row pitch shorter than a row");
  for (int d = 0; d < 3; ++d)
    if (modes_[d] < 1 || modes_[d] > n_[d]) throw std::invalid_argument("PrunedFft3d: need 1 <= N_d <= n_d");
  xs_ = needed(modes_[0], n_[0]);
  ys_ = needed(modes_[1], n_[1]);
  const int lines = modes_[0];
  const std::size_t buf_len = 2 * static_cast<std::size_t>(lines) * std::max(n_[1], n_[2]);
  for (int t = 0; t < threads_; ++t) buf_.emplace_back(buf_len);
  fftw_threads_init_once();
  std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  fftw_plan_with_nthreads(1);  // the stages are parallel over planes
  for (int s = 0; s < 2; ++s) {
    const int sign = s == 0 ? FFTW_FORWARD : FFTW_BACKWARD;
    px_[s] = FftwPlan(plan_lines(n_[0], n_[1], pitch_, grid, sign, flags));
    py_[s] = FftwPlan(plan_lines(n_[1], lines, n_[1], buf_[0].as_complex(), sign, flags));
    pz_[s] = FftwPlan(plan_lines(n_[2], lines, n_[2], buf_[0].as_complex(), sign, flags));
  }
}

void PrunedFft3d::stage_x(Complex* g, int sign) {
  const FftwPlan& p = px_[sign < 0 ? 0 : 1];
  const std::size_t plane = static_cast<std::size_t>(pitch_) * n_[1];
#pragma omp parallel for num_threads(threads_) schedule(static)
  for (int z = 0; z < n_[2]; ++z) {
    auto* a = reinterpret_cast<fftw_complex*>(g + z * plane);
    p.execute_dft(a, a);
  }
}

void PrunedFft3d::stage_y(Complex* g, int sign) {
  lines_along_y(g, n_, static_cast<std::size_t>(pitch_), xs_, py_[sign < 0 ? 0 : 1], buf_, threads_);
}

void PrunedFft3d::stage_z(Complex* g, int sign) {
  lines_along_z(g, n_, static_cast<std::size_t>(pitch_), xs_, ys_, pz_[sign < 0 ? 0 : 1], buf_, threads_);
}

void PrunedFft3d::forward_pruned(fftw_complex* grid, int sign) {
  Complex* g = reinterpret_cast<Complex*>(grid);
  stage_x(g, sign);
  stage_y(g, sign);
  stage_z(g, sign);
}

void PrunedFft3d::backward_pruned(fftw_complex* grid, int sign) {
  Complex* g = reinterpret_cast<Complex*>(grid);
  stage_z(g, sign);
  stage_y(g, sign);
  stage_x(g, sign);
}

PrunedRealFft3d::PrunedRealFft3d(std::array<int, 3> n, std::array<int, 3> K, double* data, int threads,
                                 unsigned flags)
    : n_(n), h0_(n[0] / 2 + 1), threads_(std::max(1, threads)) {
  for (int d = 0; d < 3; ++d)
    if (n_[d] < 1 || K[d] < 0) throw std::invalid_argument("PrunedRealFft3d: need n_d >= 1 and K_d >= 0");
  for (int i = 0; i <= std::min(K[0], h0_ - 1); ++i) xs_.push_back(i);
  ys_ = needed(static_cast<int>(std::min<long>(2L * K[1] + 1, n_[1])), n_[1]);  // |m1| <= K1, or every row
  const int lines = static_cast<int>(xs_.size());
  const std::size_t buf_len = 2 * static_cast<std::size_t>(lines) * std::max(n_[1], n_[2]);
  for (int t = 0; t < threads_; ++t) buf_.emplace_back(buf_len);
  fftw_threads_init_once();
  std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  fftw_plan_with_nthreads(1);  // the stages are parallel over planes
  // x: the n1 rows of one plane, in place (real rows 2 h0 doubles apart).
  int len = n_[0];
  auto* cdata = reinterpret_cast<fftw_complex*>(data);
  fftw_plan r = fftw_plan_many_dft_r2c(1, &len, n_[1], data, nullptr, 1, 2 * h0_, cdata, nullptr, 1, h0_, flags);
  fftw_plan c = fftw_plan_many_dft_c2r(1, &len, n_[1], cdata, nullptr, 1, h0_, data, nullptr, 1, 2 * h0_, flags);
  if (!r || !c) throw std::runtime_error("FFTW could not create a plan");
  rx_ = FftwPlan(r);
  cx_ = FftwPlan(c);
  for (int s = 0; s < 2; ++s) {
    const int sign = s == 0 ? FFTW_FORWARD : FFTW_BACKWARD;
    py_[s] = FftwPlan(plan_lines(n_[1], lines, n_[1], buf_[0].as_complex(), sign, flags));
    pz_[s] = FftwPlan(plan_lines(n_[2], lines, n_[2], buf_[0].as_complex(), sign, flags));
  }
}

void PrunedRealFft3d::stage_y(Complex* g, int s) {
  lines_along_y(g, n_, static_cast<std::size_t>(h0_), xs_, py_[s], buf_, threads_);
}

void PrunedRealFft3d::stage_z(Complex* g, int s) {
  lines_along_z(g, n_, static_cast<std::size_t>(h0_), xs_, ys_, pz_[s], buf_, threads_);
}

void PrunedRealFft3d::forward(double* data) {
  const std::size_t plane = 2 * static_cast<std::size_t>(h0_) * n_[1];
#pragma omp parallel for num_threads(threads_) schedule(static)
  for (int z = 0; z < n_[2]; ++z)
    fftw_execute_dft_r2c(rx_.get(), data + z * plane, reinterpret_cast<fftw_complex*>(data + z * plane));
  Complex* g = reinterpret_cast<Complex*>(data);
  stage_y(g, 0);
  stage_z(g, 0);
}

void PrunedRealFft3d::backward(double* data) {
  Complex* g = reinterpret_cast<Complex*>(data);
  stage_z(g, 1);
  stage_y(g, 1);
  const std::size_t plane = 2 * static_cast<std::size_t>(h0_) * n_[1];
#pragma omp parallel for num_threads(threads_) schedule(static)
  for (int z = 0; z < n_[2]; ++z)
    fftw_execute_dft_c2r(cx_.get(), reinterpret_cast<fftw_complex*>(data + z * plane), data + z * plane);
}

}  // namespace grains::correlation
