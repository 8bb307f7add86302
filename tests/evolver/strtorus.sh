#!/bin/sh
# strtorus.sh: the torus in the string model (2-D periodic foams) against
# Surface Evolver: 100grain.fe (100 grains in the unit torus, AUTOPOP,
# AUTOCHOP, AREA_NORMALIZATION, fixed scale) and a periodic random Voronoi
# foam (strtorus/voronoi.lua, seeded). Every cell (facet) area is the
# "volume" of its body; cells cross the cell boundary through wrapped
# edges, so the areas test the lattice lifts (string_model.h).
# Tolerances: 1e-12 relative where both programs sum the same terms in
# another order (load, one step, a dump read back); 1e-10 after 100 fixed
# steps (rounding carried along; measured 1e-15).
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
G=$EXAMPLES/100grain.fe
# every live facet's area, every body's volume, and counts and energy
# (Evolver updates facet areas on recalc)
PF='recalc; printf "C %d %d %d %d\n", vertex_count, edge_count, facet_count, body_count; printf "E %.17g\n", total_energy; foreach facet ff do printf "A %d %.17g\n", ff.id, ff.area; foreach body bb do printf "A %d %.17g\n", bb.id, bb.volume;'
TF="print(('C %d %d %d %d'):format(vertex_count, edge_count, facet_count, body_count))
print(('E %.17g'):format(total_energy))
for f in facets() do print(('A %d %.17g'):format(f.id, f.area)) end
for b in bodies() do print(('A %d %.17g'):format(b.id, b.volume)) end"
cmp() { # NAME TOL: Evolver's lines in $tmp/ev.out against tds's in $tmp/tds.out
  "$TDS" -q -e "
dofile('$ROOT/tests/evolver/numcmp.lua')
numcmp('$1', lines_of('$tmp/ev.out', '^[CEA] '), lines_of('$tmp/tds.out', '^[CEA] '), $2)"
}

# Load: counts, energy, every cell's area.
evolver_run "$G" "$PF" > "$tmp/ev.out"
"$TDS" -q "$G" -e "$TF" > "$tmp/tds.out" 2>&1
cmp strtorus/100grain/load 1e-12

# 200 steps of g with autochop, area normalization and autopop: edges
# chopped (1,776 by step 100, 272 at the first step) and collapsed (115 by
# step 100, from step 23) as Evolver's step by step, so the cells agree
# to rounding (1e-10; measured 1e-15 in the energy). Evolver's energy
# after g with autopop is the one before the collapses, so both print
# after recalc.
evolver_run "$G" "g 200; $PF" > "$tmp/ev.out"
"$TDS" -q "$G" -e "g(200) $TF" > "$tmp/tds.out" 2>&1
cmp strtorus/100grain/g200 1e-10

# Every step of the first 1500: counts and energy (1e-10; measured 7e-14
# over 12,000 steps). The first junctions merge at step 246 (an edge
# between two junctions collapses: the merged vertex at the midpoint,
# moving with the mean of both ends' motions, then popped in the moved
# positions), a cell vanishes at step 249, a chop and a collapse meet at
# step 819 (the new vertex follows the merged end): the places where the
# runs used to part.
evolver_run "$G" 'for (ii := 1; ii <= 1500; ii += 1) { g 1; recalc; printf "C %d %d %d %d %.17g\n", ii, vertex_count, edge_count, facet_count, total_energy }' > "$tmp/ev.out"
"$TDS" -q "$G" -e "for i = 1, 1500 do g(1) print(('C %d %d %d %d %.17g'):format(i, vertex_count, edge_count, facet_count, total_energy)) end" > "$tmp/tds.out" 2>&1
cmp strtorus/100grain/steps1500 1e-10

# 3000 steps (100 grains -> 53): every cell area and body volume (1e-10;
# measured 1e-14).
evolver_run "$G" "g 3000; $PF" > "$tmp/ev.out"
"$TDS" -q "$G" -e "g(3000) $TF" > "$tmp/tds.out" 2>&1
cmp strtorus/100grain/g3000 1e-10

# Without autopop and autochop (area normalization on): 100 steps.
sed '/^autopop/d; /^autochop/d' "$G" > "$tmp/an.fe"
evolver_run "$tmp/an.fe" "g 100; $PF" > "$tmp/ev.out"
"$TDS" -q "$tmp/an.fe" -e "g(100) $TF" > "$tmp/tds.out" 2>&1
cmp strtorus/100grain/normalized-g100 1e-10

# tds's dump after 1000 steps (79 grains left) read by Evolver: counts,
# energy (1e-12: the same sums in another order); and against Evolver's
# dump: the same edges, each from the same tail to the same head
# (vertices matched by position modulo the lattice to 1e-7; where two
# edges merge after a collapse, the one from the removed end stays, as in
# Evolver: 10 edges would run the other way with the higher id kept).
"$TDS" -q "$G" -e "dofile('$ROOT/tests/evolver/compare.lua') g(1000) dump('$tmp/g.dmp') print(('T %s %.17g'):format(counts(), total_energy))" > "$tmp/tds.out" 2>&1 || echo "FAIL strtorus/100grain/dump: tds exited with an error"
t=$(grab T < "$tmp/tds.out")
evd=$(evolver_run "$tmp/g.dmp" 'printf "D %d %d %d %d %.17g\n", vertex_count, edge_count, facet_count, body_count, total_energy;')
evolver_dump strtorus/100grain g1000 "$G" "g 1000"
"$TDS" -q -e "NAME, A, B, DIGITS = 'strtorus/100grain/g1000-edges', '$tmp/g1000.dmp', '$tmp/g.dmp', 7
dofile('$ROOT/tests/evolver/strtorus/edges.lua')"
"$TDS" -q -e "
dofile('$ROOT/tests/evolver/compare.lua')
local c, e = ('$t'):match('^(.*) (%S+)$')
local d = '$(echo "$evd" | grab D)'
local dc, de = d:match('^(.*) (%S+)$')
report('strtorus/100grain/dump-counts', dc == c, dc, c)
same('strtorus/100grain/dump-energy', tonumber(de) or 0/0, tonumber(e), 1e-12)"

# A periodic random Voronoi foam (30 cells, seed 7; and 60 cells, seed
# 2026), written by strtorus/voronoi.lua: load and after r, r (refined
# twice: wrapped edges split, the second half carrying the wrap): counts,
# energy, every cell area and body volume (1e-12). g with the areas held
# is compared at a fixed scale with evolver_line_search (Evolver leaves
# the areas off their targets by up to 1e-4 where tds's own projection
# puts them on; its reported pressures after g are not compared).
for spec in 30:7 60:2026; do
  n=${spec%%:*}; seed=${spec#*:}
  (cd "$ROOT/tests/evolver/strtorus" && "$TDS" -q -e "N, SEED = $n, $seed; dofile('voronoi.lua')") > "$tmp/v.fe"
  for cmds in ":load" "r; r;:r2"; do
    c=${cmds%%:*}; tag=${cmds#*:}
    evolver_run "$tmp/v.fe" "$c $PF" > "$tmp/ev.out"
    tc=$(printf '%s' "$c" | sed 's/r;/r()/g')
    "$TDS" -q "$tmp/v.fe" -e "$tc $TF" > "$tmp/tds.out" 2>&1
    cmp "strtorus/voronoi$n/$tag" 1e-12
  done
  # 50 steps at a fixed scale with the areas held, Evolver's restoring
  # moves (evolver_line_search): every cell area, body volume and the
  # energy (1e-10; measured 1e-16)
  evolver_run "$tmp/v.fe" "m 0.002; g 50; $PF" > "$tmp/ev.out"
  "$TDS" -q "$tmp/v.fe" -e "tds.setting('evolver_line_search', true) m(0.002) g(50) $TF" > "$tmp/tds.out" 2>&1
  cmp "strtorus/voronoi$n/held-g50" 1e-10
  # the same cells free (no volumes): 100 steps at a fixed scale, every
  # cell area and the energy (1e-10; measured equal)
  sed 's/ volume .*//' "$tmp/v.fe" > "$tmp/vf.fe"
  evolver_run "$tmp/vf.fe" "m 0.001; g 100; $PF" > "$tmp/ev.out"
  "$TDS" -q "$tmp/vf.fe" -e "m(0.001) g(100) $TF" > "$tmp/tds.out" 2>&1
  cmp "strtorus/voronoi$n/free-g100" 1e-10
done
