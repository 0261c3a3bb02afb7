#include "contact/correlation/fftw_util.hpp"

#include "contact/correlation/huge_pages.hpp"

#include <cstring>
#include <new>
#include <stdexcept>

namespace grains::correlation {

std::mutex& fftw_planner_mutex() {
  static std::mutex m;
  return m;
}

void fftw_threads_init_once() {
  static std::once_flag flag;
  std::call_once(flag, [] {
    if (fftw_init_threads() == 0) throw std::runtime_error("fftw_init_threads failed");
  });
}

FftwBuffer::FftwBuffer(std::size_t n_doubles) : n_(n_doubles) {
  if (n_ == 0) return;
  p_ = static_cast<double*>(allocate_large(n_ * sizeof(double)));  // FFTW needs 16/32-byte alignment: 64 or more
  zero();
}

FftwBuffer::~FftwBuffer() {
  free_large(p_);
}

FftwBuffer::FftwBuffer(FftwBuffer&& o) noexcept : p_(o.p_), n_(o.n_) {
  o.p_ = nullptr;
  o.n_ = 0;
}

FftwBuffer& FftwBuffer::operator=(FftwBuffer&& o) noexcept {
  if (this != &o) {
    free_large(p_);
    p_ = o.p_;
    n_ = o.n_;
    o.p_ = nullptr;
    o.n_ = 0;
  }
  return *this;
}

void FftwBuffer::zero() {
  if (p_) std::memset(p_, 0, n_ * sizeof(double));
}

FftwPlan::~FftwPlan() {
  if (p_) {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    fftw_destroy_plan(p_);
  }
}

FftwPlan& FftwPlan::operator=(FftwPlan&& o) noexcept {
  if (this != &o) {
    if (p_) {
      std::lock_guard<std::mutex> lock(fftw_planner_mutex());
      fftw_destroy_plan(p_);
    }
    p_ = o.p_;
    o.p_ = nullptr;
  }
  return *this;
}

namespace {
void check(fftw_plan p) {
  if (!p) throw std::runtime_error("FFTW could not create a plan");
}
}  // namespace

FftwPlan plan_c2c_3d(std::array<int, 3> n, fftw_complex* data, int sign, int threads,
                     unsigned flags) {
  fftw_threads_init_once();
  std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  fftw_plan_with_nthreads(threads);
  // FFTW is row-major: the last index is the fastest, so pass (z, y, x).
  fftw_plan p = fftw_plan_dft_3d(n[2], n[1], n[0], data, data, sign, flags);
  check(p);
  return FftwPlan(p);
}

int next_fft_size(int n) {
  if (n <= 2) return 2;
  for (int m = n + (n & 1);; m += 2) {
    int r = m;
    for (int p : {2, 3, 5})
      while (r % p == 0) r /= p;
    if (r == 1) return m;
  }
}

}  // namespace grains::correlation
