#!/usr/bin/env bash
# The include rules of docs/architecture.md ("Layering"), checked on the
# sources: contact/ is geometry and includes neither sim/ nor io/; io/output
# includes no contact law (sim/laws); sim's state types (state/, walls/ but
# for its stage, neighbor/ but for its stage, laws/ but for the stages)
# include nothing of sim/scene.
set -u
root=${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}
cd "$root" || exit 2
bad=0
check() {  # check DESCRIPTION PATTERN FILES...
  local what=$1 pattern=$2
  shift 2
  local hits
  hits=$(grep -nE "$pattern" "$@" 2>/dev/null)
  if [ -n "$hits" ]; then
    echo "layering: $what:"
    echo "$hits" | sed 's/^/  /'
    bad=1
  fi
}
check "contact/ includes io/ or sim/" '#include "(io|sim)/' $(find contact -name '*.hpp' -o -name '*.cpp' -o -name '*.inc')
check "io/output includes a contact law (sim/laws)" '#include "sim/laws/' $(find io/output -name '*.hpp' -o -name '*.cpp')
state=$(find sim/state sim/walls sim/neighbor sim/laws sim/keys -name '*.hpp' -o -name '*.cpp' | grep -v '_stage\.\(hpp\|cpp\)$')
check "a sim state type includes sim/scene" '#include "sim/scene/' $state
if [ $bad -eq 0 ]; then echo "layering: the include rules hold"; fi
exit $bad
