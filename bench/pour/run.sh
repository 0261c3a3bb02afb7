#!/usr/bin/env bash
# Serial pour benchmark: grains vs LIGGGHTS on the scene of cases/pour_spheres
# (10,000 spheres poured into a 20 d x 20 d box, 40,000 steps), same initial
# positions, same force law. Prints particle-steps/s of both, their ratio and
# the final bulk packing fractions. Results: bench/RESULTS.md.
#
#   bash bench/pour/run.sh            (about 5-10 minutes on one core)
#
# Environment: BUILD (grains build dir, default build-bench), WORK (scratch,
# default $BUILD/bench-pour), LIGGGHTS (default liggghts), CASE (default
# cases/pour_spheres/case.yaml), PACKING=0 to skip the packing fractions,
# GRAINS_REV=<git revision> to benchmark a committed revision (exported with
# git archive into $BUILD/src-<rev>, built in $BUILD/rev-<rev>) instead of the
# working tree, which other people may be editing.
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
BUILD="${BUILD:-$ROOT/build-bench}"
WORK="${WORK:-$BUILD/bench-pour}"
mkdir -p "$WORK"; WORK="$(cd "$WORK" && pwd)"  # absolute: LIGGGHTS runs from a sub-folder
LIGGGHTS="${LIGGGHTS:-liggghts}"
CASE="${CASE:-$ROOT/cases/pour_spheres/case.yaml}"
export OMP_NUM_THREADS=1   # serial comparison

echo "== load before: $(uptime)"

# (a) grains, built if needed (only the grains target).
SRC="$ROOT"; GBUILD="$BUILD"
if [ -n "${GRAINS_REV:-}" ]; then
  REV=$(git -C "$ROOT" rev-parse --short "$GRAINS_REV")
  SRC="$BUILD/src-$REV"; GBUILD="$BUILD/rev-$REV"
  if [ ! -d "$SRC" ]; then
    mkdir -p "$SRC.tmp" && git -C "$ROOT" archive "$REV" | tar -x -C "$SRC.tmp" && mv "$SRC.tmp" "$SRC"
  fi
fi
if [ ! -f "$GBUILD/CMakeCache.txt" ]; then
  cmake -S "$SRC" -B "$GBUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$GBUILD" --target grains -j2 >/dev/null
GRAINS="$GBUILD/grains"
echo "== grains: $("$GRAINS" --version 2>&1 | head -1) from ${GRAINS_REV:+revision $REV of }$SRC"
command -v "$LIGGGHTS" >/dev/null || { echo "LIGGGHTS not found: apt-get install --no-install-recommends liggghts" >&2; exit 1; }

# The scene, read from the case file (one source of truth).
eval "$(python3 "$HERE/scene.py" params "$CASE")"
rm -rf "$WORK"; mkdir -p "$WORK/grains" "$WORK/liggghts"

# (b) One set of initial positions, for both codes.
python3 "$HERE/gen_positions.py" "$WORK" "$N" "$SEED" "$R" "$RHO" "$L" "$ZTOP" "$DOMAIN"

# (c) grains on that scene: the case with placement {type: file}, first and
# last VTK frame only, no progress line.
python3 "$HERE/scene.py" case "$CASE" positions.txt "$WORK/case.yaml"
echo "== grains: $GRAINS run $WORK/case.yaml -o $WORK/grains -q"
cpu_seconds() {  # cpu_seconds FILE CMD...: runs CMD, writes its user+sys CPU seconds to FILE
  python3 -c "
import os, resource, subprocess, sys
r = subprocess.run(sys.argv[2:]).returncode
u = resource.getrusage(resource.RUSAGE_CHILDREN)
open(sys.argv[1], 'w').write('%.3f\\n' % (u.ru_utime + u.ru_stime))
sys.exit(r)" "$@"
}
cpu_seconds "$WORK/grains.cpu" "$GRAINS" run "$WORK/case.yaml" -o "$WORK/grains" -q

# (d) LIGGGHTS, serial, same scene and physics. The restitution handed to it
# gives the same damping coefficient as grains's calibrated one (match_damping.py).
read -r DAMPING E_LIGGGHTS < <(python3 "$HERE/match_damping.py" "$REST")
sed -e "s#@DATA@#$WORK/atoms.data#; s#@SKIN@#$SKIN#g; s#@E@#$E#; s#@NU@#$NU#; s#@MU@#$MU#" \
    -e "s#@E_LIGGGHTS@#$E_LIGGGHTS#; s#@DT@#$DT#; s#@L@#$L#g; s#@STEPS@#$STEPS#g" \
    -e "s#@DUMP@#$WORK/liggghts/final.dump#" "$HERE/in.liggghts" > "$WORK/liggghts/in.liggghts"
echo "== LIGGGHTS: $LIGGGHTS -in $WORK/liggghts/in.liggghts -log $WORK/liggghts/log.liggghts -echo none -screen none"
(cd "$WORK/liggghts" && cpu_seconds "$WORK/liggghts.cpu" "$LIGGGHTS" -in in.liggghts -log log.liggghts -echo none -screen none)

# (e) Figures.
G_RATE=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['particle_steps_per_second'])" "$WORK/grains/summary.json")
G_STEPS=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['steps'])" "$WORK/grains/summary.json")
G_WALL=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['wall_time_s'])" "$WORK/grains/summary.json")
G_LOST=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['lost_particles'])" "$WORK/grains/summary.json")
LOOP=$(grep -m1 '^Loop time of' "$WORK/liggghts/log.liggghts" || true)
if [ -z "$LOOP" ]; then echo "LIGGGHTS failed:" >&2; tail -5 "$WORK/liggghts/log.liggghts" >&2; exit 1; fi
L_TIME=$(echo "$LOOP" | awk '{print $4}'); L_STEPS=$(echo "$LOOP" | awk '{print $9}'); L_ATOMS=$(echo "$LOOP" | awk '{print $12}')
L_RATE=$(python3 -c "print($N * $L_STEPS / $L_TIME)")
RATIO=$(python3 -c "print('%.3f' % ($G_RATE / $L_RATE))")

echo
echo "== scene: N = $N, d = $(python3 -c "print(2*$R)") m, rho = $RHO, E = $E, nu = $NU, e = $REST (LIGGGHTS: $E_LIGGGHTS, same damping a = $DAMPING), mu = $MU, dt = $DT, $STEPS steps, skin $SKIN m"
printf "grains:   %8.0f particle-steps/s  (%s steps in %.2f s, lost %s)\n" "$G_RATE" "$G_STEPS" "$G_WALL" "$G_LOST"
printf "LIGGGHTS: %8.0f particle-steps/s  (%s steps in %.2f s, %s atoms at the end)\n" "$L_RATE" "$L_STEPS" "$L_TIME" "$L_ATOMS"
echo "ratio grains/LIGGGHTS: $RATIO"
# On a shared machine wall time depends on the load; CPU time (whole process,
# set-up included, so slightly unfavourable to both) much less.
G_CPU=$(cat "$WORK/grains.cpu"); L_CPU=$(cat "$WORK/liggghts.cpu")
python3 -c "
g, l = $N * $G_STEPS / $G_CPU, $N * $L_STEPS / $L_CPU
print('per CPU second (whole process): grains %.0f (%.2f s), LIGGGHTS %.0f (%.2f s), ratio %.3f' % (g, $G_CPU, l, $L_CPU, g / l))"
echo "grains stage seconds:"
python3 -c "
import json,sys
s=json.load(open(sys.argv[1]))['stage_seconds']
for k,v in s.items(): print('  %8.2f  %s' % (v,k))" "$WORK/grains/summary.json"
echo "LIGGGHTS breakdown:"; awk '/^Loop time of/{n++} n==1 && /^(Pair|Neigh|Comm|Outpt|Other|Modify) +time/' "$WORK/liggghts/log.liggghts" | sed 's/^/  /'
grep -E '^Neighbor list builds' "$WORK/liggghts/log.liggghts" | head -1 | sed 's/^/  LIGGGHTS /'
echo "  grains neighbor builds = $(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['neighbor_builds'])" "$WORK/grains/summary.json")"

if [ "${PACKING:-1}" != 0 ]; then
  LAST=$(ls "$WORK"/grains/frames/particles_*.vtu | sort | tail -1)
  read -r GPHI GERR GSURF GN < <(python3 "$HERE/packing.py" grains "$LAST")
  read -r LPHI LERR LSURF LN < <(python3 "$HERE/packing.py" liggghts "$WORK/liggghts/final.dump")
  echo "bulk packing fraction (3 d from walls, floor and surface; sampling error ~$GERR):"
  echo "  grains   $GPHI (surface at z = $GSURF m, $GN particles)"
  echo "  LIGGGHTS $LPHI (surface at z = $LSURF m, $LN particles)"
fi
echo "== load after: $(uptime)"
