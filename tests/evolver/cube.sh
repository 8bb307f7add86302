#!/bin/sh
# cube.sh: the cube of volume 1 in tds and in Surface Evolver.
# Counts after load and after each r must be identical; gradient descent
# run until one step changes the energy by at most 1e-13 relative must
# reach Evolver's converged energy to 1e-8 (the discrete minimum is the
# same; 1e-8 allows for both runs stopping short of it on a slow tail),
# the volume stays at its target to 1e-9, and the pressure (a Lagrange
# multiplier, first order in the remaining error) agrees to 1e-6.
. "$(dirname "$0")/lib.sh"
FE=$EXAMPLES/cube.fe
LOOP='ii := 0; do { e0 := total_energy; g 1; ii := ii + 1 } while (abs(total_energy - e0) > 1e-13*abs(e0) and ii < 100000);'
COUNTS='printf "%d %d %d %d\n", vertex_count, edge_count, facet_count, body_count'
ev=$(evolver_run "$FE" "
printf \"C0 \"; $COUNTS; r; printf \"C1 \"; $COUNTS; r; printf \"C2 \"; $COUNTS;
$LOOP hessian_normal off; hessian; hessian;
printf \"E2 %.17g %.17g\\n\", total_energy, body[1].pressure;")
ev0=$(evolver_run "$FE" "$LOOP printf \"E0 %.17g %.17g\\n\", total_energy, body[1].pressure;")

"$TDS" -q "$ROOT/scripts/cube.tds" -e "
dofile('$ROOT/tests/evolver/compare.lua')
report('cube/counts-load', counts() == '$(echo "$ev" | grab C0)', counts(), '$(echo "$ev" | grab C0)')
converge()
local e, p = nums('$(echo "$ev0" | grab E0)')
same('cube/14-vertex/energy', total_energy, e, 1e-8)
same('cube/14-vertex/volume', body[1].volume, 1, 1e-9)
same('cube/14-vertex/pressure', body[1].pressure, p, 1e-6)
r()
report('cube/counts-r1', counts() == '$(echo "$ev" | grab C1)', counts(), '$(echo "$ev" | grab C1)')
r()
report('cube/counts-r2', counts() == '$(echo "$ev" | grab C2)', counts(), '$(echo "$ev" | grab C2)')
" || echo "FAIL cube/14-vertex: tds exited with an error"

# The twice-refined cube, refined before any iteration as in Evolver's run.
"$TDS" -q "$ROOT/scripts/cube.tds" -e "
dofile('$ROOT/tests/evolver/compare.lua')
r(); r()
converge()
local e, p = nums('$(echo "$ev" | grab E2)')
same('cube/r2/energy', total_energy, e, 1e-8)
same('cube/r2/volume', body[1].volume, 1, 1e-9)
same('cube/r2/pressure', body[1].pressure, p, 1e-6)
" || echo "FAIL cube/r2: tds exited with an error"
