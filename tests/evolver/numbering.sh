#!/bin/sh
# numbering.sh: element ids after `r` are Evolver's, so a script that
# names facet[40] or edge[100] after refining means the same element in
# both programs. After one and two refinements of each datafile, every
# facet's vertices and oriented edges, every edge's ends and every
# vertex's position (to 8 digits: midpoints of the same ends) are printed
# in both programs and must be the same lines.
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
LIST='foreach facet ff do printf "F %d %d %d %d %d %d %d\n", ff.id, ff.vertex[1].id, ff.vertex[2].id, ff.vertex[3].id, ff.edge[1].oid, ff.edge[2].oid, ff.edge[3].oid
foreach edge ee do printf "E %d %d %d\n", ee.id, ee.vertex[1].id, ee.vertex[2].id
foreach vertex vv do printf "V %d %.8g %.8g %.8g\n", vv.id, vv.x, vv.y, vv.z'
for f in cube catbody quad cat column sphere octa tankex catman; do
  for n in 1 2; do
    cmds=$(printf 'r %d\n%s' "$n" "$LIST")
    evolver_run "$EXAMPLES/$f.fe" "$cmds" | grep '^[FEV] ' > "$tmp/ev"
    printf '%s\n' "$cmds" > "$tmp/c.cmd"
    "$TDS" -q "$EXAMPLES/$f.fe" -f "$tmp/c.cmd" 2>&1 | grep '^[FEV] ' > "$tmp/tds"
    if [ ! -s "$tmp/ev" ]; then
      echo "FAIL numbering/$f/r$n: Evolver printed nothing"
    elif cmp -s "$tmp/ev" "$tmp/tds"; then
      echo "PASS numbering/$f/r$n ($(wc -l < "$tmp/ev") lines)"
    else
      echo "FAIL numbering/$f/r$n: $(diff "$tmp/ev" "$tmp/tds" | grep '^[<>]' | head -n 2 | tr '\n' ' ')"
    fi
  done
done
