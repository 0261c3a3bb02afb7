#!/usr/bin/env bash
# The cost of stepping from Python: cases/pour_spheres (10,000 spheres,
# 40,000 steps) run by `grains run` and by a Python script that steps the
# same simulation in chunks of CHUNK steps (default 100), alternated ROUNDS
# times (default 2), serial. Prints each run's wall time and throughput and
# the Python/CLI ratio. Results: bench/RESULTS.md.
#
#   bash bench/python/run.sh          (about 3 minutes per round on one core)
#
# Environment: BUILD (default build; its grains and python/ are used),
# WORK (default $BUILD/bench-python), CHUNK, ROUNDS, CASE.
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
BUILD="$(cd "${BUILD:-$ROOT/build}" && pwd)"
WORK="${WORK:-$BUILD/bench-python}"
CHUNK="${CHUNK:-100}"
ROUNDS="${ROUNDS:-2}"
CASE="${CASE:-$ROOT/cases/pour_spheres/case.yaml}"
PY="${PYTHON:-/usr/bin/python3}"
export OMP_NUM_THREADS=1
mkdir -p "$WORK"
echo "== $(date -u '+%F %T UTC')  load: $(cut -d' ' -f1-3 /proc/loadavg)  chunk $CHUNK"
for r in $(seq 1 "$ROUNDS"); do
  rm -rf "$WORK/cli" "$WORK/py"
  "$BUILD/grains" run "$CASE" -o "$WORK/cli" -q >/dev/null
  PYTHONPATH="$BUILD/python" "$PY" - "$CASE" "$WORK/py" "$CHUNK" <<'PYEOF'
import sys
import grains
case, out, chunk = sys.argv[1], sys.argv[2], int(sys.argv[3])
with grains.Simulation(grains.Case(case), out=out, progress=False) as sim:
    sim.run(every=chunk)
PYEOF
  "$PY" - "$WORK/cli/summary.json" "$WORK/py/summary.json" "$r" <<'PYEOF'
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
print("round %s: grains run %.2f s (%.4g particle-steps/s); python %.2f s (%.4g); python/cli time %.4f"
      % (sys.argv[3], a["wall_time_s"], a["particle_steps_per_second"], b["wall_time_s"],
         b["particle_steps_per_second"], b["wall_time_s"] / a["wall_time_s"]))
PYEOF
done
echo "== load after: $(cut -d' ' -f1-3 /proc/loadavg)"
