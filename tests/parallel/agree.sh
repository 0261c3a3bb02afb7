#!/usr/bin/env bash
# Runs a case serial, on 2 and 4 MPI ranks (oversubscribed) and with 2
# OpenMP threads, and checks that every frame agrees with the serial run:
#   agree.sh GRAINS COMPARE CASE WORKDIR deterministic [--set k=v ...]
#       parallel.deterministic=true: every frame must agree bitwise.
#   agree.sh GRAINS COMPARE CASE WORKDIR TOL [--set k=v ...]
#       unordered (list-order, fastest) force sums, parallel.deterministic=false
#       (the default under MPI is ordered): positions within TOL m.
set -euo pipefail
grains=$1 compare=$2 case=$3 work=$4 mode=$5
shift 5
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
rm -rf "$work" && mkdir -p "$work"
sets=("$@" -q)
tol=0
if [ "$mode" = deterministic ]; then
  sets+=(--set parallel.deterministic=true)
else
  sets+=(--set parallel.deterministic=false)
  tol=$mode
fi
run() {  # name, launcher...
  local name=$1; shift
  local t0=$(date +%s.%N)
  "$@" "$grains" run "$case" -o "$work/$name" "${sets[@]}"
  printf '%-9s %6.1f s\n' "$name" "$(echo "$(date +%s.%N) - $t0" | bc)"
}
OMP_NUM_THREADS=1 run serial env
OMP_NUM_THREADS=1 run ranks2 mpirun --oversubscribe -np 2
OMP_NUM_THREADS=1 run ranks4 mpirun --oversubscribe -np 4
OMP_NUM_THREADS=2 run threads2 env
status=0
for r in ranks2 ranks4 threads2; do
  echo -n "$r vs serial: "
  "$compare" "$work/serial" "$work/$r" --tol "$tol" || status=1
done
# The CSV series (stress, profiles, wall loads): summed over ranks in another
# order, so each value within 1e-6 of its column's largest magnitude (plus
# 1e-15 of the file's largest value after step and time: a column whose
# values are themselves rounding noise, a mean velocity of zero).
for f in "$work"/serial/*.csv; do
  [ -e "$f" ] || continue
  for r in ranks2 ranks4 threads2; do
    g="$work/$r/$(basename "$f")"
    if ! awk -F, -v rel=1e-6 -v floor=1e-15 -v name="$r/$(basename "$f")" \
        -f "$(dirname "$0")/../support/csv_agree.awk" "$f" "$g"; then
      status=1
    else
      echo "$r/$(basename "$f") agrees with serial to 1e-6 of each column"
    fi
  done
done
exit $status
