#!/usr/bin/env bash
# Bitwise-identical results across a refactor: runs the shipped cases at CI
# size with an old and a new grains and compares every frame byte for byte.
#
#   bash tests/regression/same_results.sh OLD [NEW] [OUTDIR]
#
# OLD: a commit (built here in a temporary worktree, only the grains target)
# or the path of an old grains binary. NEW: the grains binary to test
# (default build/grains). Exit 0 when every particle frame of every case is
# byte-identical and every walls frame has the same surfaces (points bitwise,
# cells; compared with tests/parallel/compare_frames --wall-cells when the
# files differ: since 2026-11-26 they also carry each wall's record for
# `grains analyze`, COMPARE = that tool, default build/tests/parallel/compare_frames).
# EXTRA adds overrides to every run ("--set parallel.deterministic=true":
# the ordered force sums), LAUNCH a launcher before both binaries
# ("mpirun --oversubscribe -np 2": the runs on ranks; add
# SKIP="pour_spheres_arkode", which a run on ranks refuses) and SKIP lists
# runs to leave out.
# OLD must read every case run here: adhesive_pour needs contact.model jkr
# (c04596a on), and frictional results changed on purpose at 9f362b0 (the
# tangential spring), so compare against 9f362b0 or later.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
old=${1:?usage: same_results.sh OLD-COMMIT-OR-BINARY [NEW-BINARY] [OUTDIR]}
new=${2:-$here/build/grains}
out=${3:-$(mktemp -d /tmp/grains_same_results.XXXXXX)}
mkdir -p "$out"
compare=${COMPARE:-$here/build/tests/parallel/compare_frames}

if [ ! -x "$old" ]; then
  tree="$out/old-src"
  rm -rf "$tree"
  git -C "$here" worktree add --detach -f "$tree" "$old" >/dev/null
  trap 'git -C "$here" worktree remove --force "$tree" >/dev/null 2>&1 || true' EXIT
  cmake -S "$tree" -B "$tree/build" -DCMAKE_BUILD_TYPE=Release -DGRAINS_BUILD_TESTS=OFF -DGRAINS_BUILD_BENCH=OFF \
    >"$out/old-build.log"
  cmake --build "$tree/build" -j "$(nproc)" --target grains >>"$out/old-build.log"
  old="$tree/build/grains"
fi

cases=$here/cases
# name | case | overrides (the sizes of the bitwise parallel tests, tests/parallel)
runs=(
  "pour_spheres|$cases/pour_spheres/case.yaml|--set particles.0.count=400 --set particles.0.placement.region.max=[0.02,0.02,0.006] --set time.end=0.05 --set output.every=0.01"
  "pour_spheres_rolling_cohesion|$cases/pour_spheres/case.yaml|--set particles.0.count=400 --set particles.0.placement.region.max=[0.02,0.02,0.006] --set time.end=0.03 --set output.every=0.01 --set materials.0.rolling_friction=0.1 --set materials.0.cohesion_energy_density=2e4"
  "pour_spheres_arkode|$cases/pour_spheres/case.yaml|--set particles.0.count=200 --set particles.0.placement.region.max=[0.02,0.02,0.004] --set time.end=0.01 --set output.every=0.005 --set time.integrator=arkode"
  "pour_ellipsoids|$cases/pour_ellipsoids/case.yaml|--set particles.0.count=300 --set time.end=0.08 --set output.every=0.02"
  "pour_clumps|$cases/pour_clumps/case.yaml|--set particles.0.count=40 --set time.end=0.08 --set output.every=0.02"
  "silo_discharge|$cases/silo_discharge/case.yaml|--set particles.0.count=300 --set time.end=0.08 --set output.every=0.02"
  "silo_discharge_ellipsoids|$cases/silo_discharge/case.yaml|--set particles.0.count=300 --set particles.0.shape={type: ellipsoid, aspect_ratio: 2} --set time.end=0.08 --set output.every=0.02"
  "mesh_drum|$cases/rotating_drum/case.yaml|--set particles.0.count=600 --set walls.0.start=0.2 --set walls.0.ramp=0.1 --set time.end=0.5 --set output.every=0.1"
  "mesh_hopper|$cases/hopper_discharge/case.yaml|--set particles.0.count=800 --set walls.1.start=0.1 --set time.end=0.25 --set output.every=0.05"
  "mesh_mixer_ellipsoids|$cases/mixer/case.yaml|--set particles.0.count=300 --set particles.0.shape={type: ellipsoid, aspect_ratio: 2} --set time.end=0.15 --set output.every=0.05"
  "adhesive_pour|$cases/adhesive_pour/case.yaml|--set particles.0.count=1200 --set particles.0.placement.region.max=[0.002,0.002,0.003] --set time.end=0.03 --set output.every=0.006"
  "pour_spheres_moving_floor|$cases/pour_spheres/case.yaml|--set particles.0.count=400 --set particles.0.placement.region.max=[0.02,0.02,0.006] --set time.end=0.03 --set output.every=0.01 --set walls.0.velocity=[0.002,0,0.01]"
  "simple_shear_periodic|$cases/simple_shear/case.yaml|--set particles.0.count=400 --set time.end=0.02 --set output.every=0.005 --set output.stress.every=0.001"
  "adhesive_deposition_periodic|$cases/adhesive_deposition/case.yaml|--set time.end=0.0006 --set output.every=0.0002"
)
fail=0
for r in "${runs[@]}"; do
  IFS='|' read -r name case sets <<<"$r"
  case " ${SKIP:-} " in *" $name "*) echo "$name: skipped"; continue ;; esac
  [ -n "${EXTRA:-}" ] && sets="$sets $EXTRA"
  for which in old new; do
    bin=$old
    [ $which = new ] && bin=$new
    rm -rf "$out/$name.$which"
    # The overrides are split at " --set " (a value may hold spaces).
    args=()
    rest=${sets#--set }
    while [ -n "$rest" ]; do
      args+=(--set "${rest%% --set *}")
      [ "$rest" = "${rest#* --set }" ] && break
      rest=${rest#* --set }
    done
    # shellcheck disable=SC2086  # LAUNCH is a command line
    ${LAUNCH:-} "$bin" run "$case" -o "$out/$name.$which" -q "${args[@]}" >"$out/$name.$which.log" 2>&1 ||
      { echo "$name: the $which build failed (log: $out/$name.$which.log)"; fail=1; continue 2; }
  done
  n=0
  bad=0
  for f in "$out/$name.old"/frames/*; do
    g="$out/$name.new/frames/$(basename "$f")"
    n=$((n + 1))
    if ! cmp -s "$f" "$g"; then
      case $(basename "$f") in
        walls_*) "$compare" --wall-cells "$f" "$g" && continue ;;
      esac
      echo "$name: $(basename "$f") differs"
      bad=1
    fi
  done
  n_new=$(find "$out/$name.new/frames" -type f | wc -l)
  if [ "$n" -eq 0 ] || [ "$n" -ne "$n_new" ]; then
    echo "$name: $n old frame files, $n_new new"
    bad=1
  fi
  if [ $bad -eq 0 ]; then echo "$name: $n frame files identical (walls: same surfaces)"; else fail=1; fi
done
[ $fail -eq 0 ] && echo "same_results: every frame identical" || echo "same_results: DIFFERENCES (outputs in $out)"
exit $fail
