#!/usr/bin/env bash
# Scale benchmark (issue 26): settled beds of 10^4 ... 10^7 spheres, grains
# serial and on 2 MPI ranks, LIGGGHTS on the same beds (serial, up to
# LIGGGHTS_MAX grains). For each: particle-steps/s, ns per neighbour-list pair
# in the pair stage, peak resident memory per grain, and set-up time (the
# process's wall time less the stepping loop's). Results: bench/RESULTS.md.
#
#   bash bench/scale/run.sh                      (10^4 - 10^6: about half an hour)
#   SIZES="40x25" STEPS=300 bash bench/scale/run.sh   (10^7 grains: 8.5 GB)
#
# The beds: bench/scale/seed.yaml (10^4 grains poured into a box periodic in
# x and y; built once into $WORK/seed) repeated KX x KY times side by side by
# tile.py. SIZES lists KXxKY (default "1x1 5x2 10x10": 10^4, 10^5, 10^6).
# Environment: GRAINS (binary, default build/grains), WORK (scratch, default
# /tmp/grains-bench-scale), STEPS (default 1000), RANKS (default "1 2"),
# LIGGGHTS (default liggghts; LIGGGHTS_MAX default 1000000, 0 to skip),
# PYTHON (with numpy and vtk; default /usr/bin/python3).
#
# Wide size distributions: POLY="uniform10:2x2 uniform20 bimodal10:3x3
# bimodal20:4x4" (seeds in poly/: size ratios 10 and 20) adds those beds, each with a skin
# per grain and with one skin, beside LIGGGHTS; SIZES="" runs only them.
# SETTLE=T continues each poly seed from rest for T s of simulated time first
# (its grains stop rattling) and tiles that. Their columns to read beside the
# mono bed's: ns per list pair (pair stage)
# and ns per grain-step (neighbour stage); SIZES="6x3" adds a monodisperse bed
# of 180,000 grains, the size of bimodal10:3x3 (the cache then holds as much
# of either).
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
GRAINS="${GRAINS:-$ROOT/build/grains}"
WORK="${WORK:-/tmp/grains-bench-scale}"
STEPS="${STEPS:-1000}"
SIZES="${SIZES-1x1 5x2 10x10}"
RANKS="${RANKS:-1 2}"
LIGGGHTS="${LIGGGHTS:-liggghts}"
LIGGGHTS_MAX="${LIGGGHTS_MAX:-1000000}"
PYTHON="${PYTHON:-/usr/bin/python3}"
export OMP_NUM_THREADS=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mkdir -p "$WORK"; WORK="$(cd "$WORK" && pwd)"
echo "== $(date -u '+%Y-%m-%d %H:%M UTC') on $(hostname): $(nproc --all) cores, $(free -g | awk '/Mem:/{print $2}') GiB; load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "== grains: $GRAINS ($("$GRAINS" --version | head -1), commit $(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo '?'))"

# The seed bed, once.
SEED="$WORK/seed/frames/particles_000001.vtu"
if [ ! -f "$SEED" ]; then
  echo "== seed bed: $GRAINS run $HERE/seed.yaml (10^4 grains, 40,000 steps)"
  "$GRAINS" run "$HERE/seed.yaml" -o "$WORK/seed" -q
fi

# wall_seconds FILE CMD...: runs CMD; FILE gets its wall seconds and peak RSS (bytes) of the children.
measure() {
  "$PYTHON" -c "
import resource, subprocess, sys, time
t = time.monotonic()
r = subprocess.run(sys.argv[2:]).returncode
w = time.monotonic() - t
u = resource.getrusage(resource.RUSAGE_CHILDREN)
open(sys.argv[1], 'w').write('%.3f %d\n' % (w, u.ru_maxrss * 1024))
sys.exit(r)" "$@"
}

ROWS="$WORK/rows.md"; : > "$ROWS"

# run_bed BED LABEL [--set ...]: grains on RANKS ranks, then LIGGGHTS, on the
# bed tile.py wrote into BED; one table row each, LABEL naming the bed.
run_bed() {
  local BED="$1" LABEL="$2"; shift 2
  source "$BED/bed.env"
  local tag; tag="$(printf '%s' "$*" | tr -c 'A-Za-z0-9_.=' '_')"
  for np in $RANKS; do
    OUT="$BED/grains_np$np$tag"; rm -rf "$OUT"
    if [ "$np" = 1 ]; then
      measure "$OUT.m" "$GRAINS" run "$BED/case.yaml" -o "$OUT" -q "$@"
    else
      # (peak RSS here is the largest rank's; the row gives the ranks' sum from summary.json)
      measure "$OUT.m" mpirun --oversubscribe -np "$np" "$GRAINS" run "$BED/case.yaml" -o "$OUT" -q "$@"
    fi
    "$PYTHON" - "$OUT/summary.json" "$OUT.m" "$N" "$np" "$LABEL${*:+ ($*)}" >> "$ROWS" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])); wall, rss = open(sys.argv[2]).read().split(); n = int(sys.argv[3])
np_ = int(sys.argv[4])
pair = sum(v for k, v in s['stage_seconds'].items() if 'pair_contacts' in k)
neigh = sum(v for k, v in s['stage_seconds'].items() if k.startswith('neighbor'))
pairs = s['neighbor_pairs_per_step'] * s['steps']
mem = s['memory']
rss_n = mem['peak_resident_bytes'] / n
b = max(1, s['neighbor_builds'])
print('| grains | %s | %d | %s | %.3g | %.1f | %.2f | %d | %.1f | %.2f | %.0f | %.0f | %.1f | %.1f |' % (
    sys.argv[5], n, np_, s['particle_steps_per_second'], pair / pairs * 1e9 * np_, s['neighbor_pairs_per_step'] / n,
    s['neighbor_builds'], neigh / (n * s['steps']) * 1e9 * np_, neigh / (n * b) * 1e6 * np_, rss_n,
    mem['counted_bytes_per_particle'], float(wall) - s['wall_time_s'], s['wall_time_s']))
PY
    tail -1 "$ROWS"
  done
  if [ -z "$*" ] && [ -f "$BED/atoms.data" ] && command -v "$LIGGGHTS" > /dev/null; then
    mkdir -p "$BED/liggghts"
    read -r _ E_L < <(python3 "$ROOT/bench/pour/match_damping.py" "$REST")
    sed -e "s#@DATA@#$BED/atoms.data#; s#@SKIN@#$SKIN#g; s#@E@#$E#; s#@NU@#$NU#; s#@MU@#$MU#" \
        -e "s#@E_LIGGGHTS@#$E_L#; s#@DT@#$DT#; s#@STEPS@#$STEPS#g" "$HERE/in.liggghts" > "$BED/liggghts/in.liggghts"
    (cd "$BED/liggghts" && measure ../liggghts.m "$LIGGGHTS" -in in.liggghts -log log.liggghts -echo none -screen none)
    "$PYTHON" - "$BED/liggghts/log.liggghts" "$BED/liggghts.m" "$N" "$LABEL" >> "$ROWS" <<'PY'
import re, sys
log = open(sys.argv[1]).read(); wall, rss = open(sys.argv[2]).read().split(); n = int(sys.argv[3])
m = re.search(r'Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps', log)
loop, steps = float(m.group(1)), int(m.group(2))
sec = lambda name: float(re.search(r'^%s\s+time \(%%\) = ([0-9.eE+-]+)' % name, log, re.M).group(1))
nb = re.search(r'Total # of neighbors = (\d+)', log)
per_pair = sec('Pair') / (int(nb.group(1)) * steps) * 1e9 if nb else float('nan')
per_grain = int(nb.group(1)) / n if nb else float('nan')
builds = int(re.search(r'Neighbor list builds = (\d+)', log).group(1))
neigh = sec('Neigh')  # seconds (the number before the percentage)
print('| LIGGGHTS | %s | %d | 1 | %.3g | %.1f | %.2f | %d | %.1f | %.2f | %.0f | | %.1f | %.1f |' % (
    sys.argv[4], n, n * steps / loop, per_pair, per_grain, builds, neigh / (n * steps) * 1e9,
    neigh / (n * max(1, builds)) * 1e6, int(rss) / n, float(wall) - loop, loop))
PY
    tail -1 "$ROWS"
  fi
}

for size in $SIZES; do
  KX=${size%x*}; KY=${size#*x}
  BED="$WORK/bed_$size"
  "$PYTHON" "$HERE/tile.py" "$SEED" "$KX" "$KY" "$STEPS" "$BED" --vtk 0 --liggghts-max "$LIGGGHTS_MAX"
  run_bed "$BED" "mono $size"
done

# Wide size distributions (POLY: names of seeds in poly/, e.g. "uniform10
# bimodal20:3x3"): each seed poured once into $WORK/seed_NAME, tiled as the
# name's :KXxKY says (default POLY_TILE, or 1x1: a bed as wide as 20 of its
# largest grains has as many periodic images as grains, whose refresh each
# step then dominates the neighbour stage; tile it to the width of the
# monodisperse bed in cut-offs), run with a skin per grain (the seeds' setting) and with the
# largest grain's skin for all (neighbor.skin_per_grain=false), and in LIGGGHTS.
for entry in ${POLY:-}; do
  name="${entry%%:*}"; size="${POLY_TILE:-1x1}"
  [ "$entry" != "$name" ] && size="${entry#*:}"
  PSEED="$WORK/seed_$name/frames/particles_000001.vtu"
  if [ ! -f "$PSEED" ]; then
    echo "== seed bed: $GRAINS run $HERE/poly/$name.yaml"
    "$GRAINS" run "$HERE/poly/$name.yaml" -o "$WORK/seed_$name" -q
  fi
  if [ "${SETTLE:-0}" != 0 ]; then
    # The seed at rest as it is, then SETTLE more seconds of simulated time:
    # its last frame becomes the seed (bed_*_settled*).
    SDIR="$WORK/settle_${name}_$SETTLE"
    if [ ! -f "$SDIR/run/summary.json" ]; then
      "$PYTHON" "$HERE/tile.py" "$PSEED" 1 1 1 "$SDIR" --vtk 1 --liggghts-max 0 --seed-case "$HERE/poly/$name.yaml"
      nsettle=$("$PYTHON" -c "import sys; print(max(1, round($SETTLE / $(. "$SDIR/bed.env"; echo "$DT"))))")
      echo "== settling $name for $SETTLE s ($nsettle steps)"
      "$GRAINS" run "$SDIR/case.yaml" -o "$SDIR/run" -q --set time.end="$SETTLE" --set output.every_steps="$nsettle"
    fi
    PSEED="$(ls "$SDIR"/run/frames/particles_*.vtu | tail -1)"
    size="${size}_settled$SETTLE"
  fi
  KX=${size%%x*}; KY=${size#*x}; KY=${KY%%_*}
  BED="$WORK/bed_${name}_$size"
  "$PYTHON" "$HERE/tile.py" "$PSEED" "$KX" "$KY" "$STEPS" "$BED" --vtk 0 --liggghts-max "$LIGGGHTS_MAX" \
    --seed-case "$HERE/poly/$name.yaml"
  run_bed "$BED" "$name $size"
  RANKS=1 run_bed "$BED" "$name $size" --set neighbor.skin_per_grain=false
done
echo
echo "| code | bed | grains | ranks | particle-steps/s | ns per list pair (pair stage) | list pairs per grain | list builds | neighbour stage ns per grain-step | neighbour stage µs per grain per build | peak RSS B/grain | counted B/grain | set-up s | loop s |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
cat "$ROWS"
echo "== load after: $(cut -d' ' -f1-3 /proc/loadavg)"
