#!/bin/bash
# Cost per neighbour-list pair of the pair stage with each normal law, in a
# settled bed: cases/pour_spheres (10,000 grains, Mindlin friction) poured
# to its end once with Hertz and once with JKR (w = 0.1 J/m^2,
# surface_energy 0.05), each checkpointed; then each bed is restarted for
# STEPS steps, alternately, ROUNDS times: Hertz and DMT from the Hertz bed,
# JKR from the JKR bed (an adhesive bed is looser: per pair, not per
# grain). Prints ns per list pair per step of the pair stage, from
# summary.json's stage_seconds and neighbor_pairs_per_step.
# Usage: bench/laws/run.sh [GRAINS] [WORKDIR]   (serial; keep the machine idle)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
grains=${1:-$root/build/grains}
work=${2:-/tmp/bench_laws}
steps=${STEPS:-3000}
rounds=${ROUNDS:-3}
case=$root/cases/pour_spheres/case.yaml
export OMP_NUM_THREADS=1
mkdir -p "$work"
bed() {  # name, extra --set ...
  local name=$1; shift
  if [ ! -f "$work/bed_$name/checkpoints/checkpoint_000000040000.h5" ]; then
    echo "pouring the $name bed (40,000 steps)..." >&2
    "$grains" run "$case" -o "$work/bed_$name" --set checkpoint.every_steps=40000 "$@" -q
  fi
}
bed hertz
bed jkr --set contact.model=jkr --set materials.0.surface_energy=0.05
dt=8.654e-6
end=$(python3 -c "print(40000 * $dt + $steps * $dt)")
one() {  # label, bed, extra --set ...
  local label=$1 b=$2; shift 2
  rm -rf "$work/run_$label"
  "$grains" run "$case" --restart "$work/bed_$b/checkpoints/checkpoint_000000040000.h5" -o "$work/run_$label" \
    --set time.end="$end" "$@" -q
  python3 - "$work/run_$label/summary.json" "$label" "$steps" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); steps = int(sys.argv[3])
pair = [v for k, v in d["stage_seconds"].items() if "pair_contacts" in k][0]
print(f"{sys.argv[2]:6s} pairs/step {d['neighbor_pairs_per_step']:9.0f}  pair stage {pair:7.3f} s  "
      f"{1e9 * pair / steps / d['neighbor_pairs_per_step']:6.2f} ns per list pair")
PY
}
uptime
for r in $(seq "$rounds"); do
  one hertz hertz
  one dmt hertz --set contact.model=dmt --set materials.0.surface_energy=0.05
  one jkr jkr --set contact.model=jkr --set materials.0.surface_energy=0.05
done
uptime
