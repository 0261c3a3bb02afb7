#!/bin/bash
# The two stages of the triaxial test and the analysis, into OUT (default out/triaxial).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
grains=${GRAINS:-grains}
out=${1:-out/triaxial}
"$grains" run "$here/consolidate.yaml" -o "$out/consolidate"
last=$(ls "$out"/consolidate/checkpoints/checkpoint_*.h5 | sort | tail -n 1)
"$grains" run "$here/shear.yaml" -o "$out/shear" --restart "$last"
"${PYTHON:-python3}" "$here/analyze.py" "$out/shear" "$here/triaxial.png"
