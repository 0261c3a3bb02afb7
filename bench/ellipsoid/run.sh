#!/usr/bin/env bash
# Ellipsoid pour vs sphere pour on the same scene: cases/pour_ellipsoids
# (1,000 particles of volume-equivalent diameter 1 mm poured into a
# 10 d x 10 d box) at aspect ratio AR, and the same scene with spheres
# (cases/pour_spheres with --set: same N, box, fill region, seed, time step,
# neighbour skin, end time and output). Prints particle-steps/s of both and
# their ratio. Results: bench/RESULTS.md.
#
#   bash bench/ellipsoid/run.sh            (about 2-4 minutes on one core)
#
# Environment: BUILD (grains build dir, default build-bench; the grains target
# is built if needed), AR (default 2), END (simulated seconds, default 0.3),
# WORK (scratch, default $BUILD/bench-ellipsoid), REPEAT (runs of each, best
# kept, default 1).
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
BUILD="${BUILD:-$ROOT/build-bench}"
AR="${AR:-2}"
END="${END:-0.3}"
REPEAT="${REPEAT:-1}"
WORK="${WORK:-$BUILD/bench-ellipsoid}"
mkdir -p "$WORK"
export OMP_NUM_THREADS=1
if [ ! -f "$BUILD/CMakeCache.txt" ]; then
  cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$BUILD" --target grains -j2 >/dev/null
GRAINS="$BUILD/grains"

ELL_CASE="$ROOT/cases/pour_ellipsoids/case.yaml"
ELL_SET=(--set "particles.0.shape.aspect_ratio=$AR" --set "time.end=$END" --set "output.every=$END"
         --set "neighbor.skin=0.1")
# The ellipsoid case's time step (0.2 Rayleigh times of its particles), reused for the spheres.
DT=$("$GRAINS" check "$ELL_CASE" "${ELL_SET[@]}" | sed -n 's/^time step: \([^ ]*\) s.*/\1/p')
SPH_CASE="$ROOT/cases/pour_spheres/case.yaml"
SPH_SET=(--set "particles.0.count=1000" --set "walls.2.point=[0.01, 0, 0]" --set "walls.4.point=[0, 0.01, 0]"
         --set "particles.0.placement.region.max=[0.01, 0.01, 0.1]" --set "domain.max=[0.011, 0.011, 0.101]"
         --set "particles.0.placement.seed=7" --set "time.dt=$DT" --set "time.end=$END" --set "output.every=$END"
         --set "neighbor.skin=0.1")

best() {  # best throughput of REPEAT runs: best <name> <grains args...>
  local name=$1; shift
  local b=0
  for _ in $(seq "$REPEAT"); do
    local t
    t=$("$GRAINS" run "$@" -o "$WORK/$name" 2>/dev/null | sed -n 's/.*throughput: \([^ ]*\) particle-steps.*/\1/p')
    b=$(python3 -c "print(max($b, $t))")
  done
  echo "$b"
}

echo "== $(date -u +%FT%TZ)  $(lscpu | sed -n 's/^Model name: *//p')  load: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "== dt = $DT s, end = $END s, 1000 particles, aspect ratio $AR"
S=$(best spheres "$SPH_CASE" "${SPH_SET[@]}")
E=$(best ellipsoids "$ELL_CASE" "${ELL_SET[@]}")
echo "spheres:    $S particle-steps/s"
echo "ellipsoids: $E particle-steps/s (aspect ratio $AR)"
python3 -c "print('ratio ellipsoid/sphere: %.3f (1/%.1f)' % ($E/$S, $S/$E))"
# Cost of the pair stage per neighbour-list pair and step (last run of each).
per_pair() {
  python3 - "$WORK/$1/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
t = sum(v for k, v in s["stage_seconds"].items() if "pair" in k or "ellipsoid" in k)
n = s["neighbor_pairs_per_step"] * s["steps"]
print("%.1f ns per neighbour pair and step (%.0f pairs per step, pair stage %.2f s)" % (1e9 * t / n, s["neighbor_pairs_per_step"], t) if n > 0 else "no pairs")
PY
}
echo "spheres pair stage:    $(per_pair spheres)"
echo "ellipsoids pair stage: $(per_pair ellipsoids)"
echo "== load after: $(cut -d' ' -f1-3 /proc/loadavg)"
