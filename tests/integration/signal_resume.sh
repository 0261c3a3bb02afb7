#!/bin/bash
# SIGINT and SIGTERM stop a run with a final checkpoint, exit status 128+signal
# and a message with the resume command; resuming finishes with the same
# state as the uninterrupted run.
# Usage: signal_resume.sh GRAINS CASE WORKDIR
source "$(dirname "$0")/restart_lib.sh" "$1" "$2" "$3"
reference
OUT=$WORK/signalled
"$GRAINS" run "$CASE" -o "$OUT" -q 2>"$WORK/err1" &
pid=$!
# Signal once the run is under way (its second frame, step 500 of 6,000,
# exists), not after a fixed sleep: a fast machine could finish first.
for _ in $(seq 600); do
  [ -e "$OUT/frames/particles_000001.vtu" ] && break
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.02
done
kill -INT "$pid"
wait "$pid"
rc=$?
[ "$rc" = 130 ] || fail "exit status $rc after SIGINT, expected 130"
grep -q "stopped by SIGINT at step" "$WORK/err1" || fail "no stop message: $(cat "$WORK/err1")"
grep -q "resume with: grains run $CASE --resume $OUT" "$WORK/err1" || fail "no resume command: $(cat "$WORK/err1")"
step1=$(sed -n 's/.*at step \([0-9]*\).*/\1/p' "$WORK/err1")
[ "$(basename "$(newest "$OUT")")" = "$(printf 'checkpoint_%012d.h5' "$step1")" ] || fail "no checkpoint of step $step1"

"$GRAINS" run "$CASE" --resume "$OUT" -q 2>"$WORK/err2" &
pid=$!
# Again only once the resumed run is stepping (a newer checkpoint exists):
# before its handlers are installed a signal simply ends the process.
first=$(newest "$OUT")
for _ in $(seq 600); do
  [ "$(newest "$OUT")" != "$first" ] && break
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.02
done
kill -TERM "$pid"
wait "$pid"
rc=$?
if [ "$rc" = 143 ]; then
  grep -q "stopped by SIGTERM" "$WORK/err2" || fail "no stop message after SIGTERM"
  "$GRAINS" run "$CASE" --resume "$OUT" -q || fail "the last resume failed"
elif [ "$rc" != 0 ]; then
  fail "exit status $rc after SIGTERM"
fi
same_as_reference "$OUT"
echo "PASS: SIGINT at step $step1, then SIGTERM; final state equals the uninterrupted run"
