# Shared by the restart tests of tests/parallel (sourced; the caller defines fail()).
# same_checkpoints DIR REF MIN OBJ...: every checkpoint a continued run wrote
# into DIR/checkpoints equals the uninterrupted run's checkpoint of the same
# step in REF/checkpoints in each HDF5 object OBJ (h5diff, exact); fail() is
# called for each difference and when fewer than MIN checkpoints were compared.
same_checkpoints() {
  local dir=$1 ref=$2 min=$3 n=0 f obj
  shift 3
  for f in "$dir"/checkpoints/checkpoint_*.h5; do
    [ -e "$f" ] || continue
    for obj in "$@"; do
      h5diff -q "$f" "$ref/checkpoints/$(basename "$f")" "$obj" || fail "$(basename "$f"): $obj differs after the restart"
    done
    n=$((n + 1))
  done
  [ "$n" -ge "$min" ] || fail "the continuation in $dir wrote $n checkpoints (at least $min expected)"
  echo "the $n checkpoints of the continuation in $(basename "$dir") equal the uninterrupted run's"
}
