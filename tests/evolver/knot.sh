#!/bin/sh
# knot.sh: the knot energies, the string model's squared curvature and
# Hooke springs (knotty.fe's methods) against Surface Evolver.
#  - tests/evolver/knot/knots.fe (an irregular pentagon in space with one
#    quantity per method): every value to 1e-12 relative, at knot_power 2
#    and 3 (the same sums in another order);
#  - knotty.fe: load counts and energy, and the energy with each of its
#    set_* modes switched on (1e-12); the Lagrange multiplier of the held
#    length after one g step in the modes whose gradient Evolver computes
#    exactly (a projection of the whole gradient: 1e-10, measured 1e-15;
#    proj_knot_energy's gradient in Evolver is not its energy's, see
#    doc/string.md); the conducting knot relaxed to convergence (energy
#    1e-8 and multiplier 1e-6 relative: both programs stop on a slow tail,
#    measured 1e-9 and 1e-12); the Hooke spring
#    mode relaxed likewise (1e-8);
#  - a dump of knots.fe after some g, read by Evolver: tds's energy (1e-12).
. "$(dirname "$0")/lib.sh"
KF=$ROOT/tests/evolver/knot/knots.fe
QS='q_knot.value, q_edge.value, q_buck.value, q_proj.value, q_circle.value, q_sqcurve.value, q_hooke.value, q_hooke2.value, total_energy'
ev=$(evolver_run "$KF" "printf \"Q $(printf '%%.17g %.0s' 1 2 3 4 5 6 7 8 9)\n\", $QS; knot_power := 3; recalc; printf \"P %.17g %.17g %.17g %.17g %.17g\n\", q_knot.value, q_edge.value, q_buck.value, q_proj.value, q_circle.value")
q=$(echo "$ev" | grab Q)
p=$(echo "$ev" | grab P)
"$TDS" -q "$KF" -e "
dofile('$ROOT/tests/evolver/compare.lua')
local names = {'knot', 'edge', 'buck', 'proj', 'circle', 'sqcurve', 'hooke', 'hooke2'}
local want = {nums('$q')}
for i, n in ipairs(names) do same('knot/knots/' .. n, (tds.quantity_info('q_' .. n)), want[i], 1e-12) end
same('knot/knots/energy', total_energy, want[9], 1e-12)
evolver('knot_power := 3')
tds.recalc()
want = {nums('$p')}
for i = 1, 5 do same('knot/knots/power3-' .. names[i], (tds.quantity_info('q_' .. names[i])), want[i], 1e-12) end
" 2>&1 || echo "FAIL knot/knots: tds exited with an error"

KT=$EXAMPLES/knotty.fe
for mode in set_conduct set_insul set_buck set_proj set_circle set_bending set_hooke set_hooke2; do
  ev=$(evolver_run "$KT" "printf \"C %d %d %.17g\n\", vertex_count, edge_count, total_energy; $mode; recalc; printf \"E %.17g\n\", total_energy; g 1; printf \"P %.17g\n\", knot_length.pressure;")
  c=$(echo "$ev" | grab C)
  e=$(echo "$ev" | grab E)
  pr=$(echo "$ev" | grab P)
  "$TDS" -q "$KT" -e "
dofile('$ROOT/tests/evolver/compare.lua')
local nv, ne, e0 = nums('$c')
if '$mode' == 'set_conduct' then
  report('knot/knotty/counts', vertex_count == nv and edge_count == ne, vertex_count .. ' ' .. edge_count, nv .. ' ' .. ne)
  same('knot/knotty/energy', total_energy, e0, 1e-12)
end
evolver('$mode')
same('knot/knotty/$mode-energy', total_energy, $e, 1e-12)
local mode = '$mode'
if mode == 'set_conduct' or mode == 'set_insul' or mode == 'set_circle' or mode == 'set_bending' then
  g(1)
  local _, _, p = tds.quantity_info('knot_length')
  same('knot/knotty/$mode-multiplier', p, ${pr:-0/0}, 1e-10)
end
" 2>&1 || echo "FAIL knot/knotty/$mode: tds exited with an error"
done

LOOP='ii := 0; do { e0 := total_energy; g 1; ii := ii + 1 } while (abs(total_energy - e0) > 1e-13*abs(e0) and ii < 100000);'
ev=$(evolver_run "$KT" "$LOOP printf \"G %.17g %.17g\n\", total_energy, knot_length.pressure; hessian; hessian; hessian; printf \"H %.17g\n\", total_energy; set_hooke; $LOOP printf \"K %.17g\n\", total_energy")
g=$(echo "$ev" | grab G)
hh=$(echo "$ev" | grab H)
k=$(echo "$ev" | grab K)
"$TDS" -q "$KT" -e "
dofile('$ROOT/tests/evolver/compare.lua')
local ge, gp = nums('$g')
converge(1e-13, 100000)
local _, _, p = tds.quantity_info('knot_length')
same('knot/knotty/converged-energy', total_energy, ge, 1e-8)
same('knot/knotty/converged-multiplier', p, gp, 1e-6)
evolver('set_hooke')
converge(1e-13, 100000)
same('knot/knotty/hooke-converged-energy', total_energy, $k, 1e-8)
" 2>&1 || echo "FAIL knot/knotty/converged: tds exited with an error"

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
out=$("$TDS" -q "$KF" -e "g(10) dump('$tmp/d.fe') print(('T %.17g'):format(total_energy))" 2>&1)
t=$(echo "$out" | grab T)
ev=$(evolver_run "$tmp/d.fe" 'printf "E %.17g\n", total_energy')
"$TDS" -q -e "
dofile('$ROOT/tests/evolver/compare.lua')
same('knot/knots/dump-evolver-energy', $(echo "$ev" | grab E) + 0, tonumber('$t'), 1e-12)
" 2>&1 || echo "FAIL knot/knots/dump: $out"
