#!/bin/sh
# attributes.sh: user attributes (define ... attribute, arrays included)
# and colours through Surface Evolver and tds. The input is cube.fe with
# seeded random values (attributes/gen.awk) for every kind of element:
# a real, an integer[3] (vertices), a real[2] (edges), an integer[3] and a
# real[2][2] (facets), a real (body), and some edge and facet colours.
# The same Evolver commands (attributes/print.cmd: foreach ... printf
# "%.17g") run in both programs, so every value is compared to the bit
# (tolerance 0: both read the same decimal text, or tds's 17 digits):
#   load       Evolver and tds load the input
#   refine     after r: inheritance by split edges and facets, zeros on
#              new elements, the default facet colour 15 (white)
#   evdump     tds reads Evolver's dump (taken after r)
#   tdsdump    Evolver reads tds's dump, after values set from Lua
#   write_fe   Evolver reads the same surface written by write_fe
. "$(dirname "$0")/lib.sh"
D=$ROOT/tests/evolver/attributes
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

awk -v seed=7 -f "$D/gen.awk" "$EXAMPLES/cube.fe" > "$tmp/in.fe"
P=$(cat "$D/print.cmd")
ev=$(evolver_run "$tmp/in.fe" "$(printf 'printf "LOAD\\n";\n%s\nr;\nprintf "REFINE\\n";\n%s\ndump "%s/ev.dmp";' "$P" "$P" "$tmp")")
echo "$ev" | sed -n '/^LOAD/,/^REFINE/p' | grep '^[VEFB] ' > "$tmp/ev_load"
echo "$ev" | sed -n '/^REFINE/,$p' | grep '^[VEFB] ' > "$tmp/ev_refine"

"$TDS" -q "$tmp/in.fe" -f "$D/print.cmd" 2>&1 | grep '^[VEFB] ' > "$tmp/t_load"
"$TDS" -q "$tmp/in.fe" -e 'r()' -f "$D/print.cmd" 2>&1 | grep '^[VEFB] ' > "$tmp/t_refine"
if [ -s "$tmp/ev.dmp" ]; then
  "$TDS" -q "$tmp/ev.dmp" -f "$D/print.cmd" 2>&1 | grep '^[VEFB] ' > "$tmp/t_evdump"
else
  : > "$tmp/t_evdump"
fi
# tds changes values from Lua, prints them and dumps; Evolver reads the dump.
"$TDS" -q "$tmp/in.fe" -e "
r()
for v in vertices() do v.weight = v.weight * 1.5 + v.x / 3; v.tri = { v.id, -v.id, 7 } end
for f in facets() do local m = f.mat; m[2][1] = f.id / 7; f.mat = m end
body[1].bw = math.pi
dump('$tmp/td.dmp')
write_fe('$tmp/td.fe', { header = '// the plain element lists' })" -f "$D/print.cmd" 2>&1 |
  grep '^[VEFB] ' > "$tmp/t_set"
evolver_run "$tmp/td.dmp" "$P" | grep '^[VEFB] ' > "$tmp/ev_tdsdump"
evolver_run "$tmp/td.fe" "$P" | grep '^[VEFB] ' > "$tmp/ev_writefe"

"$TDS" -q "$ROOT/tests/evolver/numcmp.lua" -e "
numcmp('attributes/load', lines_of('$tmp/ev_load', '.'), lines_of('$tmp/t_load', '.'), 0)
numcmp('attributes/refine', lines_of('$tmp/ev_refine', '.'), lines_of('$tmp/t_refine', '.'), 0)
numcmp('attributes/evdump', lines_of('$tmp/ev_refine', '.'), lines_of('$tmp/t_evdump', '.'), 0)
numcmp('attributes/tdsdump', lines_of('$tmp/ev_tdsdump', '.'), lines_of('$tmp/t_set', '.'), 0)
numcmp('attributes/write_fe', lines_of('$tmp/ev_writefe', '.'), lines_of('$tmp/t_set', '.'), 0)"
