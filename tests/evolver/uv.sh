#!/bin/sh
# uv.sh: u as Evolver does it. From identical states (Evolver's example
# datafiles refined and evolved, every vertex off the base moved by a
# deterministic pseudo-random offset of amplitude A, dumped by Evolver),
# three successive `u` flip the same number of edges as Evolver's three
# `u` (one pass each, flipping where the opposite angles' cosines sum
# below -5e-4), and the energy after them is Evolver's to 1e-12 relative
# (u moves no vertex: the same triangulation gives the same area up to
# summation order). Then `u{delaunay = true}` (tds's repeat-until-Delaunay
# option) leaves nothing for a further u to flip.
. "$(dirname "$0")/lib.sh"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
PERTURB='foreach vertex vv where not fixed and not on_constraint 1 do { vv.x := vv.x + AMP*sin(vv.id*12.9898); vv.y := vv.y + AMP*sin(vv.id*78.233); vv.z := vv.z + AMP*sin(vv.id*37.719) };'
for c in cube:0.01 cube:0.05 cat:0.05 cat:0.1 mound:0.01 mound:0.03; do
  f=${c%%:*} amp=${c#*:}
  name=$f-$amp
  cp "$EXAMPLES/$f.fe" "$dir/in.fe"
  printf 'r; g 5; r; r; %s dump "state.dmp"\nq\n' "$(echo "$PERTURB" | sed "s/AMP/$amp/g")" > "$dir/cmds"
  rm -f "$dir/state.dmp"
  (cd "$dir" && "$EVOLVER" -f cmds in.fe < /dev/null > /dev/null 2>&1)
  if [ ! -s "$dir/state.dmp" ]; then
    echo "FAIL uv/$name: Evolver wrote no dump"
    continue
  fi
  ev=$(evolver_run "$dir/state.dmp" 'u; u; u; printf "E %.17g\n", total_energy;')
  counts=$(echo "$ev" | sed -n 's/^Edges switched in equiangulation: //p' | tr '\n' ' ')
  e=$(echo "$ev" | grab E)
  "$TDS" -q "$dir/state.dmp" -e "
dofile('$ROOT/tests/evolver/compare.lua')
local n = {}
for i = 1, 3 do n[i] = tds.equiangulate() end
local got = table.concat(n, ' ')
report('uv/$name/u-counts', got .. ' ' == '$counts', got, '$counts')
same('uv/$name/u-energy', total_energy, nums('$e'), 1e-12)
u{delaunay = true}
report('uv/$name/delaunay-complete', tds.equiangulate() == 0, 'flips left', 'none')
" 2>/dev/null || echo "FAIL uv/$name: tds exited with an error"
done
