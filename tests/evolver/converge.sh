#!/bin/sh
# converge.sh: Evolver's example datafiles, loaded unchanged in tds and in
# Surface Evolver, refined the same way and iterated with g until one step
# changes the energy by at most 1e-13 relative, must reach the same
# minimum: energies within 1e-8 relative (both programs stop on a slow
# tail, within about 1e-10 of the minimum on these meshes; Evolver's value
# is polished with `hessian_normal off; hessian` when that helps), volumes
# at their targets to 1e-9, and pressures within 1e-5: a multiplier is
# first order in the position error, and positions stopped by an energy
# criterion of 1e-13 are only converged to about its square root.
. "$(dirname "$0")/lib.sh"

LOOP='ii := 0; do { e0 := total_energy; g 1; ii := ii + 1 } while (abs(total_energy - e0) > 1e-13*abs(e0) and ii < 300000);'
POLISH='printf "G %.17g %.17g\n", total_energy, (body_count > 0 ? body[1].pressure : 0); hessian_normal off; hessian; hessian; printf "H %.17g %.17g\n", total_energy, (body_count > 0 ? body[1].pressure : 0);'
VOLQ='printf "G %.17g %.17g\n", total_energy, vol.pressure; hessian_normal off; hessian; hessian; printf "H %.17g %.17g\n", total_energy, vol.pressure;'

# case NAME FILE EVOLVER_SETUP TDS_SETUP [EVOLVER_REPORT]
# The report prints "G energy pressure" after g and "H ..." after hessian.
case_() {
  name=$1 fe=$EXAMPLES/$2
  ev=$(evolver_run "$fe" "$3 $LOOP ${5:-$POLISH}")
  g=$(echo "$ev" | grab G)
  h=$(echo "$ev" | grab H)
  "$TDS" -q "$fe" -e "
dofile('$ROOT/tests/evolver/compare.lua')
$4
converge(1e-13, 300000)
local ge, gp = nums('$g')
local he, hp = nums('$h')
-- the polished value, unless the Newton step went astray (energy rose)
local e, p = ge, gp
if he and he <= ge then e, p = he, hp end
same('converge/$name/energy', total_energy, e, 1e-8)
if body_count > 0 and body[1].target then
  same('converge/$name/volume', body[1].volume, body[1].target, 1e-9)
  same('converge/$name/pressure', body[1].pressure, p, 1e-5)
elseif tds.quantity_info('vol') then -- qmound: the volume is a quantity
  local value, target, pressure = tds.quantity_info('vol')
  same('converge/$name/volume', value, target, 1e-9)
  same('converge/$name/pressure', pressure, p, 1e-5)
end
" 2>/dev/null || echo "FAIL converge/$name: tds exited with an error"
}

REFINE_LINE='refine(edges(function(e) return e:on_constraint(1) end))'
case_ quad quad.fe "r; r; r;" "r() r() r()"
case_ mound-90 mound.fe "re; r; r;" "$REFINE_LINE r() r()"
case_ mound-45 mound.fe "angle := 45; re; r; r;" "angle = 45 $REFINE_LINE r() r()"
case_ mound-G1 mound.fe "G 1; re; r; r;" "G(1) $REFINE_LINE r() r()"
case_ qmound qmound.fe "re; r; r;" "$REFINE_LINE r() r()" "$VOLQ"
case_ sphere sphere.fe "r; r;" "r() r()"
