# Shared by the restart script tests. Usage: source restart_lib.sh GRAINS CASE WORKDIR
set -u
GRAINS=$1
CASE=$2
WORK=$3
rm -rf "$WORK"
mkdir -p "$WORK"

fail() { echo "FAIL: $*" >&2; exit 1; }

# The newest checkpoint of an output folder.
newest() { ls "$1"/checkpoints/checkpoint_*.h5 2>/dev/null | sort | tail -n 1; }

# Bitwise equality of two checkpoints' state (h5diff compares exactly unless
# given a tolerance); exits the test on a difference.
same_state() {
  for obj in /particles /neighbor /walls /clock /scene /output; do
    h5diff -q "$1" "$2" "$obj" >/dev/null 2>&1 || fail "$obj differs between $1 and $2"
  done
}

# The uninterrupted reference run.
reference() {
  "$GRAINS" run "$CASE" -o "$WORK/ref" -q || fail "reference run failed"
  REF=$(newest "$WORK/ref")
  [ -n "$REF" ] || fail "the reference run wrote no checkpoint"
  # The comparison can fail: an earlier checkpoint differs from the final one.
  OLDER=$(ls "$WORK"/ref/checkpoints/checkpoint_*.h5 | sort | head -n 1)
  if h5diff -q "$OLDER" "$REF" /particles >/dev/null 2>&1; then fail "h5diff sees no difference between steps"; fi
}

# Final state and frame series of OUTDIR equal the reference.
same_as_reference() {
  local out=$1
  local last
  last=$(newest "$out")
  [ "$(basename "$last")" = "$(basename "$REF")" ] || fail "$out ended at $(basename "$last"), reference at $(basename "$REF")"
  same_state "$REF" "$last"
  cmp -s "$WORK/ref/particles.pvd" "$out/particles.pvd" || fail "particles.pvd differs (duplicate or missing frames)"
  for f in "$WORK"/ref/frames/*.vtu; do
    cmp -s "$f" "$out/frames/$(basename "$f")" || fail "frame $(basename "$f") differs"
  done
  # The series written as CSV (wall loads, stress and profiles, mass, ...):
  # rows up to each restart kept, the rest written again. The same bytes;
  # or, where a continuation holds its grains in another order (periodic and
  # MPI scenes: sorted by id, then by cell), sums over grains may round
  # otherwise: each value then within 1e-12 of its column's largest.
  for f in "$WORK"/ref/*.csv; do
    [ -e "$f" ] || continue
    g="$out/$(basename "$f")"
    cmp -s "$f" "$g" && continue
    awk -F, -v rel=1e-12 -v floor=0 -v name="$(basename "$f")" -f "$(dirname "${BASH_SOURCE[0]}")/../support/csv_agree.awk" \
      "$f" "$g" || fail "$(basename "$f") differs"
    echo "$(basename "$f"): equal to 1e-12 of each column (sums in another order)"
  done
}

# After kill number $2: every checkpoint left in output folder $1 must open.
checkpoints_readable() {
  local f
  for f in "$1"/checkpoints/checkpoint_*.h5; do
    [ -e "$f" ] || continue
    h5dump -H "$f" >/dev/null 2>&1 || fail "corrupt checkpoint $f after kill $2"
  done
}

# Finishes the run in output folder $1: resumes from its newest checkpoint,
# or runs from the start when no checkpoint was written before the kills.
finish_run() {
  if [ -n "$(newest "$1")" ]; then
    "$GRAINS" run "$CASE" --resume "$1" -q || fail "the final resume failed"
  else
    "$GRAINS" run "$CASE" -o "$1" -q || fail "the final run failed"
  fi
}
