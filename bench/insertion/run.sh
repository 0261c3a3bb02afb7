#!/usr/bin/env bash
# FFT insertion against random trial insertion in a dense bed, in equal
# wall-clock budgets (bench/RESULTS.md, "Insertion"):
#   bash bench/insertion/run.sh [BUILD_DIR]        (default: build)
# 1. cases/jam_frictionless (2,000 spheres jammed in a periodic box,
#    phi ~ 0.637) is run to its end and checkpointed (about 20-40 s);
# 2. bench_insertion places as many grains as fit into a 6 mm corner cube of
#    that packing (crossing the periodic faces), with each method and budget:
#    spheres of 0.30, 0.35, 0.40 times the bed's radius, and prolate
#    ellipsoids (aspect 2) of bounding radius 0.50 and 0.60 times it.
# One thread; results in $BUILD/bench-insertion/*.csv and on stdout.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build}
out=$build/bench-insertion
mkdir -p "$out"
cmake --build "$build" -j2 --target grains bench_insertion > /dev/null
export OMP_NUM_THREADS=1
case=$root/cases/jam_frictionless/case.yaml
if [ ! -d "$out/bed/checkpoints" ]; then
  "$build/grains" run "$case" -o "$out/bed" -q --set output.vtk=false --set checkpoint.every=10
fi
ck=$(ls "$out/bed/checkpoints/"*.h5 | sort | tail -1)
echo "date: $(date -u '+%Y-%m-%d %H:%M UTC')"
echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; load average: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "commit: $(git -C "$root" rev-parse --short HEAD)"
# Final bed radius: 0.45 mm x growth (read from the checkpoint by the program).
region="--region 0 0 0 0.006 0.006 0.006"
budgets=${BUDGETS:-0.5,1,2,4,8}
: > "$out/results.csv"
# Spheres of 0.30, 0.35 and 0.40 times the bed's radius (0.6356 mm): the
# largest barely fit the biggest pores of a jammed packing.
for r in 0.00019 0.000222 0.000254; do
  "$build/bench/insertion/bench_insertion" "$case" "$ck" $region --radius $r --budgets "$budgets" \
    | sed "s/^sphere,/sphere $r,/" | tee -a "$out/results.csv"
done
# Prolate ellipsoids (aspect 2, semi-axes q, q/2, q/2) of q = 0.50 and 0.60
# times the bed's radius; grid spacing 0.05 mm (the default, a quarter of
# the cover's largest ball, would be 0.04 / 0.05 mm).
for r in 0.000318 0.000381; do
  "$build/bench/insertion/bench_insertion" "$case" "$ck" $region --radius $r --shape ellipsoid --aspect 2 \
    --orientations 8 --spacing 0.00005 --budgets "$budgets" | sed "s/^ellipsoid,/ellipsoid $r,/" | tee -a "$out/results.csv"
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
