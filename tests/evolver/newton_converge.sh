#!/bin/sh
# newton_converge.sh: Newton steps reach the minima. Each surface is
# refined as in converge.sh, evolved by a few g steps in tds, then
# `hessian` with hessian_normal off (every coordinate moves, so the limit
# is the discrete minimum itself, not the best shape with the vertices'
# tangential positions frozen) is repeated at most 6 times. The number of
# g steps first: 100 for the cube and quad; 3000 for the mound and qmound,
# whose full Hessian is indefinite in tangential directions (index 9 to
# 36 after 100 to 1000 steps: Newton then leaves for a saddle, in Evolver
# too) until gradient descent has brought the contact line near its
# basin (index <= 1). The energy
# must reach Evolver's minimum (g to a 1e-13 stall, polished by Newton
# steps: the same Evolver runs as converge.sh, so the cache serves both)
# to 1e-10 relative, where gradient descent alone only gets to about
# 1e-8 in thousands of steps. Also the volume or quantity must be at its
# target to 1e-10. The sphere (a convex constraint with gap energy): Evolver
# cannot make the Hessian of the gap energy, so its reference is its g
# stall, which converge.sh finds within 1e-10 of the minimum; tds's
# Newton steps must agree to 1e-10 and not be above it.
. "$(dirname "$0")/lib.sh"

LOOP='ii := 0; do { e0 := total_energy; g 1; ii := ii + 1 } while (abs(total_energy - e0) > 1e-13*abs(e0) and ii < 300000);'
POLISH='printf "G %.17g %.17g\n", total_energy, (body_count > 0 ? body[1].pressure : 0); hessian_normal off; hessian; hessian; printf "H %.17g %.17g\n", total_energy, (body_count > 0 ? body[1].pressure : 0);'
VOLQ='printf "G %.17g %.17g\n", total_energy, vol.pressure; hessian_normal off; hessian; hessian; printf "H %.17g %.17g\n", total_energy, vol.pressure;'

# case NAME FILE EVOLVER_SETUP TDS_SETUP G_STEPS [EVOLVER_REPORT]
case_() {
  name=$1 fe=$EXAMPLES/$2
  ev=$(evolver_run "$fe" "$3 $LOOP ${6:-$POLISH}")
  g=$(echo "$ev" | grab G)
  h=$(echo "$ev" | grab H)
  "$TDS" -q "$fe" -e "
dofile('$ROOT/tests/evolver/compare.lua')
$4
g($5)
tds.hessian_setting('hessian_normal', false)
local ge = nums('$g')
local he = nums('$h')
local want = (he and he <= ge) and he or ge
local steps = 0
for i = 1, 6 do
  hessian()
  steps = i
  if near(total_energy, want, 1e-11) then break end
end
same('newton_converge/$name/energy', total_energy, want, 1e-10)
if not he then
  report('newton_converge/$name/not-above', total_energy <= want * (1 + 1e-14), total_energy, want)
end
if body_count > 0 and body[1].target then
  same('newton_converge/$name/volume', body[1].volume, body[1].target, 1e-10)
elseif tds.quantity_info('vol') then
  local value, target = tds.quantity_info('vol')
  same('newton_converge/$name/volume', value, target, 1e-10)
end
" 2>&1 | grep -v '^ *1\. area\|^WARNING\|^Gravity' || true
}

REFINE_LINE='refine(edges(function(e) return e:on_constraint(1) end))'
case_ cube cube.fe "r; r;" "r() r()" 100
case_ sphere sphere.fe "r; r;" "r() r()" 100
case_ quad quad.fe "r; r; r;" "r() r() r()" 100
case_ mound-90 mound.fe "re; r; r;" "$REFINE_LINE r() r()" 3000
case_ qmound qmound.fe "re; r; r;" "$REFINE_LINE r() r()" 3000 "$VOLQ"
