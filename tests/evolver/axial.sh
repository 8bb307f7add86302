#!/bin/sh
# axial.sh: axial_point (a vertex on the rotation axis of a symmetry
# group; Evolver's elements.htm) against Surface Evolver and exact
# answers, on sectors of a disc-like film under "rotate" whose centre is
# an axial point (axial/sector.lua; seeded offsets, orders 5 and 6). The
# facet at the centre has wraps that multiply to the generator, not the
# identity, which only an axial point allows.
# * load, r, r: counts, energy, volume (1e-12: the same sums in another
#   order; refining composes the wraps from the axial corner);
# * u after 10 steps: the same flips (edges' ends) and energy;
# * 50 steps at a fixed scale (the film free; with the body held at its
#   volume, evolver_line_search): energy, volume, pressure and the centre's
#   height (1e-10; measured equal to 1e-15);
# * the free film converged (r, r, g 2000): a flat sector, energy
#   sin(pi/N) (the polygon of the fixed ring) to 1e-9 and the centre's
#   height 0 to 1e-6 (g alone leaves 2e-7 in both programs), as Evolver's;
# * tds's dump (with axial_point) read by Evolver: counts, energy, volume;
# * errors: file:line: message for a face at an axial point that is not a
#   triangle, and for the same face without axial_point.
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$TDS" -q -e "
for _, c in ipairs {{'o5', 5, 3, nil}, {'o6', 6, 8, nil}, {'b5', 5, 4, 0}, {'b6', 6, 11, 0}} do
  OUT, N, SEED, AMP, BODY = '$tmp/' .. c[1] .. '.fe', c[2], c[3], 0.04, c[4]
  dofile('$ROOT/tests/evolver/axial/sector.lua')
end" || echo "FAIL axial/generate: tds exited with an error"
# the bodies held at their volume at load (tds's, equal to Evolver's: the
# load comparison below)
for f in b5 b6; do
  v=$("$TDS" -q "$tmp/$f.fe" -e "print(('%.17g'):format(body[1].volume))")
  sed "s/ volume 0\$/ volume $v/" "$tmp/$f.fe" > "$tmp/$f.tmp" && mv "$tmp/$f.tmp" "$tmp/$f.fe"
done

P='printf "K0 %d %d %d\n", vertex_count, edge_count, facet_count; printf "K1 %.15g\n", total_energy;'
PB="$P"' printf "K2 %.15g %.15g\n", body[1].volume, body[1].pressure;'
for f in o5 o6; do
  kcompare "axial/$f/load" "$tmp/$f.fe" 1e-12 "$P r; $P r; $P"
  kcompare "axial/$f/g50" "$tmp/$f.fe" 1e-10 "r; r; m 0.005; g 50; $P"' printf "K3 %.15g\n", vertex[1].z;'
  # u: the same flips (each edge's two ends; Evolver may run a flipped
  # edge the other way, with the inverse wrap), energy 1e-10
  kcompare "axial/$f/u" "$tmp/$f.fe" 1e-10 "r; r; m 0.005; g 10; u; $P"' foreach edge ee do printf "K4 %d %d %d\n", ee.id, minimum(ee.vertex[1].id, ee.vertex[2].id), maximum(ee.vertex[1].id, ee.vertex[2].id);'
done
for f in b5 b6; do
  kcompare "axial/$f/load" "$tmp/$f.fe" 1e-12 'printf "K %.15g\n", body[1].volume; '"$P r; $P r; $P"
  ev=$(evolver_run "$tmp/$f.fe" 'r; m 0.01; g 50; printf "K %.17g %.17g %.17g %.17g\n", total_energy, body[1].volume, body[1].pressure, vertex[1].z;' | grep '^K')
  td=$("$TDS" -q "$tmp/$f.fe" -e "tds.setting('evolver_line_search', true) r() m(0.01) g(50)
print(('K %.17g %.17g %.17g %.17g'):format(total_energy, body[1].volume, body[1].pressure, vertex[1].z))" | grep '^K')
  "$TDS" -q -e "dofile('$ROOT/tests/evolver/numcmp.lua') numcmp('axial/$f/held-g50', {'$ev'}, {'$td'}, 1e-10)"
done

# The free film converged: flat, energy sin(pi/N).
for spec in o5:5 o6:6; do
  f=${spec%%:*} n=${spec#*:}
  ev=$(evolver_run "$tmp/$f.fe" 'r; r; g 2000; printf "E1 %.17g %.17g\n", total_energy, vertex[1].z;')
  set -- $(echo "$ev" | grab E1)
  "$TDS" -q "$tmp/$f.fe" -e "
dofile('$ROOT/tests/evolver/compare.lua')
r() r() g(2000)
same('axial/$f/flat-energy-evolver', total_energy, $1, 1e-9)
same('axial/$f/flat-energy-exact', total_energy, math.sin(math.pi / $n), 1e-9)
report('axial/$f/flat-centre', math.abs(vertex[1].z) <= 1e-6 and math.abs($2) <= 1e-6, vertex[1].z, $2)
" 2>&1 || echo "FAIL axial/$f/flat: tds exited with an error"
done

# tds's dump after r read by Evolver.
"$TDS" -q "$tmp/b5.fe" -e "r() dump('$tmp/b5.dmp')" || echo "FAIL axial/dump: tds exited with an error"
if grep -q 'axial_point' "$tmp/b5.dmp"; then echo "PASS axial/dump-attribute"
else echo "FAIL axial/dump-attribute: no axial_point in the dump"; fi
kcompare "axial/tds-dump-in-evolver" "$tmp/b5.dmp" 1e-12 "$PB"

# Errors.
err() { # NAME SED WANT
  sed "$2" "$tmp/o5.fe" > "$tmp/bad.fe"
  got=$("$TDS" -q "$tmp/bad.fe" -e '' 2>&1 < /dev/null)
  if [ "$got" = "$tmp/bad.fe:$3" ]; then echo "PASS axial/refused/$1"
  else echo "FAIL axial/refused/$1: '$got', want '$tmp/bad.fe:$3'"; fi
}
err not-axial 's/ axial_point//' "27: face 2: the product of its edges' wraps is not the identity (the face does not close in the quotient space)"
err not-triangle 's/^5 4 5 fixed$/5 4 5 fixed\n11 3 6\n12 6 2 wrap 1/; s/^2 2 4 -1$/2 2 11 12 -1/; s/^5 .* 0 fixed$/&\n6 0.3 -0.3 0.05/' \
  "30: face 2: a face at an axial_point whose wraps do not multiply to the identity must be a triangle"
