#!/bin/sh
# cube.sh: speed of one gradient-descent step, tds against Surface Evolver,
# on the cube of volume 1 refined 6 times (98,304 facets). Both programs
# refine the same cube, take 20 `g` steps from the same mesh and report
# process CPU seconds per step; the ratio is Evolver / tds. Also prints
# the energy after the 20 steps (the faster program must not be worse)
# and tds's mesh storage in bytes per facet.
# Usage: bench/cube.sh [TDS_BINARY]
TDS=${1:-./tds}
EXAMPLES=${EXAMPLES:-/usr/share/doc/evolver/examples}
STEPS=20
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cp "$EXAMPLES/cube.fe" "$dir/cube.fe"
cat > "$dir/cmds" <<EOC
quiet on; r; r; r; r; r; r;
t0 := clock; g $STEPS; t1 := clock;
printf "EVOLVER %.6f %.15g %d\n", (t1 - t0)/$STEPS, total_energy, facet_count;
q
EOC
ev=$(cd "$dir" && evolver-nox-d -f cmds cube.fe < /dev/null 2>&1 | grep '^EVOLVER ')
here=$(cd "$(dirname "$0")/.." && pwd)
td=$("$TDS" -q "$here/scripts/cube.tds" -e "
for i = 1, 6 do r() end
local t0 = os.clock()
g($STEPS)
local t1 = os.clock()
print(('TDS %.6f %.15g %d %.1f'):format((t1 - t0) / $STEPS, total_energy, facet_count,
      tds.memory() / facet_count))")
set -- $ev
ev_sec=$2 ev_energy=$3 facets=$4
set -- $td
td_sec=$2 td_energy=$3 bytes=$5
echo "cube refined 6 times: $facets facets, $STEPS steps of g"
printf '%-10s %14s %20s\n' program "s per step" "energy after $STEPS"
printf '%-10s %14s %20s\n' evolver "$ev_sec" "$ev_energy"
printf '%-10s %14s %20s\n' tds "$td_sec" "$td_energy"
awk -v e="$ev_sec" -v t="$td_sec" -v ee="$ev_energy" -v te="$td_energy" -v b="$bytes" 'BEGIN {
  printf "speed ratio (Evolver / tds): %.1fx (goal: at least 10x)\n", e / t
  printf "energy: tds %s that of Evolver (goal: no worse)\n", (te <= ee ? "at or below" : "ABOVE")
  printf "tds mesh memory: %.1f bytes per facet (goal: under 200)\n", b }'
