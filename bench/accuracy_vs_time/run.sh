#!/usr/bin/env bash
# The accuracy-vs-time report: builds what it needs (at most -j2) and runs
# the sweeps, writing docs/accuracy-vs-time.md and docs/accuracy-vs-time/*.png.
#
#   bash bench/accuracy_vs_time/run.sh [--quick] [--only 1,2,...] [--out DIR]
#
# BUILD_DIR (default build/) is configured if needed (Release, SUNDIALS and
# benchmarks on). About 15 minutes on a 2-core machine; --quick: one minute.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${BUILD_DIR:-$root/build}
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DGRAINS_WITH_SUNDIALS=ON -DGRAINS_BUILD_BENCH=ON
fi
cmake --build "$build" -j2 --target grains accuracy_pw85 accuracy_nfft accuracy_skin accuracy_impact
exec /usr/bin/python3 "$here/run.py" --build "$build" "$@"
