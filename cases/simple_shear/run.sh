#!/bin/bash
# The mu(I) sweep: case.yaml at each inertial number of I_VALUES (rate and
# duration set from I: 8 strain units, the means over the last 5), then
# analyze.py. Usage: run.sh [OUT] ; env GRAINS (grains), PYTHON (python3),
# I_VALUES (default "0.001 0.002 0.005 0.01 0.02 0.05 0.1 0.2 0.3"),
# STRAIN (8), GRAINS_ARGS (extra options for every run), PNG (OUT/mu_I.png).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
grains=${GRAINS:-grains}
out=${1:-out/simple_shear}
I_VALUES=${I_VALUES:-"0.001 0.002 0.005 0.01 0.02 0.05 0.1 0.2 0.3"}
STRAIN=${STRAIN:-8}
# P = 1000 Pa, rho = 2500 kg/m^3, mean d = 1 mm: rate = I sqrt(P/rho) / d.
for I in $I_VALUES; do
  read -r rate end every after < <(awk -v I="$I" -v g="$STRAIN" 'BEGIN {
    r = I * sqrt(1000 / 2500) / 0.001; e = g / r;
    printf "%.6g %.6g %.6g %.6g\n", r, e, e / 200, e * 3 / 8 }')
  dir="$out/I_$I"
  if [ -f "$dir/summary.json" ]; then echo "simple_shear: $dir done already"; continue; fi
  resume=()
  last=$(ls "$dir"/checkpoints/checkpoint_*.h5 2>/dev/null | sort | tail -n 1 || true)
  [ -n "$last" ] && resume=(--restart "$last")
  echo "simple_shear: I = $I, rate $rate /s, $end s"
  mkdir -p "$dir" && echo "$rate" > "$dir/rate.txt"
  # shellcheck disable=SC2086
  "$grains" run "$here/case.yaml" -o "$dir" "${resume[@]}" --set domain.shear.rate="$rate" --set time.end="$end" \
    --set output.stress.every="$every" --set output.stress.average_after="$after" --set output.every="$(awk -v e="$end" 'BEGIN{printf "%.6g", e/10}')" \
    --set checkpoint.every="$(awk -v e="$end" 'BEGIN{printf "%.6g", e/10}')" ${GRAINS_ARGS:-}
done
"${PYTHON:-python3}" "$here/analyze.py" "$out" "${PNG:-$out/mu_I.png}"
