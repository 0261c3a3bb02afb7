#include "io/run/simulation.hpp"

#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include <signal.h>

#include <omp.h>

#include "io/output/mass_output.hpp"
#include "io/output/wall_load_output.hpp"
#include "io/output/progress.hpp"
#include "sim/laws/sphere_lanes.hpp"
#include "sim/neighbor/neighbor_stage.hpp"
#include "sim/parallel/comm.hpp"
#include "sim/parallel/exchange.hpp"
#include "sim/scene/memory_report.hpp"
#include "io/output/solid_fraction_output.hpp"
#include "io/output/vtk_output.hpp"
#include "io/run/checkpoint_stage.hpp"
#include "sim/integrate/arkode.hpp"
#include "grains/version.hpp"
#include "sim/state/free_heap.hpp"

namespace grains::io {

Simulation make_simulation(Case c) {
  const auto started = std::chrono::steady_clock::now();
  Simulation s;
  s.c = std::move(c);
  s.scene = sim::build_scene(s.c.scene);
  if (const auto& st = s.c.output.stress; st.enabled) {
    // The probe gathers one force evaluation per step, of spheres' or ellipsoids' centres.
    if (s.c.scene.integrator == sim::Integrator::Arkode)
      throw sim::SetupError(st.where + ": output.stress measures with the Verlet integrator (ARKODE evaluates "
                            "the forces at several trial states per step); use time.integrator: verlet");
    bool clumps = false;
    for (const auto& set : s.c.scene.sets) clumps = clumps || set.shape.kind == sim::ShapeConfig::Kind::Clump;
    for (const auto& in : s.c.scene.insertions) clumps = clumps || in.grains.shape.kind == sim::ShapeConfig::Kind::Clump;
    if (clumps)
      throw sim::SetupError(st.where + ": output.stress does not measure clumps (their contacts' branch vectors "
                            "would have to join the bodies' centres, not the balls')");
  }
  s.rayleigh_time = sim::rayleigh_time(s.c.scene);
  s.pipeline = sim::assemble_pipeline(s.scene, s.c.scene);
  sim::release_free_heap();  // what set-up freed (sim/state/free_heap.hpp)
  s.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return s;
}

namespace {
std::int64_t frame_steps(const OutputConfig& o, double dt) {
  if (o.every_steps > 0) return o.every_steps;
  if (o.every > 0) return std::max<std::int64_t>(1, std::llround(o.every / dt));
  return 0;
}

std::int64_t checkpoint_steps(const CheckpointConfig& k, double dt) {
  if (k.every_steps > 0) return k.every_steps;
  if (k.every > 0) return std::max<std::int64_t>(1, std::llround(k.every / dt));
  return 0;
}

volatile std::sig_atomic_t g_signal = 0;
extern "C" void on_signal(int sig) { g_signal = sig; }

// Installs the SIGINT/SIGTERM handlers for the duration of a run.
class SignalGuard {
 public:
  explicit SignalGuard(bool on) : on_(on) {
    g_signal = 0;
    if (!on_) return;
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    sigaction(SIGINT, &sa, &old_int_);
    sigaction(SIGTERM, &sa, &old_term_);
  }
  ~SignalGuard() {
    if (!on_) return;
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  SignalGuard(const SignalGuard&) = delete;
  SignalGuard& operator=(const SignalGuard&) = delete;

 private:
  bool on_;
  struct sigaction old_int_ {}, old_term_ {};
};

std::string effective_case(const Case& c) {
  YAML::Emitter e;
  e << c.root;
  return e.c_str();
}

std::filesystem::path emergency_dir(const RunOptions& opt) {
  if (!opt.emergency_dir.empty()) return opt.emergency_dir;
  if (const char* e = std::getenv("GRAINS_EMERGENCY_DIR"); e && *e) return e;
  std::error_code ec;
  auto t = std::filesystem::temp_directory_path(ec);
  return (ec ? std::filesystem::path("/tmp") : t) / "grains-emergency";
}

// Saves the state after a signal or a failed output: into the checkpoint
// folder, else into the emergency folder. Returns the file, or empty with
// the reasons in `why`.
std::filesystem::path save_somewhere(CheckpointStage& ck, Simulation& s, const RunOptions& opt, std::string& why) {
  s.pipeline.settle(s.scene);  // a kick left waiting (Pipeline::step) is done first
  try {
    return ck.save_now(s.scene);
  } catch (const BlowUp&) {
    throw;
  } catch (const std::exception& e) {
    why = e.what();
  }
  try {
    return ck.save_to(s.scene, emergency_dir(opt));
  } catch (const BlowUp&) {
    throw;
  } catch (const std::exception& e) {
    why += "; " + std::string(e.what());
  }
  return {};
}

// Fails early, with a clear message, when the output folder cannot be written.
void probe_output_dir(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw OutputFailure("cannot create the output folder '" + dir.string() + "': " + ec.message());
  const auto probe = dir / (".grains-write-probe-" + std::to_string(sim::Comm::world().rank()));
  errno = 0;
  {
    std::ofstream o(probe);
    o << "probe\n";
    o.flush();
    if (!o)
      throw OutputFailure("the output folder '" + dir.string() + "' is not writable" +
                          (errno ? std::string(": ") + std::strerror(errno) : std::string()) +
                          "; choose another with -o");
  }
  std::filesystem::remove(probe, ec);
}

// Per rank, for docs/parallel.md's cost model (summary.json "ranks"): owned
// grains, ghosts, interior grains (farther than the ghost cut-off from every
// face the rank shares with a neighbour, itself across a periodic face
// included), list pairs, messages and ghost bytes of a ghost refresh (one
// step between builds), and the seconds of the pair and neighbour stages.
// Collective: every rank calls it; each gets every rank's figures.
struct RankFigures {
  std::vector<std::int64_t> owned, ghosts, interior, pairs, messages, ghost_bytes;
  std::vector<double> pair_seconds, neighbor_seconds;
  std::vector<double> stage_max;  // per pipeline stage: the slowest rank's seconds
};

RankFigures rank_figures(const Simulation& s) {
  RankFigures f;
  const auto& x = *s.scene.exchange;
  const auto& comm = x.comm();
  const auto& dec = x.decomposition();
  const auto& p = s.scene.particles;
  const int me = comm.rank();
  const sim::Vec3 lo = dec.lo(me), hi = dec.hi(me);
  const double cut = x.cutoff();
  std::int64_t interior = 0, messages = 0;
  std::array<bool, 3> low_face{}, high_face{};
  for (int d = 0; d < 3; ++d) {
    bool wraps = false;
    const int down = dec.neighbor(me, d, -1, wraps), up = dec.neighbor(me, d, +1, wraps);
    low_face[static_cast<std::size_t>(d)] = down >= 0;
    high_face[static_cast<std::size_t>(d)] = up >= 0;
    messages += (down >= 0 && down != me) + (up >= 0 && up != me);
  }
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    bool in = true;
    for (int d = 0; d < 3; ++d) {
      const auto k = static_cast<std::size_t>(d);
      in = in && (!low_face[k] || p.x[i][d] - lo[d] > cut) && (!high_face[k] || hi[d] - p.x[i][d] > cut);
    }
    interior += in;
  }
  double pair = 0, neigh = 0;
  const auto names = s.pipeline.stage_names();
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (names[k].find("pair_contacts") != std::string::npos) pair += s.pipeline.stage_seconds()[k];
    if (names[k].rfind("neighbor", 0) == 0) neigh += s.pipeline.stage_seconds()[k];
  }
  const auto ghosts = static_cast<std::int64_t>(p.n_ghost());
  f.owned = comm.all_gather(static_cast<std::int64_t>(p.n_owned()));
  f.ghosts = comm.all_gather(ghosts);
  f.interior = comm.all_gather(interior);
  f.pairs = comm.all_gather(static_cast<std::int64_t>(s.scene.neighbors.stats().pairs));
  f.messages = comm.all_gather(messages);
  f.ghost_bytes = comm.all_gather(ghosts * static_cast<std::int64_t>(p.kinematic_bytes()));
  f.pair_seconds.assign(static_cast<std::size_t>(comm.size()), 0.0);
  f.neighbor_seconds = f.pair_seconds;
  f.pair_seconds[static_cast<std::size_t>(me)] = pair;
  f.neighbor_seconds[static_cast<std::size_t>(me)] = neigh;
  comm.sum_in_place(f.pair_seconds);
  comm.sum_in_place(f.neighbor_seconds);
  for (double sec : s.pipeline.stage_seconds()) f.stage_max.push_back(comm.max(sec));
  return f;
}

template <class T>
std::string json_list(const std::vector<T>& v) {
  std::ostringstream o;
  o.precision(6);
  o << "[";
  for (std::size_t k = 0; k < v.size(); ++k) o << (k ? ", " : "") << v[k];
  return o.str() + "]";
}

}  // namespace

OutputStages add_output_stages(Simulation& s, const RunOptions& opt) {
  const auto& o = s.c.output;
  // Growing radii push grains apart at up to the growth rate times the domain size.
  double growth_rate = s.c.scene.growth.enabled ? s.c.scene.growth.rate : 0.0;
  for (const auto& ph : s.c.scene.growth.phases) growth_rate = std::max(growth_rate, ph.rate);
  const double growth_speed = growth_rate * (s.scene.domain.hi - s.scene.domain.lo).norm();
  // Inserted grains come in at their own speed.
  auto blow = std::make_unique<BlowUpCheck>(s.scene, s.rayleigh_time, 200,
                                            growth_speed + s.c.scene.fastest_insertion());
  BlowUpCheck* blow_up = blow.get();
  s.pipeline.add(std::move(blow));
  VtkOutput* vtk = nullptr;
  if (o.vtk) {
    auto v = std::make_unique<VtkOutput>(opt.out_dir, frame_steps(o, s.scene.clock.dt));
    vtk = v.get();
    s.pipeline.add(std::move(v));
  }
  // An output's cadence in steps: every_steps, else every (s), else the frames'.
  auto cadence = [&](std::int64_t every_steps, double every) -> std::int64_t {
    if (every_steps > 0) return every_steps;
    if (every > 0) return std::max<std::int64_t>(1, std::llround(every / s.scene.clock.dt));
    return frame_steps(o, s.scene.clock.dt);
  };
  if (o.solid_fraction.enabled) {
    const auto& sf = o.solid_fraction;
    s.pipeline.add(std::make_unique<SolidFractionOutput>(opt.out_dir, sf, cadence(sf.every_steps, sf.every)));
  }
  if (o.mass.enabled) {
    s.pipeline.add(std::make_unique<MassOutput>(opt.out_dir, o.mass, cadence(o.mass.every_steps, o.mass.every)));
  }
  if (o.wall_loads.enabled) {
    const auto& wl = o.wall_loads;
    s.pipeline.add(std::make_unique<WallLoadOutput>(opt.out_dir, wl, cadence(wl.every_steps, wl.every)));
  }
  if (o.stress.enabled) {
    const auto& st = o.stress;
    s.pipeline.add(std::make_unique<StressOutput>(opt.out_dir, st, cadence(st.every_steps, st.every)));
  }
  if (o.progress && !opt.quiet) s.pipeline.add(std::make_unique<Progress>(*opt.log, o.progress_interval));
  // Last of the output phase: a checkpoint holds the frames of its own step.
  CheckpointExtras info{s.c.path, s.c.text, effective_case(s.c), {}, {}, {}, {}};
  auto ck = std::make_unique<CheckpointStage>(opt.out_dir / "checkpoints",
                                              checkpoint_steps(s.c.checkpoint, s.scene.clock.dt), s.c.checkpoint.keep,
                                              std::move(info));
  ck->attach(vtk, blow_up);
  ck->set_sort(s.c.scene.sort_particles);
  CheckpointStage* checkpoints = ck.get();
  s.pipeline.add(std::move(ck));
  return {vtk, checkpoints};
}

Runner::Runner(Simulation& s, const RunOptions& opt) : s_(s), opt_(opt) {
  const auto& comm = sim::Comm::world();
  {
    std::string err;
    try {
      probe_output_dir(opt.out_dir);
      if (comm.parallel()) (void)parallel_checkpoint_io();  // an invalid $GRAINS_CHECKPOINT_IO is a set-up error
    } catch (const std::exception& e) {
      err = e.what();
    }
    if (comm.agree_error(err)) throw OutputFailure(err);
  }
  const OutputStages outputs = add_output_stages(s, opt);
  const bool talk = !opt.quiet && comm.root();
  for (const auto& w : s.c.scene.warnings)
    if (talk) *opt.log << w << "\n";
  vtk_ = outputs.vtk;
  ck_ = outputs.checkpoints;
  t0_ = std::chrono::steady_clock::now();
  if (!opt.restart.empty()) {
    const auto x = read_checkpoint(opt.restart, s.scene);
    if (s.scene.exchange) {
      // Every rank read the whole state: keep this rank's part and rebuild;
      // the histories follow their pairs by global ids.
      const auto builds = s.scene.neighbors.stats().builds;
      if (s.scene.domain.shear.servo()) s.scene.exchange->set_domain(s.scene.domain);  // the cell's height then
      s.scene.exchange->distribute_initial(s.scene, &x.cuts);
      sim::NeighborStage::full_update(s.scene, s.c.scene.sort_particles, true);
      s.scene.neighbors.keep_build_count(builds);  // (the saving run counted this update)
    }
    if (!x.fresh_fields.empty() && talk) {
      *opt.log << "note: " << opt.restart.string() << " has no";
      for (std::size_t k = 0; k < x.fresh_fields.size(); ++k) *opt.log << (k ? ", " : " ") << x.fresh_fields[k];
      *opt.log << " (its stage ran without them): they start as a new particle's, its contacts with no history\n";
    }
    if (x.case_effective != effective_case(s.c) && talk)
      *opt.log << "note: the case differs from the one " << opt.restart.string()
               << " was written with; continuing with the given case\n";
    for (const auto& name : comm.root() ? remove_checkpoints_after(ck_->dir(), s.scene.clock.step)
                                        : std::vector<std::string>{})
      if (talk) *opt.log << "removed " << name << " (after the restart point)\n";
    s.pipeline.restart(s.scene, sim::RestartPoint{opt.restart.string(), x.frame_times, x.frame_steps});
    r_.restarted_from = opt.restart.string();
    if (talk)
      *opt.log << "restarting from " << opt.restart.string() << " at step " << s.scene.clock.step << " (t = "
               << s.scene.clock.time << " s)\n";
  } else {
    s.pipeline.initialize(s.scene);
    s.pipeline.start(s.scene);
  }
  sim::release_free_heap();  // what the first neighbour build freed (sim/state/free_heap.hpp)
  r_.particles_start = s.scene.particles.n_owned();
}

Runner::~Runner() = default;

std::int64_t Runner::advance(std::int64_t target, const std::function<bool()>& stop_asked) {
  if (finished_ || r_.signal != 0) throw std::logic_error("the run has ended: it cannot step further");
  auto& s = s_;
  const auto& comm = sim::Comm::world();
  if (target > s.scene.clock.n_steps) {  // past the case's end: the end moves there
    s.scene.clock.n_steps = target;
    s.scene.clock.end_time = static_cast<double>(target) * s.scene.clock.dt;
  }
  const std::int64_t first = s.scene.clock.step;
  SignalGuard guard(opt_.handle_signals);
  try {
    // Under MPI the ranks agree on a signal (mpirun forwards it to all,
    // not necessarily at the same step), so they stop at the same step.
    auto stop = [&comm] { return comm.parallel() ? comm.any(g_signal != 0) : g_signal != 0; };
    // Between two steps of this loop the kick may wait for the next drift
    // (Pipeline::step); never after the last, and the loop's end settles it.
    while (s.scene.clock.step < target && !stop() && !(stop_asked && stop_asked())) {
      particle_steps_ += static_cast<double>(s.scene.particles.n_owned());
      s.pipeline.step(s.scene, s.scene.clock.step + 1 < target);
      pair_steps_ += static_cast<double>(s.scene.neighbors.partner.size());
      steps_run_ += 1;
    }
    s.pipeline.settle(s.scene);
    if (stop()) {
      r_.signal = g_signal != 0 ? static_cast<int>(g_signal) : SIGTERM;
      std::string why;
      const auto f = save_somewhere(*ck_, s, opt_, why);
      if (f.empty()) throw OutputFailure("interrupted, and no checkpoint could be written: " + why);
      r_.checkpoint = f.string();
    }
  } catch (const BlowUp&) {
    throw;
  } catch (const sim::IntegrationFailure&) {
    throw;
  } catch (const OutputFailure&) {
    throw;
  } catch (const std::exception& e) {
    // An output failed (disk full, folder gone): the physics of this step is
    // complete, so its state is saved wherever it still fits.
    output_failed(e);
  }
  return s.scene.clock.step - first;
}

void Runner::output_failed(const std::exception& e) {
  auto& s = s_;
  std::string why;
  const auto f = save_somewhere(*ck_, s, opt_, why);
  std::ostringstream m;
  m << e.what() << "\nthe run stopped at step " << s.scene.clock.step << " (t = " << s.scene.clock.time << " s); ";
  if (f.empty())
    m << "no checkpoint could be written (" << why << "); work since "
      << (ck_->last().empty() ? std::string("the start") : ck_->last().string()) << " is lost";
  else
    m << "its state is saved in " << f.string() << "; once there is room, continue with: grains run " << s.c.path
      << " --restart " << f.string() << " -o " << opt_.out_dir.string();
  throw OutputFailure(m.str());
}

std::filesystem::path Runner::checkpoint() {
  s_.pipeline.settle(s_.scene);
  return ck_->save_now(s_.scene);
}

RunSummary Runner::finish() {
  if (finished_) throw std::logic_error("the run has already finished");
  finished_ = true;
  auto& s = s_;
  const auto& comm = sim::Comm::world();
  auto& r = r_;
  if (r.signal == 0) {
    try {
      s.pipeline.finish(s.scene);
    } catch (const BlowUp&) {
      throw;
    } catch (const OutputFailure&) {
      throw;
    } catch (const std::exception& e) {
      output_failed(e);
    }
  }
  double particle_steps = particle_steps_, pair_steps = pair_steps_;
  const double steps_run = steps_run_;
  if (r.checkpoint.empty() && !ck_->last().empty()) r.checkpoint = ck_->last().string();
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
  r.steps = s.scene.clock.step;
  r.simulated_time = s.scene.clock.time;
  particle_steps = comm.sum(particle_steps);
  pair_steps = comm.sum(pair_steps);
  r.particles_start = static_cast<std::size_t>(comm.sum(static_cast<std::int64_t>(r.particles_start)));
  r.particle_steps_per_second = r.wall_seconds > 0 ? particle_steps / r.wall_seconds : 0;
  r.particles_end = static_cast<std::size_t>(comm.sum(static_cast<std::int64_t>(s.scene.particles.n_owned())));
  r.lost_particles = comm.sum(s.scene.lost_particles);
  r.wall_seconds = comm.max(r.wall_seconds);
  r.neighbor_builds = s.scene.neighbors.stats().builds;
  if (vtk_) r.frames = vtk_->frames();

  const std::int64_t migrated = s.scene.exchange ? comm.sum(s.scene.exchange->stats().migrated) : 0;
  // Memory: what the scene holds, part by part, and the peak resident set
  // size, summed over the ranks (docs/memory.md).
  auto parts = sim::memory_parts(s.scene, s.pipeline);
  double counted = 0;
  for (auto& part : parts) counted += (part.bytes = comm.sum(part.bytes));
  const double peak_rss = comm.sum(sim::resident_bytes(true));
  RankFigures ranks;
  if (s.scene.exchange) ranks = rank_figures(s);
  if (!comm.root()) return r;
  std::ofstream j(opt_.out_dir / "summary.json");
  j.precision(10);
  j << "{\n  \"grains_version\": \"" << kVersion << "\",\n  \"case\": \"" << s.c.path << "\",\n"
    << "  \"steps\": " << r.steps << ",\n  \"simulated_time_s\": " << r.simulated_time << ",\n"
    << "  \"time_step_s\": " << s.scene.clock.dt << ",\n  \"wall_time_s\": " << r.wall_seconds << ",\n"
    << "  \"particle_steps_per_second\": " << r.particle_steps_per_second << ",\n"
    << "  \"particles_start\": " << r.particles_start << ",\n  \"particles_end\": " << r.particles_end << ",\n"
    << "  \"lost_particles\": " << r.lost_particles << ",\n  \"neighbor_builds\": " << r.neighbor_builds << ",\n"
    << "  \"neighbor_pairs_per_step\": " << (steps_run > 0 ? pair_steps / steps_run : 0.0)
    << ",\n  \"frames\": " << r.frames << ",\n"
    << "  \"mpi_ranks\": " << comm.size() << ",\n  \"omp_threads\": " << omp_get_max_threads() << ",\n"
    << "  \"deterministic\": " << (s.scene.deterministic ? "true" : "false") << ",\n"
    // Which copy of the sphere pair kernel ran (README: GRAINS_SIMD): benchmark
    // figures from different machines say what they measured.
    << "  \"sphere_pair_simd\": \""
    << (sim::sphere_lanes_enabled() ? sim::sphere_lanes_instruction_set() : "scalar") << "\",\n";
  if (s.scene.exchange) {
    const auto& x = s.scene.exchange->stats();
    j << "  \"decomposition\": \"" << s.scene.exchange->decomposition().describe() << "\",\n"
      << "  \"rebalances\": " << x.rebalances << ",\n  \"migrated_particles\": " << migrated << ",\n"
      << "  \"load_imbalance\": " << x.imbalance << ",\n"
      << "  \"ranks\": {\n    \"owned\": " << json_list(ranks.owned) << ",\n    \"ghosts\": "
      << json_list(ranks.ghosts) << ",\n    \"interior\": " << json_list(ranks.interior)
      << ",\n    \"list_pairs\": " << json_list(ranks.pairs) << ",\n    \"messages_per_step\": "
      << json_list(ranks.messages) << ",\n    \"ghost_bytes_per_step\": " << json_list(ranks.ghost_bytes)
      << ",\n    \"pair_seconds\": " << json_list(ranks.pair_seconds) << ",\n    \"neighbor_seconds\": "
      << json_list(ranks.neighbor_seconds) << "\n  },\n";
  }
  j << "  \"setup_seconds\": {\"case\": " << s.c.read_seconds << ", \"scene\": " << s.build_seconds << "},\n";
  {
    const double n = std::max<double>(1.0, static_cast<double>(r.particles_end));
    j << "  \"memory\": {\n    \"peak_resident_bytes\": " << peak_rss << ",\n    \"peak_resident_bytes_per_particle\": "
      << peak_rss / n << ",\n    \"counted_bytes_per_particle\": " << counted / n
      << ",\n    \"bytes_per_particle\": {";
    bool first = true;
    for (const auto& part : parts) {
      if (part.bytes == 0) continue;
      j << (first ? "" : ",") << "\n      \"" << part.name << "\": " << part.bytes / n;
      first = false;
    }
    j << "\n    }\n  },\n";
  }
  if (!r.restarted_from.empty()) j << "  \"restarted_from\": \"" << r.restarted_from << "\",\n";
  if (r.signal != 0) j << "  \"interrupted_by_signal\": " << r.signal << ",\n";
  if (!r.checkpoint.empty()) j << "  \"checkpoint\": \"" << r.checkpoint << "\",\n";
  j << "  \"stage_seconds\": {";
  const auto names = s.pipeline.stage_names();
  for (std::size_t k = 0; k < names.size(); ++k)
    j << (k ? ", " : "") << "\n    \"" << names[k] << "\": " << s.pipeline.stage_seconds()[k];
  j << "\n  }";
  // On several ranks stage_seconds are rank 0's; the slowest rank's, stage by
  // stage, are beside them (a stage's time includes its waits for the others).
  if (ranks.stage_max.size() == names.size() && comm.size() > 1) {
    j << ",\n  \"stage_seconds_max_over_ranks\": {";
    for (std::size_t k = 0; k < names.size(); ++k)
      j << (k ? ", " : "") << "\n    \"" << names[k] << "\": " << ranks.stage_max[k];
    j << "\n  }";
  }
  // Figures some stages keep (the ARKODE driver: steps, rejections, evaluations).
  bool details = false;
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string d = s.pipeline.stages()[k]->summary_json();
    if (d.empty()) continue;
    j << (details ? ",\n    \"" : ",\n  \"stage_details\": {\n    \"") << names[k] << "\": {" << d << "}";
    details = true;
  }
  if (details) j << "\n  }";
  j << "\n}\n";
  if (!j) throw std::runtime_error("could not write '" + (opt_.out_dir / "summary.json").string() + "'");
  return r;
}

RunSummary run(Simulation& s, const RunOptions& opt) {
  Runner runner(s, opt);
  runner.advance(s.scene.clock.n_steps);
  return runner.finish();
}

std::string estimate_run_time(Simulation& s, double budget) {
  auto& sc = s.scene;
  const std::int64_t total = sc.clock.n_steps;
  if (total <= 0) return "run time: no steps\n";
  const auto& stages = s.pipeline.stages();
  for (const auto& st : stages)
    if (st->phase() != sim::Phase::Output) st->start(sc);
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  s.pipeline.initialize(sc);
  const double init = std::chrono::duration<double>(clock::now() - t0).count();
  const auto t1 = clock::now();
  std::int64_t k = 0;
  double took = 0;
  while (k < total && k < 200 && (k < 3 || took < budget)) {  // Pipeline::step without its output phase
    bool driven = false;
    for (const auto& st : stages)
      if (st->is_driver()) st->drive(sc, s.pipeline), driven = true;
    if (!driven)
      for (const auto& st : stages)
        if (st->phase() != sim::Phase::Output) st->run(sc);
    sc.clock.step += 1;
    sc.clock.time = static_cast<double>(sc.clock.step) * sc.clock.dt;
    ++k;
    took = std::chrono::duration<double>(clock::now() - t1).count();
  }
  const double per = took / static_cast<double>(k);
  const double run = init + per * static_cast<double>(total);
  auto span = [](double sec) {
    char b[64];
    if (sec < 120)
      std::snprintf(b, sizeof b, "%.3g s", sec);
    else if (sec < 7200)
      std::snprintf(b, sizeof b, "%.3g min", sec / 60);
    else
      std::snprintf(b, sizeof b, "%.3g h", sec / 3600);
    return std::string(b);
  };
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "run time: about %s for %lld steps on %d thread(s) (an estimate: the first %lld steps took %.3g ms "
                "each, the first neighbour build and forces %s; a bed that densifies, as a pour does, or gains "
                "grains runs slower later; outputs come on top); set-up: %s reading the case, %s building the "
                "scene\n",
                span(run).c_str(), static_cast<long long>(total), omp_get_max_threads(), static_cast<long long>(k),
                per * 1e3, span(init).c_str(), span(s.c.read_seconds).c_str(), span(s.build_seconds).c_str());
  return buf;
}

std::string describe(const Simulation& s) {
  std::ostringstream o;
  const auto& sc = s.scene;
  o << "case: " << s.c.path << "\n";
  o << "particles: " << sc.particles.n_owned();
  if (sc.bodies.size() > 0) o << " (of which the balls of " << sc.bodies.size() << " clumps)";
  o << " in " << s.c.scene.sets.size() << " set(s); walls: " << sc.walls.describe() << "\n";
  sc.walls.for_each([&](const auto& w, std::size_t) {  // kinds with more to say than their count
    if constexpr (requires { w.description(); }) o << w.description() << "\n";
  });
  o << "time step: " << sc.clock.dt << " s (" << sc.clock.dt / s.rayleigh_time << " Rayleigh times), "
    << sc.clock.n_steps << " steps to t = " << sc.clock.end_time << " s\n";
  o << "contact history per contact: " << sc.neighbors.history_size() << " doubles\n";
  if (sc.neighbors.reach() > 0)  // a law whose contacts hold in tension (JKR)
    o << "contacts hold up to " << sc.neighbors.reach() << " m beyond touching (the pull-off separation of the "
      << "largest grains against a wall); the neighbour lists, wall near lists and ghosts reach that far\n";
  {
    const auto& m = sc.memory;
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "memory: about %.3g MiB for the %lld particles the case asks for (fields %.0f bytes each, exact; "
                  "neighbour lists about %.0f bytes each in a dense bed at a rebuild%s, estimated; docs/memory.md)\n",
                  m.total() / 1048576.0, static_cast<long long>(m.particles), m.field_bytes, m.list_bytes,
                  sc.deterministic ? ", ordered force sums included" : "");
    o << buf;
  }
  o << "per-particle fields:";
  for (const auto& f : sc.particles.field_names()) o << " " << f;
  o << "\nstep pipeline:\n";
  for (const auto& n : s.pipeline.stage_names()) o << "  " << n << "\n";
  for (const auto& w : s.c.scene.warnings) o << w << "\n";
  return o.str();
}

}  // namespace grains::io
