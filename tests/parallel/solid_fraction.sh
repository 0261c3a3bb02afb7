#!/usr/bin/env bash
# The solid-fraction field (a case output) of a run on 2 and 4 ranks equals
# the serial run's: each rank spreads its own particles, the sum over ranks
# is written once by rank 0. Deterministic force sums, so the particles are
# the same; the field differs only by the summation order (rounding).
#   solid_fraction.sh GRAINS COMPARE_VTI CASE WORKDIR [--set k=v ...]
set -euo pipefail
grains=$1 compare=$2 case=$3 work=$4
shift 4
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
rm -rf "$work" && mkdir -p "$work"
sets=("$@" --set parallel.deterministic=true -q)
"$grains" run "$case" -o "$work/serial" "${sets[@]}"
status=0
for np in 2 4; do
  mpirun --oversubscribe -np $np "$grains" run "$case" -o "$work/ranks$np" "${sets[@]}"
  n=0
  for f in "$work"/serial/frames/solid_fraction_*.vti; do
    echo -n "$np ranks, $(basename "$f"): "
    "$compare" "$f" "$work/ranks$np/frames/$(basename "$f")" 1e-12 || status=1
    n=$((n + 1))
  done
  [ "$n" -ge 2 ] || { echo "FAIL: only $n solid-fraction frames"; status=1; }
  cmp -s "$work/serial/solid_fraction.pvd" "$work/ranks$np/solid_fraction.pvd" || { echo "FAIL: .pvd differs"; status=1; }
done
exit $status
