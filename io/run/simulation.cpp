#include "io/run/simulation.hpp"

#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>

#include "io/output/progress.hpp"
#include "io/output/vtk_output.hpp"
#include "grains/version.hpp"

namespace grains::io {

Simulation make_simulation(Case c) {
  Simulation s;
  s.c = std::move(c);
  s.scene = sim::build_scene(s.c.scene);
  s.rayleigh_time = sim::rayleigh_time(s.c.scene);
  s.pipeline = sim::assemble_pipeline(s.scene, s.c.scene);
  return s;
}

namespace {
std::int64_t frame_steps(const OutputConfig& o, double dt) {
  if (o.every_steps > 0) return o.every_steps;
  if (o.every > 0) return std::max<std::int64_t>(1, std::llround(o.every / dt));
  return 0;
}
}  // namespace

void add_output_stages(Simulation& s, const RunOptions& opt) {
  const auto& o = s.c.output;
  s.pipeline.add(std::make_unique<BlowUpCheck>(s.scene, s.rayleigh_time));
  if (o.vtk) s.pipeline.add(std::make_unique<VtkOutput>(opt.out_dir, frame_steps(o, s.scene.clock.dt)));
  if (o.progress && !opt.quiet) s.pipeline.add(std::make_unique<Progress>(*opt.log, o.progress_interval));
}

RunSummary run(Simulation& s, const RunOptions& opt) {
  std::filesystem::create_directories(opt.out_dir);
  add_output_stages(s, opt);
  for (const auto& w : s.c.scene.warnings)
    if (!opt.quiet) *opt.log << w << "\n";
  RunSummary r;
  r.particles_start = s.scene.particles.n_owned();
  const auto t0 = std::chrono::steady_clock::now();
  s.pipeline.initialize(s.scene);
  for (const auto& st : s.pipeline.stages())
    if (auto* v = dynamic_cast<VtkOutput*>(st.get())) v->write_frame(s.scene);
  double particle_steps = 0;
  while (s.scene.clock.step < s.scene.clock.n_steps) {
    particle_steps += static_cast<double>(s.scene.particles.n_owned());
    s.pipeline.step(s.scene);
  }
  s.pipeline.finish(s.scene);
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.steps = s.scene.clock.step;
  r.simulated_time = s.scene.clock.time;
  r.particle_steps_per_second = r.wall_seconds > 0 ? particle_steps / r.wall_seconds : 0;
  r.particles_end = s.scene.particles.n_owned();
  r.lost_particles = s.scene.lost_particles;
  r.neighbor_builds = s.scene.neighbors.stats().builds;
  for (const auto& st : s.pipeline.stages())
    if (auto* v = dynamic_cast<VtkOutput*>(st.get())) r.frames = v->frames();

  std::ofstream j(opt.out_dir / "summary.json");
  j.precision(10);
  j << "{\n  \"grains_version\": \"" << kVersion << "\",\n  \"case\": \"" << s.c.path << "\",\n"
    << "  \"steps\": " << r.steps << ",\n  \"simulated_time_s\": " << r.simulated_time << ",\n"
    << "  \"time_step_s\": " << s.scene.clock.dt << ",\n  \"wall_time_s\": " << r.wall_seconds << ",\n"
    << "  \"particle_steps_per_second\": " << r.particle_steps_per_second << ",\n"
    << "  \"particles_start\": " << r.particles_start << ",\n  \"particles_end\": " << r.particles_end << ",\n"
    << "  \"lost_particles\": " << r.lost_particles << ",\n  \"neighbor_builds\": " << r.neighbor_builds << ",\n"
    << "  \"frames\": " << r.frames << ",\n  \"stage_seconds\": {";
  const auto names = s.pipeline.stage_names();
  for (std::size_t k = 0; k < names.size(); ++k)
    j << (k ? ", " : "") << "\n    \"" << names[k] << "\": " << s.pipeline.stage_seconds()[k];
  j << "\n  }\n}\n";
  if (!j) throw std::runtime_error("could not write '" + (opt.out_dir / "summary.json").string() + "'");
  return r;
}

std::string describe(const Simulation& s) {
  std::ostringstream o;
  const auto& sc = s.scene;
  o << "case: " << s.c.path << "\n";
  o << "particles: " << sc.particles.n_owned() << " in " << s.c.scene.sets.size() << " set(s); walls: "
    << sc.walls.planes.size() << " plane(s), " << sc.walls.cylinders.size() << " cylinder(s)\n";
  o << "time step: " << sc.clock.dt << " s (" << sc.clock.dt / s.rayleigh_time << " Rayleigh times), "
    << sc.clock.n_steps << " steps to t = " << sc.clock.end_time << " s\n";
  o << "contact history per contact: " << sc.neighbors.history_size() << " doubles\n";
  o << "per-particle fields:";
  for (const auto& f : sc.particles.field_names()) o << " " << f;
  o << "\nstep pipeline:\n";
  for (const auto& n : s.pipeline.stage_names()) o << "  " << n << "\n";
  for (const auto& w : s.c.scene.warnings) o << w << "\n";
  return o.str();
}

}  // namespace grains::io
