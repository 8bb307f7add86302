#!/bin/sh
# string_cmds.sh: the command language's words on string surfaces against
# Surface Evolver: o, O and `pop vertex[...]` (the string pop), `t`
# (edgeweed) and `delete edge`, surface_dimension / space_dimension.
# Each runs the same command file in both programs (tds -f) and compares
# what they print: Vertices popped / Deleted edges messages exactly, every
# vertex position and cell area to 1e-12 relative (printed with 15
# digits; the same arithmetic), edge ends and the cells' edge lists
# exactly, then the energy.
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
P2='foreach vertex vv do printf "V %d %.15g %.15g\n", vv.id, vv.x, vv.y; foreach edge ee do printf "E %d %d %d\n", ee.id, ee.vertex[1].id, ee.vertex[2].id; foreach facet ff do { printf "L %d %.15g", ff.id, ff.area; foreach ff.edge ee do printf " %d", ee.oid; printf "\n"}; printf "T %.15g %d %d\n", total_energy, surface_dimension, space_dimension;'
# without areas and energy (Evolver's stay stale after delete until a
# recalc, which in tds, as in Evolver's g, stops at a body left without
# cells: "volume constraints are dependent")
PL='foreach vertex vv do printf "V %d %.15g %.15g\n", vv.id, vv.x, vv.y; foreach edge ee do printf "E %d %d %d\n", ee.id, ee.vertex[1].id, ee.vertex[2].id; foreach facet ff do { printf "L %d", ff.id; foreach ff.edge ee do printf " %d", ee.oid; printf "\n"};'
P3='foreach vertex vv do printf "V %d %.15g %.15g %.15g\n", vv.id, vv.x, vv.y, vv.z; foreach edge ee do printf "E %d %d %d\n", ee.id, ee.vertex[1].id, ee.vertex[2].id; printf "T %.15g %d %d\n", total_energy, surface_dimension, space_dimension;'
run() { # name datafile commands
  cp "$2" "$tmp/in.fe"
  printf '%s\n' "$3" > "$tmp/c.cmd"
  evolver_run "$2" "$3" > "$tmp/ev.out"
  (cd "$tmp" && "$TDS" in.fe -f c.cmd < /dev/null) > "$tmp/tds.out" 2>&1
  "$TDS" -q -e "
dofile('$ROOT/tests/evolver/numcmp.lua')
local ev, td = lines_of('$tmp/ev.out', '^[VELT] '), lines_of('$tmp/tds.out', '^[VELT] ')
for _, pat in ipairs({'popped: ', 'eleted: '}) do -- the messages, in order
  for _, l in ipairs(lines_of('$tmp/ev.out', pat)) do ev[#ev + 1] = l:match(pat:gsub(' ', '') .. '.*') end
  for _, l in ipairs(lines_of('$tmp/tds.out', pat)) do td[#td + 1] = l:match(pat:gsub(' ', '') .. '.*') end
end
numcmp('string_cmds/$1', ev, td, 1e-12)"
}
POP=$EXAMPLES/popstr.fe
T1=$ROOT/tests/evolver/string/t1.fe
run popstr-o "$POP" "o; $P3"
run popstr-O "$POP" "O; $P3"
# pop on a list: vertex 5 pops (the message), vertex 1 (fixed) does not
# and pop then prints nothing, as Evolver (whose energy is stale after pop
# until a recalc)
run popstr-pop "$POP" "pop vertex[1]; pop vertex[5]; pop vertex[5]; recalc; $P3"
run pop4-o "$ROOT/tests/evolver/string/pop4.fe" "o; $P2"
run t1-edgeweed "$T1" "t 1.1; recalc; $P2"
run t1-popped-edgeweed "$POP" "o; t 0.1; $P3"
# edge 3's ends merge, so edges 2 and 10 join the same vertices: edge 10
# (at the kept vertex) stays, and cell 3, now edge 10 out and back, goes
run t1-delete "$T1" "delete edge[3]; $PL"
run t1-delete-where "$T1" "delete edge where id == 10 or id == 5; $PL"
