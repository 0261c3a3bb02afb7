#!/usr/bin/env bash
# Regenerates docs/packing.md and docs/packing/*.png: runs the packing
# regression suite (CI sizes, then unless --ci the long sizes), collects the
# result records (JSON, one per measurement) and writes the doc with
# tests/regression/make_packing_doc.py.
#
#   bash tests/regression/make_packing_doc.sh          # CI + long: ~1-2 h on 2 cores
#   bash tests/regression/make_packing_doc.sh --ci     # CI sizes only: ~5 min
#   bash tests/regression/make_packing_doc.sh --reuse  # keep records already in $RESULTS
#   bash tests/regression/make_packing_doc.sh --section adhesive  # only the adhesive deposits
#                                                      # (CI + long, ~25 min) and their section
#
# Environment: BUILD (build folder, default build; configured and built if
# needed), RESULTS (default $BUILD/packing-results), JOBS (parallel test
# processes, default 1: the measurements are timed by nobody, but the
# machine is shared).
# A failing test does not stop the script: its record is still written and
# the doc shows which values fall outside their band; the exit status is
# non-zero when any test failed.
set -uo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
BUILD="${BUILD:-$ROOT/build}"
RESULTS="${RESULTS:-$BUILD/packing-results}"
CI_ONLY=0
REUSE=0
SECTION=
while [ $# -gt 0 ]; do
  case "$1" in
    --ci) CI_ONLY=1 ;;
    --reuse) REUSE=1 ;;
    --section) SECTION="${2:-}"; shift ;;
    *) echo "usage: $0 [--ci] [--reuse] [--section adhesive]" >&2; exit 2 ;;
  esac
  shift
done
case "$SECTION" in
  ''|adhesive) ;;
  *) echo "$0: unknown section '$SECTION'; known: adhesive" >&2; exit 2 ;;
esac
if [ ! -f "$BUILD/CMakeCache.txt" ]; then
  cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null || exit 1
fi
cmake --build "$BUILD" -j2 --target grains test_packing test_packing_long test_ellipsoid_packing test_adhesive_packing \
  test_clump_regression test_clump_regression_long >/dev/null || exit 1
mkdir -p "$RESULTS"
if [ "$REUSE" = 0 ]; then
  if [ -n "$SECTION" ]; then rm -f "$RESULTS"/$SECTION*.json "$RESULTS"/$SECTION*.commit
  else rm -f "$RESULTS"/*.json "$RESULTS"/*.commit; fi
fi
export GRAINS_RESULTS_DIR="$RESULTS"
status=0
commit="$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo '?')"
# (the generated doc itself does not count as a change)
[ -n "$(git -C "$ROOT" status --porcelain --untracked-files=no -- . ':!docs/packing.md' ':!docs/packing' 2>/dev/null)" ] &&
  commit="$commit+changes"

# run NAME RECORD COMMAND...: runs the command unless RECORD.json exists (--reuse).
run() {
  local name=$1 rec=$2
  shift 2
  if [ "$REUSE" = 1 ] && [ -f "$RESULTS/$rec.json" ]; then
    echo "== $name: reusing $RESULTS/$rec.json"
    return
  fi
  echo "== $name"
  local t0=$SECONDS
  "$@" > "$RESULTS/$name.log" 2>&1 || { echo "   FAILED (log: $RESULTS/$name.log)"; status=1; }
  echo "   $((SECONDS - t0)) s"
  echo "$commit" > "$RESULTS/$rec.commit"  # what the record was measured with
}

T="$BUILD/tests/regression"
if [ "$SECTION" = adhesive ]; then
  run adhesive_ci adhesive_ci "$T/test_adhesive_packing" --gtest_filter=Packing.AdhesiveDepositionSweep
  [ "$CI_ONLY" = 1 ] || run adhesive_long adhesive_long "$T/test_packing_long" --gtest_filter=PackingLong.AdhesiveDepositionSweep
  cat > "$RESULTS/adhesive_meta.json" <<EOF
{"date": "$(date -u +%Y-%m-%d)", "machine": "$(lscpu 2>/dev/null | sed -n 's/^Model name: *//p' | head -1), $(nproc) cores"}
EOF
  /usr/bin/python3 "$HERE/make_packing_doc.py" "$RESULTS" --section adhesive || exit 1
  exit $status
fi
run friction_ci friction_sweep_ci "$T/test_packing" --gtest_filter=Packing.FrictionSweepPouredSpheres
run beverloo_ci beverloo_ci "$T/test_packing" --gtest_filter=Packing.SiloDischargeFollowsBeverloo
run jamming_ci jamming_ci "$T/test_packing" --gtest_filter=Packing.JammedFrictionlessSpheres
run ellipsoid_ci ellipsoid_ci "$T/test_ellipsoid_packing"
run dimer_ci dimer_ci "$T/clump/test_clump_regression" --gtest_filter=ClumpRegression.DimersOfAspectRatio1p5PackDenserThanSpheres
run adhesive_ci adhesive_ci "$T/test_adhesive_packing" --gtest_filter=Packing.AdhesiveDepositionSweep
run clump_resolution_ci clump_resolution_ci "$T/clump/test_clump_regression" --gtest_filter=ClumpRegression.CubeFirstResolutionStepLoosensThePour
if [ "$CI_ONLY" = 0 ]; then
  run jamming_long jamming_long "$T/test_packing_long" --gtest_filter=PackingLong.JammedFrictionlessSpheres
  run friction_seeds friction_seeds_ci "$T/test_packing_long" --gtest_filter=PackingLong.FrictionSweepSeedSpread
  run friction_long friction_sweep_long "$T/test_packing_long" --gtest_filter=PackingLong.FrictionSweepPouredSpheres
  run beverloo_long beverloo_long "$T/test_packing_long" --gtest_filter=PackingLong.SiloDischargeFollowsBeverloo
  run dimer_sweep dimer_sweep "$T/clump/test_clump_regression_long" --gtest_filter=ClumpRegressionLong.DimerAspectRatioSweep
  run clump_resolution clump_resolution "$T/clump/test_clump_regression_long" --gtest_filter=ClumpRegressionLong.CubeResolutionSweep
  run adhesive_long adhesive_long "$T/test_packing_long" --gtest_filter=PackingLong.AdhesiveDepositionSweep
  run ellipsoid_sweep ellipsoid_sweep env BUILD="$BUILD" REUSE="$REUSE" bash "$HERE/ellipsoid_packing_sweep.sh"
fi

machine="$(lscpu 2>/dev/null | sed -n 's/^Model name: *//p' | head -1), $(nproc) cores"
cat > "$RESULTS/meta.json" <<EOF
{"date": "$(date -u +%Y-%m-%d)", "commit": "$commit", "machine": "$machine"}
EOF
/usr/bin/python3 "$HERE/make_packing_doc.py" "$RESULTS" || exit 1
exit $status
