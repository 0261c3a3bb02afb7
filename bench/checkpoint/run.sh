#!/usr/bin/env bash
# Checkpoint write time of a 50,000-sphere state (bench/RESULTS.md,
# docs/checkpoint.md): on 2 MPI ranks with parallel HDF5 (MPI-IO, each rank
# writes its block of rows) against the gather on rank 0
# (GRAINS_CHECKPOINT_IO=gather), and serial for reference.
#
# The 50k scene of bench/parallel (pour_spheres widened to 45 d x 45 d), run
# for STEPS steps with a checkpoint every EVERY steps (keep 3); the time per
# checkpoint is the checkpoint stage's time in summary.json (rank 0's clock:
# redistribution or gather, blow-up diagnosis, HDF5 write, fsyncs, rename,
# pruning) divided by the number of checkpoints. Variants alternate, REPEATS
# rounds; min and median are printed.
#
#   bash bench/checkpoint/run.sh      (a few minutes; BUILD=build WORK=... REPEATS=3 STEPS=40 EVERY=4)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
BUILD="${BUILD:-$ROOT/build}"
WORK="${WORK:-$BUILD/bench-checkpoint}"
REPEATS=${REPEATS:-3} STEPS=${STEPS:-40} EVERY=${EVERY:-4}
CASE="$ROOT/cases/pour_spheres/case.yaml"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
MPIRUN=(mpirun --oversubscribe --bind-to none)
rm -rf "$WORK"; mkdir -p "$WORK"
GRAINS="$BUILD/grains"
DT=8.654e-6
END=$(python3 -c "print($STEPS * $DT)")
SETS=(--set particles.0.count=50000 --set "walls.2.point=[0.045, 0, 0]" --set "walls.4.point=[0, 0.045, 0]"
      --set "particles.0.placement.region.max=[0.045, 0.045, 0.07]" --set "domain.max=[0.046, 0.046, 0.071]"
      --set time.end=$END --set output.every=1 --set checkpoint.every_steps=$EVERY --set checkpoint.keep=3 -q)
N_CK=$((STEPS / EVERY))

echo "== $(date -u '+%Y-%m-%d %H:%M UTC'), $(lscpu | sed -n 's/^Model name: *//p'), $(nproc --all) cores, $(git -C "$ROOT" rev-parse --short HEAD)"
echo "== load before: $(uptime)"
per_ck() {  # OUT -> ms per checkpoint
  python3 - "$1/summary.json" "$N_CK" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))["stage_seconds"]
t = sum(v for k, v in s.items() if "output.checkpoint" in k)
print(f"{1000 * t / int(sys.argv[2]):.1f}")
PY
}
declare -A T
for ((k = 1; k <= REPEATS; k++)); do
  "$GRAINS" run "$CASE" -o "$WORK/serial$k" "${SETS[@]}"
  T[serial]+="$(per_ck "$WORK/serial$k") "
  GRAINS_CHECKPOINT_IO=gather "${MPIRUN[@]}" -np 2 "$GRAINS" run "$CASE" -o "$WORK/gather$k" "${SETS[@]}"
  T[gather]+="$(per_ck "$WORK/gather$k") "
  GRAINS_CHECKPOINT_IO=mpiio "${MPIRUN[@]}" -np 2 "$GRAINS" run "$CASE" -o "$WORK/mpiio$k" "${SETS[@]}"
  T[mpiio]+="$(per_ck "$WORK/mpiio$k") "
  echo "round $k: serial ${T[serial]}| gather ${T[gather]}| mpiio ${T[mpiio]}(ms per checkpoint)"
done
last=$(ls "$WORK/mpiio1/checkpoints/"*.h5 | sort | tail -n 1)
h5diff "$last" "$WORK/gather1/checkpoints/$(basename "$last")" && echo "MPI-IO and gather files equal (h5diff)"
echo "== checkpoint size: $(stat -c %s "$last") bytes for 50,000 particles"
for v in serial gather mpiio; do
  python3 -c "import sys, statistics as s; x=[float(a) for a in sys.argv[2:]]; print(f'{sys.argv[1]:7s} min {min(x):7.1f} ms  median {s.median(x):7.1f} ms  ({len(x)} runs x $N_CK checkpoints)')" $v ${T[$v]}
done
echo "== load after: $(uptime)"
