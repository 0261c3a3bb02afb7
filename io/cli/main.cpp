// The grains command line: run, check, docs and the tools built on the
// library. Every user error ends in a message that says what was wrong,
// where, and what is valid; exit status 2 for bad input, 1 for failures.
#include <csignal>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "grains/version.hpp"
#include "io/case/case.hpp"
#include "io/checkpoint/checkpoint.hpp"
#include "io/cli/commands.hpp"
#include "io/output/progress.hpp"
#include "io/run/allocator.hpp"
#include "io/run/simulation.hpp"
#include "sim/parallel/comm.hpp"

namespace {

const char* kUsage =
    "grains — discrete-element simulation of granular matter\n"
    "\n"
    "usage:\n"
    "  grains run CASE.yaml [-o OUTDIR] [--set key.path=value ...] [-q]\n"
    "             [--restart CHECKPOINT.h5 | --resume OUTDIR]\n"
    "      run a case; writes VTK frames (particles.pvd, walls.pvd) and summary.json to OUTDIR\n"
    "      (default out/<case name>); progress on stderr unless -q. --restart continues from a\n"
    "      checkpoint, --resume from the newest valid one in OUTDIR/checkpoints (and writes to OUTDIR);\n"
    "      SIGINT/SIGTERM stop the run with a checkpoint (exit status 128+signal)\n"
    "  grains check CASE.yaml [--set key.path=value ...]\n"
    "      validate a case and print the assembled step pipeline and per-particle fields\n"
    "  grains docs [EFFECT]\n"
    "      the case-file keys each effect accepts (all effects, or one, e.g. 'grains docs materials')\n"
    "  grains analyze OUTDIR [--frame N] [--region xmin,ymin,zmin,xmax,ymax,zmax] [-o DIR]\n"
    "      packing fraction, coordination, RDF, order, contact forces and profiles of a frame (grains analyze -h)\n"
    "  grains render OUTDIR [--frame N] [--color FIELD] -o snapshot.png\n"
    "      an offscreen picture of a frame (grains render -h)\n"
    "  grains repose OUTDIR [--axis x|y] [--centre X,Y,Z] [--from T] [--to T] [-o DIR]\n"
    "      dynamic angle of repose of the free surface in a rotating drum, over the frames (grains repose -h)\n"
    "  grains pw85 [FILE]\n"
    "      Perram-Wertheim contact function of ellipsoid pairs from CSV (stdin without FILE):\n"
    "      columns q1_0..q1_5,q2_0..q2_5,r_0,r_1,r_2 in, the same plus mu2,lambda out\n"
    "  grains clump MESH [--grid N] [--mu 0.25] [-o CLUMP.yaml]\n"
    "      sphere decomposition of a closed mesh (STL/OBJ/OFF) into a rigid clump of balls\n"
    "  grains --help | --version\n"
    "\n"
    "--set overrides a case-file value before validation; list entries by index,\n"
    "e.g. --set time.end=0.5 --set materials.0.friction=0.3\n";

struct RunArgs {
  std::string case_path;
  std::string out;
  std::vector<std::string> sets;
  bool quiet = false;
  std::string restart, resume;
};

// Parses the arguments shared by run and check; returns false on a usage error.
bool parse_run_args(const std::vector<std::string>& a, RunArgs& r, bool allow_out) {
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string& s = a[i];
    if ((s == "-o" || s == "--out") && allow_out) {
      if (i + 1 >= a.size()) return std::cerr << "grains: " << s << " needs a folder\n", false;
      r.out = a[++i];
    } else if (s == "--set") {
      if (i + 1 >= a.size()) return std::cerr << "grains: --set needs key.path=value\n", false;
      r.sets.push_back(a[++i]);
    } else if (s.rfind("--set=", 0) == 0) {
      r.sets.push_back(s.substr(6));
    } else if ((s == "--restart" || s == "--resume") && allow_out) {
      if (i + 1 >= a.size())
        return std::cerr << "grains: " << s << (s == "--restart" ? " needs a checkpoint file\n" : " needs a folder\n"), false;
      (s == "--restart" ? r.restart : r.resume) = a[++i];
      if (!r.restart.empty() && !r.resume.empty())
        return std::cerr << "grains: give either --restart or --resume, not both\n", false;
    } else if ((s == "-q" || s == "--quiet") && allow_out) {
      r.quiet = true;
    } else if (!s.empty() && s[0] == '-') {
      return std::cerr << "grains: unknown option '" << s << "'\n\n" << kUsage, false;
    } else if (r.case_path.empty()) {
      r.case_path = s;
    } else {
      return std::cerr << "grains: unexpected argument '" << s << "' (one case file only)\n", false;
    }
  }
  if (r.case_path.empty()) return std::cerr << "grains: missing the case file\n\n" << kUsage, false;
  return true;
}

int cmd_run(const std::vector<std::string>& a, bool check_only) {
  RunArgs r;
  if (!parse_run_args(a, r, !check_only)) return 2;
  const auto& comm = grains::sim::Comm::world();
  // Under MPI only rank 0 talks; set-up errors are the same on every rank.
  std::ostringstream sink;
  std::ostream& out = comm.root() ? std::cout : sink;
  std::ostream& err = comm.root() ? std::cerr : sink;
  try {
    auto sim = grains::io::make_simulation(grains::io::load_case(r.case_path, r.sets));
    if (check_only) {
      grains::io::RunOptions opt;
      grains::io::add_output_stages(sim, opt);
      out << "case is valid\n" << grains::io::describe(sim);
      if (!comm.parallel()) out << grains::io::estimate_run_time(sim);  // (last: it advances the simulation)
      return 0;
    }
    grains::io::RunOptions opt;
    opt.out_dir = r.out.empty() ? std::filesystem::path("out") / std::filesystem::path(r.case_path).parent_path().filename()
                                : std::filesystem::path(r.out);
    if (r.out.empty() && std::filesystem::path(r.case_path).parent_path().filename().empty())
      opt.out_dir = std::filesystem::path("out") / std::filesystem::path(r.case_path).stem();
    opt.quiet = r.quiet;  // the same on every rank: stages must match across ranks
    opt.handle_signals = true;
    if (!r.resume.empty()) {
      if (r.out.empty()) opt.out_dir = r.resume;
      std::vector<std::string> skipped;
      opt.restart = grains::io::newest_valid_checkpoint(std::filesystem::path(r.resume) / "checkpoints", &skipped);
      for (const auto& why : skipped) err << "grains: skipping " << why << "\n";
      if (opt.restart.empty()) {
        err << "grains: no valid checkpoint in '" << (std::filesystem::path(r.resume) / "checkpoints").string()
                  << "' to resume from; run without --resume to start from the beginning\n";
        return 2;
      }
    } else if (!r.restart.empty()) {
      opt.restart = r.restart;
    }
    const auto sum = grains::io::run(sim, opt);
    if (sum.signal != 0) {
      err << "grains: stopped by " << (sum.signal == SIGINT ? "SIGINT" : sum.signal == SIGTERM ? "SIGTERM" : "a signal")
                << " at step " << sum.steps << " (t = " << sum.simulated_time << " s); checkpoint: " << sum.checkpoint
                << "\nresume with: grains run " << r.case_path << " --resume " << opt.out_dir.string() << "\n";
      return 128 + sum.signal;
    }
    if (!r.quiet) {
      out << "steps: " << sum.steps << "  simulated: " << sum.simulated_time << " s  wall: " << sum.wall_seconds
                << " s  throughput: " << sum.particle_steps_per_second << " particle-steps/s\n"
                << "particles: " << sum.particles_end << " (lost " << sum.lost_particles << ")  neighbour builds: "
                << sum.neighbor_builds << "  frames: " << sum.frames << "\n"
                << "output: " << opt.out_dir.string() << " (open particles.pvd in ParaView)\n";
    }
    return 0;
  } catch (const grains::io::CaseError& e) {
    err << e.what() << "\n";
    return 2;
  } catch (const grains::sim::SetupError& e) {
    err << e.what() << "\n";
    return 2;
  } catch (const grains::io::CheckpointError& e) {
    err << "grains: " << e.what() << "\n";
    return 2;
  } catch (const grains::io::BlowUp& e) {
    err << "grains: " << e.what() << "\n";
    return 1;
  } catch (const grains::io::OutputFailure& e) {
    // Agreed on by every rank (the outputs and checkpoints agree on their
    // errors before the run saves its state), so all stop here together.
    err << "grains: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    // An error that not every rank saw: say which rank, and stop them all
    // (the others may be waiting in a collective).
    if (comm.parallel()) {
      std::cerr << "grains: rank " << comm.rank() << ": " << e.what() << "\n" << std::flush;
      comm.abort(1);
    }
    err << "grains: " << e.what() << "\n";
    return 1;
  }
}

int cmd_docs(const std::vector<std::string>& a) {
  grains::io::register_io_docs();
  if (a.size() > 1) return std::cerr << "grains docs takes at most one effect name\n", 2;
  const auto& all = grains::sim::effect_docs();
  if (a.empty()) {
    std::cout << "Case-file sections and effects (grains docs NAME for one):\n\n";
    for (const auto& d : all) std::cout << grains::io::format_doc(d) << "\n";
    return 0;
  }
  if (const auto* d = grains::sim::find_effect_doc(a[0])) {
    std::cout << grains::io::format_doc(*d);
    return 0;
  }
  std::cerr << "grains docs: no effect named '" << a[0] << "'; known:";
  for (const auto& d : all) std::cerr << " " << d.name;
  std::cerr << "\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  grains::io::set_allocator_policy();
  // MPI starts only when mpirun launched us; a plain run stays serial.
  grains::sim::Comm::init(&argc, &argv);
  struct Finalize {
    ~Finalize() { grains::sim::Comm::finalize(); }
  } finalize;
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    std::cout << kUsage;
    return args.empty() ? 2 : 0;
  }
  if (args[0] == "--version") {
    std::cout << "grains " << grains::kVersion << "\n";
    return 0;
  }
  const std::string cmd = args[0];
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (cmd == "run") return cmd_run(rest, false);
  if (cmd == "check") return cmd_run(rest, true);
  if (cmd == "docs") return cmd_docs(rest);
  if (const int rc = grains::io::run_tool_command(cmd, rest); rc >= 0) return rc;
  std::cerr << "grains: unknown command '" << cmd << "'\n\n" << kUsage;
  return 2;
}
