#!/bin/bash
# kill -9 a run at random moments, resume each time from the newest valid
# checkpoint; the finished run must equal the uninterrupted one bitwise, and
# no checkpoint left behind may be unreadable.
# Usage: kill_resume.sh GRAINS CASE WORKDIR [KILLS]
source "$(dirname "$0")/restart_lib.sh" "$1" "$2" "$3"
KILLS=${4:-6}
reference
OUT=$WORK/killed
RANDOM=${KILL_SEED:-$$}
for ((k = 1; k <= KILLS; k++)); do
  if [ -n "$(newest "$OUT")" ]; then
    "$GRAINS" run "$CASE" --resume "$OUT" -q 2>>"$WORK/log" &
  else
    "$GRAINS" run "$CASE" -o "$OUT" -q 2>>"$WORK/log" &
  fi
  pid=$!
  delay=$(printf '0.%03d' $((RANDOM % 900 + 100)))
  sleep "$delay"
  kill -9 "$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
  echo "kill $k after ${delay}s: newest $(basename "$(newest "$OUT")")"
  checkpoints_readable "$OUT" "$k"
done
finish_run "$OUT"
same_as_reference "$OUT"
echo "PASS: $KILLS kills, final state equals the uninterrupted run"
