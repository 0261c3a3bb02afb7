#pragma once
// Contacts in scenes with ellipsoids: the same Law as for spheres, with the
// geometry chosen per pair from the shapes: sphere-sphere (closed form),
// sphere-ellipsoid (closest point on the ellipsoid, contact/ellipsoid/
// point_ellipsoid.hpp) or ellipsoid-ellipsoid (PW85, contact/ellipsoid/
// ellipsoid_contact.hpp). The PW85 lambda of each pair is kept after the
// law's history and warm-starts the next step's solve. Scenes of spheres
// only never instantiate this stage.
#include <omp.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "contact/ellipsoid/pw85_lanes.hpp"
#include "sim/laws/contact_law.hpp"
#include "sim/laws/entry_forces.hpp"
#include "sim/laws/probe_entries.hpp"
#include "sim/neighbor/pair_geometry.hpp"
#include "sim/scene/stage.hpp"

namespace grains::sim {

/// The pair stage of scenes with ellipsoids. Each step runs in passes over
/// a block of list rows: (1) the cheap tests (bounding spheres, separating
/// axis along the line of centres) and every pair with a sphere in it,
/// directly; (2) the ellipsoid pairs that pass, through PW85 kLanes pairs at
/// a time (contact/ellipsoid/pw85_lanes.hpp); (3) the contact geometry of
/// those that touch, likewise; (4) the law for each contact. The result of
/// every pair is the one of shape_pair_geometry + the law (the same
/// arithmetic, tested); batching only lets independent pairs' division and
/// square-root chains overlap (bench/RESULTS.md).
template <class Law>
class ShapePairContactStage final : public Stage {
 public:
  std::string name() const override { return "force.pair_contacts[sphere|ellipsoid]<" + Law::name() + ">"; }
  Phase phase() const override { return Phase::Force; }

  void run(Scene& s) override {
    if (s.deterministic)
      run_deferred(s);
    else
      run_direct(s);
  }

  std::vector<std::pair<std::string, double>> memory_parts() const override {
    return {{"ordered_sums_entry_forces", e_.bytes()}};
  }

 private:
  static constexpr int H = Law::history_size;
  static constexpr int NH = H + 1;  // + PW85 lambda

  // Scratch of one block of rows (one per thread).
  struct Batch {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pending;  // (i, k) of ellipsoid pairs for PW85
    std::vector<contact::Pw85LaneJob> jobs;
    std::vector<contact::Pw85LaneResult> results;
    std::vector<std::uint32_t> touching;  // indices into pending
    std::vector<contact::PairGeometryJob> geometry_jobs;
    std::vector<contact::ContactGeometry> geometry;
  };

  static double* history(Scene& s, std::uint32_t k) {
    return s.neighbors.history.data() + static_cast<std::size_t>(k) * NH;
  }

  // The law for the pair (i, k) touching with geometry g: force on i and the
  // torques on i and j.
  static GRAINS_INLINE void law(Scene& s, std::size_t i, std::uint32_t k, const contact::ContactGeometry& g,
                                double* hist, Vec3& force, Vec3& ti, Vec3& tj) {
    ParticleStore& p = s.particles;
    const std::size_t j = s.neighbors.partner[k];
    const PairParams& pp = s.pairs(p.material[i], p.material[j]);
    const Vec3 ci = g.point - p.x[i], cj = g.point - p.x[j];
    const Vec3 v_rel = p.v[i] + p.omega[i].cross(ci) - p.v[j] - p.omega[j].cross(cj);
    const Vec3 w_rel = p.omega[i] - p.omega[j];
    const auto r = Law::evaluate(g, v_rel, w_rel, s.neighbors.pair_mass(p, i, j), pp, s.clock.dt, hist);
    force = r.force;
    ti = ci.cross(r.force) + r.rolling_torque;
    tj = -(cj.cross(r.force) + r.rolling_torque);
  }

  // A pair with a sphere in it (sphere-sphere or sphere-ellipsoid), one at a
  // time; such pairs keep no PW85 lambda.
  static GRAINS_INLINE bool contact_with_sphere(Scene& s, std::size_t i, std::uint32_t k, Vec3& force, Vec3& ti,
                                                Vec3& tj) {
    const std::size_t j = s.neighbors.partner[k];
    double* hist = history(s, k);
    double lambda = -1.0;
    contact::ContactGeometry g;
    if (!shape_pair_geometry(s.particles, i, j, lambda, g)) {
      if constexpr (H > 0) std::fill_n(hist, H, 0.0);
      return false;
    }
    law(s, i, k, g, hist, force, ti, tj);
    return true;
  }

  // Rows [r0, r1): touched(i, k, force, ti, tj) for every entry in contact,
  // apart(k) for every other entry.
  template <class Touched, class Apart>
  static void run_rows(Scene& s, std::size_t r0, std::size_t r1, Batch& b, Touched&& touched, Apart&& apart) {
    ParticleStore& p = s.particles;
    const NeighborList& nl = s.neighbors;
    b.pending.clear();
    b.jobs.clear();
    Vec3 f, ti, tj;
    for (std::size_t i = r0; i < r1; ++i) {
      const bool ei = p.shape[i] == kEllipsoid;
      for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
        const std::size_t j = nl.partner[k];
        double* hist = history(s, k);
        const Vec3 r = p.x[j] - p.x[i];
        const double r2 = r.squaredNorm();
        const double rc = nl.contact_distance(p, i, j);
        if (r2 >= rc * rc) {      // bounding spheres apart
          if (hist[H] != -1.0) {  // (most such entries were cleared at an earlier step)
            std::fill_n(hist, NH, 0.0);
            hist[H] = -1.0;
          }
          apart(k);
          continue;
        }
        if (!(ei && p.shape[j] == kEllipsoid)) {
          if (contact_with_sphere(s, i, k, f, ti, tj))
            touched(i, k, f, ti, tj);
          else
            apart(k);
          continue;
        }
        if (apart_along_centres(p, i, j, true, true, r, r2)) {
          if constexpr (H > 0) std::fill_n(hist, H, 0.0);
          apart(k);
          continue;
        }
        b.pending.emplace_back(static_cast<std::uint32_t>(i), k);
        b.jobs.push_back({p.form[i].data(), p.form[j].data(), {r[0], r[1], r[2]}, hist[H] > 0 ? hist[H] : -1.0});
      }
    }
    // PW85 with early exit and warm start at the DEM tolerance; the geometry
    // (support points, curvatures, R*) only for the pairs that touch.
    b.results.resize(b.jobs.size());
    contact::pw85_contact_lanes(b.jobs.data(), b.jobs.size(), b.results.data(), kPw85DemTolerance, true);
    b.touching.resize(b.pending.size());
    b.geometry_jobs.resize(b.pending.size());
    std::size_t touching = 0;
    for (std::size_t m = 0; m < b.pending.size(); ++m) {
      const auto [i, k] = b.pending[m];
      const auto& pw = b.results[m];
      double* hist = history(s, k);
      if (pw.status == contact::Pw85Status::ok || pw.status == contact::Pw85Status::separated) hist[H] = pw.lambda;
      if (pw.status == contact::Pw85Status::ok && pw.mu2 < 1.0) {
        const std::size_t j = nl.partner[k];
        b.touching[touching] = static_cast<std::uint32_t>(m);
        b.geometry_jobs[touching++] = {
            p.x[i].data(), p.form[i].data(), p.x[j].data(), p.form[j].data(), {pw.x[0], pw.x[1], pw.x[2]}};
        continue;
      }
      if constexpr (H > 0) std::fill_n(hist, H, 0.0);
      apart(k);
    }
    b.geometry.resize(touching);
    contact::contact_geometry_lanes(b.geometry_jobs.data(), touching, b.geometry.data());
    for (std::size_t t = 0; t < touching; ++t) {
      const auto [i, k] = b.pending[b.touching[t]];
      double* hist = history(s, k);
      const contact::ContactGeometry& g = b.geometry[t];
      if (!(g.overlap > 0)) {
        if constexpr (H > 0) std::fill_n(hist, H, 0.0);
        apart(k);
        continue;
      }
      law(s, i, k, g, hist, f, ti, tj);
      touched(i, k, f, ti, tj);
    }
  }

  void run_direct(Scene& s) {
    ParticleStore& p = s.particles;
    const NeighborList& nl = s.neighbors;
    const std::size_t rows = nl.row_start.empty() ? 0 : nl.row_start.size() - 1;
    if (batches_.empty()) batches_.resize(1);
    run_rows(
        s, 0, rows, batches_[0],
        [&](std::size_t i, std::uint32_t k, const Vec3& f, const Vec3& ti, const Vec3& tj) {
          const std::size_t j = nl.partner[k];
          p.f[i] += f;
          p.f[j] -= f;
          p.torque[i] += ti;
          p.torque[j] += tj;
          if (s.stress_probe) s.stress_probe->add_pair(0, p, i, j, f);
        },
        [](std::uint32_t) {});
  }

  void run_deferred(Scene& s) {
    const NeighborList& nl = s.neighbors;
    const std::size_t rows = nl.row_start.empty() ? 0 : nl.row_start.size() - 1;
    e_.resize<true>(nl.partner.size());
    constexpr std::size_t kBlock = 64;  // rows per block
    const auto blocks = static_cast<std::ptrdiff_t>((rows + kBlock - 1) / kBlock);
    const auto threads = static_cast<std::size_t>(omp_get_max_threads());
    if (batches_.size() < threads) batches_.resize(threads);
#pragma omp parallel for schedule(dynamic, 1)
    for (std::ptrdiff_t bb = 0; bb < blocks; ++bb) {
      const std::size_t r0 = static_cast<std::size_t>(bb) * kBlock, r1 = std::min(rows, r0 + kBlock);
      run_rows(
          s, r0, r1, batches_[static_cast<std::size_t>(omp_get_thread_num())],
          [&](std::size_t, std::uint32_t k, const Vec3& f, const Vec3& ti, const Vec3& tj) {
            e_.set<true>(k, f, ti, tj);
          },
          [&](std::uint32_t k) { e_.zero<true>(k, k + 1); });
    }
    gather_entry_forces<true>(s.particles, nl, e_);
    if (s.stress_probe) probe_entries<true>(*s.stress_probe, s.particles, nl, e_);
  }

  EntryForces e_;
  std::vector<Batch> batches_;
};

}  // namespace grains::sim
