#!/usr/bin/env bash
# The granular chute of LAMMPS's benchmark inputs, run by grains and by LAMMPS
# (Debian package lammps) on the same particles and physics, serial, one after
# the other (issue 25): 31,924 spheres of diameter 1 (1,600 of them a frozen
# rough base), Hooke law with history (k_n = 200000, k_t = 2/7 k_n,
# gamma_n = 50 per unit m*, no tangential damping, friction 0.5), gravity 1
# tilted 26 degrees, dt = 1e-4, periodic in x and y. The scene is made by
# gen.py (LAMMPS's data.chute is not in its Debian package). Prints each
# code's time and particle-steps per second, their ratio, and the flowing
# grains' kinetic energy and mean x velocity at the end of each run (the two
# runs are the same physics, not the same bits: those should agree to a few
# per cent). Results: bench/RESULTS.md.
#
#   bash bench/chute/run.sh        (STEPS, default 20000; BUILD, default build; WORK; LMP, default lmp)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
BUILD="${BUILD:-$ROOT/build}"
GRAINS="${GRAINS:-$BUILD/grains}"
WORK="${WORK:-/tmp/grains-bench-chute}"
STEPS="${STEPS:-20000}"
LMP="${LMP:-lmp}"
PY=/usr/bin/python3  # Debian's, with VTK's Python module (reads grains' last frame)
export OMP_NUM_THREADS=1
command -v "$LMP" >/dev/null || { echo "LAMMPS not found: apt-get install --no-install-recommends lammps" >&2; exit 1; }
rm -rf "$WORK" && mkdir -p "$WORK"
echo "== $(date -u +%FT%TZ) $(uname -n), $(getconf _NPROCESSORS_ONLN) cores; load before: $(uptime)"
echo "== grains: $("$GRAINS" --version 2>&1 | head -1) ($GRAINS); LAMMPS: $(dpkg-query -W -f='${Version}' lammps 2>/dev/null || echo '?')"
python3 "$HERE/gen.py" "$WORK" "$STEPS"

# LAMMPS: its Loop time (the run itself, set-up excluded).
(cd "$WORK" && "$LMP" -in in.chute -log lammps.log -screen none)
$PY - "$WORK" <<'PY'
import re, sys
log = open(sys.argv[1] + "/lammps.log").read()
loop = re.search(r"Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps with (\d+) atoms", log)
rows = re.findall(r"^\s*(\d+)\s+(\d+)\s+([0-9.eE+-]+)\s+([0-9.eE+-]+)\s*$", log, re.M)
t, steps, n = float(loop.group(1)), int(loop.group(2)), int(loop.group(3))
step, atoms, ke, vx = rows[-1]
print("LAMMPS  %8.2f s  %.3e particle-steps/s   flowing grains at the end: kinetic energy %.2f, mean vx %.4f"
      % (t, n * steps / t, float(ke), float(vx)))
open(sys.argv[1] + "/lammps.txt", "w").write("%r %r\n" % (t, n * steps / t))
PY

# grains: the run's wall time less its set-up (summary.json), the bed's state from the last frame.
"$GRAINS" run "$WORK/case.yaml" -o "$WORK/grains" -q
$PY - "$WORK" <<'PY'
import glob, json, sys
import vtk
from vtk.util.numpy_support import vtk_to_numpy
work = sys.argv[1]
s = json.load(open(work + "/grains/summary.json"))
frames = sorted(glob.glob(work + "/grains/frames/*.vtu")) or sorted(glob.glob(work + "/grains/**/*.vtu", recursive=True))
r = vtk.vtkXMLUnstructuredGridReader()
r.SetFileName(frames[-1])
r.Update()
pd = r.GetOutput().GetPointData()
v = vtk_to_numpy(pd.GetArray("velocity"))
ids = vtk_to_numpy(pd.GetArray("id"))
bed = ids >= 1600  # the base is the case's first set: ids 0..1599
m = 3.141592653589793 / 6  # diameter 1, density 1
ke = 0.5 * m * (v[bed] ** 2).sum()
t = s["wall_time_s"]
pps = s["particle_steps_per_second"]
lt, lpps = map(float, open(work + "/lammps.txt").read().split())
print("grains  %8.2f s  %.3e particle-steps/s   flowing grains at the end: kinetic energy %.2f, mean vx %.4f"
      % (t, pps, ke, v[bed][:, 0].mean()))
print("grains / LAMMPS throughput: %.2f" % (pps / lpps))
print("grains stages (s): " + ", ".join("%s %.2f" % (k, x) for k, x in s["stage_seconds"].items() if x > 0.05))
PY
echo "== load after: $(uptime)"
