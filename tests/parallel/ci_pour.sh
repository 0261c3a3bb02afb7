#!/usr/bin/env bash
# The CI pour of 3,000 frictional spheres (cases/pour_spheres at CI size, as
# the mu = 0.5 point of the serial friction sweep in
# tests/regression/test_packing.cpp, whose fill is a little lower: 6.2 cm)
# run on 2 MPI ranks and with 2 OpenMP threads (default force sums): the bulk
# packing fraction must fall in the same documented band, [0.575, 0.615]
# (tests/regression/packing_references.yaml, pour_phi_mu05).
#   ci_pour.sh GRAINS CASE WORKDIR
set -euo pipefail
grains=$1 case=$2 work=$3
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
rm -rf "$work" && mkdir -p "$work"
sets=(--set particles.0.count=3000 --set "walls.2.point=[0.01, 0, 0]" --set "walls.4.point=[0, 0.01, 0]"
      --set "particles.0.placement.region.max=[0.01, 0.01, 0.07]" --set "domain.max=[0.011, 0.011, 0.071]"
      --set time.end=0.4 --set output.every=0.4 -q)
OMP_NUM_THREADS=1 mpirun --oversubscribe -np 2 "$grains" run "$case" -o "$work/ranks2" "${sets[@]}"
OMP_NUM_THREADS=2 "$grains" run "$case" -o "$work/threads2" "${sets[@]}"
status=0
for r in ranks2 threads2; do
  "$grains" analyze "$work/$r" --no-plots -o "$work/$r/analysis" > /dev/null
  phi=$(grep -o '"packing_fraction": {"value": [0-9.e-]*' "$work/$r/analysis/analysis.json" | grep -o '[0-9.e-]*$')
  ok=$(awk -v p="$phi" 'BEGIN {print (p > 0.575 && p < 0.615) ? "yes" : "no"}')
  echo "$r: bulk packing fraction $phi (band 0.575-0.615): $ok"
  [ "$ok" = yes ] || status=1
done
exit $status
