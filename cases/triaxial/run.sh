#!/bin/bash
# The two stages of the triaxial test and the analysis, into OUT (default out/triaxial).
#   PREP_FRICTION=0 bash run.sh OUT   consolidates with frictionless grains (a dense
#                                     sample), then shears it with the case's friction 0.5
#   SHEAR_END=0.6 ...                 ends the shear stage at that time (0.2 s of shear:
#                                     9.5 % axial strain; the case: 1.2, 33 %)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
grains=${GRAINS:-grains}
out=${1:-out/triaxial}
prep=()
[ -n "${PREP_FRICTION:-}" ] && prep=(--set "materials.0.friction=$PREP_FRICTION")
"$grains" run "$here/consolidate.yaml" -o "$out/consolidate" ${GRAINS_ARGS:-} "${prep[@]}"
last=$(ls "$out"/consolidate/checkpoints/checkpoint_*.h5 | sort | tail -n 1)
end=()
[ -n "${SHEAR_END:-}" ] && end=(--set "time.end=$SHEAR_END")
"$grains" run "$here/shear.yaml" -o "$out/shear" --restart "$last" ${GRAINS_ARGS:-} "${end[@]}"
"${PYTHON:-python3}" "$here/analyze.py" "$out/shear" "${PNG:-$out/triaxial.png}"
