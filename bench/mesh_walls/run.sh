#!/usr/bin/env bash
# Mesh walls against plane walls on the same scene: cases/pour_spheres
# (10,000 spheres poured into a 20 d x 20 d box) with its box as
#   planes  the case's five plane walls
#   mesh10  one mesh wall of 10 triangles (the floor and four sides, two each)
#   mesh100k the same box as 100,920 triangles (the floor a 58 x 58 grid of
#           two-triangle cells, each side 58 x 203): every triangle near grains
#   far100k  the 10-triangle box and, in the same mesh, a plate of 100,352
#           triangles beside it where no grain goes (the domain widened to
#           hold it): what a large mesh costs where grains are not
# run alternately (ROUNDS times each, serial). For each run: the wall time,
# the seconds of the wall stage (force.walls) and of the neighbour stage
# (which builds the walls' near lists), and the wall contacts of the last
# frame (grains analyze over the whole domain). The cost per wall contact of a
# mesh wall against a plane wall is the ratio of the wall stages: the three
# runs pour the same particles (their contacts agree in number to a few per
# cent: printed). The 100k-triangle box shows what the mesh's size costs.
#   bash bench/mesh_walls/run.sh      (BUILD: grains build dir, default build; END, ROUNDS, WORK,
#                                      KINDS: e.g. "planes mesh10" for the per-contact ratio alone)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
BUILD="${BUILD:-$ROOT/build}"
GRAINS="${GRAINS:-$BUILD/grains}"
WORK="${WORK:-/tmp/grains-bench-mesh-walls}"
END="${END:-0.34616}"
ROUNDS="${ROUNDS:-2}"
KINDS="${KINDS:-planes mesh10 mesh100k far100k}"  # which boxes, in this order each round
CASE="$ROOT/cases/pour_spheres/case.yaml"
export OMP_NUM_THREADS=1
rm -rf "$WORK" && mkdir -p "$WORK"
echo "== $(date -u +%FT%TZ) $(uname -n), $(getconf _NPROCESSORS_ONLN) cores; load before: $(uptime)"
echo "== grains: $("$GRAINS" --version 2>&1 | head -1) ($GRAINS)"

python3 - "$WORK" <<'PY'
import sys
work = sys.argv[1]
def grid(o, u, w, nu, nw, V, F):
    base = len(V)
    for j in range(nw + 1):
        for i in range(nu + 1):
            V.append(tuple(o[k] + u[k] * i / nu + w[k] * j / nw for k in range(3)))
    idx = lambda i, j: base + j * (nu + 1) + i
    for j in range(nw):
        for i in range(nu):
            a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
            F.extend([(a, b, c), (a, c, d)] if (i + j) % 2 == 0 else [(a, b, d), (b, c, d)])
def box(n_side, n_up, path):
    V, F = [], []
    X, Y, Z = (0.02, 0, 0), (0, 0.02, 0), (0, 0, 0.07)
    grid((0, 0, 0), X, Y, n_side, n_side, V, F)          # floor
    grid((0, 0, 0), Z, X, n_up, n_side, V, F)            # y = 0
    grid((0, 0.02, 0), X, Z, n_side, n_up, V, F)         # y = 0.02
    grid((0, 0, 0), Y, Z, n_side, n_up, V, F)            # x = 0
    grid((0.02, 0, 0), Z, Y, n_up, n_side, V, F)         # x = 0.02
    # weld the shared box edges
    key = {}
    remap = []
    W = []
    for v in V:
        k = tuple(round(c, 12) for c in v)
        if k not in key:
            key[k] = len(W); W.append(v)
        remap.append(key[k])
    with open(path, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(W), len(F)))
        for v in W: f.write("%.17g %.17g %.17g\n" % v)
        for t in F: f.write("3 %d %d %d\n" % tuple(remap[i] for i in t))
    print("%s: %d triangles" % (path, len(F)))
box(1, 1, work + "/box10.off")
box(58, 203, work + "/box100k.off")
# The 10-triangle box and, beside it (x from 0.025 to 0.055 m, where no
# particle goes), a plate of 100,352 triangles: one mesh of 100,362.
V, F = [], []
X, Y, Z = (0.02, 0, 0), (0, 0.02, 0), (0, 0, 0.07)
for o, u, w in [((0, 0, 0), X, Y), ((0, 0, 0), Z, X), ((0, 0.02, 0), X, Z), ((0, 0, 0), Y, Z), ((0.02, 0, 0), Z, Y)]:
    grid(o, u, w, 1, 1, V, F)
grid((0.025, 0, 0.01), (0.03, 0, 0), (0, 0.02, 0), 224, 224, V, F)
with open(work + "/box10_far100k.off", "w") as f:
    f.write("OFF\n%d %d 0\n" % (len(V), len(F)))
    for v in V: f.write("%.17g %.17g %.17g\n" % v)
    for t in F: f.write("3 %d %d %d\n" % t)
print("%s: %d triangles" % (work + "/box10_far100k.off", len(F)))
PY

run() {  # name, extra --set...
  local name=$1 r=$2; shift 2
  local out="$WORK/$name-$r"
  "$GRAINS" run "$CASE" -o "$out" -q --set time.end=$END --set output.every=$END "$@"
  "$GRAINS" analyze "$out" --no-plots --region -1,-1,-1,1,1,1 -o "$out/analysis" > /dev/null 2>&1 || true
  python3 - "$out" "$name" <<'PY'
import json, sys
out, name = sys.argv[1], sys.argv[2]
s = json.load(open(out + "/summary.json"))
walls = sum(v for k, v in s["stage_seconds"].items() if "force.walls" in k)
neigh = sum(v for k, v in s["stage_seconds"].items() if k.startswith("neighbor"))
try:
    wc = json.load(open(out + "/analysis/analysis.json"))["coordination"]["wall_contacts_total"]
except Exception:
    wc = -1
print("%-9s wall %7.2f s  walls stage %6.3f s  neighbour stage %6.3f s  wall contacts (last frame) %5d  lost %d" %
      (name, s["wall_time_s"], walls, neigh, wc, s["lost_particles"]))
with open(out + "/../stages.txt", "a") as f:
    f.write("%s %s %.6f %d\n" % (name, out.rsplit("-", 1)[1], walls, wc))
PY
}
for r in $(seq 1 "$ROUNDS"); do
  for kind in $KINDS; do
    case $kind in
      planes) run planes $r ;;
      mesh10) run mesh10 $r "--set" "walls=[{type: mesh, name: box, file: $WORK/box10.off, material: grain}]" ;;
      mesh100k) run mesh100k $r "--set" "walls=[{type: mesh, name: box, file: $WORK/box100k.off, material: grain}]" ;;
      far100k) run far100k $r --set "domain.max=[0.056,0.021,0.071]" \
        "--set" "walls=[{type: mesh, name: box, file: $WORK/box10_far100k.off, material: grain}]" ;;
      *) echo "bench/mesh_walls: unknown kind '$kind' (planes, mesh10, mesh100k, far100k)" >&2; exit 2 ;;
    esac
  done
done
# Per contact, a mesh against the planes of the same round (their runs are
# minutes apart; the machine's speed drifts between rounds), and the median.
python3 - "$WORK/stages.txt" <<'PY'
import collections, statistics, sys
runs = collections.defaultdict(dict)
for line in open(sys.argv[1]):
    name, r, walls, wc = line.split()
    runs[int(r)][name] = (float(walls), int(wc))
for kind in ("mesh10", "mesh100k", "far100k"):
    ratios = [(m[kind][0] / m[kind][1]) / (m["planes"][0] / m["planes"][1])
              for m in runs.values() if kind in m and "planes" in m and m[kind][1] > 0 and m["planes"][1] > 0]
    if ratios:
        print("%-9s per wall contact over planes, round by round: %s; median %.2f" %
              (kind, " ".join("%.2f" % x for x in ratios), statistics.median(ratios)))
PY
echo "== load after: $(uptime)"
