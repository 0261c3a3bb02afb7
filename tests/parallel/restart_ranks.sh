#!/usr/bin/env bash
# Checkpoints of a 2-rank run restart on 1 and on 4 ranks (and with 2
# threads), and the continuation equals the uninterrupted serial run bitwise
# (deterministic force sums; histories keyed by global ids).
#   restart_ranks.sh GRAINS COMPARE CASE WORKDIR [--set k=v ...]
set -euo pipefail
grains=$1 compare=$2 case=$3 work=$4
shift 4
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
rm -rf "$work" && mkdir -p "$work"
sets=("$@" --set parallel.deterministic=true --set checkpoint.every_steps=1000 --set checkpoint.keep=10 -q)
"$grains" run "$case" -o "$work/serial" "${sets[@]}"
mpirun --oversubscribe -np 2 "$grains" run "$case" -o "$work/ranks2" "${sets[@]}"
ck=$(ls "$work/ranks2/checkpoints/"*.h5 | sort | sed -n 2p)  # the second checkpoint (step 2000)
echo "restarting from $ck"
h5dump -H "$ck" > /dev/null  # readable by the HDF5 tools
status=0
for np in 1 4; do
  mpirun --oversubscribe -np $np "$grains" run "$case" --restart "$ck" -o "$work/restart$np" "${sets[@]}"
  echo -n "restart on $np rank(s) vs uninterrupted serial: "
  "$compare" "$work/serial" "$work/restart$np" --frames last || status=1
done
OMP_NUM_THREADS=2 "$grains" run "$case" --restart "$ck" -o "$work/restart_t2" "${sets[@]}"
echo -n "restart with 2 threads vs uninterrupted serial: "
"$compare" "$work/serial" "$work/restart_t2" --frames last || status=1
echo -n "uninterrupted 2 ranks vs serial: "
"$compare" "$work/serial" "$work/ranks2" || status=1
exit $status
