#!/bin/sh
# topo.sh: the mesh-maintenance commands (t w l K n delete edgeswap) against
# Surface Evolver from identical states. Evolver evolves an example and
# dumps it; both programs load that dump and run the same commands.
# * After each command the counts must be equal exactly and the area
#   (recomputed: `recalc`) to 1e-12: the commands are deterministic given
#   the state, so the same edges must go and the same vertices be placed.
#   Only states with no deleted elements are compared for commands that
#   visit in id order after deletions (Evolver reuses freed ids, tds keeps
#   them dead), and K only once (a second K differs by a few splits).
# * From such a state both iterate until a step changes the energy by at
#   most 1e-13 relative; the minima must agree to 1e-8 (converge.sh).
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# dump NAME FE CMDS: Evolver evolves FE with CMDS and dumps NAME.dmp.
mkdump() { evolver_dump topo "$@"; }

# run NAME DUMP TOL CMDS: CMDS (printing K lines) in both from DUMP.
run() {
  dmp=$tmp/$2.dmp
  case $2 in /*) dmp=$2 ;; esac
  kcompare "topo/$1" "$dmp" "$3" "$4"
}

P='recalc; printf "K %d %d %d %d %.15g\n", vertex_count, edge_count, facet_count, body_count, total_energy'
LOOP='ii := 0; do { e0 := total_energy; g 1; ii := ii + 1 } while (abs(total_energy - e0) > 1e-13*abs(e0) and ii < 100000);'
C="$LOOP printf \"K %d %d %d %.15g\n\", vertex_count, edge_count, facet_count, total_energy"

mkdump catg "$EXAMPLES/cat.fe" 'r; u; g 120'
run cat/t catg 1e-12 "$P; t 0.05; $P"
run cat/delete-edge catg 1e-12 "delete edge where length < 0.1; $P; delete edge[3]; $P"
run cat/delete-facet catg 1e-12 "delete facet where area < 0.02; $P"
run cat/w catg 1e-12 "w 0.01; $P; areaweed 0.03; $P"
run cat/l catg 1e-12 "l 0.3; $P; edge_divide 0.2; $P"
run cat/t-l catg 1e-12 "t 0.05; $P; l 0.3; $P"
run cat/K catg 1e-12 "l 0.3; K 0.5; $P"
run cat/n catg 1e-12 "n 0.3; $P; notch 0.1; $P"
run cat/edgeswap catg 1e-12 "edgeswap edge where id < 80; $P; edgeswap edge[7]; $P"

mkdump moundg "$EXAMPLES/mound.fe" 're; g 5; r; g 5; r; g 20'
run mound/t moundg 1e-12 "t 0.115; $P"
run mound/l moundg 1e-12 "l 0.12; $P"
run mound/K moundg 1e-12 "K 0.6; $P"
run mound/w moundg 1e-12 "w 0.0063; $P"
run mound/n moundg 1e-12 "n 0.1; $P; n 0.05; $P"
run mound/l-converge moundg 1e-8 "l 0.12; $C"
run mound/t-converge moundg 1e-8 "t 0.115; $C"

mkdump qmoundg "$EXAMPLES/qmound.fe" 're; g 5; r; g 5; r; g 20'
run qmound/t qmoundg 1e-12 "t 0.117; $P"
run qmound/w qmoundg 1e-12 "w 0.006; $P"
run qmound/l-t qmoundg 1e-12 "l 0.12; $P; t 0.05; $P"

mkdump octag "$EXAMPLES/octa.fe" 'g 5; r; g 5'
run octa/t octag 1e-12 "t 1.1; $P"
run octa/l octag 1e-12 "l 1.2; $P"

# The catenoid tutorial from the datafile: the neck pinches (t), pops (o)
# and the two caps converge to the inscribed 12-gons, area 6*RMAX^2.
run cat/tutorial-converge "$EXAMPLES/cat.fe" 1e-8 "r; u; g 120; t 0.05; o; g 5; $C"

# dissolve and reverse_orientation on the cube: counts, and volumes and
# energies unchanged by reversing (1e-12; `g` after it would compare line
# searches, not the reversal).
V='recalc; printf "K %d %d %d %.15g %.15g\n", vertex_count, edge_count, facet_count, total_energy, body[1].volume'
run cube/dissolve "$EXAMPLES/cube.fe" 1e-12 "dissolve facet[1]; dissolve edges; dissolve vertices; $P; dissolve facet where id < 5; dissolve edge; dissolve vertex; $P"
run cube/reverse "$EXAMPLES/cube.fe" 1e-12 "r; reverse_orientation facet where id < 20; reverse_orientation edge where id < 30; $V"
# new_vertex, new_edge, new_facet, new_body: the ids they return.
run cube/new "$EXAMPLES/cube.fe" 0 'aa := new_vertex(2,2,2); bb := new_vertex(3,2,2); cc := new_vertex(2,3,2); e1 := new_edge(aa,bb); e2 := new_edge(bb,cc); e3 := new_edge(cc,aa); ff := new_facet(e1,e2,e3); bd := new_body; printf "K %d %d %d %d %d %d %d %d\n", aa, cc, e1, e3, ff, bd, vertex_count, facet_count'
