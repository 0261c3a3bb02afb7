#pragma once
// Small RAII helpers around FFTW3: aligned buffers, plans destroyed with their
// owner, a process-wide mutex for the (non-thread-safe) planner, and the
// one-time initialisation of FFTW's OpenMP threads.
#include <fftw3.h>

#include <array>
#include <cstddef>
#include <mutex>

namespace grains::correlation {

// The FFTW planner is not re-entrant: every plan creation/destruction holds it.
std::mutex& fftw_planner_mutex();

// Calls fftw_init_threads() once per process.
void fftw_threads_init_once();

// Aligned array of doubles (huge pages when large: huge_pages.hpp),
// zero-initialised.
class FftwBuffer {
 public:
  FftwBuffer() = default;
  explicit FftwBuffer(std::size_t n_doubles);
  ~FftwBuffer();
  FftwBuffer(const FftwBuffer&) = delete;
  FftwBuffer& operator=(const FftwBuffer&) = delete;
  FftwBuffer(FftwBuffer&& o) noexcept;
  FftwBuffer& operator=(FftwBuffer&& o) noexcept;

  double* data() { return p_; }
  const double* data() const { return p_; }
  fftw_complex* as_complex() { return reinterpret_cast<fftw_complex*>(p_); }
  std::size_t size() const { return n_; }
  void zero();

 private:
  double* p_ = nullptr;
  std::size_t n_ = 0;
};

// Owning handle of an fftw_plan.
class FftwPlan {
 public:
  FftwPlan() = default;
  explicit FftwPlan(fftw_plan p) : p_(p) {}
  ~FftwPlan();
  FftwPlan(const FftwPlan&) = delete;
  FftwPlan& operator=(const FftwPlan&) = delete;
  FftwPlan(FftwPlan&& o) noexcept : p_(o.p_) { o.p_ = nullptr; }
  FftwPlan& operator=(FftwPlan&& o) noexcept;
  explicit operator bool() const { return p_ != nullptr; }
  void execute() const { fftw_execute(p_); }
  void execute_dft(fftw_complex* in, fftw_complex* out) const { fftw_execute_dft(p_, in, out); }
  fftw_plan get() const { return p_; }

 private:
  fftw_plan p_ = nullptr;
};

// In-place complex 3D DFT on an x-fastest grid n[0] x n[1] x n[2] with the
// given exponent sign (-1: FFTW_FORWARD, +1: FFTW_BACKWARD).
FftwPlan plan_c2c_3d(std::array<int, 3> n, fftw_complex* data, int sign, int threads,
                     unsigned flags);

// Smallest even size >= n whose only prime factors are 2, 3 and 5.
int next_fft_size(int n);

}  // namespace grains::correlation
