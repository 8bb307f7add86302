#!/bin/sh
# numbering.sh: element ids after loading (numbered in file order, the
# file's id kept as `original`, as Evolver does) and after `r` are
# Evolver's, so a script that names facet[40] or edge[100] means the same
# element in both programs. As loaded and after one and two refinements
# of each datafile (mound and qmound have a gap in their face ids), every
# facet's vertices, oriented edges and original, every edge's ends and
# original, every vertex's position (to 8 digits: midpoints of the same
# ends) and original, and every body's original are printed in both
# programs and must be the same lines.
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
LIST='foreach facet ff do printf "F %d %d %d %d %d %d %d %d\n", ff.id, ff.vertex[1].id, ff.vertex[2].id, ff.vertex[3].id, ff.edge[1].oid, ff.edge[2].oid, ff.edge[3].oid, ff.original
foreach edge ee do printf "E %d %d %d %d\n", ee.id, ee.vertex[1].id, ee.vertex[2].id, ee.original
foreach vertex vv do printf "V %d %.8g %.8g %.8g %d\n", vv.id, vv.x, vv.y, vv.z, vv.original
foreach body bb do printf "B %d %d\n", bb.id, bb.original'
for f in cube catbody quad cat column sphere octa tankex catman mound qmound; do
  for n in 0 1 2; do
    cmds=$(printf 'r %d\n%s' "$n" "$LIST")
    evolver_run "$EXAMPLES/$f.fe" "$cmds" | grep '^[FEVB] ' > "$tmp/ev"
    printf '%s\n' "$cmds" > "$tmp/c.cmd"
    "$TDS" -q "$EXAMPLES/$f.fe" -f "$tmp/c.cmd" 2>&1 | grep '^[FEVB] ' > "$tmp/tds"
    if [ ! -s "$tmp/ev" ]; then
      echo "FAIL numbering/$f/r$n: Evolver printed nothing"
    elif cmp -s "$tmp/ev" "$tmp/tds"; then
      echo "PASS numbering/$f/r$n ($(wc -l < "$tmp/ev") lines)"
    else
      echo "FAIL numbering/$f/r$n: $(diff "$tmp/ev" "$tmp/tds" | grep '^[<>]' | head -n 2 | tr '\n' ' ')"
    fi
  done
done
