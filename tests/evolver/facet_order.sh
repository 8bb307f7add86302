#!/bin/sh
# facet_order.sh: the facets around each edge in Evolver's order
# (src/ring.h): `foreach ee.facet` lists the same signed facets in the
# same order in Surface Evolver and tds, exactly, after loading and after
# one and two `r`. Surfaces: cube, mound (a fixed no_refine table),
# octa, twointor (the torus model) and a double bubble (edges of three
# facets, sorted by angle) with its vertices moved at random (seeds 1-3).
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
L='foreach edge ee do { printf "K %d", ee.id; foreach ee.facet ff do printf " %d", ff.oid; printf "\n" }'
run() { # NAME FILE
  for r in "load|" "r|r" "rr|r; r"; do
    name=${r%%|*} cmd=${r#*|}
    evolver_run "$2" "$cmd
$L" | grep '^K ' > "$tmp/ev.k"
    printf '%s\n%s\n' "$cmd" "$L" > "$tmp/c.cmd"
    cp "$2" "$tmp/in.fe"
    (cd "$tmp" && "$TDS" -q in.fe -f c.cmd) 2>&1 | grep '^K ' > "$tmp/tds.k"
    "$TDS" -q -e "
dofile('$ROOT/tests/evolver/numcmp.lua')
numcmp('facet_order/$1/$name', lines_of('$tmp/ev.k', '^K'), lines_of('$tmp/tds.k', '^K'), 0)"
  done
}
for f in cube mound octa twointor; do run "$f" "$EXAMPLES/$f.fe"; done
for seed in 1 2 3; do
  "$TDS" -q -e "
math.randomseed($seed)
local out = {}
for l in io.lines('$ROOT/tests/evolver/data/dbubble.fe') do
  local id, x, y, z = l:match('^(%d+) (%S+) (%S+) (%S+)$')
  if id and not l:find('vertices') and tonumber(id) <= 12 and z and not out.edges then
    l = ('%s %.6f %.6f %.6f'):format(id, x + 0.4 * (math.random() - 0.5),
      y + 0.4 * (math.random() - 0.5), z + 0.4 * (math.random() - 0.5))
  end
  if l == 'edges' then out.edges = true end
  out[#out + 1] = l
end
local f = assert(io.open('$tmp/db$seed.fe', 'w'))
f:write(table.concat(out, '\n'), '\n')
f:close()"
  run "dbubble$seed" "$tmp/db$seed.fe"
done
