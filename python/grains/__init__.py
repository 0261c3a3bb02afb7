"""grains: discrete-element simulation of granular matter, from Python.

    import grains
    case = grains.Case("cases/pour_spheres/case.yaml", set={"time.end": 0.05})
    with grains.Simulation(case, out="out/pour") as sim:
        sim.run(until=0.02)
        sim.velocities[:, 2] = 0.0        # a view of the grains' memory
        sim.run()                         # to the case's end
    print(sim.summary)

The user's guide is docs/python.md; the examples are in examples/python.
"""
import numpy as np

from . import _core, output
from ._core import (BlowUpError, Case, CaseError, CheckpointError, IntegrationError, OutputError, SetupError,
                    __version__, mpi_rank, mpi_size, omp_threads)

__all__ = ["Case", "Simulation", "CaseError", "SetupError", "CheckpointError", "BlowUpError", "OutputError",
           "IntegrationError", "analyze", "omp_threads", "mpi_rank", "mpi_size", "output", "__version__"]


def _field(name, doc):
    def get(self):
        return self.field(name)

    def put(self, values):
        self.set_field(name, values)

    return property(get, put, doc=doc)


class Simulation(_core.Simulation):
    """A simulation of a case, stepped from Python.

    Simulation(case, out="out", restart=None, progress=None)

    case: a grains.Case, a path to a case file or a dict. out: the output
    folder. restart: a checkpoint to continue from. progress: progress lines
    on stderr (default: when stderr is a terminal).

    The per-particle properties (positions, velocities, ...) are numpy views
    of this rank's grains, without a copy; they stay live until the
    simulation next changes (a step, a checkpoint, a write through
    set_field, close), when they become read-only snapshots that keep their
    memory. Read the property again for the live view. Values written
    through a view are checked (finite, inside the domain) before the next
    step; assigning a whole array (sim.velocities = a) checks it first.
    """

    positions = _field("positions", "Centres (m), shape (n, 3); writable (not for clump balls).")
    velocities = _field("velocities", "Velocities (m/s), shape (n, 3); writable (not for clump balls).")
    angular_velocities = _field("angular_velocities", "Angular velocities (rad/s), shape (n, 3); writable.")
    forces = _field("forces", "Forces of the last evaluation (N), shape (n, 3); read-only.")
    torques = _field("torques", "Torques of the last evaluation (N m), shape (n, 3); read-only.")
    radii = _field("radii", "Radii (m; an ellipsoid's bounding radius), shape (n,); read-only.")
    masses = _field("masses", "Masses (kg), shape (n,); read-only.")
    ids = _field("ids", "Global ids, shape (n,); read-only.")
    materials = _field("materials", "Material indices, shape (n,); read-only.")
    orientations = _field("orientations",
                          "Ellipsoids' orientations as unit quaternions in the store's order (x, y, z, w), "
                          "shape (n, 4); read-only.")
    semi_axes = _field("semi_axes", "Ellipsoids' semi-axes (m), shape (n, 3); read-only.")
    body_ids = _field("body_ids", "The clump each ball belongs to (-1: a free grain), shape (n,); read-only.")

    def __enter__(self):
        return self

    def __exit__(self, exc_type, exc, tb):
        if not self.closed:
            try:
                self.close()
            except Exception:
                if exc_type is None:
                    raise
        return False

    def run(self, until=None, every=100, callback=None, max_time=None):
        """Steps in chunks of `every` steps.

        until: a time (s) to run to (default: the case's end; past it, the
        end moves), or a callable f(sim) -> bool asked after each chunk: the
        run stops once it returns True (then max_time, if given, bounds the
        run, else the case's end does). callback: f(sim) called after each
        chunk. Returns the steps taken. An exception a callable raises stops
        the run after the chunk it ends and propagates.
        """
        if not isinstance(every, int) or every < 1:
            raise ValueError("run(every=...): a positive number of steps")
        condition = None
        if callable(until):
            condition = until
            until = max_time
        if until is None:
            until = self.end_time
        target = self._steps_for(float(until))
        taken = 0
        while self.step_count < target:
            taken += self._advance_to(min(target, self.step_count + every))
            if callback is not None:
                callback(self)
            if condition is not None and condition(self):
                break
        return taken

    def remove(self, mask=None, region=None):
        """Removes grains: those whose `mask` entry is true (one per grain of
        this rank), or those whose centre lies in `region` = (lo, hi), two
        corners. A clump goes as a whole when any of its balls is picked.
        Returns how many grains (balls) went, over all ranks."""
        if (mask is None) == (region is None):
            raise ValueError("remove: give a mask or a region")
        if region is not None:
            lo, hi = (np.asarray(c, dtype=float) for c in region)
            if lo.shape != (3,) or hi.shape != (3,) or not np.all(lo <= hi):
                raise ValueError("remove: region = ((xmin, ymin, zmin), (xmax, ymax, zmax)) with min <= max")
            x = self.field("positions", False)
            mask = np.all((x >= lo) & (x <= hi), axis=1)
        return self._remove(np.asarray(mask))

    def insert(self, positions, radii, velocities=None, orientations=None, set=0):
        """Adds grains of the case's particle set number `set` (spheres,
        ellipsoids of the set's aspect ratios, or clumps of its shape):
        positions (k, 3), bounding radii (k,), velocities (k, 3; default zero), orientations (k, 4)
        quaternions (x, y, z, w; default identity). Refused (ValueError,
        nothing inserted) when a grain overlaps another or lies outside the
        domain. Under MPI every rank calls it with the same grains. Returns
        how many were inserted."""
        x = np.atleast_2d(np.asarray(positions, dtype=float))
        k = len(x)
        r = np.broadcast_to(np.asarray(radii, dtype=float), (k,))
        v = np.zeros((k, 3)) if velocities is None else np.atleast_2d(np.asarray(velocities, dtype=float))
        q = np.tile([0.0, 0.0, 0.0, 1.0], (k, 1)) if orientations is None else np.atleast_2d(
            np.asarray(orientations, dtype=float))
        return self._insert(x, np.ascontiguousarray(r), v, q, int(set))

    def __repr__(self):
        if self.closed:
            return "<grains.Simulation (closed)>"
        return "<grains.Simulation t=%g s, step %d, %d grains>" % (self.time, self.step_count, self.n_particles)



def analyze(out_dir, frame=-1, time=None, region=None):
    """What `grains analyze OUTDIR` computes for one frame of a finished run
    (the last by default; or the frame nearest `time`), as a dict: the
    packing fraction of the region (automatic: the bulk, 2 diameters from
    the bed's bounds; or region = ((xmin, ymin, zmin), (xmax, ymax, zmax))),
    coordination, RDF, contact forces and order, the keys of analysis.json
    (docs/postprocess.md: packing_fraction.value, coordination.mean, ...), plus numpy arrays: phi_profile (lo, hi, phi,
    error along z), rdf_arrays (r, g) and coordination_histogram."""
    import os
    return _core._analyze(os.fspath(out_dir), int(frame), time, region)
