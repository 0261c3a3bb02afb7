#!/bin/bash
# Angle of repose from a lifted cylinder: fill.yaml (pour and settle), then
# lift.yaml from its last checkpoint, then analyze.py on the heap.
#   run.sh [OUT]   env: GRAINS (grains), PYTHON (python3, with VTK's Python
#                  module: Debian's /usr/bin/python3), PNG (OUT/heap.png), GRAINS_ARGS
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
grains=${GRAINS:-grains}
out=${1:-out/angle_of_repose}
# shellcheck disable=SC2086
[ -f "$out/fill/summary.json" ] || "$grains" run "$here/fill.yaml" -o "$out/fill" ${GRAINS_ARGS:-}
last=$(ls "$out"/fill/checkpoints/checkpoint_*.h5 | sort | tail -n 1)
# shellcheck disable=SC2086
"$grains" run "$here/lift.yaml" -o "$out/lift" --restart "$last" ${GRAINS_ARGS:-}
"${PYTHON:-python3}" "$here/analyze.py" "$out/lift" "${PNG:-$out/heap.png}"
