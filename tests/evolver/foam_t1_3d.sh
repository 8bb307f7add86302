#!/bin/sh
# foam_t1_3d.sh: the foam T1 in 3-D as Evolver does it, on the five-bubble
# cluster of data/cluster5.fe (A, B, C around the short triple edge 1, D
# and E beyond its ends; volumes held but E's). Both programs: refine the
# other edges (Evolver's `refine edges`: each edge splits its facets in
# two, in id order), g 10, pop_edge_to_tri edge[1], then iterate until a
# step changes the energy by at most 1e-14 relative; then pop_tri_to_edge
# on the new triangle and iterate again.
# * after the refine and g 10: the energy, 1e-10 (the same mesh and steps);
# * after the pop: the counts exactly, the new corners (a third of the way
#   from the edge's midpoint to the midpoints of the far ends of their
#   pairs of triple edges) through sums of coordinates, and the energy
#   (every film between two triple edges at one end follows the corner
#   counterclockwise after the other about the edge's direction, as
#   Evolver's), 1e-10; converged: energy and volumes 1e-10 (measured
#   1e-13 apart);
# * pop_tri_to_edge: the counts exactly, the new edge's ends (the
#   triangle collapsed from its first edge, one end a quarter of the way
#   to the far ends on the side its normal points to, the other opposite;
#   the films beside it follow the other end) through sums of coordinates
#   and the energy just after it, 1e-6 (they start from the relaxed
#   state, whose places agree to about 1e-8; tds's former rule put the
#   ends 0.24 apart instead of 0.1, moving the sums by 1e-2), and the
#   converged energy 1e-10.
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
LOOP='ii := 0; do { e0 := total_energy; g 1; ii := ii + 1 } while (abs(total_energy - e0) > 1e-14*abs(e0) and ii < 20000);'
E='printf "K %d %d %d %.15g\n", vertex_count, edge_count, facet_count, total_energy;'
V='printf "K %.15g %.15g %.15g %.15g %.15g\n", total_energy, body[1].volume, body[2].volume, body[4].volume, body[5].volume;'
S='printf "K %.15g %.15g %.15g %.15g\n", sum(vertex, x), sum(vertex, y), sum(vertex, z), sum(vertex, x*x + 2*y*y + 3*z*z);'
PRE="foreach body bb where id < 5 do set bb target bb.volume;
refine edge where id != 1; g 10; $E
pop_edge_to_tri edge[1]; recalc; $E $S
$LOOP $V"
TRI='foreach facet ff where ff.frontbody + ff.backbody == 9 and ff.frontbody * ff.backbody == 20 do pop_tri_to_edge ff;'
kcompare foam_t1_3d/cluster5 "$ROOT/tests/evolver/data/cluster5.fe" 1e-10 "$PRE $TRI
printf \"K %d %d %d\n\", vertex_count, edge_count, facet_count;
$LOOP $V"
kcompare foam_t1_3d/cluster5-tri-edge "$ROOT/tests/evolver/data/cluster5.fe" 1e-6 "$PRE $TRI recalc; $E $S"
