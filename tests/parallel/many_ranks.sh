#!/usr/bin/env bash
# More ranks than cores (issue 26): a bed of 6,000 spheres falling onto the
# floor of cases/pour_spheres, serial and on 8 MPI ranks (oversubscribed on a
# 2-core machine), with ordered force sums: every frame must agree bitwise,
# and every rank must own interior grains (farther than the ghost cut-off
# from each face it shares with another rank, summary.json "ranks"), so that
# the test covers ranks with a bulk, a ghost layer and neighbours on several
# sides, not only thin slabs.
#   many_ranks.sh GRAINS COMPARE CASE WORKDIR RANKS
set -euo pipefail
grains=$1 compare=$2 case=$3 work=$4 ranks=$5
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 OMP_NUM_THREADS=1
rm -rf "$work" && mkdir -p "$work"
sets=(--set particles.0.count=6000 --set "particles.0.placement.region.max=[0.02, 0.02, 0.03]"
      --set time.end=0.05 --set output.every=0.0125 --set parallel.deterministic=true -q)
"$grains" run "$case" -o "$work/serial" "${sets[@]}"
mpirun --oversubscribe -np "$ranks" "$grains" run "$case" -o "$work/ranks" "${sets[@]}" \
  --set "parallel.decomposition=[2, 2, $((ranks / 4))]"
echo -n "$ranks ranks vs serial: "
"$compare" "$work/serial" "$work/ranks" --tol 0
python3 - "$work/ranks/summary.json" "$ranks" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])); ranks = int(sys.argv[2])
r = s["ranks"]
assert s["mpi_ranks"] == ranks and len(r["owned"]) == ranks, (s["mpi_ranks"], r)
print("per rank: owned %s, interior %s, ghosts %s, messages per step %s" % (
    r["owned"], r["interior"], r["ghosts"], r["messages_per_step"]))
assert sum(r["owned"]) == s["particles_end"], "the ranks' grains add up to the scene's"
assert all(i > 0 for i in r["interior"]), "every rank owns interior grains"
assert all(0 < i < o for i, o in zip(r["interior"], r["owned"])), "and a ghost layer's worth that are not"
assert all(m >= 3 for m in r["messages_per_step"]), "each rank has neighbours along all three axes"
assert min(s["ranks"]["list_pairs"]) > 0, "contacts on every rank"
m = s["stage_seconds_max_over_ranks"]
assert list(m) == list(s["stage_seconds"]), "the slowest rank's seconds name the same stages"
assert all(m[k] >= v for k, v in s["stage_seconds"].items()), "and none is below rank 0's"
PY
