#!/bin/sh
# symmetry.sh: SYMMETRY_GROUP "torus" (Evolver's symmetry-group form of the
# torus: `wrap` codes on edges, Euclidean body volumes) against Surface
# Evolver, on symtest.fe and on variants nobody designed: symtest mapped
# onto a skew cell with seeded random vertex offsets (symmetry/perturb.lua)
# and a wavy periodic film over a skew cell (symmetry/membrane.lua).
# * load, r, r: counts exactly; energy and every body volume 1e-12
#   relative (the same sums in another order); after each r every wrapped
#   edge's id, ends and wrap code exactly (refining composes the wraps);
# * dumps: tds's dump read by Evolver (counts, energy 1e-12) and Evolver's
#   dump read by tds (counts, energy and volumes 1e-12);
# * the film converged (g 10; r; g 200; hessian x3): energy to Evolver's
#   and to the exact area |P1 x P2| at 1e-8 relative (Newton converges
#   quadratically, so both stop at rounding level), the volume to its
#   target at 1e-10, every vertex at the height volume/area at 1e-7, the
#   pressure 0 to 1e-6 absolute (Evolver leaves ~4e-9);
# * errors: an unknown group and the groups tds does not have yet stop at
#   the keyword with file:line: message.
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

PRINT='printf "K0 %d %d %d %d\n", vertex_count, edge_count, facet_count, body_count; printf "K1 %.15g\n", total_energy; foreach body bb do printf "K2 %d %.15g\n", bb.id, bb.volume; foreach edge ee where ee.wrap != 0 do printf "K3 %d %d %d %d\n", ee.id, ee.vertex[1].id, ee.vertex[2].id, ee.wrap;'

cp "$EXAMPLES/symtest.fe" "$tmp/symtest.fe"
"$TDS" -q -e "IN='$tmp/symtest.fe' OUT='$tmp/skew1.fe' SEED=7 AMP=0.03
P={{1,0,0},{0.1,1.1,0},{0.05,-0.2,0.9}} VOLS={0.16}
dofile('$ROOT/tests/evolver/symmetry/perturb.lua')
IN='$tmp/symtest.fe' OUT='$tmp/skew2.fe' SEED=11 AMP=0.05
P={{1.3,0.2,-0.1},{0,0.8,0.3},{0.2,0,1.1}} VOLS=nil
dofile('$ROOT/tests/evolver/symmetry/perturb.lua')
OUT='$tmp/film.fe' N=4 SEED=3 AMP=0.1 Z0=0.3 P={{1,0,0},{0.3,1.2,0},{0.1,0.2,1}} VOL=0.35
dofile('$ROOT/tests/evolver/symmetry/membrane.lua')" || echo "FAIL symmetry/generate: tds exited with an error"

for f in symtest skew1 skew2 film; do
  kcompare "symmetry/$f/load" "$tmp/$f.fe" 1e-12 "$PRINT"
  kcompare "symmetry/$f/r" "$tmp/$f.fe" 1e-12 "r; $PRINT"
  kcompare "symmetry/$f/r2" "$tmp/$f.fe" 1e-12 "r; r; $PRINT"
done

# Dumps both ways (after one r: wraps the file did not give).
for f in symtest skew1; do
  "$TDS" -q "$tmp/$f.fe" -e "r() dump('$tmp/$f.tds.dmp')" || echo "FAIL symmetry/$f/dump: tds exited with an error"
  kcompare "symmetry/$f/tds-dump-in-evolver" "$tmp/$f.tds.dmp" 1e-12 \
    'printf "K0 %d %d %d %d\n", vertex_count, edge_count, facet_count, body_count; printf "K1 %.15g\n", total_energy;'
  evolver_dump "symmetry/$f" "$f.ev" "$tmp/$f.fe" "r"
  kcompare "symmetry/$f/evolver-dump-in-tds" "$tmp/$f.ev.dmp" 1e-12 "$PRINT"
done

# The film converged.
ev=$(evolver_run "$tmp/film.fe" 'g 10; r; g 200; hessian; hessian; hessian; printf "E1 %.17g\n", total_energy;')
"$TDS" -q "$tmp/film.fe" -e "
dofile('$ROOT/tests/evolver/compare.lua')
g(10) r() g(200) hessian() hessian() hessian()
same('symmetry/film/converged-energy', total_energy, $(echo "$ev" | grab E1), 1e-8)
same('symmetry/film/converged-area-exact', total_energy, 1.2, 1e-8)
same('symmetry/film/converged-volume', body[1].volume, 0.35, 1e-10)
local h, worst = 0.35 / 1.2, 0
for v in vertices() do worst = math.max(worst, math.abs(v.z - h)) end
report('symmetry/film/converged-flat', worst <= 1e-7, worst, '<= 1e-7')
report('symmetry/film/converged-pressure', math.abs(body[1].pressure) <= 1e-6, body[1].pressure, 0)
" 2>&1 || echo "FAIL symmetry/film/converged: tds exited with an error"

# Errors at the keyword.
err() { # NAME GROUP WANT: a copy of symtest.fe with GROUP
  sed "s/^SYMMETRY_GROUP \"torus\"/SYMMETRY_GROUP \"$2\"/" "$tmp/symtest.fe" > "$tmp/bad.fe"
  got=$("$TDS" -q "$tmp/bad.fe" -e '' 2>&1 < /dev/null)
  if [ "$got" = "$tmp/bad.fe:7: $3" ]; then echo "PASS symmetry/refused/$1"
  else echo "FAIL symmetry/refused/$1: '$got', want '$tmp/bad.fe:7: $3'"; fi
}
err unknown 'torrus' 'SYMMETRY_GROUP: unknown group "torrus" (Evolver'"'"'s built-in groups: torus, rotate, flip_rotate, cubocta, cubelat, xyz, genus2, dodecahedron, central_symmetry, screw_symmetry, quarter_turn)'
err genus2 'genus2' 'SYMMETRY_GROUP "genus2" is not supported yet (tds has the group "torus")'
