"""Every entry point of the Python API, and its misuse."""
import json
import os

import numpy as np
import pytest

import grains

from conftest import ROOT


# ------------------------------------------------------------------ cases

def test_case_from_file_with_edits():
    c = grains.Case(ROOT / "tests/integration/restart_case.yaml", set={"time.end": 0.01})
    assert c["time.end"] == 0.01
    assert c["particles.0.count"] == 2000
    assert c.end_time == pytest.approx(0.01)
    c.set("materials.0.friction", 0.3)
    assert c.to_dict()["materials"][0]["friction"] == 0.3
    assert "friction: 0.3" in c.text
    assert [e.split("=")[0] for e in c.edits] == ["time.end", "materials.0.friction"]


def test_case_from_dict_round_trip(pour):
    c = grains.Case(pour)
    d = c.to_dict()
    assert d["particles"][0]["count"] == 300
    assert d["walls"][2]["point"] == [0.01, 0, 0]
    assert grains.Case(d).to_dict() == d


def test_case_errors_are_located_and_listed(pour):
    pour["time"]["dtt"] = 1e-6
    pour["materials"][0]["friction"] = -1
    with pytest.raises(grains.CaseError) as e:
        grains.Case(pour)
    assert isinstance(e.value, ValueError)
    msgs = e.value.messages
    assert len(msgs) >= 2
    assert any("dtt" in m and "<dict>:" in m for m in msgs)
    assert any("friction" in m for m in msgs)


def test_an_invalid_edit_is_not_kept(pour):
    c = grains.Case(pour)
    with pytest.raises(grains.CaseError, match="friction"):
        c.set("materials.0.friction", "slippery")
    assert c["materials.0.friction"] == 0.5
    assert c.edits == []
    with pytest.raises(KeyError):
        c.set("time.end=3", 1)
    with pytest.raises(KeyError):
        c["time.nothing"]
    assert c.get("time.nothing", 7) == 7


def test_case_rejects_what_yaml_cannot_hold(pour):
    pour["time"]["end"] = object()
    with pytest.raises(TypeError, match="time.end"):
        grains.Case(pour)
    with pytest.raises(TypeError):
        grains.Case(42)
    with pytest.raises(grains.CaseError, match="cannot open"):
        grains.Case("/nonexistent/case.yaml")


def test_numpy_values_in_a_case(pour):
    pour["gravity"] = np.array([0.0, 0.0, -9.81])
    pour["particles"][0]["count"] = np.int64(300)
    c = grains.Case(pour)
    assert c["gravity"] == [0.0, 0.0, -9.81]
    assert c["particles.0.count"] == 300


def test_setup_errors_raise(pour, out):
    pour["time"]["dt"] = 1e-2  # far above the Rayleigh time
    with pytest.raises(grains.SetupError, match="Rayleigh"):
        grains.Simulation(grains.Case(pour), out=out)


# ------------------------------------------------------------------ running

def test_step_run_and_close(pour, out):
    sim = grains.Simulation(pour, out=out)
    assert sim.n_particles == 300
    assert sim.step_count == 0 and sim.time == 0
    assert sim.step(10) == 10
    assert sim.step_count == 10
    assert sim.time == pytest.approx(10 * sim.dt)
    sim.run(until=0.001)
    assert sim.step_count == 125
    seen = []
    sim.run(until=0.002, every=25, callback=lambda s: seen.append(s.step_count))
    assert seen == list(range(150, 251, 25))
    summary = sim.close()
    assert summary["steps"] == 250
    assert json.loads((out / "summary.json").read_text())["steps"] == 250
    assert sim.closed
    with pytest.raises(RuntimeError, match="closed"):
        sim.step()
    with pytest.raises(RuntimeError, match="closed"):
        sim.positions
    assert sim.close() is summary  # closing twice is harmless


def test_run_to_the_end_and_past_it(pour, out):
    with grains.Simulation(pour, out=out) as sim:
        sim.run()
        assert sim.step_count == 500
        sim.run(until=0.0048)  # the end moves
        assert sim.step_count == 600
        assert sim.end_time == pytest.approx(0.0048)
    assert sim.summary["steps"] == 600


def test_run_until_a_condition(pour, out):
    with grains.Simulation(pour, out=out) as sim:
        # The grains start at -0.3 m/s and fall: the condition stops the run
        # (free fall reaches -0.32 m/s after 2 ms).
        sim.run(until=lambda s: s.velocities[:, 2].min() < -0.32, every=10)
        assert sim.velocities[:, 2].min() < -0.32
        assert sim.step_count % 10 == 0 and sim.step_count < 500
        with pytest.raises(ValueError):
            sim.run(every=0)


def test_a_callback_that_raises_stops_the_run_and_leaves_it_usable(pour, out):
    with grains.Simulation(pour, out=out) as sim:
        def boom(s):
            if s.step_count >= 40:
                raise RuntimeError("stop here")
        with pytest.raises(RuntimeError, match="stop here"):
            sim.run(every=20, callback=boom)
        assert sim.step_count == 40
        sim.step(5)
        assert sim.step_count == 45


def test_gravity_between_stages(pour, gas, out, tmp_path):
    with grains.Simulation(pour, out=out) as sim:
        assert sim.gravity == (0, 0, -9.81)
        sim.gravity = (4.0, 0, -9.0)
        sim.step(1)
        assert sim.gravity == (4.0, 0, -9.0)
        with pytest.raises(ValueError):
            sim.gravity = (0, float("nan"), 0)
        with pytest.raises(ValueError):
            sim.gravity = (0, 0)
    with grains.Simulation(gas, out=tmp_path / "gas") as sim:
        with pytest.raises(ValueError, match="no gravity stage"):
            sim.gravity = (0, 0, -9.81)


# ------------------------------------------------------------------ views

def test_views_are_the_store_memory(pour, out):
    with grains.Simulation(pour, out=out) as sim:
        for name in ("positions", "velocities", "forces", "radii", "ids", "angular_velocities"):
            a = getattr(sim, name)
            assert a.__array_interface__["data"][0] == sim._address(name), name
            assert a.shape[0] == 300
        assert sim.positions.dtype == np.float64 and sim.positions.shape == (300, 3)
        assert sim.ids.dtype == np.int64
        assert not sim.forces.flags.writeable and not sim.radii.flags.writeable
        assert sim.velocities.flags.writeable
        assert set(sim.field_names) >= {"positions", "velocities", "angular_velocities"}


def test_a_write_through_a_view_is_seen_by_the_next_step(gas, out):
    with grains.Simulation(gas, out=out) as sim:
        x0 = sim.positions.copy()
        v = sim.velocities
        v[3] = (0.5, -0.25, 0.125)  # written in place: no copy made
        sim.step(4)
        x = sim.positions
        dx = x[3] - x0[3]
        np.testing.assert_allclose(dx, np.array([0.5, -0.25, 0.125]) * 4 * sim.dt, rtol=0, atol=1e-16)
        np.testing.assert_array_equal(x[0], x0[0])  # the others did not move


def test_a_view_held_across_a_step_becomes_a_read_only_snapshot(pour, out):
    with grains.Simulation(pour, out=out) as sim:
        held = sim.positions
        before = held.copy()
        sim.step(50)
        assert not held.flags.writeable
        np.testing.assert_array_equal(held, before)  # its memory is alive and unchanged
        with pytest.raises(ValueError):
            held[0, 0] = 1.0
        live = sim.positions
        assert live.__array_interface__["data"][0] == sim._address("positions")
        assert not np.array_equal(live, before)  # the grains fell
        del sim
    assert held.sum() == pytest.approx(before.sum())  # still readable after the simulation closed


def test_absent_fields(pour, out):
    with grains.Simulation(pour, out=out) as sim:
        with pytest.raises(AttributeError, match="ellipsoids"):
            sim.orientations
        with pytest.raises(AttributeError, match="clumps"):
            sim.body_ids
        with pytest.raises(KeyError):
            sim.field("temperature")


def test_set_field_validates_before_writing(gas, out):
    with grains.Simulation(gas, out=out) as sim:
        n = sim.n_particles
        good = np.zeros((n, 3))
        good[:, 0] = 0.01
        sim.velocities = good
        np.testing.assert_array_equal(sim.velocities, good)
        sim.velocities = np.ones((n, 3), dtype=np.int32)  # integers convert
        with pytest.raises(TypeError, match="dtype"):
            sim.velocities = np.ones((n, 3), dtype=complex)
        with pytest.raises(TypeError):
            sim.velocities = [["a", "b", "c"]] * n
        with pytest.raises(ValueError, match="shape"):
            sim.velocities = np.zeros((n, 2))
        with pytest.raises(ValueError, match="shape"):
            sim.velocities = np.zeros(3 * n)
        bad = np.ones((n, 3))
        bad[2, 1] = np.nan
        with pytest.raises(ValueError, match="not finite"):
            sim.velocities = bad
        np.testing.assert_array_equal(sim.velocities, np.ones((n, 3)))  # nothing was written
        with pytest.raises(ValueError, match="cannot be written"):
            sim.forces = np.zeros((n, 3))
        far = sim.positions.copy()
        far[0, 2] = 5.0
        with pytest.raises(ValueError, match="outside the domain"):
            sim.positions = far


def test_nan_written_through_a_view_stops_the_step(gas, out):
    with grains.Simulation(gas, out=out) as sim:
        v = sim.velocities
        v[1, 0] = np.inf
        with pytest.raises(ValueError, match="not finite"):
            sim.step(1)
        assert sim.step_count == 0
        sim.velocities[1, 0] = 0.0
        sim.step(1)
        assert sim.step_count == 1


def test_moved_grains_are_found_by_their_new_neighbours(gas, out):
    with grains.Simulation(gas, out=out) as sim:
        x = sim.positions.copy()
        x[1] = x[0] + (0.0015, 0, 0)  # overlaps grain 0 by 0.5 mm: far beyond the skin
        sim.positions = x
        sim.step(1)
        f = sim.forces
        assert f[0, 0] < 0 and f[1, 0] > 0  # pushed apart along x


# ------------------------------------------------------------------ checkpoints

def test_checkpoint_and_continue_bitwise(pour, tmp_path):
    with grains.Simulation(pour, out=tmp_path / "a") as a:
        a.run(until=0.002)
        ck = a.checkpoint()
        assert os.path.exists(ck)
        a.run(until=0.003)
        ref = a.positions.copy()
        ref_ids = a.ids.copy()
    with grains.Simulation(pour, out=tmp_path / "b", restart=ck) as b:
        assert b.step_count == 250
        b.run(until=0.003)
        order = np.argsort(b.ids)
        np.testing.assert_array_equal(b.positions[order], ref[np.argsort(ref_ids)])
    with pytest.raises(grains.CheckpointError):
        grains.Simulation(pour, out=tmp_path / "c", restart=tmp_path / "none.h5")


def test_output_folder_errors(pour, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(grains.OutputError, match="cannot create"):
        grains.Simulation(pour, out=blocker / "out")


# ------------------------------------------------------------------ grains in and out, materials

def test_remove_grains_in_a_region_or_by_mask(pour, out):
    with grains.Simulation(pour, out=out) as sim:
        sim.run(until=0.001)
        x = sim.positions.copy()
        inside = np.all((x >= [0, 0, 0.015]) & (x <= [0.01, 0.01, 0.031]), axis=1)
        gone = sim.remove(region=((0, 0, 0.015), (0.01, 0.01, 0.031)))
        assert gone == inside.sum() > 0
        assert sim.n_particles == 300 - gone
        assert np.all(sim.positions[:, 2] < 0.015)
        ids = sim.ids.copy()
        assert sim.remove(mask=sim.ids % 2 == 0) == (ids % 2 == 0).sum()
        assert np.all(sim.ids % 2 == 1)
        sim.step(10)  # the lists were rebuilt: stepping goes on
        with pytest.raises(ValueError, match="mask"):
            sim.remove(mask=np.ones(3, dtype=bool))
        with pytest.raises(ValueError):
            sim.remove()


def test_insert_overlapping_a_grain_through_a_periodic_face_is_refused(gas, out):
    gas["domain"]["periodic"] = [True, False, False]
    with grains.Simulation(gas, out=out) as sim:
        x = sim.positions.copy()
        x[0, 0] = 0.0005  # 0.5 mm from the face x = 0: its image reaches past x = 0.1
        sim.positions = x
        sim.step(2)  # its image pairs with nothing: the list keeps none of it
        near = [[0.0995, x[0, 1], x[0, 2]]]  # 1 mm from grain 0 through the face, radius 1 mm
        with pytest.raises(ValueError, match="overlaps grain"):
            sim.insert(near, 0.001)
        assert sim.insert([[0.097, x[0, 1], x[0, 2]]], 0.001) == 1  # 3.5 mm from it
        with pytest.raises(ValueError, match="rows 0 and 1 overlap"):  # two new ones, through the face
            sim.insert([[0.0005, 0.05, 0.05], [0.0995, 0.05, 0.05]], 0.001)


def test_insert_grains(gas, out):
    with grains.Simulation(gas, out=out) as sim:
        n = sim.n_particles
        top = sim.ids.max()
        new = [[0.035, 0.035, 0.035], [0.035, 0.035, 0.040]]
        assert sim.insert(new, 0.001, velocities=[[0.1, 0, 0], [0, 0, 0]]) == 2
        assert sim.n_particles == n + 2
        ids = sim.ids
        assert len(set(ids.tolist())) == n + 2 and ids.max() == top + 2
        k = int(np.argmax(ids))
        np.testing.assert_array_equal(sim.positions[k], new[1])
        np.testing.assert_allclose(sim.radii[sim.ids > top], 0.001)
        sim.step(3)
        j = int(np.argmax(np.where(sim.ids > top, sim.velocities[:, 0], -1)))
        assert sim.velocities[j, 0] == pytest.approx(0.1)
        with pytest.raises(ValueError, match="overlaps"):
            sim.insert([[0.0355, 0.035, 0.035]], 0.001)
        with pytest.raises(ValueError, match="overlap"):
            sim.insert([[0.06, 0.06, 0.065], [0.06, 0.06, 0.066]], 0.001)
        with pytest.raises(ValueError, match="outside"):
            sim.insert([[0.5, 0.5, 0.5]], 0.001)
        with pytest.raises(ValueError, match="not finite"):
            sim.insert([[0.06, 0.06, 0.065]], float("nan"))
        with pytest.raises(ValueError, match="set"):
            sim.insert([[0.06, 0.06, 0.065]], 0.001, set=3)
        assert sim.n_particles == n + 2  # nothing was inserted by the refused calls


def sliding(case, out, friction_after):
    """Grains sliding on the floor at 0.1 m/s, after the friction changed to
    `friction_after` (from the case's 0.5): their mean deceleration over
    1-3 ms, and the mean normal force per mass over the same time (g plus
    the change of their vertical velocity: they still bounce a little)."""
    with grains.Simulation(case, out=out) as sim:
        on_floor = np.isclose(sim.positions[:, 2], 0.021)
        v = sim.velocities.copy()
        v[on_floor, 0] = 0.1
        sim.velocities = v
        sim.set_material("grain", friction=friction_after)
        sim.run(until=0.001)
        v1 = sim.velocities[on_floor].copy()
        sim.run(until=0.003)
        v3 = sim.velocities[on_floor].copy()
        return (v1[:, 0] - v3[:, 0]).mean() / 0.002, 9.81 + (v3[:, 2] - v1[:, 2]).mean() / 0.002


def test_set_material_changes_the_friction(gas, tmp_path):
    case = dict(gas, gravity=[0, 0, -9.81],
                walls=[{"type": "plane", "name": "floor", "point": [0, 0, 0.020], "normal": [0, 0, 1],
                        "material": "grain"}])
    # Sliding: the deceleration is mu N / m (measured 0.476 g and 0.0952 g,
    # the normal force averaging 0.952 m g over the window).
    for mu in (0.5, 0.1):
        decel, normal = sliding(case, tmp_path / str(mu), mu)
        assert decel == pytest.approx(mu * normal, rel=1e-3)
        assert normal == pytest.approx(9.81, rel=0.1)
    with grains.Simulation(case, out=tmp_path / "c") as sim:
        with pytest.raises(KeyError, match="no material"):
            sim.set_material("sand", friction=0.3)
        with pytest.raises(KeyError, match="cannot change"):
            sim.set_material("grain", youngs_modulus=1e9)
        with pytest.raises(ValueError, match="rolling friction"):
            sim.set_material("grain", rolling_friction=0.1)
        with pytest.raises(ValueError, match="restitution"):
            sim.set_material("grain", restitution=1.5)


def test_analyze_a_finished_run(pour, out):
    with grains.Simulation(pour, out=out) as sim:
        sim.run(until=0.004)
    a = grains.analyze(out)
    assert a["time"] == pytest.approx(0.004)
    assert 0 < a["packing_fraction"]["value"] < 0.75
    assert a["coordination"]["mean"] >= 0 and a["particles"] == 300
    prof = a["phi_profile"]
    assert prof["phi"].shape == prof["lo"].shape and len(prof["phi"]) > 3
    assert a["coordination_histogram"].sum() > 0
    first = grains.analyze(out, frame=0, region=((0, 0, 0), (0.01, 0.01, 0.03)))
    assert first["time"] == 0
    with pytest.raises(Exception):
        grains.analyze(out / "nothing")


def test_wall_velocity_between_stages(pour, out, tmp_path):
    pour["walls"][0]["velocity"] = [0, 0, 0.0]
    pour["walls"][1]["velocity"] = [0.001, 0, 0]  # a moving wall: the step has a wall-motion stage
    with grains.Simulation(pour, out=out) as sim:
        sim.run(until=0.001)
        sim.set_wall_velocity("floor", (0, 0, 0.05))
        sim.run(until=0.004)
    walls = grains.output.read_frames(out, "walls")
    assert walls[-1].time == pytest.approx(0.004)
    # The floor (the first wall: the first four points of the frame) rose
    # at 0.05 m/s for 3 ms.
    z0, z1 = walls[0].points[:4, 2], walls[-1].points[:4, 2]
    np.testing.assert_array_equal(z0, 0.0)
    np.testing.assert_allclose(z1, 0.05 * 0.003, rtol=1e-9)
    with grains.Simulation(pour, out=tmp_path / "b") as sim:
        with pytest.raises(KeyError, match="no wall"):
            sim.set_wall_velocity("roof", (0, 0, 1))
        with pytest.raises(ValueError, match="finite"):
            sim.set_wall_velocity("floor", (0, 0, float("nan")))
    still = dict(pour, walls=[dict(w, velocity=[0, 0, 0]) for w in pour["walls"]])
    with grains.Simulation(still, out=tmp_path / "c") as sim:
        with pytest.raises(ValueError, match="wall-motion stage"):
            sim.set_wall_velocity("floor", (0, 0, 0.01))


def test_arkode_scenes_are_read_only(pour, out):
    pour["time"]["integrator"] = "arkode"
    pour["particles"][0]["count"] = 50
    with grains.Simulation(pour, out=out) as sim:
        sim.step(5)
        assert not sim.velocities.flags.writeable
        with pytest.raises(ValueError, match="ARKODE"):
            sim.velocities = np.zeros((50, 3))
        with pytest.raises(ValueError, match="ARKODE"):
            sim.set_wall_velocity("floor", (0, 0, 0.01))
        sim.step(5)
        assert sim.step_count == 10


def test_progress_goes_to_python_stderr(pour, out, capsys):
    pour["output"]["progress"] = True
    with grains.Simulation(pour, out=out, progress=True) as sim:
        sim.run()
    err = capsys.readouterr().err
    assert "done: step 500/500" in err  # the closing line, through sys.stderr (a notebook shows it)
    with grains.Simulation(pour, out=out, progress=False) as sim:
        sim.run()
    assert "step" not in capsys.readouterr().err


def test_insert_and_remove_clumps(tmp_path):
    case = grains.Case(ROOT / "cases/pour_clumps/case.yaml",
                       set={"particles.0.count": 10, "time.end": 0.01, "output.vtk": False})
    with grains.Simulation(case, out=tmp_path / "c") as sim:
        balls = sim.n_particles
        per = balls // 10
        bodies = set(sim.body_ids.tolist())
        assert len(bodies) == 10
        sim.step(2)
        assert sim.insert([[0.005, 0.005, 0.0585]], 0.0008, velocities=[[0, 0, -0.2]]) == 1
        assert sim.n_particles == balls + per
        new = sim.body_ids == max(bodies) + 1
        assert new.sum() == per
        np.testing.assert_allclose(sim.velocities[new], [[0, 0, -0.2]] * per)
        sim.step(10)
        assert sim.velocities[new, 2].mean() < -0.2  # it falls as one body
        with pytest.raises(ValueError, match="outside"):
            sim.insert([[0.002, 0.002, 0.0605]], 0.0008)  # its bounding sphere crosses the domain's top (0.061)
        # Removing one ball of a clump removes the clump.
        first = np.flatnonzero(sim.body_ids == sim.body_ids[0])
        mask = np.zeros(sim.n_particles, dtype=bool)
        mask[first[0]] = True
        assert sim.remove(mask=mask) == per
        assert sim.n_particles == balls
        sim.step(5)


# ------------------------------------------------------ mesh-wall motion

def drum_case(**edits):
    """The rotating drum of cases/, small: 100 beads, spinning from t = 0 at 120 rpm."""
    sets = {"particles.0.count": 100, "walls.0.start": 0.0, "walls.0.ramp": 0.0, "walls.0.rpm": 120.0,
            "time.end": 0.02, "output.every": 0.005, "output.progress": False}
    sets.update(edits)
    return grains.Case(ROOT / "cases/rotating_drum/case.yaml", set=sets)


def turned(p0, p1):
    """The angle about +y (through the origin, the drum's axis) that takes the vertices p0 to p1."""
    x0, z0, x1, z1 = p0[:, 0], p0[:, 2], p1[:, 0], p1[:, 2]
    keep = x0 * x0 + z0 * z0 > 1e-6
    a = np.arctan2(z0[keep] * x1[keep] - x0[keep] * z1[keep], x0[keep] * x1[keep] + z0[keep] * z1[keep])
    assert np.ptp(a) < 1e-5  # a rigid rotation
    return float(np.mean(a))


def drum_angles(out, ref=None):
    """(time, angle) of the drum in each walls frame, from the pose `ref` (default: the first frame's)."""
    frames = grains.output.read_frames(out, "walls")
    ref = frames[0].points if ref is None else ref
    return [(f.time, turned(ref, f.points)) for f in frames]


def test_mesh_wall_motion_between_stages(out):
    w1, w2 = 120 * 2 * np.pi / 60, -3.0
    with grains.Simulation(drum_case(), out=out) as sim:
        sim.run(until=0.01)
        t1 = sim.time
        sim.set_wall_motion("drum", angular_velocity=w2)
        sim.run(until=0.02)
    angles = drum_angles(out)
    assert len(angles) >= 4 and angles[0] == (0.0, 0.0)
    # The drum turned at w1 until t1, then at w2 from the angle it had: no jump.
    for t, a in angles:
        assert a == pytest.approx(w1 * min(t, t1) + w2 * max(0.0, t - t1), abs=1e-5), t
    assert angles[-1][0] == pytest.approx(0.02, abs=1e-4)
    with grains.Simulation(drum_case(), out=out.parent / "b") as sim:
        with pytest.raises(ValueError, match="not both"):
            sim.set_wall_motion("drum", angular_velocity=1.0, rpm=10)
        with pytest.raises(ValueError, match="velocity must be finite"):
            sim.set_wall_motion("drum", velocity=(0, float("inf"), 0))
        with pytest.raises(ValueError, match="angular_velocity must be finite"):
            sim.set_wall_motion("drum", angular_velocity=float("nan"))
        with pytest.raises(ValueError, match="three components"):
            sim.set_wall_motion("drum", vibration_amplitude=(0, 1))
        with pytest.raises(ValueError, match=">= 0"):
            sim.set_wall_motion("drum", vibration_frequency=-1)
        assert sim.step_count == 0
        # A translation and a vibration too: the pose stays continuous.
        sim.step(100)
        sim.set_wall_motion("drum", velocity=(0, 0, 0.01), vibration_amplitude=(0.001, 0, 0), vibration_frequency=50)
        sim.step(100)


def test_plane_walls_do_not_rotate(pour, out):
    pour["walls"][1]["velocity"] = [0.001, 0, 0]
    with grains.Simulation(pour, out=out) as sim:
        with pytest.raises(ValueError, match="only its velocity"):
            sim.set_wall_motion("floor", angular_velocity=1.0)
        sim.set_wall_motion("floor", velocity=(0, 0, 0.01))


def positions_by_id(sim):
    order = np.argsort(sim.ids)
    return sim.positions[order].copy(), sim.velocities[order].copy()


def test_mesh_wall_motion_survives_a_restart(tmp_path):
    w1, w2 = 120 * 2 * np.pi / 60, -3.0
    with grains.Simulation(drum_case(), out=tmp_path / "a") as sim:
        sim.run(until=0.01)
        t1 = sim.time
        sim.set_wall_motion("drum", angular_velocity=w2)
        sim.run(until=0.015)
        ck, t_ck = sim.checkpoint(), sim.time
        sim.run(until=0.02)
        xa, va = positions_by_id(sim)
    # The case edited to the motion the script set: the run continues bitwise.
    with grains.Simulation(drum_case(**{"walls.0.rpm": w2 * 60 / (2 * np.pi)}), out=tmp_path / "b", restart=ck) as sim:
        assert sim.time == t_ck
        sim.run(until=0.02)
        xb, vb = positions_by_id(sim)
    np.testing.assert_array_equal(xa, xb)
    np.testing.assert_array_equal(va, vb)
    # The original case: its motion again, from the checkpoint's pose.
    with grains.Simulation(drum_case(), out=tmp_path / "c", restart=ck) as sim:
        sim.run(until=0.02)
    at_rest = grains.output.read_frames(tmp_path / "a", "walls")[0].points  # the pose at time 0
    angles = drum_angles(tmp_path / "c", ref=at_rest)
    assert len(angles) >= 1 and angles[0][0] >= t_ck
    for t, a in angles:  # from the pose it had, at the case's speed
        assert a == pytest.approx(w1 * t1 + w2 * (t_ck - t1) + w1 * (t - t_ck), abs=1e-5), t
    # Another rotation axis cannot continue the pose.
    with pytest.raises(Exception, match="rotation axis"):
        grains.Simulation(drum_case(**{"walls.0.axis": [1, 0, 0]}), out=tmp_path / "d", restart=ck)
