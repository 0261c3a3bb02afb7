"""The module under MPI: `mpirun -np 2 python3 script.py` with mpi4py."""
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))


@pytest.mark.skipif(shutil.which("mpirun") is None, reason="no mpirun")
def test_two_ranks_give_the_serial_result_bitwise(tmp_path):
    script = os.path.join(HERE, "mpi_pour.py")
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMP_NUM_THREADS="1")
    subprocess.run([sys.executable, script, str(tmp_path / "serial"), str(tmp_path / "serial.npz")],
                   check=True, env=env, cwd=HERE, timeout=300)
    subprocess.run(["mpirun", "--oversubscribe", "-np", "2", sys.executable, script, str(tmp_path / "mpi"),
                    str(tmp_path / "mpi.npz")], check=True, env=env, cwd=HERE, timeout=300)
    a, b = np.load(tmp_path / "serial.npz"), np.load(tmp_path / "mpi.npz")
    assert int(b["ranks"]) == 2
    assert 0 < int(b["local"]) < len(b["ids"])  # the grains were split between the ranks
    np.testing.assert_array_equal(a["ids"], b["ids"])
    np.testing.assert_array_equal(a["x"], b["x"])
    np.testing.assert_array_equal(a["v"], b["v"])
    # Each rank wrote its piece of the frames and rank 0 the index.
    assert (tmp_path / "mpi" / "particles.pvd").exists()
    assert (tmp_path / "mpi" / "summary.json").exists()
