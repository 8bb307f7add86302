#!/bin/sh
# topo2.sh: renumber_all, vertex_merge and rebody against Surface Evolver
# 2.70 from identical states. These commands are exact (no iteration):
# counts, ids, the elements' references and coordinates must be equal
# (coordinates to 1e-12, the rest exactly).
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
DATA=$ROOT/tests/evolver/data

mkdump() { evolver_dump topo2 "$@"; }
run() {
  fe=$2
  case $fe in /*) ;; *) fe=$tmp/$fe.dmp ;; esac
  kcompare "topo2/$1" "$fe" "$3" "$4"
}

# Everything about the elements, by id.
ALL='recalc; printf "K %d %d %d %d %d %d %d %.15g\n", vertex_count, edge_count, facet_count, body_count, max(vertex, id), max(edge, id), max(facet, id), total_area; foreach vertex vv do printf "KV %d %.15g %.15g %.15g\n", vv.id, vv.x, vv.y, vv.z; foreach edge ee do printf "KE %d %d %d\n", ee.id, ee.vertex[1].id, ee.vertex[2].id; foreach facet ff do printf "KF %d %d %d %d\n", ff.id, ff.edge[1].oid, ff.edge[2].oid, ff.edge[3].oid'
mkdump catg "$EXAMPLES/cat.fe" 'r; u; g 120'
# after dissolving (holes in every kind) and after t (collapses)
run renumber/dissolve "$EXAMPLES/cube.fe" 1e-12 "r; dissolve facet where id % 5 == 2; dissolve edges; dissolve vertices; renumber_all; $ALL"
# (after t, the edges compared through the facets' corners: when two edges
# of a collapsed facet merge, tds and Evolver keep different ones)
VF='recalc; printf "K %d %d %d %d %d %.15g\n", vertex_count, facet_count, max(vertex, id), max(edge, id), max(facet, id), total_area; foreach vertex vv do printf "KV %d %.15g %.15g %.15g\n", vv.id, vv.x, vv.y, vv.z; foreach facet ff do printf "KF %d %d %d %d\n", ff.id, ff.vertex[1].id, ff.vertex[2].id, ff.vertex[3].id'
run renumber/t catg 1e-12 "t 0.05; renumber_all; $VF"
# vertex_merge: two triangles joined at a corner; refused across an edge
run vertex_merge "$DATA/twotri.fe" 1e-12 "vertex_merge(1,4); $ALL"
# rebody: two cubes in one body become two bodies, the second with its
# volume as target
run rebody "$DATA/onebody.fe" 1e-12 'rebody; printf "K %d %.15g %.15g %.15g %.15g\n", body_count, body[1].volume, body[1].target, body[2].volume, body[2].target; foreach facet ff do printf "KF %d %d\n", ff.id, ff.frontbody'
