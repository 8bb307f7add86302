#!/bin/sh
# foam3.sh: a periodic 3-D foam against Evolver, the bench's foam made
# smaller: 54 Voronoi cells of the body-centred cubic lattice in the unit
# torus (bench/foam3.lua: N = 3, every point moved by up to a tenth of the
# spacing, seed 2), TORUS_FILLED, every body holding its volume. That is
# 53 volume constraints, so the Gram system goes to LAPACK's Cholesky
# (fixq.c: 32 or more), the bodies' gradients through the facet entry map
# (fixq.h's emap), and each body's facets are lifted in the facet pass
# (eval.c's s_volume_lift). After r and 8 steps of g (Evolver's line
# search, a datafile's default) the energy, every body's volume and
# pressure agree with Evolver's to 1e-9 relative (numcmp.lua; they agree
# to 1e-12: the two programs take the same steps, rounding apart).
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
(cd "$ROOT/bench" && "$TDS" -q -e "N, AMP, SEED = 3, 0.1, 2; dofile('foam3.lua')") > "$tmp/foam.fe"
kcompare foam3/g8 "$tmp/foam.fe" 1e-9 'quiet on; r; g 8; printf "K %.15g\n", total_energy; foreach body bb do printf "K %d %.15g %.15g\n", bb.id, bb.volume, bb.pressure;'
