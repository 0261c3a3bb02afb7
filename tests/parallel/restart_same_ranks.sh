#!/usr/bin/env bash
# A checkpoint of a run on 2 MPI ranks with the case's own parallel settings
# (no parallel.deterministic override: ordered sums are the default under
# MPI) continues on 2 ranks bitwise: every frame after the restart and every
# checkpoint the continuation writes equal the uninterrupted run's.
#   restart_same_ranks.sh GRAINS COMPARE CASE WORKDIR EVERY_STEPS [--set k=v ...]
set -euo pipefail
grains=$1 compare=$2 case=$3 work=$4 every=$5
shift 5
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
rm -rf "$work" && mkdir -p "$work"
sets=("$@" --set checkpoint.every_steps=$every --set checkpoint.keep=10 -q)
status=0
fail() { echo "FAIL: $*"; status=1; }
source "$(dirname "$0")/checkpoint_lib.sh"

mpirun --oversubscribe -np 2 "$grains" run "$case" -o "$work/full" "${sets[@]}"
ck=$(ls "$work/full/checkpoints/"*.h5 | sort | sed -n 1p)  # the first checkpoint
echo "restarting on 2 ranks from $ck"
mpirun --oversubscribe -np 2 "$grains" run "$case" --restart "$ck" -o "$work/restart" "${sets[@]}"
echo -n "last frame of the continuation vs uninterrupted: "
"$compare" "$work/full" "$work/restart" --frames last --tol 0 || status=1
same_checkpoints "$work/restart" "$work/full" 2 /particles /walls /clock /growth /parallel
exit $status
