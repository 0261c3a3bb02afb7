"""The examples of examples/python, run at a small size."""
import sys

import numpy as np
import pytest

from conftest import ROOT

sys.path.insert(0, str(ROOT / "examples/python"))

import calibrate_friction  # noqa: E402
import read_output  # noqa: E402
import tilt_test  # noqa: E402


def test_tilt_test_avalanches_at_a_plausible_angle(tmp_path):
    lines = []
    angle = tilt_test.tilt_test(n=300, out=str(tmp_path / "tilt"), log=lines.append)
    assert angle is not None, "\n".join(lines)
    # A frictional bed in a box 11 grains wide: the side walls hold it
    # beyond a free heap's angle of repose (measured 35-36 degrees for 300
    # and 400 grains, 48 for a bed twice as deep).
    assert 20 <= angle <= 50, "\n".join(lines)
    assert lines[0].startswith("settled")


def test_calibration_brackets_and_converges(tmp_path):
    lines = []
    target = 0.595
    mu, phi = calibrate_friction.calibrate(target, n=1000, tol=0.004, iterations=5, out=str(tmp_path / "c"),
                                           log=lines.append)
    ends = [float(l.split("phi ")[1]) for l in lines[:2]]
    assert ends[0] > target > ends[1], "\n".join(lines)  # friction loosens the bed
    assert abs(phi - target) <= 0.004, "\n".join(lines)
    assert 0.05 < mu < 1.0
    with pytest.raises(ValueError, match="outside"):
        calibrate_friction.calibrate(0.70, n=1000, out=str(tmp_path / "d"), log=lines.append)


def test_read_output_matches_the_simulation(tmp_path):
    frames, final, gap = read_output.main(str(tmp_path / "run"))
    assert len(frames) == 5  # t = 0, 0.005, ..., 0.02
    assert frames[0].time == 0 and frames[-1].time == pytest.approx(0.02)
    assert gap < 1e-12
    assert set(frames[-1].keys()) >= {"id", "radius", "velocity"}
