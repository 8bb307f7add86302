#!/bin/sh
# string.sh: speed of one gradient-descent step in the string model, tds
# against Surface Evolver, on a 2-D foam of 10,000 cells: a 100 x 100
# honeycomb of unit hexagons whose junctions are moved by up to 0.2
# (seeded: tests/evolver/string/foam.lua), every cell a body holding its
# area, the outer corners fixed. Both programs load the same datafile, take
# 20 `g` steps and report process CPU seconds per step; the ratio is
# Evolver / tds. Also prints both energies after the steps (the faster
# program must not be worse). tds takes its own line search (exact
# projection onto the areas), as in the cube bench: a datafile would
# otherwise take Evolver's, which makes about 1.5 times the trials.
# Usage: bench/string.sh [TDS_BINARY]
TDS=${1:-./tds}
STEPS=${STEPS:-20}
here=$(cd "$(dirname "$0")/.." && pwd)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$TDS" -q -e "local F = dofile('$here/tests/evolver/string/foam.lua')
local f = assert(io.open('$dir/foam.fe', 'w')) f:write((F.honeycomb_fe(100, 100, 0.2, 2024))) f:close()"
cat > "$dir/cmds" <<EOC
quiet on;
t0 := clock; g $STEPS; t1 := clock;
printf "EVOLVER %.6f %.15g %d\n", (t1 - t0)/$STEPS, total_energy, facet_count;
q
EOC
ev=$(cd "$dir" && evolver-nox-d -f cmds foam.fe < /dev/null 2>&1 | grep '^EVOLVER ')
td=$("$TDS" -q "$dir/foam.fe" -e "
tds.setting('evolver_line_search', false) -- tds's own search, as the cube bench
local t0 = os.clock()
g($STEPS)
local t1 = os.clock()
print(('TDS %.6f %.15g %d'):format((t1 - t0) / $STEPS, total_energy, facet_count))")
set -- $ev
ev_sec=$2 ev_energy=$3 cells=$4
set -- $td
td_sec=$2 td_energy=$3
. "$(dirname "$0")/report.sh"
report "2-D foam (string model): $cells cells, $STEPS steps of g" "$STEPS" "$ev_sec" "$ev_energy" "$td_sec" "$td_energy"
