"""Small cases for the Python API tests (a few hundred grains, seconds to run)."""
import copy
import os
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]

# 300 frictional spheres poured into a box: gravity, walls, contacts.
POUR = {
    "title": "python_pour",
    "domain": {"min": [-0.001, -0.001, -0.001], "max": [0.011, 0.011, 0.031]},
    "gravity": [0, 0, -9.81],
    "materials": [{"name": "grain", "density": 2500, "youngs_modulus": 1.0e7, "poisson_ratio": 0.3,
                   "restitution": 0.5, "friction": 0.5, "rolling_friction": 0.05}],
    "particles": [{"name": "spheres", "material": "grain",
                   "radius": {"distribution": "uniform", "min": 0.0004, "max": 0.0005},
                   "count": 300, "velocity": [0, 0, -0.3],
                   "placement": {"type": "random_fill",
                                 "region": {"min": [0.0, 0.0, 0.0], "max": [0.01, 0.01, 0.03]}, "seed": 5}}],
    "walls": [
        {"type": "plane", "name": "floor", "point": [0, 0, 0], "normal": [0, 0, 1], "material": "grain"},
        {"type": "plane", "name": "x0", "point": [0, 0, 0], "normal": [1, 0, 0], "material": "grain"},
        {"type": "plane", "name": "x1", "point": [0.01, 0, 0], "normal": [-1, 0, 0], "material": "grain"},
        {"type": "plane", "name": "y0", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "grain"},
        {"type": "plane", "name": "y1", "point": [0, 0.01, 0], "normal": [0, -1, 0], "material": "grain"},
    ],
    "time": {"dt": 8.0e-6, "end": 0.004},
    "output": {"every_steps": 250, "progress": False},
}

# 8 spheres far apart in a box without gravity: no contact, free flight.
GAS = {
    "title": "python_gas",
    "domain": {"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]},
    "materials": [{"name": "grain", "density": 2500, "youngs_modulus": 1.0e7, "poisson_ratio": 0.3,
                   "restitution": 0.5, "friction": 0.5}],
    "particles": [{"name": "spheres", "material": "grain", "radius": 0.001,
                   "placement": {"type": "lattice", "region": {"min": [0.02, 0.02, 0.02], "max": [0.08, 0.08, 0.08]},
                                 "spacing": 0.03}}],
    "time": {"dt": 1.0e-5, "end": 0.001},
    "output": {"vtk": False, "progress": False},
}


@pytest.fixture
def pour():
    return copy.deepcopy(POUR)


@pytest.fixture
def gas():
    return copy.deepcopy(GAS)


@pytest.fixture
def out(tmp_path):
    return tmp_path / "out"
