#!/bin/sh
# hessian.sh: speed of one Newton step (`hessian`, hessian_normal on),
# tds against Surface Evolver, on the cube of volume 1 refined 6 times
# (49,154 vertices) and on cat.fe's catenoid refined 5 times. Each program
# refines, takes 5 `g` steps (Evolver needs them for its pressures), then
# one timed `hessian`; process CPU seconds of that step are reported, with
# the ratio Evolver / tds measured in the same run, the energy after the
# step in both, and tds's peak memory per vertex (the whole process).
# Usage: bench/hessian.sh [TDS_BINARY]
# (NOCUBE=1: the catenoid only; CATREF=n: refine it n times, not 5)
TDS=${1:-./tds}
EXAMPLES=${EXAMPLES:-/usr/share/doc/evolver/examples}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
here=$(cd "$(dirname "$0")/.." && pwd)

# one NAME FILE REFINES
one() {
  name=$1 fe=$2 nr=$3
  cp "$fe" "$dir/in.fe"
  rs=""; i=0; while [ $i -lt "$nr" ]; do rs="$rs r;"; i=$((i + 1)); done
  cat > "$dir/cmds" <<EOC
quiet on; $rs g 5;
t0 := clock; hessian; t1 := clock;
printf "EVOLVER %.6f %.15g %d\n", t1 - t0, total_energy, vertex_count;
q
EOC
  ev=$(cd "$dir" && evolver-nox-d -f cmds in.fe < /dev/null 2>&1 | grep '^EVOLVER ')
  td=$( { /usr/bin/time -f "MAXRSS %M" "$TDS" -q "$dir/in.fe" -e "
for i = 1, $nr do r() end
g(5)
local t0 = os.clock()
hessian()
local t1 = os.clock()
print(('TDS %.6f %.15g %d'):format(t1 - t0, total_energy, vertex_count))"; } 2>&1)
  set -- $ev
  ev_sec=$2 ev_energy=$3 nv=$4
  td_sec=$(echo "$td" | awk '/^TDS /{print $2}')
  td_energy=$(echo "$td" | awk '/^TDS /{print $3}')
  rss=$(echo "$td" | awk '/^MAXRSS /{print $2}')
  printf '%s: %s vertices, one hessian step\n' "$name" "$nv"
  printf '  %-8s %12s %22s\n' program "CPU s" "energy after"
  printf '  %-8s %12s %22s\n' evolver "$ev_sec" "$ev_energy"
  printf '  %-8s %12s %22s\n' tds "$td_sec" "$td_energy"
  awk -v e="$ev_sec" -v t="$td_sec" -v r="$rss" -v n="$nv" 'BEGIN {
    printf "  speed ratio (Evolver / tds): %.2fx (goal: at least 3x)\n", e / t
    printf "  tds peak memory: %.0f MB, %.0f bytes per vertex\n", r / 1024, r * 1024 / n }'
}
[ -n "$NOCUBE" ] || one cube "$EXAMPLES/cube.fe" 6
one catenoid "$EXAMPLES/cat.fe" ${CATREF:-5}
