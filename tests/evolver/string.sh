#!/bin/sh
# string.sh: the string model (STRING, SPACE_DIMENSION 2) against Surface
# Evolver. Evolver's string examples load with the same element counts,
# energy and body area (1e-12 relative: the same sums in another order);
# the ones that need what tds does not have stop with a "not supported
# yet" message at the keyword's line; r gives Evolver's counts and energy;
# V moves every vertex of tests/evolver/string/vavg.fe where Evolver moves
# it (1e-14: a few roundings); slidestr's gogo (r, 40 times g 10 and V)
# followed by g to convergence reaches Evolver's minimum: energy 1e-8,
# pressure 1e-6 relative (both programs stop on a slow tail, the
# multiplier first order in the position error; measured 1e-11 and 3e-7).
. "$(dirname "$0")/lib.sh"
PRINT='printf "C0 %d %d %d %d\n", vertex_count, edge_count, facet_count, body_count; printf "E0 %.17g\n", total_energy; printf "B0 %.17g\n", (body_count > 0 ? body[1].volume : 0);'

for f in popstr slidestr; do
  fe=$EXAMPLES/$f.fe
  ev=$(evolver_run "$fe" "$PRINT r; $PRINT")
  c=$(echo "$ev" | grab C0)
  e=$(echo "$ev" | grab E0)
  b=$(echo "$ev" | grab B0)
  c1=$(echo "$ev" | grep '^C0 ' | sed -n 2p | cut -d' ' -f2-)
  e1=$(echo "$ev" | grep '^E0 ' | sed -n 2p | cut -d' ' -f2-)
  b1=$(echo "$ev" | grep '^B0 ' | sed -n 2p | cut -d' ' -f2-)
  "$TDS" -q "$fe" -e "
dofile('$ROOT/tests/evolver/compare.lua')
local function vol() for bb in bodies() do return bb.volume end return 0 end
report('string/$f/counts', counts() == '$c', counts(), '$c')
same('string/$f/energy', total_energy, $e, 1e-12)
same('string/$f/area', vol(), $b, 1e-12)
r()
report('string/$f/refine-counts', counts() == '$c1', counts(), '$c1')
same('string/$f/refine-energy', total_energy, $e1, 1e-12)
same('string/$f/refine-area', vol(), $b1, 1e-12)
" 2>&1 || echo "FAIL string/$f: tds exited with an error"
done

# V: every vertex where Evolver puts it.
fe=$ROOT/tests/evolver/string/vavg.fe
want=$(evolver_run "$fe" 'V; foreach vertex vv do printf "V %d %.17g %.17g\n", vv.id, vv.x, vv.y;' |
  grep '^V ' | cut -d' ' -f2- | tr '\n' ';')
"$TDS" -q "$fe" -e "
local want, worst, n = {}, 0, 0
for id, x, y in ('$want'):gmatch('(%d+) (%S+) (%S+);') do want[tonumber(id)] = {tonumber(x), tonumber(y)} end
V()
for v in vertices() do
  local w = want[v.id]
  worst = math.max(worst, math.abs(v.x - w[1]), math.abs(v.y - w[2]))
  n = n + 1
end
if n == 12 and worst <= 1e-14 then print('PASS string/vavg/positions')
else print(('FAIL string/vavg/positions: %d vertices, worst difference %.3g'):format(n, worst)) end
" 2>&1 || echo "FAIL string/vavg: tds exited with an error"

# slidestr's gogo, then g to convergence.
LOOP='ii := 0; do { e0 := total_energy; g 1; ii := ii + 1 } while (abs(total_energy - e0) > 1e-13*abs(e0) and ii < 300000);'
ev=$(evolver_run "$EXAMPLES/slidestr.fe" "gogo; $LOOP printf \"G %.17g %.17g\n\", total_energy, body[1].pressure;")
g=$(echo "$ev" | grab G)
"$TDS" -q "$EXAMPLES/slidestr.fe" -e "
dofile('$ROOT/tests/evolver/compare.lua')
local ge, gp = nums('$g')
r()
for i = 1, 40 do g(10); V() end
converge(1e-13, 300000)
local p
for bb in bodies() do p = bb.pressure; same('string/slidestr/converged-area', bb.volume, 0.7, 1e-9) end
same('string/slidestr/converged-energy', total_energy, ge, 1e-8)
same('string/slidestr/converged-pressure', p, gp, 1e-6)
" 2>&1 || echo "FAIL string/slidestr/converged: tds exited with an error"

# dump: slidestr refined and moved, written by tds, read back by Evolver
# and by tds: the same counts and energy (1e-12).
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
out=$("$TDS" -q "$EXAMPLES/slidestr.fe" -e "r(); g(5); V(); dump('$tmp/d.fe')
print(('T %d %d %d %d %.17g'):format(vertex_count, edge_count, facet_count, body_count, total_energy))" 2>&1)
t=$(echo "$out" | grab T)
ev=$(evolver_run "$tmp/d.fe" "$PRINT")
"$TDS" -q "$tmp/d.fe" -e "
dofile('$ROOT/tests/evolver/compare.lua')
local c, e = ('$t'):match('^(%d+ %d+ %d+ %d+) (%S+)$')
report('string/dump/evolver-counts', '$(echo "$ev" | grab C0)' == c, '$(echo "$ev" | grab C0)', c)
same('string/dump/evolver-energy', $(echo "$ev" | grab E0), tonumber(e), 1e-12)
report('string/dump/tds-counts', counts() == c, counts(), c)
same('string/dump/tds-energy', total_energy, tonumber(e), 1e-12)
" 2>&1 || echo "FAIL string/dump: tds exited with an error: $out"

# The command language on a string surface: element attributes (edge
# length and vertices, facet area and its oriented edges), counts, sums,
# r and V, printed by Evolver and by tds (`tds -f`): the same lines, the
# numbers to 1e-12 relative (printed with 15 digits).
cp "$EXAMPLES/slidestr.fe" "$tmp/slidestr.fe"
cp "$ROOT/tests/evolver/string/slidestr.cmd" "$tmp/s.cmd"
evolver_run "$EXAMPLES/slidestr.fe" "$(cat "$tmp/s.cmd")" > "$tmp/ev.out"
(cd "$tmp" && "$TDS" -q slidestr.fe -f s.cmd) > "$tmp/tds.out" 2>&1
"$TDS" -q -e "
dofile('$ROOT/tests/evolver/numcmp.lua')
local pat = '^[LFONXS] '
numcmp('string/slidestr/commands', lines_of('$tmp/ev.out', pat), lines_of('$tmp/tds.out', pat), 1e-12)"

# o for strings (tds.string_pop, until the command language's o reaches
# it): the popped vertices, edges and cells as Evolver makes them. After o,
# every vertex position to 1e-14, the edge ends and the cells' edge lists
# exactly, the facet areas to 1e-12; then g to convergence: popstr to the
# Steiner network of the square, 1 + sqrt(3) (1e-12), pop4 to Evolver's
# minimum (energy 1e-8, pressures 1e-6, as above).
POP='foreach vertex vv do printf "V %d %.15g %.15g ZZ\n", vv.id, vv.x, vv.y XX; foreach edge ee do printf "E %d %d %d\n", ee.id, ee.vertex[1].id, ee.vertex[2].id; foreach facet ff do { printf "L %d %.15g", ff.id, ff.area; foreach ff.edge ee do printf " %d", ee.oid; printf "\n"}'
TPOP="for v in vertices() do print(('V %d %.15g %.15g ZZ'):format(v.id, v.x, v.y XX)) end
for e in edges() do print(('E %d %d %d'):format(e.id, e.tail.id, e.head.id)) end
for f in facets() do print(('L %d %.15g '):format(f.id, f.area) .. table.concat(f.edges, ' ')) end"
for f in "$EXAMPLES/popstr.fe" "$ROOT/tests/evolver/string/star5.fe" "$ROOT/tests/evolver/string/pop4.fe"; do
  name=$(basename "$f" .fe)
  # z only in 3-D space (Evolver has no z in 2-D)
  zz=''; xx=''; [ "$name" = popstr ] && zz='%.15g' && xx=', vv.z'
  p=$(printf '%s' "$POP" | sed "s/ZZ/$zz/; s/ XX/$xx/")
  tp=$(printf '%s' "$TPOP" | sed "s/ZZ/$zz/; s/ XX/$(echo "$xx" | sed 's/vv/v/')/")
  evolver_run "$f" "o; $p" > "$tmp/ev.out"
  "$TDS" -q "$f" -e "tds.string_pop(); $tp" > "$tmp/tds.out" 2>&1
  "$TDS" -q -e "
dofile('$ROOT/tests/evolver/numcmp.lua')
numcmp('string/$name/pop', lines_of('$tmp/ev.out', '^[VEL] '), lines_of('$tmp/tds.out', '^[VEL] '), 1e-12)"
done
"$TDS" -q "$EXAMPLES/popstr.fe" -e "
dofile('$ROOT/tests/evolver/compare.lua')
tds.string_pop()
converge(1e-14, 10000)
same('string/popstr/steiner', total_energy, 1 + math.sqrt(3), 1e-12)
" 2>&1 || echo "FAIL string/popstr/steiner: tds exited with an error"
ev=$(evolver_run "$ROOT/tests/evolver/string/pop4.fe" "o; $LOOP printf \"G %.17g %.17g %.17g\n\", total_energy, body[1].pressure, body[2].pressure;")
g=$(echo "$ev" | grab G)
"$TDS" -q "$ROOT/tests/evolver/string/pop4.fe" -e "
dofile('$ROOT/tests/evolver/compare.lua')
local ge, p1, p2 = nums('$g')
tds.string_pop()
converge(1e-13, 300000)
same('string/pop4/converged-energy', total_energy, ge, 1e-8)
same('string/pop4/converged-pressure1', body[1].pressure, p1, 1e-6)
same('string/pop4/converged-pressure2', body[2].pressure, p2, 1e-6)
" 2>&1 || echo "FAIL string/pop4/converged: tds exited with an error"
# ... and a cell's vertices, bodies and cells, valences, max/min/count.
cp "$ROOT/tests/evolver/string/slidestr2.cmd" "$tmp/s2.cmd"
evolver_run "$EXAMPLES/slidestr.fe" "$(cat "$tmp/s2.cmd")" > "$tmp/ev.out"
(cd "$tmp" && "$TDS" -q slidestr.fe -f s2.cmd) > "$tmp/tds.out" 2>&1
"$TDS" -q -e "
dofile('$ROOT/tests/evolver/numcmp.lua')
numcmp('string/slidestr/attributes', lines_of('$tmp/ev.out', '^[A-G] '), lines_of('$tmp/tds.out', '^[A-G] '), 1e-12)"

# t1_edgeswap for strings (tds.string_t1 until the command language's
# t1_edgeswap reaches it): the same positions, edge ends and cell lists as
# Evolver (areas after recalc; Evolver keeps stale facet areas until one),
# then g to convergence: Evolver's minimum (energy 1e-8, pressures 1e-6).
f=$ROOT/tests/evolver/string/t1.fe
p=$(printf '%s' "$POP" | sed "s/ZZ//; s/ XX//")
tp=$(printf '%s' "$TPOP" | sed "s/ZZ//; s/ XX//")
evolver_run "$f" "t1_edgeswap edge[1]; recalc; $p" > "$tmp/ev.out"
# (tds through Evolver's syntax: `t1_edgeswap edge[1]` reaches tds.string_t1)
cp "$f" "$tmp/t1.fe"
printf '%s\n' "t1_edgeswap edge[1]; recalc; $p" > "$tmp/t1.cmd"
(cd "$tmp" && "$TDS" -q t1.fe -f t1.cmd) > "$tmp/tds.out" 2>&1
"$TDS" -q -e "
dofile('$ROOT/tests/evolver/numcmp.lua')
numcmp('string/t1/swap', lines_of('$tmp/ev.out', '^[VEL] '), lines_of('$tmp/tds.out', '^[VEL] '), 1e-12)"
# The cells after the swap relax (refined twice) to a minimum Evolver
# agrees with: tds's converged dump, loaded into Evolver, has tds's energy
# (1e-12) and 2000 more Evolver steps lower it by less than 1e-10
# relative. (Evolver's own run from the swap ends in another local minimum
# of this floating cluster, measured 0.06% higher, so the two runs are not
# compared with each other.)
out=$("$TDS" -q "$f" -e "
dofile('$ROOT/tests/evolver/compare.lua')
tds.string_t1(edge[1]); r(); r()
converge(1e-13, 300000)
dump('$tmp/t1min.fe')
print(('T %.17g'):format(total_energy))" 2>&1)
t=$(echo "$out" | grab T)
ev=$(evolver_run "$tmp/t1min.fe" 'printf "A %.17g\n", total_energy; g 2000; printf "B %.17g\n", total_energy;')
"$TDS" -q -e "
dofile('$ROOT/tests/evolver/compare.lua')
local t, a, b = tonumber('$t'), tonumber('$(echo "$ev" | grab A)'), tonumber('$(echo "$ev" | grab B)')
same('string/t1/minimum-energy', a, t, 1e-12)
report('string/t1/evolver-stays', b and a and b >= a * (1 - 1e-10), b, a)
" 2>&1 || echo "FAIL string/t1/converged: tds exited with an error"

# facet_crosscut (Evolver's function; in tds a global function calling
# tds.facet_crosscut): the new edge's id, ends and tension 0, both cells'
# edge lists and bodies, areas (1e-12), the same lines as Evolver's.
cp "$ROOT/tests/evolver/string/pop4.fe" "$tmp/pop4.fe"
cp "$ROOT/tests/evolver/string/crosscut.cmd" "$tmp/cc.cmd"
evolver_run "$ROOT/tests/evolver/string/pop4.fe" "$(cat "$tmp/cc.cmd")" > "$tmp/ev.out"
(cd "$tmp" && "$TDS" -q pop4.fe -f cc.cmd) > "$tmp/tds.out" 2>&1
"$TDS" -q -e "
dofile('$ROOT/tests/evolver/numcmp.lua')
numcmp('string/pop4/crosscut', lines_of('$tmp/ev.out', '^[NLEB] '), lines_of('$tmp/tds.out', '^[NLEB] '), 1e-12)"

# rawv and rawestv in the string model, as Evolver 2.70 does them
# (measured): every vertex with two or more edges, junctions too, on no
# constraint or boundary, moves a quarter of the way to the mean of its
# edges' far ends (each edge counted, two edges to one neighbour twice,
# wraps followed); ends and constrained vertices stay. (V keeps its chord
# rule above.) Every position to 1e-12 (measured 2e-14): seeded random
# networks (tests/evolver/genus2/net.lua without the group, Euclidean and
# KLEIN_METRIC: the rule is Euclidean), refined and relaxed; drops on a
# tilted line (constrained ends); slidestr; popstr (3-D space); 100grain
# (the 2-D torus) after g 10; a genus2 net (wrapped edges).
P2='foreach vertex vv do printf "K %d %.17g %.17g\n", vv.id, vv.x, vv.y;'
for seed in 3 4; do
  "$TDS" -q -e "OUT='$tmp/net$seed.fe' SEED=$seed NV=8 NE=16 KLEIN=true LONG=false FIXED=3
dofile('$ROOT/tests/evolver/genus2/net.lua')" || echo "FAIL string/rawv/net$seed: the generator failed"
  cp "$tmp/net$seed.fe" "$tmp/g2net$seed.fe"
  sed -i '/SYMMETRY_GROUP/d; s/ wrap [0-9]*//; s/ tension [0-9.e-]*//' "$tmp/net$seed.fe"
  sed '/KLEIN_METRIC/d' "$tmp/net$seed.fe" > "$tmp/enet$seed.fe"
done
"$TDS" -q -e "io.write((dofile('$ROOT/tests/evolver/string/hessgen.lua').drop_fe(1)))" > "$tmp/drop1.fe"
for spec in "net3:$tmp/net3.fe" "net4:$tmp/net4.fe" "enet3:$tmp/enet3.fe" "enet4:$tmp/enet4.fe" \
            "drop1:$tmp/drop1.fe" "slidestr:$EXAMPLES/slidestr.fe" "g2net3:$tmp/g2net3.fe"; do
  n=${spec%%:*} f=${spec#*:}
  kcompare "string/rawv/$n" "$f" 1e-12 "rawv; $P2"
  kcompare "string/rawv/$n-r-rawestv" "$f" 1e-12 "r; rawestv; rawv; $P2"
done
kcompare string/rawv/popstr "$EXAMPLES/popstr.fe" 1e-12 "r; rawv; foreach vertex vv do printf \"K %d %.17g %.17g %.17g\n\", vv.id, vv.x, vv.y, vv.z;"
kcompare string/rawv/100grain "$EXAMPLES/100grain.fe" 1e-12 "g 10; rawestv; rawv; $P2"
