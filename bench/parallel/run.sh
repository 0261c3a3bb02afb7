#!/usr/bin/env bash
# Parallel pour benchmark (bench/RESULTS.md): the 10k-sphere pour of
# bench/pour (same initial positions for both codes, 40,000 steps) serial,
# on 2 MPI ranks (own grid, and cut vertically) and as 1 rank x 2 OpenMP
# threads, and two serial runs at the same time (what the machine gives two
# processes), beside LIGGGHTS serial and on 2 ranks (its best of two grids); then a 50k-sphere pour (the same scene widened to 45 d x 45 d)
# serial, on 2 ranks and with 2 threads. Prints wall times, speed-ups,
# parallel efficiencies and grains/LIGGGHTS throughput ratios.
#
#   bash bench/parallel/run.sh        (about 15-20 minutes on two idle cores)
#
# Environment: BUILD (default build-bench), WORK (default $BUILD/bench-parallel),
# LIGGGHTS (default liggghts), SKIP_50K=1, STEPS_50K (default 40000).
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
POUR="$ROOT/bench/pour"
BUILD="${BUILD:-$ROOT/build-bench}"
WORK="${WORK:-$BUILD/bench-parallel}"
LIGGGHTS="${LIGGGHTS:-liggghts}"
CASE="$ROOT/cases/pour_spheres/case.yaml"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
MPIRUN=(mpirun --oversubscribe --bind-to none)
rm -rf "$WORK"; mkdir -p "$WORK"; WORK="$(cd "$WORK" && pwd)"

echo "== $(date -u '+%Y-%m-%d %H:%M UTC'), $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores"
echo "== load before: $(uptime)"
if [ ! -f "$BUILD/CMakeCache.txt" ]; then cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null; fi
cmake --build "$BUILD" --target grains -j2 >/dev/null
GRAINS="$BUILD/grains"

# The 10k scene exactly as bench/pour builds it (positions shared with LIGGGHTS).
eval "$(python3 "$POUR/scene.py" params "$CASE")"
python3 "$POUR/gen_positions.py" "$WORK" "$N" "$SEED" "$R" "$RHO" "$L" "$ZTOP" "$DOMAIN"
python3 "$POUR/scene.py" case "$CASE" positions.txt "$WORK/case.yaml"

summary() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])" "$1/summary.json" "$2"; }
declare -A WALL
grains_run() {  # name, threads, launcher...
  local name=$1 threads=$2; shift 2
  OMP_NUM_THREADS=$threads "$@" "$GRAINS" run "$CASE_FILE" -o "$WORK/$name" -q "${SETS[@]}"
  WALL[$name]=$(summary "$WORK/$name" wall_time_s)
  printf '  %-22s %8.2f s  %.3g particle-steps/s\n' "$name" "${WALL[$name]}" "$(summary "$WORK/$name" particle_steps_per_second)"
}

echo "== 10k pour, $STEPS steps"
CASE_FILE="$WORK/case.yaml"; SETS=()
grains_run g10k_serial 1 env
SETS=(--set parallel.deterministic=false)  # list-order sums (ordered is the default under MPI)
grains_run g10k_2ranks 1 "${MPIRUN[@]}" -np 2
SETS=()
grains_run g10k_2threads 2 env
SETS=(--set parallel.deterministic=true)
grains_run g10k_2ranks_det 1 "${MPIRUN[@]}" -np 2
SETS=()

SETS=(--set "parallel.decomposition=[2, 1, 1]" --set parallel.deterministic=false)
grains_run g10k_2ranks_x 1 "${MPIRUN[@]}" -np 2
SETS=()

# What the machine gives two processes: two serial runs at once, each
# against the serial run alone (a VM's second core may deliver less than a
# core; 2 ranks cannot beat this).
OMP_NUM_THREADS=1 "$GRAINS" run "$CASE_FILE" -o "$WORK/g10k_twin1" -q &
OMP_NUM_THREADS=1 "$GRAINS" run "$CASE_FILE" -o "$WORK/g10k_twin2" -q &
wait
TWIN=$(python3 -c "import sys; s, a, b = map(float, sys.argv[1:]); print('%.2fx (each %.2f and %.2f s)' % (s / a + s / b, a, b))" \
  "${WALL[g10k_serial]}" "$(summary "$WORK/g10k_twin1" wall_time_s)" "$(summary "$WORK/g10k_twin2" wall_time_s)")
printf '  %-22s %s\n' "two serial at once" "$TWIN"

# LIGGGHTS serial and on 2 ranks, with its own choice of grid (processors
# * * *, which cuts the tall box at mid-height, above the bed) and with a
# vertical cut (processors 2 1 1, which halves the bed); the faster counts.
read -r DAMPING E_LIGGGHTS < <(python3 "$POUR/match_damping.py" "$REST")
lig() {  # name, np, processor grid
  local name=$1 np=$2 grid=$3
  mkdir -p "$WORK/$name"
  sed -e "s#@DATA@#$WORK/atoms.data#; s#@SKIN@#$SKIN#g; s#@E@#$E#; s#@NU@#$NU#; s#@MU@#$MU#" \
      -e "s#@E_LIGGGHTS@#$E_LIGGGHTS#; s#@DT@#$DT#; s#@L@#$L#g; s#@STEPS@#$STEPS#g" \
      -e "s#@DUMP@#$WORK/$name/final.dump#" -e "s#^processors .*#processors      $grid#" \
      "$POUR/in.liggghts" > "$WORK/$name/in.liggghts"
  (cd "$WORK/$name" && OMP_NUM_THREADS=1 "${MPIRUN[@]}" -np "$np" "$LIGGGHTS" -in in.liggghts -log log.liggghts -echo none -screen none)
  WALL[$name]=$(grep -m1 '^Loop time of' "$WORK/$name/log.liggghts" | awk '{print $4}')
  printf '  %-22s %8.2f s  (loop time)\n' "$name" "${WALL[$name]}"
}
if command -v "$LIGGGHTS" >/dev/null; then
  lig lig10k_serial 1 '1 1 1'
  lig lig10k_2ranks_auto 2 '* * *'
  lig lig10k_2ranks_x 2 '2 1 1'
  WALL[lig10k_2ranks]=$(python3 -c "import sys; print(min(map(float, sys.argv[1:])))" "${WALL[lig10k_2ranks_auto]}" "${WALL[lig10k_2ranks_x]}")
fi

if [ "${SKIP_50K:-0}" != 1 ]; then
  S50=${STEPS_50K:-40000}
  echo "== 50k pour (45 d x 45 d box), $S50 steps"
  CASE_FILE="$CASE"
  SETS=(--set particles.0.count=50000 --set "walls.2.point=[0.045, 0, 0]" --set "walls.4.point=[0, 0.045, 0]"
        --set "particles.0.placement.region.max=[0.045, 0.045, 0.07]" --set "domain.max=[0.046, 0.046, 0.071]"
        --set "time.end=$(python3 -c "print($S50 * 8.654e-6)")" --set output.every=1)
  grains_run g50k_serial 1 env
  grains_run g50k_2ranks 1 "${MPIRUN[@]}" -np 2
  grains_run g50k_2threads 2 env
fi

echo
echo "== speed-up over serial (parallel efficiency = speed-up / 2)"
sp() { python3 -c "import sys; a, b = float(sys.argv[1]), float(sys.argv[2]); print('%.2fx (efficiency %.0f %%)' % (a / b, 50 * a / b))" "$1" "$2"; }
echo "  grains 10k, 2 ranks:          $(sp "${WALL[g10k_serial]}" "${WALL[g10k_2ranks]}")"
echo "  grains 10k, 2 ranks cut in x: $(sp "${WALL[g10k_serial]}" "${WALL[g10k_2ranks_x]}")"
echo "  grains 10k, 1 rank x 2 thr:   $(sp "${WALL[g10k_serial]}" "${WALL[g10k_2threads]}")"
echo "  two serial runs at once:      $TWIN of one run's throughput (the ceiling for 2 ranks)"
[ -n "${WALL[g10k_2ranks_det]:-}" ] && echo "  grains 10k, 2 ranks determ.:  $(sp "${WALL[g10k_serial]}" "${WALL[g10k_2ranks_det]}")"
if [ -n "${WALL[lig10k_2ranks]:-}" ]; then
  echo "  LIGGGHTS 10k, 2 ranks * * *:  $(sp "${WALL[lig10k_serial]}" "${WALL[lig10k_2ranks_auto]}")"
  echo "  LIGGGHTS 10k, 2 ranks 2 1 1:  $(sp "${WALL[lig10k_serial]}" "${WALL[lig10k_2ranks_x]}")"
  python3 -c "import sys; print('  grains / LIGGGHTS throughput: serial %.2fx, 2 ranks %.2fx' % (float(sys.argv[1]) / float(sys.argv[2]), float(sys.argv[3]) / float(sys.argv[4])))" \
    "${WALL[lig10k_serial]}" "${WALL[g10k_serial]}" "${WALL[lig10k_2ranks]}" "${WALL[g10k_2ranks]}"
fi
if [ -n "${WALL[g50k_serial]:-}" ]; then
  echo "  grains 50k, 2 ranks:          $(sp "${WALL[g50k_serial]}" "${WALL[g50k_2ranks]}")"
  echo "  grains 50k, 1 rank x 2 thr:   $(sp "${WALL[g50k_serial]}" "${WALL[g50k_2threads]}")"
  echo "  50k decomposition: $(summary "$WORK/g50k_2ranks" decomposition), imbalance $(summary "$WORK/g50k_2ranks" load_imbalance), rebalances $(summary "$WORK/g50k_2ranks" rebalances)"
fi
echo "  10k decomposition: $(summary "$WORK/g10k_2ranks" decomposition), imbalance $(summary "$WORK/g10k_2ranks" load_imbalance), rebalances $(summary "$WORK/g10k_2ranks" rebalances)"
echo "== load after: $(uptime)"
