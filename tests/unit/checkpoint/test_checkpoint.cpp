// Checkpoints: round trip of every field, bitwise continuation, the signal
// path with .pvd continuity, retention, invalid files and mismatched cases.
#include <algorithm>
#include <fstream>
#include <sstream>

#include "io/checkpoint/checkpoint.hpp"
#include "io/checkpoint/h5_file.hpp"

#include <hdf5.h>
#include "tests/unit/checkpoint/checkpoint_scene.hpp"

namespace grains::test {
namespace {

io::RunOptions quiet_into(const fs::path& dir) {
  io::RunOptions o;
  o.out_dir = dir;
  o.quiet = true;
  return o;
}

TEST(Checkpoint, RoundTripRestoresEveryFieldListAndWall) {
  TempDir tmp("roundtrip");
  auto a = make(silo_case());
  a.pipeline.initialize(a.scene);
  for (int k = 0; k < 437; ++k) a.pipeline.step(a.scene);  // mid-way between list builds
  const fs::path file = tmp.path / "x.h5";
  io::write_checkpoint(file, a.scene, {"silo.yaml", "text", "effective", {0.0, 1.0}, {0, 300}, {}, {}});
  ASSERT_TRUE(fs::exists(file));
  EXPECT_FALSE(fs::exists(tmp.path / ".x.h5.tmp"));

  auto b = make(silo_case());  // the initial state
  const auto x = io::read_checkpoint(file, b.scene);
  expect_same_state(a.scene, b.scene);
  EXPECT_EQ(x.case_text, "text");
  EXPECT_EQ(x.frame_steps, (std::vector<std::int64_t>{0, 300}));
  // (may_touch is a cache: restored as 1 for every entry, which only re-zeroes zero history.)
  ASSERT_EQ(a.scene.neighbors.may_touch.size(), b.scene.neighbors.may_touch.size());
  for (const auto t : b.scene.neighbors.may_touch) ASSERT_EQ(t, 1);
  EXPECT_EQ(a.scene.neighbors.wall_near, b.scene.neighbors.wall_near);
  EXPECT_GT(a.scene.walls.of<sim::PlaneWall>()[0].point.z(), 0.0);  // the floor moved, and came back moved

  // Readable by any HDF5 tool: units as attributes, format tags.
  const auto f = io::h5::File::open_read(file.string());
  EXPECT_EQ(f.read_attribute("/", "format"), "grains checkpoint");
  EXPECT_EQ(f.read_attribute("/particles/position", "units"), "m");
  EXPECT_EQ(f.read_attribute("/particles/velocity", "units"), "m/s");
  EXPECT_EQ(f.read_attribute("/particles/angular_velocity", "units"), "rad/s");
  EXPECT_EQ(f.read_attribute("/clock/time", "units"), "s");
  EXPECT_EQ(f.shape("/particles/position"), (std::pair<std::size_t, std::size_t>{300, 3}));
  EXPECT_EQ(f.shape("/neighbor/history").second, 6u);  // tangential + rolling
}

TEST(Checkpoint, ReadsTheWallNearListsOfEarlierCheckpoints) {
  // Before 2026-11-26 a checkpoint kept the planes' and the cylinders' near
  // lists in groups of their own: rewrite a new file into that layout (HDF5
  // links moved) and read it back.
  TempDir tmp("old_near");
  auto a = make(silo_case());
  a.pipeline.initialize(a.scene);
  for (int k = 0; k < 437; ++k) a.pipeline.step(a.scene);
  const fs::path file = tmp.path / "x.h5";
  io::write_checkpoint(file, a.scene, {"silo.yaml", "text", "effective", {}, {}, {}, {}});
  ASSERT_EQ(a.scene.neighbors.wall_near.size(), 2u);  // the floor, then the silo (its list may be empty)
  ASSERT_FALSE(a.scene.neighbors.wall_near[0].empty());
  {
    const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    for (const char* g : {"/neighbor/plane_near", "/neighbor/cylinder_near"}) H5Gclose(H5Gcreate2(f, g, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    EXPECT_GE(H5Lmove(f, "/neighbor/wall_near/0", f, "/neighbor/plane_near/0", H5P_DEFAULT, H5P_DEFAULT), 0);
    EXPECT_GE(H5Lmove(f, "/neighbor/wall_near/1", f, "/neighbor/cylinder_near/0", H5P_DEFAULT, H5P_DEFAULT), 0);
    EXPECT_GE(H5Ldelete(f, "/neighbor/wall_near", H5P_DEFAULT), 0);
    H5Fclose(f);
  }
  auto b = make(silo_case());
  (void)io::read_checkpoint(file, b.scene);
  EXPECT_EQ(a.scene.neighbors.wall_near, b.scene.neighbors.wall_near);
  expect_same_state(a.scene, b.scene);
}

TEST(Checkpoint, ContinuationIsBitwiseIdentical) {
  TempDir tmp("continue");
  auto full = make(silo_case());
  const auto rf = io::run(full, quiet_into(tmp.path / "full"));
  EXPECT_EQ(rf.steps, 1500);
  EXPECT_GT(full.scene.neighbors.stats().builds, 5);

  // Restart from step 750, then once more from the continuation's 1250.
  auto part = make(silo_case());
  auto opt = quiet_into(tmp.path / "part");
  opt.restart = tmp.path / "full" / "checkpoints" / io::checkpoint_name(750);
  const auto rp = io::run(part, opt);
  EXPECT_EQ(rp.steps, 1500);
  expect_same_state(full.scene, part.scene);

  auto again = make(silo_case());
  auto opt2 = quiet_into(tmp.path / "again");
  opt2.restart = tmp.path / "part" / "checkpoints" / io::checkpoint_name(1250);
  io::run(again, opt2);
  expect_same_state(full.scene, again.scene);
}

// Spheres compressed by growing radii (radius_growth) in a box of walls or a
// periodic box, through a schedule whose phase changes after the restart
// point: the servo (its last measurement, the rate in force, the phase) and
// the list's growth since its build are part of the state.
std::string growth_case(bool periodic) {
  const std::string walls = periodic ? "" : R"(
walls:
  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: grain}
  - {type: plane, point: [0, 0, 0.006], normal: [0, 0, -1], material: grain}
  - {type: plane, point: [0, 0, 0], normal: [0, 1, 0], material: grain}
  - {type: plane, point: [0, 0.006, 0], normal: [0, -1, 0], material: grain}
  - {type: plane, point: [0, 0, 0], normal: [1, 0, 0], material: grain}
  - {type: plane, point: [0.006, 0, 0], normal: [-1, 0, 0], material: grain})";
  return std::string(R"(
domain: {min: [0, 0, 0], max: [0.006, 0.006, 0.006], periodic: )") +
         (periodic ? "[true, true, true]" : "[false, false, false]") + R"(}
materials:
  - {name: grain, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, restitution: 0.1, friction: 0.0}
particles:
  - name: spheres
    material: grain
    radius: 0.0004
    count: 120
    placement: {type: random_fill, region: {min: [0.0004, 0.0004, 0.0004], max: [0.0056, 0.0056, 0.0056]}, seed: 3}
radius_growth:
  phases:
    - {rate: 20.0, target_overlap: 2.0e-3, until: 0.02}
    - {rate: 5.0, target_overlap: 1.0e-3, until: 0.04}
  max_scale: 1.6)" + walls + R"(
time: {dt_rayleigh: 0.28, end: 0.05}
output: {vtk: false, progress: false}
checkpoint: {every_steps: 1000, keep: 10}
)";
}

TEST(Checkpoint, RadiusGrowthContinuesBitwise) {
  for (const bool periodic : {false, true}) {
    SCOPED_TRACE(periodic ? "periodic box" : "box of walls");
    TempDir tmp(periodic ? "growth_periodic" : "growth_walls");
    auto full = make(growth_case(periodic));
    const auto rf = io::run(full, quiet_into(tmp.path / "full"));
    ASSERT_GT(rf.steps, 3000);
    EXPECT_TRUE(full.scene.growth.started);
    EXPECT_GT(full.scene.growth.overlap, 0.0);  // the packing was compressed into contact
    // Restart from step 1000 (first phase), and the continuation again from 3000 (second phase).
    auto part = make(growth_case(periodic));
    auto opt = quiet_into(tmp.path / "part");
    opt.restart = tmp.path / "full" / "checkpoints" / io::checkpoint_name(1000);
    io::run(part, opt);
    auto again = make(growth_case(periodic));
    auto opt2 = quiet_into(tmp.path / "again");
    opt2.restart = tmp.path / "part" / "checkpoints" / io::checkpoint_name(3000);
    io::run(again, opt2);
    if (!periodic) {
      expect_same_state(full.scene, part.scene);
      expect_same_state(full.scene, again.scene);
    } else {
      // A periodic run's checkpoint holds the lists in the rank-independent
      // form and the continuation rebuilds them: the particles and the servo
      // must still agree bitwise.
      // (The particles may be stored in another order: compared by id.)
      auto by_id = [](const sim::ParticleStore& p) {
        std::vector<std::size_t> k(p.n_owned());
        for (std::size_t i = 0; i < k.size(); ++i) k[i] = i;
        std::sort(k.begin(), k.end(), [&](auto i, auto j) { return p.id[i] < p.id[j]; });
        std::vector<double> v;
        for (auto i : k) v.insert(v.end(), {p.x[i].x(), p.x[i].y(), p.x[i].z(), p.v[i].x(), p.v[i].y(), p.v[i].z(),
                                            p.radius[i], p.mass[i]});
        return v;
      };
      for (auto* b : {&part, &again}) {
        EXPECT_TRUE(bytes(by_id(full.scene.particles)) == bytes(by_id(b->scene.particles)))
            << "positions, velocities, radii or masses differ";
        EXPECT_EQ(std::memcmp(&full.scene.growth.rate, &b->scene.growth.rate, sizeof(double)), 0);
        EXPECT_EQ(full.scene.growth.last_measure, b->scene.growth.last_measure);
      }
    }
  }
}

TEST(Checkpoint, SignalWritesCheckpointAndResumeContinuesThePvdSeries) {
  TempDir tmp("signal");
  auto full = make(silo_case());
  io::run(full, quiet_into(tmp.path / "full"));

  auto first = make(silo_case());
  first.pipeline.add(std::make_unique<RaiseAt>(1013, SIGTERM));
  auto opt = quiet_into(tmp.path / "cut");
  opt.handle_signals = true;
  const auto r1 = io::run(first, opt);
  EXPECT_EQ(r1.signal, SIGTERM);
  EXPECT_EQ(r1.steps, 1013);
  EXPECT_EQ(fs::path(r1.checkpoint).filename(), io::checkpoint_name(1013));
  EXPECT_NE(read_text(tmp.path / "cut" / "summary.json").find("\"interrupted_by_signal\": 15"), std::string::npos);

  auto second = make(silo_case());
  auto opt2 = quiet_into(tmp.path / "cut");
  opt2.restart = io::newest_valid_checkpoint(tmp.path / "cut" / "checkpoints");
  EXPECT_EQ(opt2.restart.filename(), io::checkpoint_name(1013));
  io::run(second, opt2);
  expect_same_state(full.scene, second.scene);
  // The same series: no duplicated and no missing frame.
  EXPECT_EQ(read_text(tmp.path / "cut" / "particles.pvd"), read_text(tmp.path / "full" / "particles.pvd"));
  EXPECT_EQ(read_text(tmp.path / "cut" / "walls.pvd"), read_text(tmp.path / "full" / "walls.pvd"));
}

TEST(Checkpoint, KeepsTheNewestAndSkipsInvalidFiles) {
  TempDir tmp("keep");
  auto s = make(silo_case("{every_steps: 100, keep: 2}"));
  io::run(s, quiet_into(tmp.path));
  const fs::path dir = tmp.path / "checkpoints";
  auto all = io::list_checkpoints(dir);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].filename(), io::checkpoint_name(1400));
  EXPECT_EQ(all[1].filename(), io::checkpoint_name(1500));

  // A truncated file under a newer name (as a broken disk might leave) and an
  // empty one are skipped; the temporary of an interrupted write is ignored.
  {
    std::ifstream in(all[1], std::ios::binary);
    std::string data((std::istreambuf_iterator<char>(in)), {});
    std::ofstream(dir / io::checkpoint_name(1600), std::ios::binary) << data.substr(0, data.size() / 2);
    std::ofstream(dir / io::checkpoint_name(1700)) << "";
    std::ofstream(dir / ".checkpoint_000000001800.h5.tmp") << "partial";
  }
  std::vector<std::string> skipped;
  EXPECT_EQ(io::newest_valid_checkpoint(dir, &skipped).filename(), io::checkpoint_name(1500));
  EXPECT_EQ(skipped.size(), 2u);
  io::prune_checkpoints(dir, 5);
  EXPECT_FALSE(fs::exists(dir / ".checkpoint_000000001800.h5.tmp"));
}

TEST(Checkpoint, RefusesACheckpointOfADifferentCase) {
  TempDir tmp("mismatch");
  auto a = make(silo_case());
  a.pipeline.initialize(a.scene);
  const fs::path file = tmp.path / "a.h5";
  io::write_checkpoint(file, a.scene, {});
  auto expect_error = [&](const std::vector<std::string>& sets, const std::string& what) {
    auto b = make(silo_case(), sets);
    try {
      io::read_checkpoint(file, b.scene);
      ADD_FAILURE() << "no error for " << sets[0];
    } catch (const io::CheckpointError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  expect_error({"time.dt=4.0e-6"}, "a restart keeps the time step");
  expect_error({"materials.0.rolling_friction=0"}, "different contact-law slots");
  expect_error({"walls.1={type: plane, name: lid, point: [0, 0, 0.03], normal: [0, 0, -1], material: grain}"},
               "1 plane wall(s), the case has 2");
  EXPECT_THROW(io::checkpoint_info(tmp.path / "missing.h5"), io::CheckpointError);
}

// A stage of frictionless spheres keeps no rotation state and no contact
// history; a frictional case may continue from it (cases/triaxial: a dense
// sample consolidated frictionless, then sheared): those start as a new
// particle's and a new contact's. The other way round stays refused.
TEST(Checkpoint, AFrictionlessStageContinuesAsAFrictionalOne) {
  TempDir tmp("frictionless");
  const std::vector<std::string> frictionless = {"materials.0.friction=0", "materials.0.rolling_friction=0"};
  auto a = make(silo_case(), frictionless);
  a.pipeline.initialize(a.scene);
  for (int k = 0; k < 300; ++k) a.pipeline.step(a.scene);
  ASSERT_EQ(a.scene.neighbors.history_size(), 0);
  ASSERT_TRUE(a.scene.particles.omega.empty());
  const fs::path file = tmp.path / "frictionless.h5";
  io::write_checkpoint(file, a.scene, {});

  auto b = make(silo_case());
  const int H = b.scene.neighbors.history_size();
  ASSERT_GT(H, 0);
  const auto x = io::read_checkpoint(file, b.scene);
  EXPECT_EQ(x.fresh_fields, (std::vector<std::string>{"angular_velocity", "torque", "inertia", "wall_history"}));
  const auto& p = b.scene.particles;
  ASSERT_EQ(p.n_owned(), a.scene.particles.n_owned());
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    EXPECT_EQ(p.x[i], a.scene.particles.x[i]);
    EXPECT_EQ(p.v[i], a.scene.particles.v[i]);
    EXPECT_EQ(p.omega[i], sim::Vec3::Zero());
    EXPECT_EQ(p.torque[i], sim::Vec3::Zero());
    const double I = 0.4 * p.mass[i] * p.radius[i] * p.radius[i];
    EXPECT_EQ(p.inertia[i], sim::Vec3(I, I, I));
  }
  EXPECT_TRUE(std::all_of(p.wall_history.begin(), p.wall_history.end(), [](double h) { return h == 0.0; }));
  const auto& nl = b.scene.neighbors;
  EXPECT_EQ(nl.partner, a.scene.neighbors.partner);
  EXPECT_EQ(nl.history.size(), nl.partner.size() * static_cast<std::size_t>(H));
  EXPECT_TRUE(std::all_of(nl.history.begin(), nl.history.end(), [](double h) { return h == 0.0; }));
  // It runs on, frictional: the grains start to spin.
  for (int k = 0; k < 300; ++k) b.pipeline.step(b.scene);
  double spin = 0;
  for (const auto& w : b.scene.particles.omega) spin = std::max(spin, w.norm());
  EXPECT_GT(spin, 0.0);

  // Such a checkpoint holding a non-spherical particle was written for
  // another case (other shapes always rotate): refused, saying so.
  {
    const fs::path odd = tmp.path / "odd.h5";
    fs::copy_file(file, odd);
    const hid_t h = H5Fopen(odd.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(h, 0);
    const hid_t d = H5Dopen2(h, "/particles/shape", H5P_DEFAULT);
    std::vector<std::int32_t> shape(a.scene.particles.n_owned(), 0);
    shape[7] = sim::kEllipsoid;
    EXPECT_GE(H5Dwrite(d, H5T_NATIVE_INT32, H5S_ALL, H5S_ALL, H5P_DEFAULT, shape.data()), 0);
    H5Dclose(d);
    H5Fclose(h);
    auto e = make(silo_case());
    try {
      io::read_checkpoint(odd, e.scene);
      ADD_FAILURE() << "no error for a non-spherical particle without rotation state";
    } catch (const io::CheckpointError& err) {
      EXPECT_NE(std::string(err.what()).find("has no particle field 'angular_velocity' and holds non-spherical "
                                             "particles"),
                std::string::npos)
          << err.what();
    }
  }

  // The other way round a checkpoint's state would be dropped: refused.
  const fs::path frictional = tmp.path / "frictional.h5";
  io::write_checkpoint(frictional, b.scene, {});
  auto c = make(silo_case(), frictionless);
  EXPECT_THROW(io::read_checkpoint(frictional, c.scene), io::CheckpointError);
}

TEST(Checkpoint, CaseSectionIsValidatedWithLocations) {
  try {
    make(silo_case("{every: 0.001, keep: 0, evry_steps: 3}"));
    ADD_FAILURE() << "no error";
  } catch (const io::CaseError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("silo.yaml:18:37: checkpoint: unknown key"), std::string::npos) << m;
    EXPECT_NE(m.find("unknown key 'evry_steps'; did you mean 'every_steps'?"), std::string::npos) << m;
    EXPECT_NE(m.find("silo.yaml:18:34: checkpoint: keep = 0 is out of range; valid: [1, 1000000]"), std::string::npos) << m;
  }
  const auto s = make(silo_case("{every: 0.0024}"));
  EXPECT_EQ(s.c.checkpoint.every, 0.0024);
  EXPECT_EQ(s.c.checkpoint.keep, 3);
}

}  // namespace
}  // namespace grains::test
