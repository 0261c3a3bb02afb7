#!/usr/bin/env bash
# An error on one MPI rank (a blow-up among rank 1's particles) must reach the
# user as one clear message and stop every rank cleanly: exit status 1, no
# hang (the timeout), the diagnosis printed once.
#   error.sh GRAINS WORKDIR
set -uo pipefail
grains=$1 work=$2
here=$(cd "$(dirname "$0")" && pwd)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
rm -rf "$work" && mkdir -p "$work"
timeout 120 mpirun --oversubscribe -np 2 "$grains" run "$here/blowup.yaml" -o "$work/out" -q 2> "$work/stderr.txt"
rc=$?
cat "$work/stderr.txt"
[ $rc -ne 124 ] || { echo "FAIL: the ranks hung"; exit 1; }
[ $rc -eq 1 ] || { echo "FAIL: exit status $rc, expected 1"; exit 1; }
n=$(grep -c "Likely cause" "$work/stderr.txt")
[ "$n" -eq 1 ] || { echo "FAIL: the diagnosis was printed $n times"; exit 1; }
grep -Eq "rank [0-9]+: blow-up at step [0-9]+ .*particle id [0-9]+" "$work/stderr.txt" ||
  { echo "FAIL: the message does not name the rank, step and particle"; exit 1; }
echo "one diagnosis naming rank, step and particle; all ranks stopped with status 1"
