// The ARKODE driver (sim/integrate/arkode.hpp; docs/integrators.md).
#include "sim/integrate/arkode.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <limits>
#include <memory>
#include <sstream>

#if GRAINS_HAVE_MPI
#include <mpi.h>
#endif

#if GRAINS_HAVE_SUNDIALS
#include <omp.h>

#include <arkode/arkode_erkstep.h>
#include <nvector/nvector_openmp.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

#include "contact/ellipsoid/ellipsoid.hpp"
#include "sim/integrate/clump_bodies.hpp"
#include "sim/parallel/exchange.hpp"
#endif

namespace grains::sim {

namespace {

void refuse_several_ranks(const std::string& where) {
#if GRAINS_HAVE_MPI
  int initialised = 0, finalised = 0;
  MPI_Initialized(&initialised);
  MPI_Finalized(&finalised);
  if (!initialised || finalised) return;
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size > 1)
    throw SetupError(where + ": integrator: arkode runs on one MPI rank (serial, or OpenMP threads: set "
                             "OMP_NUM_THREADS), but this run has " +
                     std::to_string(size) +
                     " ranks. Run it without mpirun, or use integrator: verlet for domain decomposition");
#else
  (void)where;
#endif
}

}  // namespace

#if GRAINS_HAVE_SUNDIALS

namespace {

inline Vec3 get3(const double* a) { return Vec3(a[0], a[1], a[2]); }
inline void put3(double* a, const Vec3& v) {
  a[0] = v.x();
  a[1] = v.y();
  a[2] = v.z();
}
// Quaternions in y as (w, x, y, z).
inline Quat get_quat(const double* a) { return Quat(a[0], a[1], a[2], a[3]); }
inline void put_quat(double* a, const Quat& q) {
  a[0] = q.w();
  a[1] = q.x();
  a[2] = q.y();
  a[3] = q.z();
}
// dq/dt = 1/2 (0, w) q for the world-frame angular velocity w (q unnormalised, as in y).
inline void put_quat_rate(double* d, const Vec3& w, const double* q) {
  const Vec3 qv(q[1], q[2], q[3]);
  d[0] = -0.5 * w.dot(qv);
  const Vec3 r = 0.5 * (q[0] * w + w.cross(qv));
  d[1] = r.x();
  d[2] = r.y();
  d[3] = r.z();
}

constexpr int kBodyWidth = 13;  // x, v, q, L
// OpenMP only pays off for large states: below these sizes the loops and the
// SUNDIALS vector operations run serially (a parallel region per vector
// operation costs more than a small vector's work, and far more when the
// cores are shared with other processes).
constexpr std::size_t kThreadedAbove = 4096;          // free particles
constexpr std::size_t kThreadedVectorAbove = 100000;  // entries of y

// Error norm: the largest weighted component (ARKODE's default is the RMS
// over all components, which lets one colliding pair hide among many quiet
// particles).
realtype max_weighted_norm(N_Vector x, N_Vector w) {
  const double* a = N_VGetArrayPointer(x);
  const double* b = N_VGetArrayPointer(w);
  const sunindextype n = N_VGetLength(x);
  double m = 0;
  for (sunindextype i = 0; i < n; ++i) m = std::max(m, std::abs(a[i] * b[i]));
  return m;
}

class ErkDriver final : public ArkodeIntegrator {
 public:
  ErkDriver(const ArkodeConfig& c, const ArkodeLayout& l, const ArkodeScales& sc) : cfg_(c), lay_(l), scales_(sc) {
    if (SUNContext_Create(nullptr, &ctx_) != 0) throw std::runtime_error("SUNDIALS: cannot create a context");
    threads_ = omp_get_max_threads();
    width_ = 6 + (lay_.rigid ? 7 : lay_.rotation ? 3 : 0);
    H_ = lay_.tangential_history + lay_.rolling_history;
  }
  ~ErkDriver() override {
    free_solver();
    if (ctx_) SUNContext_Free(&ctx_);
  }
  ErkDriver(const ErkDriver&) = delete;
  ErkDriver& operator=(const ErkDriver&) = delete;

  std::string name() const override {
    std::ostringstream o;
    o << "arkode.erk(order " << cfg_.order << ", rtol " << cfg_.rtol << ", atol " << cfg_.atol << "; steps <= dt"
      << (H_ > 0 ? ", contact history in the ODE state" : "") << (lay_.rigid || lay_.clumps ? ", |q| projected" : "")
      << ")";
    return o.str();
  }
  Phase phase() const override { return Phase::Drift; }
  void run(Scene&) override {
    throw std::logic_error("the ARKODE driver evaluates the force phase itself: it runs through Pipeline::step");
  }
  bool is_driver() const override { return true; }
  void drive(Scene& s, Pipeline& p) override;
  const ArkodeStats& stats() const override { return stats_; }
  std::string summary_json() const override {
    std::ostringstream o;
    o.precision(10);
    o << "\"accepted_steps\": " << stats_.steps << ", \"rejected_steps\": " << stats_.error_test_failures
      << ", \"rhs_evaluations\": " << stats_.rhs_evaluations
      << ", \"projection_evaluations\": " << stats_.projection_evaluations
      << ", \"end_evaluations\": " << stats_.end_evaluations << ", \"repacks\": " << stats_.repacks
      << ", \"lookahead_rebuilds\": " << stats_.lookahead_rebuilds << ", \"min_step_s\": " << stats_.min_step
      << ", \"max_step_s\": " << stats_.max_step << ", \"state_length\": " << n_state_;
    return o.str();
  }

 private:
  // ---- SUNDIALS callbacks ----
  static int rhs_callback(realtype t, N_Vector y, N_Vector ydot, void* self) {
    auto* d = static_cast<ErkDriver*>(self);
    try {
      return d->rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
    } catch (...) {
      d->pending_ = std::current_exception();
      return -1;
    }
  }
  static void error_callback(int code, const char* module, const char* function, char* msg, void* self) {
    auto* d = static_cast<ErkDriver*>(self);
    std::ostringstream o;
    o << module << "::" << function << " (" << code << "): " << msg;
    d->message_ = o.str();
  }

  N_Vector new_vector(std::size_t n) const {
    const auto len = static_cast<sunindextype>(n);
    N_Vector v = threads_ > 1 && n > kThreadedVectorAbove ? N_VNew_OpenMP(len, threads_, ctx_)
                                                           : N_VNew_Serial(len, ctx_);
    if (!v) throw std::runtime_error("SUNDIALS: cannot allocate a vector of " + std::to_string(n));
    // Fused operations: one pass over memory for each linear combination of
    // stages (without them SUNDIALS loops scale-and-add over the vectors).
    if (threads_ > 1 && n > kThreadedVectorAbove)
      N_VEnableFusedOps_OpenMP(v, SUNTRUE);
    else
      N_VEnableFusedOps_Serial(v, SUNTRUE);
    v->ops->nvwrmsnorm = max_weighted_norm;  // clones (ARKODE's own vectors) inherit it
    return v;
  }
  void free_vectors() {
    for (N_Vector* v : {&y_, &atol_})
      if (*v) {
        N_VDestroy(*v);
        *v = nullptr;
      }
  }
  void free_solver() {
    if (mem_) ERKStepFree(&mem_);
    mem_ = nullptr;
    free_vectors();
  }
  void check(int flag, const char* what) const {
    if (flag < 0) throw std::runtime_error(std::string("SUNDIALS: ") + what + " failed: " + message_);
  }

  int rhs(double t, const double* y, double* ydot);
  void evaluate(double t, const double* y);
  void unpack(const double* y);
  bool derivatives(const double* y, double* ydot) const;
  void pack();
  void place_walls(double t);
  double neighbours(double stop);
  void run_neighbor_phase();
  void refresh_build();
  int take_step(double stop);
  void project(double* y);

  // Offsets of the parts of y.
  std::size_t bodies_offset() const { return free_.size() * static_cast<std::size_t>(width_); }
  std::size_t pairs_offset() const { return bodies_offset() + bodies_ * kBodyWidth; }
  std::size_t walls_offset() const { return pairs_offset() + pairs_ * static_cast<std::size_t>(H_); }
  // The wall-history slots in y: offsets into ParticleStore::wall_history of
  // [state | rate] for the particles in each wall's near list (the only
  // slots the wall stages read or write).
  std::vector<std::size_t> wall_entry_;

  ArkodeConfig cfg_;
  ArkodeLayout lay_;
  ArkodeScales scales_;
  SUNContext ctx_ = nullptr;
  void* mem_ = nullptr;
  N_Vector y_ = nullptr, atol_ = nullptr;
  int threads_ = 1;
  int width_ = 6;            // doubles per free particle
  int H_ = 0;                // history state per contact (tangential + rolling)
  std::size_t n_state_ = 0;  // length of y
  std::vector<std::size_t> free_;  // owned particles in y (not clump balls), in order
  std::size_t bodies_ = 0;         // clumps in y, after the free particles
  std::size_t pairs_ = 0;          // neighbour-list entries in y (H_ doubles each), after the bodies
  std::vector<Vec3> x_ref_, body_ref_;  // positions at the last pack: y holds x - x_ref
  long packed_builds_ = -1;             // neighbour build count at the last pack
  // Neighbour look-ahead: positions and time of the last build.
  long cached_builds_ = -1;
  std::vector<Vec3> x_build_;
  double build_time_ = 0;
  // Walls move with prescribed velocities: positions at time t are the
  // reference advanced by t - walls_t0_.
  bool ready_ = false, walls_move_ = false;
  Walls walls_ref_;
  double walls_t0_ = 0;
  double t_ = 0, dt_ = 0;  // time of y_; the clock's step
  double last_step_ = 0;   // the last accepted step
  // Valid during drive().
  Scene* scene_ = nullptr;
  Pipeline* pipe_ = nullptr;
  std::exception_ptr pending_;
  std::string message_;
  ArkodeStats stats_;
};

void ErkDriver::place_walls(double t) {
  if (!walls_move_) return;
  scene_->walls = walls_ref_;
  scene_->walls.advance(t - walls_t0_);
}

void ErkDriver::unpack(const double* y) {
  auto& p = scene_->particles;
  const std::size_t n = free_.size();
  const int w = width_;
#pragma omp parallel for schedule(static) if (n > kThreadedAbove)
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = free_[k];
    const double* yk = y + k * static_cast<std::size_t>(w);
    p.x[i] = x_ref_[k] + get3(yk);
    p.v[i] = get3(yk + 3);
    if (lay_.rigid) {
      const Quat q = get_quat(yk + 6).normalized();
      const Vec3 L = get3(yk + 10);
      const Eigen::Matrix3d R = q.toRotationMatrix();
      p.orientation[i] = q;
      p.angular_momentum[i] = L;
      p.omega[i] = R * (R.transpose() * L).cwiseQuotient(p.inertia[i]);
      if (p.shape[i] == kEllipsoid) p.form[i] = contact::quadratic_form(p.semi_axes[i], R);
    } else if (lay_.rotation) {
      p.omega[i] = get3(yk + 6);
    }
  }
  if (lay_.clumps) {
    auto& b = scene_->bodies;
    const double* yb = y + bodies_offset();
    for (std::size_t k = 0; k < bodies_; ++k, yb += kBodyWidth) {
      b.x[k] = body_ref_[k] + get3(yb);
      b.v[k] = get3(yb + 3);
      b.orientation[k] = get_quat(yb + 6).normalized();
      b.angular_momentum[k] = get3(yb + 10);
      b.omega[k] = angular_velocity(b.orientation[k], b.inertia[k], b.angular_momentum[k]);
    }
    place_clump_balls(p, b, true);
  }
  // Periodic images follow their particles.
  if (scene_->exchange) scene_->exchange->update_ghosts(p, scene_->clock.time);
  if (H_ == 0) return;
  // The springs of this state; rates are written by the laws of touching
  // contacts only, so they start at zero. Every entry may touch: a separated
  // pair's spring must be zeroed by its stage.
  auto& nl = scene_->neighbors;
  const std::size_t S = static_cast<std::size_t>(nl.history_size());
  const double* yp = y + pairs_offset();
  for (std::size_t k = 0; k < pairs_; ++k) {
    double* h = nl.history.data() + k * S;
    std::copy_n(yp + k * static_cast<std::size_t>(H_), H_, h);
    std::fill_n(h + H_, H_, 0.0);
    nl.may_touch[k] = 1;
  }
  const double* yw = y + walls_offset();
  for (const std::size_t e : wall_entry_) {
    double* h = p.wall_history.data() + e;
    std::copy_n(yw, H_, h);
    std::fill_n(h + H_, H_, 0.0);
    yw += H_;
  }
}

bool ErkDriver::derivatives(const double* y, double* ydot) const {
  const auto& p = scene_->particles;
  const std::size_t n = free_.size();
  const int w = width_;
  bool finite = true;
#pragma omp parallel for schedule(static) reduction(&& : finite) if (n > kThreadedAbove)
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = free_[k];
    const double* yk = y + k * static_cast<std::size_t>(w);
    double* d = ydot + k * static_cast<std::size_t>(w);
    d[0] = yk[3];
    d[1] = yk[4];
    d[2] = yk[5];
    put3(d + 3, p.inv_mass[i] * p.f[i]);
    if (lay_.rigid) {
      put_quat_rate(d + 6, p.omega[i], yk + 6);
      put3(d + 10, p.torque[i]);
    } else if (lay_.rotation) {
      put3(d + 6, p.torque[i] / p.inertia[i].x());
    }
    for (int c = 0; c < w; ++c) finite = finite && std::isfinite(d[c]);
  }
  if (lay_.clumps) {
    const auto& b = scene_->bodies;
    const double* yb = y + bodies_offset();
    double* d = ydot + bodies_offset();
    for (std::size_t k = 0; k < bodies_; ++k, yb += kBodyWidth, d += kBodyWidth) {
      d[0] = yb[3];
      d[1] = yb[4];
      d[2] = yb[5];
      put3(d + 3, b.force[k] / b.mass[k]);
      put_quat_rate(d + 6, b.omega[k], yb + 6);
      put3(d + 10, b.torque[k]);
      for (int c = 0; c < kBodyWidth; ++c) finite = finite && std::isfinite(d[c]);
    }
  }
  if (H_ > 0) {
    const auto& nl = scene_->neighbors;
    const std::size_t S = static_cast<std::size_t>(nl.history_size());
    double* dp = ydot + pairs_offset();
    for (std::size_t k = 0; k < pairs_; ++k) std::copy_n(nl.history.data() + k * S + H_, H_, dp + k * H_);
    double* dw = ydot + walls_offset();
    for (const std::size_t e : wall_entry_) {
      std::copy_n(p.wall_history.data() + e + H_, H_, dw);
      dw += H_;
    }
    // (Rates are finite whenever the velocities are.)
  }
  return finite;
}

void ErkDriver::evaluate(double t, const double* y) {
  unpack(y);
  place_walls(t);
  pipe_->run_phase(*scene_, Phase::Force);
}

int ErkDriver::rhs(double t, const double* y, double* ydot) {
  evaluate(t, y);
  ++stats_.rhs_evaluations;
  // Non-finite forces (a trial step far too long): ARKODE retries shorter.
  return derivatives(y, ydot) ? 0 : 1;
}

void ErkDriver::pack() {
  auto& s = *scene_;
  auto& p = s.particles;
  auto& nl = s.neighbors;
  const bool balls = p.fields().has(Field::Body);
  free_.clear();
  for (std::size_t i = 0; i < p.n_owned(); ++i)
    if (!balls || p.body[i] < 0) free_.push_back(i);
  bodies_ = lay_.clumps ? s.bodies.size() : 0;
  pairs_ = H_ > 0 ? nl.partner.size() : 0;
  wall_entry_.clear();
  if (H_ > 0 && p.wall_history_size() > 0) {
    const std::size_t WH = static_cast<std::size_t>(p.wall_history_size());
    auto add = [&](const std::vector<std::uint32_t>& near, int slot) {
      for (const auto i : near) wall_entry_.push_back(i * WH + static_cast<std::size_t>(slot) * 2 * H_);
    };
    s.walls.for_each([&](const auto& wall, std::size_t w) {
      if (w >= nl.wall_near.size()) return;
      for (int k = 0; k < wall.history_slots; ++k) add(nl.wall_near[w], wall.history_slot + k);
    });
  }
  const std::size_t n = walls_offset() + wall_entry_.size() * static_cast<std::size_t>(H_);
  const bool resize = mem_ && n != n_state_;
  if (!y_ || n != n_state_) {
    // ARKODE keeps clones, never these vectors: they can go.
    free_vectors();
    if (n > 0) {
      y_ = new_vector(n);
      atol_ = N_VClone(y_);
    }
  }
  n_state_ = n;
  packed_builds_ = nl.stats().builds;
  ++stats_.repacks;
  if (n == 0) {  // every particle has left: nothing to integrate
    if (mem_) ERKStepFree(&mem_);
    mem_ = nullptr;
    return;
  }
  double* y = N_VGetArrayPointer(y_);
  double* a = N_VGetArrayPointer(atol_);
  const double tol = cfg_.atol, L = scales_.length, V = scales_.speed;
  x_ref_.resize(free_.size());
  for (std::size_t k = 0; k < free_.size(); ++k) {
    const std::size_t i = free_[k];
    double* yk = y + k * static_cast<std::size_t>(width_);
    double* ak = a + k * static_cast<std::size_t>(width_);
    x_ref_[k] = p.x[i];
    put3(yk, Vec3::Zero());
    put3(yk + 3, p.v[i]);
    std::fill_n(ak, 3, tol * L);
    std::fill_n(ak + 3, 3, tol * V);
    if (lay_.rigid) {
      put_quat(yk + 6, p.orientation[i]);
      put3(yk + 10, p.angular_momentum[i]);
      std::fill_n(ak + 6, 4, tol);
      std::fill_n(ak + 10, 3, tol * p.inertia[i].maxCoeff() * V / L);
    } else if (lay_.rotation) {
      put3(yk + 6, p.omega[i]);
      std::fill_n(ak + 6, 3, tol * V / L);
    }
  }
  const auto& b = s.bodies;
  body_ref_.resize(bodies_);
  double* yb = y + bodies_offset();
  double* ab = a + bodies_offset();
  for (std::size_t k = 0; k < bodies_; ++k, yb += kBodyWidth, ab += kBodyWidth) {
    body_ref_[k] = b.x[k];
    put3(yb, Vec3::Zero());
    put3(yb + 3, b.v[k]);
    put_quat(yb + 6, b.orientation[k]);
    put3(yb + 10, b.angular_momentum[k]);
    std::fill_n(ab, 3, tol * L);
    std::fill_n(ab + 3, 3, tol * V);
    std::fill_n(ab + 6, 4, tol);
    std::fill_n(ab + 10, 3, tol * b.inertia[k].maxCoeff() * V / L);
  }
  // Springs (m) and rolling torques (N m).
  auto history_tolerances = [&](double* at) {
    std::fill_n(at, lay_.tangential_history, tol * L);
    std::fill_n(at + lay_.tangential_history, lay_.rolling_history, tol * scales_.mass * V * V);
  };
  const std::size_t S = static_cast<std::size_t>(nl.history_size());
  for (std::size_t k = 0; k < pairs_; ++k) {
    std::copy_n(nl.history.data() + k * S, H_, y + pairs_offset() + k * H_);
    history_tolerances(a + pairs_offset() + k * H_);
  }
  double* yw = y + walls_offset();
  double* aw = a + walls_offset();
  for (const std::size_t e : wall_entry_) {
    std::copy_n(p.wall_history.data() + e, H_, yw);
    history_tolerances(aw);
    yw += H_;
    aw += H_;
  }
  if (!mem_) {
    mem_ = ERKStepCreate(rhs_callback, t_, y_, ctx_);
    if (!mem_) throw std::runtime_error("SUNDIALS: ERKStepCreate failed");
    check(ERKStepSetUserData(mem_, this), "ERKStepSetUserData");
    check(ERKStepSetErrHandlerFn(mem_, error_callback, this), "ERKStepSetErrHandlerFn");
    check(ERKStepSetOrder(mem_, cfg_.order), "ERKStepSetOrder");
    check(ERKStepSetMaxStep(mem_, dt_), "ERKStepSetMaxStep");
  } else if (resize) {
    // The step-size history carries over: the dynamics did not change.
    check(ERKStepResize(mem_, y_, 1.0, t_, nullptr, nullptr), "ERKStepResize");
  } else {
    check(ERKStepReset(mem_, t_, y_), "ERKStepReset");
  }
  check(ERKStepSVtolerances(mem_, cfg_.rtol, atol_), "ERKStepSVtolerances");
}

void ErkDriver::run_neighbor_phase() {
  // The neighbour stage reads the clock for the walls' travel.
  const double saved = scene_->clock.time;
  scene_->clock.time = t_;
  pipe_->run_phase(*scene_, Phase::Neighbor);
  scene_->clock.time = saved;
  refresh_build();
}

void ErkDriver::refresh_build() {
  const auto& nl = scene_->neighbors;
  if (nl.stats().builds == cached_builds_) return;
  auto b = nl.build_state();
  x_build_ = std::move(b.x);
  build_time_ = b.time;
  cached_builds_ = nl.stats().builds;
}

double ErkDriver::neighbours(double stop) {
  auto& s = *scene_;
  const auto& p = s.particles;
  // The plain skin trigger first, as in the Verlet pipeline's neighbour phase.
  run_neighbor_phase();
  const double skin = s.neighbors.smallest_skin(), g = s.gravity.norm();
  double m = 0, vmax = 0;
  auto measure = [&] {
    double m2 = 0, v2 = 0;
    const std::size_t n = p.n_owned();
    for (std::size_t i = 0; i < n; ++i) {
      if (x_build_.size() == n) m2 = std::max(m2, (p.x[i] - x_build_[i]).squaredNorm());
      v2 = std::max(v2, p.v[i].squaredNorm());
    }
    m = x_build_.size() == n ? std::sqrt(m2) : std::numeric_limits<double>::infinity();
    vmax = std::sqrt(v2);
  };
  // Within `horizon` a particle moves at most twice the fastest current speed
  // (a collision can speed a particle up), plus the fall under gravity.
  auto fits = [&](double horizon) {
    const double travel = m + 2.0 * vmax * horizon + 0.5 * g * horizon * horizon;
    return 2.0 * travel <= skin && travel + s.walls.max_displacement(t_ + horizon - build_time_) <= skin;
  };
  // The longest stretch (up to `stop`) the list covers, by bisection (fits
  // is monotone in the horizon).
  auto longest = [&](double horizon) {
    if (fits(horizon)) return horizon;
    double lo = 0, hi = horizon;
    for (int k = 0; k < 40; ++k) {
      const double mid = 0.5 * (lo + hi);
      (fits(mid) ? lo : hi) = mid;
    }
    return lo;
  };
  measure();
  const double wanted = stop - t_;
  double horizon = longest(wanted);
  // Rebuild early only when the list would cut the next stretch shorter
  // than a step ARKODE is taking (or a twentieth of the clock step).
  const double useful = std::min(wanted, std::max(last_step_, 0.05 * dt_));
  if (horizon < useful && m > 0) {
    s.neighbors.invalidate();
    run_neighbor_phase();
    ++stats_.lookahead_rebuilds;
    measure();
    horizon = longest(wanted);
  }
  if (!(horizon > 0)) throw IntegrationFailure("ARKODE: the neighbour skin cannot cover any step (particles too fast)");
  stop = horizon < wanted ? t_ + horizon : stop;
  if (!mem_ || packed_builds_ != s.neighbors.stats().builds) pack();
  return stop;
}

void ErkDriver::project(double* y) {
  if (H_ > 0) {
    // The evaluation at this state projected the springs in the buffers (and
    // zeroed those of separated contacts): they replace the ones in y.
    const auto& nl = scene_->neighbors;
    const std::size_t S = static_cast<std::size_t>(nl.history_size());
    double* yp = y + pairs_offset();
    for (std::size_t k = 0; k < pairs_; ++k) std::copy_n(nl.history.data() + k * S, H_, yp + k * H_);
    const auto& p = scene_->particles;
    double* yw = y + walls_offset();
    for (const std::size_t e : wall_entry_) {
      std::copy_n(p.wall_history.data() + e, H_, yw);
      yw += H_;
    }
  }
  if (lay_.rigid)
    for (std::size_t k = 0; k < free_.size(); ++k) {
      double* q = y + k * static_cast<std::size_t>(width_) + 6;
      put_quat(q, get_quat(q).normalized());
    }
  double* yb = y + bodies_offset();
  for (std::size_t k = 0; k < bodies_; ++k, yb += kBodyWidth) put_quat(yb + 6, get_quat(yb + 6).normalized());
}

int ErkDriver::take_step(double stop) {
  realtype tret = t_;
  message_.clear();
  const int flag = ERKStepEvolve(mem_, stop, y_, &tret, ARK_ONE_STEP);
  if (pending_) {
    auto e = pending_;
    pending_ = nullptr;
    std::rethrow_exception(e);
  }
  if (flag < 0) {
    // SUNDIALS allocates the flag name with malloc; the caller frees it (a
    // leak the AddressSanitizer run of the suite found).
    const std::unique_ptr<char, decltype(&std::free)> name(ERKStepGetReturnFlagName(flag), &std::free);
    std::ostringstream o;
    o << "ARKODE could not continue at t = " << t_ << " s (" << (name ? name.get() : "unknown flag") << "): " << message_
      << ". The state has probably blown up; see docs/integrators.md";
    throw IntegrationFailure(o.str());
  }
  const double h = tret - t_;
  last_step_ = h;
  stats_.min_step = stats_.steps == 0 ? h : std::min(stats_.min_step, h);
  stats_.max_step = std::max(stats_.max_step, h);
  ++stats_.steps;
  long fails = 0;
  ERKStepGetNumErrTestFails(mem_, &fails);
  stats_.error_test_failures = fails;
  t_ = tret;
  double* y = N_VGetArrayPointer(y_);
  if (H_ > 0) {
    // The forces at the accepted state: projects the springs (and leaves the
    // forces of the step's end in the particle store).
    evaluate(t_, y);
    ++stats_.projection_evaluations;
  }
  project(y);
  if (H_ > 0 || lay_.rigid || lay_.clumps) {
    // The next step starts from the projected state (ARKODE keeps its
    // step-size history).
    check(ERKStepReset(mem_, t_, y_), "ERKStepReset");
    if (flag != ARK_TSTOP_RETURN) check(ERKStepSetStopTime(mem_, stop), "ERKStepSetStopTime");
  }
  if (observer_) {
    unpack(y);
    place_walls(t_);
    const double saved = scene_->clock.time;
    scene_->clock.time = t_;
    observer_(*scene_);
    scene_->clock.time = saved;
  }
  return flag;
}

void ErkDriver::drive(Scene& s, Pipeline& p) {
  scene_ = &s;
  pipe_ = &p;
  dt_ = s.clock.dt;
  if (!ready_) {
    t_ = s.clock.time;
    walls_ref_ = s.walls;
    walls_t0_ = t_;
    walls_move_ = s.walls.max_speed() > 0;
    ready_ = true;
  }
  const double t_end = static_cast<double>(s.clock.step + 1) * dt_;  // as Pipeline::step sets the clock
  while (t_ < t_end) {
    const double stop = neighbours(t_end);
    if (n_state_ == 0) {
      t_ = stop;
      continue;
    }
    check(ERKStepSetStopTime(mem_, stop), "ERKStepSetStopTime");
    while (take_step(stop) != ARK_TSTOP_RETURN) {
    }
    t_ = stop;
    unpack(N_VGetArrayPointer(y_));
    place_walls(t_);
  }
  place_walls(t_end);
  if (H_ == 0 || n_state_ == 0) {
    // The forces at the end state, for the outputs (with springs, the
    // projection after the last step has left them).
    p.run_phase(s, Phase::Force);
    ++stats_.end_evaluations;
  }
  scene_ = nullptr;
  pipe_ = nullptr;
}

}  // namespace

bool arkode_available() { return true; }

std::unique_ptr<ArkodeIntegrator> make_arkode_integrator(const ArkodeConfig& c, const ArkodeLayout& layout,
                                                         const ArkodeScales& scales, const std::string& where) {
  refuse_several_ranks(where);
  return std::make_unique<ErkDriver>(c, layout, scales);
}

#else  // no SUNDIALS

bool arkode_available() { return false; }

std::unique_ptr<ArkodeIntegrator> make_arkode_integrator(const ArkodeConfig&, const ArkodeLayout&,
                                                         const ArkodeScales&, const std::string& where) {
  refuse_several_ranks(where);
  throw SetupError(where +
                   ": integrator: arkode needs SUNDIALS, and this build has none; configure with "
                   "-DGRAINS_WITH_SUNDIALS=ON (Debian: libsundials-dev), or use integrator: verlet");
}

#endif

}  // namespace grains::sim
