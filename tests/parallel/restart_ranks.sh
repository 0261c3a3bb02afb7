#!/usr/bin/env bash
# Checkpoints of a 2-rank run, written with parallel HDF5 (MPI-IO, each rank
# its own rows), restart on 1, 2 and 4 ranks and with threads, and the
# continuation equals the uninterrupted serial run bitwise (deterministic
# force sums; histories keyed by global ids). The MPI-IO files are the same
# as those the rank-0 gather writes (GRAINS_CHECKPOINT_IO=gather), compared
# exactly with h5diff, also from 3 ranks (uneven blocks), and readable by the
# HDF5 tools.
#   restart_ranks.sh GRAINS COMPARE CASE WORKDIR EVERY_STEPS [--set k=v ...]
set -euo pipefail
grains=$1 compare=$2 case=$3 work=$4 every=$5
shift 5
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
rm -rf "$work" && mkdir -p "$work"
sets=("$@" --set parallel.deterministic=true --set checkpoint.every_steps=$every --set checkpoint.keep=10 -q)
status=0
fail() { echo "FAIL: $*"; status=1; }
source "$(dirname "$0")/checkpoint_lib.sh"

"$grains" run "$case" -o "$work/serial" "${sets[@]}"
mpirun --oversubscribe -np 2 "$grains" run "$case" -o "$work/ranks2" "${sets[@]}"
GRAINS_CHECKPOINT_IO=gather mpirun --oversubscribe -np 2 "$grains" run "$case" -o "$work/ranks2_gather" "${sets[@]}"
mpirun --oversubscribe -np 3 "$grains" run "$case" -o "$work/ranks3" "${sets[@]}"

# MPI-IO and gather write the same checkpoints (every dataset and attribute).
n=0
for f in "$work"/ranks2/checkpoints/checkpoint_*.h5; do
  name=$(basename "$f")
  # (h5diff notes the empty datasets, e.g. build_position, as "not comparable"; exit status 0)
  h5diff "$f" "$work/ranks2_gather/checkpoints/$name" > "$work/h5diff.txt" ||
    fail "$name: MPI-IO (2 ranks) and gather files differ: $(cat "$work/h5diff.txt")"
  # (the rank grids' cut planes, /parallel, differ between 2 and 3 ranks)
  h5diff --exclude-path /parallel "$f" "$work/ranks3/checkpoints/$name" > "$work/h5diff.txt" ||
    fail "$name: 2-rank and 3-rank MPI-IO files differ: $(cat "$work/h5diff.txt")"
  n=$((n + 1))
done
[ "$n" -ge 3 ] || fail "only $n checkpoints written"
first=$(ls "$work"/ranks2/checkpoints/*.h5 | sort | head -n 1)
last=$(ls "$work"/ranks2/checkpoints/*.h5 | sort | tail -n 1)
if h5diff -q "$first" "$last" /particles > /dev/null 2>&1; then fail "h5diff sees no difference between steps"; fi
echo "$n checkpoints: MPI-IO on 2 and 3 ranks = gather on 2 ranks (h5diff, exact)"

ck=$(ls "$work/ranks2/checkpoints/"*.h5 | sort | sed -n 2p)  # the second checkpoint
echo "restarting from $ck"
# Readable by the HDF5 tools: the header, and a whole dataset in global-id order.
h5dump -H "$ck" > /dev/null || fail "h5dump -H cannot read $ck"
count=$(h5dump -a /particles/count "$ck" | sed -n 's/.*(0): "\([0-9]*\)".*/\1/p')
# The values of the dataset (its first DATA block; the units attribute follows).
h5dump -y -w 0 -d /particles/id "$ck" | awk '/DATA {/ {f = 1; next} f && /}/ {exit} f' | tr -c '0-9\n' ' ' |
  tr -s ' ' '\n' | grep . > "$work/ids.txt" || true
ids=$(wc -l < "$work/ids.txt")
[ -n "$count" ] && [ "$ids" -eq "$count" ] || fail "h5dump reads $ids ids, /particles count says '$count'"
sorted=$(sort -n -c "$work/ids.txt" && echo yes || true)
[ "$sorted" = yes ] || fail "the ids in $ck are not in increasing order"
echo "h5dump reads all $ids particle ids, in increasing order"

for np in 1 2 4; do
  mpirun --oversubscribe -np $np "$grains" run "$case" --restart "$ck" -o "$work/restart$np" "${sets[@]}"
  echo -n "restart on $np rank(s) vs uninterrupted serial: "
  "$compare" "$work/serial" "$work/restart$np" --frames last || status=1
done
# Every checkpoint the restarted 2-rank run wrote equals the uninterrupted
# 2-rank run's of the same step (particles, histories, walls, clock).
same_checkpoints "$work/restart2" "$work/ranks2" 2 /particles /neighbor/row_start /neighbor/partner \
  /neighbor/history /walls /clock /scene
OMP_NUM_THREADS=2 "$grains" run "$case" --restart "$ck" -o "$work/restart_t2" "${sets[@]}"
echo -n "restart with 2 threads vs uninterrupted serial: "
"$compare" "$work/serial" "$work/restart_t2" --frames last || status=1
OMP_NUM_THREADS=2 mpirun --oversubscribe -np 2 "$grains" run "$case" --restart "$ck" -o "$work/restart2_t2" "${sets[@]}"
echo -n "restart on 2 ranks x 2 threads vs uninterrupted serial: "
"$compare" "$work/serial" "$work/restart2_t2" --frames last || status=1
echo -n "uninterrupted 2 ranks vs serial: "
"$compare" "$work/serial" "$work/ranks2" || status=1
exit $status
