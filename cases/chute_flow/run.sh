#!/bin/bash
# Inclined chute flow over a rough frozen base (Silbert et al. 2001), and
# its Bagnold profile: bench/chute/gen.py makes the scene (the LAMMPS chute
# benchmark's physics: Hooke with history, k_n = 2e5 m g/d, k_t = 2/7 k_n,
# gamma_n = 50, friction 0.5, dt = 1e-4 sqrt(d/g)) at 24 degrees, NX x NX
# grains per layer, periodic in x and y; grains runs it with output.stress
# profiles along z (bins of one diameter), and analyze.py fits the profile.
#   run.sh [OUT]   env: GRAINS (grains), PYTHON (python3), STEPS (1500000),
#                       NX (10), LAYERS (20), ANGLE (24), AVERAGE_AFTER (100, in sqrt(d/g)),
#                       PNG (OUT/chute_flow.png)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
grains=${GRAINS:-grains}
out=${1:-out/chute_flow}
STEPS=${STEPS:-1500000}
NX=${NX:-10}
LAYERS=${LAYERS:-20}
ANGLE=${ANGLE:-24}
AFTER=${AVERAGE_AFTER:-100}
mkdir -p "$out"
"${PYTHON:-python3}" "$here/../../bench/chute/gen.py" "$out" "$STEPS" "$NX" "$LAYERS" 1 "$ANGLE" random
resume=()
last=$(ls "$out"/run/checkpoints/checkpoint_*.h5 2>/dev/null | sort | tail -n 1 || true)
[ -n "$last" ] && resume=(--restart "$last")
end=$(awk -v s="$STEPS" 'BEGIN{printf "%.10g", s * 1e-4}')
"$grains" run "$out/case.yaml" -o "$out/run" "${resume[@]}" \
  --set "output={every: $(awk -v e="$end" 'BEGIN{printf "%.10g", e/10}'), progress: true, stress: {every: 0.5, average_after: $AFTER, region: {min: [0, 0, 0.5], max: [$NX, $NX, 40.5]}, profile_axis: z, bins: 40}}" \
  --set "checkpoint={every: $(awk -v e="$end" 'BEGIN{printf "%.10g", e/20}'), keep: 2}"
"${PYTHON:-python3}" "$here/analyze.py" "$out/run" "$ANGLE" "${PNG:-$out/chute_flow.png}"
