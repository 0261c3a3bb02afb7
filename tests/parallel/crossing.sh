#!/usr/bin/env bash
# The loaded tangential contact of tests/parallel/crossing.yaml crosses from
# rank 0 to rank 1: the 2-rank run must be bitwise identical to the serial
# one (deterministic force sums), the particles must have migrated, and the
# contact's tangential force must be carried by its spring when it crosses
# (well above zero, below the Coulomb limit mu m g = 1.6e-4 N). Dropping the
# history at migration makes this test fail (checked by hand).
#   crossing.sh GRAINS COMPARE WORKDIR
set -euo pipefail
grains=$1 compare=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
rm -rf "$work" && mkdir -p "$work"
"$grains" run "$here/crossing.yaml" -o "$work/serial" -q --set parallel.deterministic=true
mpirun --oversubscribe -np 2 "$grains" run "$here/crossing.yaml" -o "$work/ranks2" -q --set parallel.deterministic=true
"$compare" "$work/serial" "$work/ranks2"
migrated=$(grep -o '"migrated_particles": [0-9]*' "$work/ranks2/summary.json" | grep -o '[0-9]*$')
echo "particles migrated between ranks: $migrated"
[ "$migrated" -ge 1 ] || { echo "FAIL: the slider never changed rank"; exit 1; }
# The slider (id 1) around the crossing: x from -20 um to +20 um.
"$compare" --track 1 "$work/ranks2" > "$work/track.txt"
awk '$2 > -2e-5 && $2 < 2e-5 {n++; f = ($5 < 0 ? -$5 : $5); if (f < 2e-5 || f > 1.5e-4) bad++; printf "t = %.5f s  x = %+.3e m  tangential force fx = %.3e N\n", $1, $2, $5}
     END {if (n < 2) {print "FAIL: fewer than 2 frames near the crossing"; exit 1}
          if (bad) {print "FAIL: the tangential spring was not loaded below the Coulomb limit at the crossing"; exit 1}
          print "loaded tangential contact across the rank boundary: " n " frames, history kept (bitwise equal to serial)"}' "$work/track.txt"
