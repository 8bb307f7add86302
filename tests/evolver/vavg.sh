#!/bin/sh
# vavg.sh: V, rawv, rawestv and vertex_average as Evolver 2.70 does them
# (src/topo_vavg_ev.c). From identical states, every vertex ends where
# Evolver puts it, to 1e-12 (relative, absolute below 1: the same
# arithmetic up to summation order; constrained vertices are projected by
# Newton steps to the constraint tolerance on both sides, which lands on
# the same point to rounding since both start from the same tangent move).
#  - seeded random patches written by vavg_gen.lua (inputs nobody tuned):
#    closed fans, some folded over (the order in which V sums the facet
#    normals), border fans, triple lines, contact lines on a plane and a
#    sphere, a star lying on the sphere with its facets;
#  - Evolver's example datafiles refined, evolved, and every vertex not on
#    constraint 1 moved by a deterministic pseudo-random offset (Evolver
#    dumps that state; both load the dump): a body (cube), fixed wires
#    (cat), a contact line (mound), triple lines (octa after o and g),
#    parametric boundaries with a body (catbody), curved walls (tankex,
#    sphere), a torus foam (phelanc).
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
P='foreach vertex vv do printf "K %d %.17g %.17g %.17g\n", id, x, y, z'
for c in "stars 1 0.3" "stars 2 1.0" "fans 3" "triples 4" "contact 5"; do
  set -- $c
  name=$1-$2
  "$TDS" -q -e "dofile('$ROOT/tests/evolver/vavg_gen.lua'); $1('$tmp/$name.fe', $2, ${3:-0})" ||
    { echo "FAIL vavg/$name: the generator failed"; continue; }
  for cmd in V rawv rawestv; do
    kcompare "vavg/$name/$cmd" "$tmp/$name.fe" 1e-12 "$cmd; $P"
  done
  kcompare "vavg/$name/V-twice" "$tmp/$name.fe" 1e-12 "V; V; $P"
  kcompare "vavg/$name/vertex_average" "$tmp/$name.fe" 1e-12 \
    "vertex_average vertex where id < 120; raw_vertex_average vertex where id > 200; $P"
done

PERTURB='foreach vertex vv where not fixed and not on_constraint 1 and not on_constraint 2 do { vv.x := vv.x + AMP*sin(vv.id*12.9898); vv.y := vv.y + AMP*sin(vv.id*78.233); vv.z := vv.z + AMP*sin(vv.id*37.719) };'
for c in "cube:r; g 5; r:0.05" "cat:r; g 5; r:0.05" "mound:r; g 5; r:0.03" \
         "octa:o; g 20; r:0.03" "catbody:r; g 5:0.02" "tankex:r; g 5; r:0.02" \
         "sphere:r; g 5; r:0.02" "phelanc:r:0.01"; do
  f=${c%%:*} rest=${c#*:}
  prep=${rest%%:*} amp=${rest#*:}
  name=$f-$amp
  evolver_dump vavg "$name" "$EXAMPLES/$f.fe" "$prep; $(echo "$PERTURB" | sed "s/AMP/$amp/g")"
  [ -s "$tmp/$name.dmp" ] || continue
  kcompare "vavg/$name/V" "$tmp/$name.dmp" 1e-12 "V; $P"
  kcompare "vavg/$name/rawv-rawestv" "$tmp/$name.dmp" 1e-12 "rawv; rawestv; $P"
done
