#!/usr/bin/env bash
# Old and new builds alternated on the mesh walls' cost: for each binary in
# turn, the 10k pour (cases/pour_spheres, serial) with its five planes and
# with the 10-triangle mesh box of run.sh; prints each run's wall time and
# its walls and neighbour stages. Run run.sh once first (it writes the box).
#   bash bench/mesh_walls/alternate.sh OLD/grains NEW/grains   (ROUNDS, default 2; WORK as run.sh)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
WORK="${WORK:-/tmp/grains-bench-mesh-walls}"
CASE="$ROOT/cases/pour_spheres/case.yaml"
BOX="$WORK/box10.off"
[ -f "$BOX" ] || { echo "no $BOX: run bench/mesh_walls/run.sh first" >&2; exit 1; }
export OMP_NUM_THREADS=1
echo "== $(date -u +%FT%TZ) $(uname -n); load before: $(uptime)"
for r in $(seq 1 "${ROUNDS:-2}"); do
  for G in "$@"; do
    for k in planes mesh; do
      out="$WORK/alt-$k"
      rm -rf "$out"
      if [ $k = planes ]; then
        "$G" run "$CASE" -o "$out" -q --set output.every=0.34616 >/dev/null
      else
        "$G" run "$CASE" -o "$out" -q --set output.every=0.34616 \
          --set "walls=[{type: mesh, name: box, file: $BOX, material: grain}]" >/dev/null
      fi
      python3 - "$out" "$G" "$k" "$r" <<'PY'
import json, sys
out, g, k, r = sys.argv[1:]
s = json.load(open(out + "/summary.json"))
st = s["stage_seconds"]
w = sum(v for n, v in st.items() if "force.walls" in n)
n = sum(v for n, v in st.items() if n.startswith("neighbor"))
print("round %s %-40s %-6s wall %6.2f s  walls stage %6.3f s  neighbour stage %6.3f s" % (r, g, k, s["wall_time_s"], w, n))
PY
    done
  done
done
echo "== load after: $(uptime)"
