"""Run by test_mpi.py, serial or under mpirun: the POUR case to t = 2 ms
with deterministic force sums, grains removed from the top slab and two
inserted there, on to 3 ms; rank 0 writes every grain's id, position and
velocity (gathered with mpi4py) to the .npz file given."""
import sys

import numpy as np
from mpi4py import MPI

import grains
from conftest import POUR

out, result = sys.argv[1], sys.argv[2]
comm = MPI.COMM_WORLD
case = dict(POUR, parallel={"deterministic": True})
with grains.Simulation(case, out=out) as sim:
    assert grains.mpi_size() == comm.Get_size() and grains.mpi_rank() == comm.Get_rank()
    sim.run(until=0.002, every=50)
    # Grains out of the top slab and two new ones in it, on every rank alike.
    gone = sim.remove(region=((0, 0, 0.025), (0.01, 0.01, 0.031)))
    assert gone > 0
    sim.insert([[0.002, 0.002, 0.028], [0.008, 0.008, 0.028]], 0.0004, velocities=[[0, 0, -0.3]] * 2)
    sim.run(until=0.003, every=50)
    total = sim.n_total
    ids = comm.gather(sim.ids.copy())
    x = comm.gather(sim.positions.copy())
    v = comm.gather(sim.velocities.copy())
    local = sim.n_particles
if comm.Get_rank() == 0:
    ids, x, v = np.concatenate(ids), np.concatenate(x), np.concatenate(v)
    order = np.argsort(ids)
    assert len(ids) == total < 300, (len(ids), total)
    np.savez(result, ids=ids[order], x=x[order], v=v[order], ranks=comm.Get_size(), local=local)
