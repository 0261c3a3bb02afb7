#!/usr/bin/env bash
# Faults while a 2-rank run writes its checkpoints with parallel HDF5:
#  1. every process of the run (mpirun and both ranks) killed with -9 at
#     random moments, resumed with --resume on 2 ranks each time: no
#     checkpoint left behind is unreadable, and the finished run equals the
#     uninterrupted one bitwise (deterministic force sums);
#  2. a full disk (a 2 MB tmpfs; skipped, exit 77, where mounting is not
#     allowed): every rank stops with status 1 and one message saying the
#     disk is full, no partial checkpoint is left, the state goes to the
#     emergency folder and a 2-rank restart from it finishes exactly;
#  3. a read-only output folder: status 1 and a clear message.
#   checkpoint_faults.sh GRAINS COMPARE CASE WORKDIR [KILLS]
grains=$1 compare=$2
source "$(dirname "$0")/../integration/restart_lib.sh" "$1" "$3" "$4"
KILLS=${5:-4}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
# `grains` on 2 ranks, with ordered force sums (a resumed run is then bitwise
# the uninterrupted one whatever the ranks own after the restart).
GRAINS=$WORK/grains2
printf '#!/bin/bash\nexec mpirun --oversubscribe -np 2 %q "$@" --set parallel.deterministic=true\n' "$grains" > "$GRAINS"
chmod +x "$GRAINS"

# The state compared: particles, contact histories, walls, clock, frames
# (not /neighbor/builds: a restart rebuilds its lists once more).
same_state() {
  for obj in /particles /walls /clock /scene /output /neighbor/row_start /neighbor/partner /neighbor/history; do
    h5diff -q "$1" "$2" "$obj" >/dev/null 2>&1 || fail "$obj differs between $1 and $2"
  done
}
same_as_reference() {
  local last
  last=$(newest "$1")
  [ "$(basename "$last")" = "$(basename "$REF")" ] || fail "$1 ended at $(basename "$last"), reference at $(basename "$REF")"
  same_state "$REF" "$last"
  cmp -s "$WORK/ref/particles.pvd" "$1/particles.pvd" || fail "particles.pvd differs (duplicate or missing frames)"
  "$compare" "$WORK/ref" "$1" > /dev/null || fail "the frames of $1 differ from the uninterrupted run's"
}
# Every process of a tree, killed at once.
kill_tree() {
  local all=() queue=("$1") p
  while [ ${#queue[@]} -gt 0 ]; do
    p=${queue[0]}
    queue=("${queue[@]:1}")
    all+=("$p")
    for c in $(ps -o pid= --ppid "$p"); do queue+=("$c"); done
  done
  kill -9 "${all[@]}" 2>/dev/null
}

reference
echo "reference: $(basename "$REF")"

# 1. kill -9 at random moments.
OUT=$WORK/killed
RANDOM=${KILL_SEED:-$$}
for ((k = 1; k <= KILLS; k++)); do
  if [ -n "$(newest "$OUT")" ]; then
    "$GRAINS" run "$CASE" --resume "$OUT" -q 2>>"$WORK/log" &
  else
    "$GRAINS" run "$CASE" -o "$OUT" -q 2>>"$WORK/log" &
  fi
  pid=$!
  delay=$(printf '%d.%03d' $((RANDOM % 2 + 1)) $((RANDOM % 1000)))
  sleep "$delay"
  kill_tree "$pid"
  wait "$pid" 2>/dev/null
  echo "kill $k after ${delay}s: newest $(basename "$(newest "$OUT")")"
  checkpoints_readable "$OUT" "$k"
done
finish_run "$OUT"
same_as_reference "$OUT"
echo "PASS: $KILLS kills of every process, the resumed run equals the uninterrupted one"

# 2. A full disk while the ranks write a checkpoint (frames rare, so that a
# checkpoint is what fills it).
MNT=$WORK/mnt
mkdir -p "$MNT"
if ! mount -t tmpfs -o size=2m tmpfs "$MNT" 2>/dev/null; then
  echo "SKIP: cannot mount a tmpfs here (needs root or CAP_SYS_ADMIN)"
  exit 77
fi
trap 'umount "$MNT" 2>/dev/null' EXIT
export GRAINS_EMERGENCY_DIR=$WORK/rescue
"$GRAINS" run "$CASE" -o "$MNT/out" -q --set output.every_steps=100000 2>"$WORK/err"
rc=$?
cat "$WORK/err"
[ "$rc" = 1 ] || fail "exit status $rc on a full disk, expected 1"
grep -q "No space left on device" "$WORK/err" || fail "the error does not say the disk is full"
grep -q "could not write checkpoint" "$WORK/err" || fail "the error does not say a checkpoint failed"
n=$(grep -c "the run stopped at step" "$WORK/err")
[ "$n" = 1 ] || fail "the message was printed $n times"
saved=$(sed -n 's/.*its state is saved in \([^;]*\.h5\);.*/\1/p' "$WORK/err")
[ -n "$saved" ] && [ -f "$saved" ] || fail "no saved state named"
for f in "$MNT"/out/checkpoints/checkpoint_*.h5; do
  [ -e "$f" ] || continue
  h5dump -H "$f" >/dev/null 2>&1 || fail "a truncated checkpoint was left: $f"
done
ls -a "$MNT/out/checkpoints" | grep -q '\.tmp$' && fail "a temporary was left on the full disk"
cp -r "$MNT/out" "$WORK/moved"
"$GRAINS" run "$CASE" --restart "$saved" -o "$WORK/moved" -q --set output.every_steps=100000 ||
  fail "the restart after the full disk failed"
last=$(newest "$WORK/moved")
[ "$(basename "$last")" = "$(basename "$REF")" ] || fail "the rescued run ended at $(basename "$last")"
for obj in /particles /walls /clock /scene /neighbor/partner /neighbor/history; do  # its frames were fewer
  h5diff -q "$REF" "$last" "$obj" >/dev/null 2>&1 || fail "$obj of the rescued run differs from the reference"
done
echo "PASS: full disk reported once, state rescued to $saved and continued exactly"

# 3. Read-only output folder.
mkdir -p "$MNT/ro"
mount -o remount,ro "$MNT" || fail "cannot remount read-only"
"$GRAINS" run "$CASE" -o "$MNT/ro" -q 2>"$WORK/err_ro"
rc=$?
[ "$rc" = 1 ] || fail "exit status $rc for a read-only folder, expected 1"
grep -q "the output folder '$MNT/ro' is not writable: Read-only file system" "$WORK/err_ro" ||
  fail "unclear message for a read-only folder: $(cat "$WORK/err_ro")"
echo "PASS: read-only folder: $(head -n 1 "$WORK/err_ro")"
