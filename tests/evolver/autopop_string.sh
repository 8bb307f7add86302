#!/bin/sh
# autopop_string.sh: autopop in the string model against Evolver, on a
# seeded random 2-D foam (tests/evolver/string/foam.lua, 30 cells) after a
# wall was driven to ~1e-12 as in foam_t1.sh (Evolver's dump, so both
# start from the same state). With a fixed scale dt each step first
# deletes the edges the move would shorten below sqrt(2 dt) and then, as
# o, splits the vertices where four walls now meet; the counts after one
# step and after 21 equal Evolver's at dt 1e-4 and 1e-3 (at 1e-3 one wall
# of length 0.015 goes and its junction pops; without the pop tds had one
# vertex and one edge fewer). The energies are not compared: Evolver
# moves with the motion computed before the autopop and restores the
# cells' areas, changed by the pop, only at the next step, where tds
# projects them at once (2e-3 apart after one step at dt 1e-3).
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
LOOP='ii := 0; do { e0 := total_energy; g 1; ii := ii + 1 } while (abs(total_energy - e0) > 1e-14*abs(e0) and ii < 100000);'
"$TDS" -q -e "local F = dofile('$ROOT/tests/evolver/string/foam.lua')
local f = assert(io.open('$tmp/v30.fe', 'w')) f:write((F.voronoi_fe(30, 12345))) f:close()"
# the cells around the shortest free wall and at its ends, as foam_t1.sh picks them (seed 12345)
evolver_run "$tmp/v30.fe" "$LOOP body[4].target := body[4].target*0.7; body[17].target := body[17].target*0.7; body[29].target := body[29].target*1.4; body[1].target := body[1].target*1.4; $LOOP dump \"$tmp/pre.dmp\";" > /dev/null
if [ ! -s "$tmp/pre.dmp" ]; then echo "FAIL autopop_string: Evolver wrote no dump"; exit 0; fi
for dt in 0.0001 0.001; do
  cmds="m $dt; autopop on; g 1; printf \"C %d %d %d\\n\", vertex_count, edge_count, facet_count; g 20; printf \"D %d %d %d\\n\", vertex_count, edge_count, facet_count;"
  ev=$(evolver_run "$tmp/pre.dmp" "$cmds")
  cp "$tmp/pre.dmp" "$tmp/in.dmp"
  printf '%s\n' "$cmds" > "$tmp/c.cmd"
  out=$(cd "$tmp" && "$TDS" -q in.dmp -f c.cmd 2>&1)
  for k in C D; do
    name=autopop_string/$dt/$( [ $k = C ] && echo step1 || echo step21)
    e=$(echo "$ev" | grab $k) t=$(echo "$out" | grab $k)
    if [ -n "$t" ] && [ "$t" = "$e" ]; then echo "PASS $name"; else echo "FAIL $name: tds '$t', Evolver '$e'"; fi
  done
done
