#!/bin/sh
# foam3.sh: speed of one gradient-descent step on a periodic 3-D foam (the
# torus model), tds against Surface Evolver: 128 Voronoi cells of the
# body-centred cubic lattice in the unit cube torus, every point moved by
# up to a tenth of the spacing (seeded: bench/foam3.lua), TORUS_FILLED,
# every body holding its volume, refined once (r). Both programs load the
# same datafile, refine, take 20 `g` steps and report process CPU seconds
# per step; the ratio is Evolver / tds. Also prints both energies after
# the steps (the faster program must not be worse). tds takes its own
# line search (exact projection), as in the cube bench (bench/string.sh).
# Usage: bench/foam3.sh [TDS_BINARY]
TDS=${1:-./tds}
case $TDS in /*) ;; */*) TDS=$(pwd)/$TDS ;; esac # the generator runs in bench/
STEPS=${STEPS:-20}
here=$(cd "$(dirname "$0")/.." && pwd)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
(cd "$here/bench" && "$TDS" -q -e "N, AMP, SEED = 4, 0.1, 1; dofile('foam3.lua')") > "$dir/foam.fe"
cat > "$dir/cmds" <<EOC
quiet on; r;
t0 := clock; g $STEPS; t1 := clock;
printf "EVOLVER %.6f %.15g %d %d\n", (t1 - t0)/$STEPS, total_energy, facet_count, body_count;
q
EOC
ev=$(cd "$dir" && evolver-nox-d -f cmds foam.fe < /dev/null 2>&1 | grep '^EVOLVER ')
td=$("$TDS" -q "$dir/foam.fe" -e "
tds.setting('evolver_line_search', false) -- tds's own search, as the cube bench
r()
local t0 = os.clock()
g($STEPS)
local t1 = os.clock()
print(('TDS %.6f %.15g %d'):format((t1 - t0) / $STEPS, total_energy, facet_count))")
set -- $ev
ev_sec=$2 ev_energy=$3 facets=$4 cells=$5
set -- $td
td_sec=$2 td_energy=$3
. "$(dirname "$0")/report.sh"
report "periodic 3-D foam (torus): $cells cells, $facets facets after r, $STEPS steps of g" "$STEPS" "$ev_sec" "$ev_energy" "$td_sec" "$td_energy"
