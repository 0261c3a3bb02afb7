#!/bin/bash
# A full disk and a read-only output folder (both on a small tmpfs; skipped,
# exit 77, where mounting is not allowed). The full disk stops the run with a
# clear error, the state goes to the emergency folder, and a restart from it
# finishes with the same state as the uninterrupted run.
# Usage: disk_full.sh GRAINS CASE WORKDIR
source "$(dirname "$0")/restart_lib.sh" "$1" "$2" "$3"
MNT=$WORK/mnt
mkdir -p "$MNT"
if ! mount -t tmpfs -o size=2m tmpfs "$MNT" 2>/dev/null; then
  echo "SKIP: cannot mount a tmpfs here (needs root or CAP_SYS_ADMIN)"
  exit 77
fi
trap 'umount "$MNT" 2>/dev/null' EXIT
reference

# Disk full.
export GRAINS_EMERGENCY_DIR=$WORK/rescue
"$GRAINS" run "$CASE" -o "$MNT/out" -q 2>"$WORK/err"
rc=$?
[ "$rc" = 1 ] || fail "exit status $rc on a full disk, expected 1: $(cat "$WORK/err")"
grep -q "No space left on device" "$WORK/err" || fail "the error does not say the disk is full: $(cat "$WORK/err")"
saved=$(sed -n 's/.*its state is saved in \([^;]*\.h5\);.*/\1/p' "$WORK/err")
[ -n "$saved" ] && [ -f "$saved" ] || fail "no saved state named: $(cat "$WORK/err")"
grep -q -- "--restart $saved -o $MNT/out" "$WORK/err" || fail "no restart command: $(cat "$WORK/err")"
echo "disk full: $(head -n 1 "$WORK/err")"
echo "saved: $saved"
for f in "$MNT"/out/checkpoints/checkpoint_*.h5; do
  [ -e "$f" ] || continue
  h5dump -H "$f" >/dev/null 2>&1 || fail "a truncated checkpoint was left: $f"
done
# Room again: the outputs move to a larger disk and the run continues.
cp -r "$MNT/out" "$WORK/moved"
"$GRAINS" run "$CASE" --restart "$saved" -o "$WORK/moved" -q || fail "the restart after the full disk failed"
same_as_reference "$WORK/moved"

# Read-only output folder.
mkdir -p "$MNT/ro"
mount -o remount,ro "$MNT" || fail "cannot remount read-only"
"$GRAINS" run "$CASE" -o "$MNT/ro" -q 2>"$WORK/err_ro"
rc=$?
[ "$rc" = 1 ] || fail "exit status $rc for a read-only folder, expected 1"
grep -q "the output folder '$MNT/ro' is not writable: Read-only file system; choose another with -o" "$WORK/err_ro" ||
  fail "unclear message for a read-only folder: $(cat "$WORK/err_ro")"
echo "read-only: $(cat "$WORK/err_ro")"
echo "PASS: full disk reported, state rescued and continued exactly; read-only folder reported"
