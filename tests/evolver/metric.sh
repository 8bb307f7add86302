#!/bin/sh
# metric.sh: the string model in a Riemannian metric (METRIC, metric.fe)
# against Surface Evolver: load energy and an edge's metric length
# (1e-12: Evolver's 2-point Gauss rule, the same sums); one g step at
# Evolver's scale (m) gives Evolver's energy (1e-12: the same gradient;
# the two programs' line searches pick different scales); after gogo
# (g 5; r; g 5; r; g 5; r; g 5) and g to convergence both reach the same
# loop around the catenoid's throat (1e-8: both stop on a slow tail,
# measured 3e-11), the same counts; three hessian steps from there reach
# Evolver's (1e-9, measured 3e-10: Evolver's hessian stops that close);
# a dump after r and g read by Evolver has tds's energy (1e-12); bad
# METRIC input stops at its line.
. "$(dirname "$0")/lib.sh"
MF=$EXAMPLES/metric.fe
LOOP='ii := 0; do { e0 := total_energy; g 1; ii := ii + 1 } while (abs(total_energy - e0) > 1e-13*abs(e0) and ii < 100000);'
ev=$(evolver_run "$MF" "printf \"A %.17g %.17g\n\", total_energy, edge[1].length; g 1; printf \"S %.17g %.17g\n\", total_energy, scale; gogo; $LOOP printf \"G %.17g %d %d\n\", total_energy, vertex_count, edge_count; hessian; hessian; hessian; printf \"H %.17g\n\", total_energy")
a=$(echo "$ev" | grab A)
sc=$(echo "$ev" | grab S)
g=$(echo "$ev" | grab G)
h=$(echo "$ev" | grab H)
"$TDS" -q "$MF" -e "
dofile('$ROOT/tests/evolver/compare.lua')
local e0, l1 = nums('$a')
same('metric/load-energy', total_energy, e0, 1e-12)
same('metric/edge-length', edge[1].length, l1, 1e-12)
local es, s = nums('$sc')
evolver('m ' .. ('%.17g'):format(s))
g(1)
same('metric/step-energy', total_energy, es, 1e-12)
" 2>&1 || echo "FAIL metric/load: tds exited with an error"
"$TDS" -q "$MF" -e "
dofile('$ROOT/tests/evolver/compare.lua')
local ge, nv, ne = nums('$g')
evolver('gogo')
converge(1e-13, 100000)
same('metric/converged-energy', total_energy, ge, 1e-8)
report('metric/converged-counts', vertex_count == nv and edge_count == ne, vertex_count .. ' ' .. edge_count, nv .. ' ' .. ne)
for i = 1, 3 do evolver('hessian') end
same('metric/hessian-energy', total_energy, $h, 1e-9)
" 2>&1 || echo "FAIL metric/converged: tds exited with an error"

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
out=$("$TDS" -q "$MF" -e "r() g(3) dump('$tmp/d.fe') print(('T %.17g'):format(total_energy))" 2>&1)
t=$(echo "$out" | grab T)
ev=$(evolver_run "$tmp/d.fe" 'printf "E %.17g\n", total_energy')
"$TDS" -q "$tmp/d.fe" -e "
dofile('$ROOT/tests/evolver/compare.lua')
same('metric/dump-evolver-energy', $(echo "$ev" | grab E) + 0, tonumber('$t'), 1e-12)
same('metric/dump-tds-energy', total_energy, tonumber('$t'), 1e-12)
" 2>&1 || echo "FAIL metric/dump: $out"

# Bad input: the line and what is wrong, exit status 1.
printf 'METRIC\n1 0 0\n0 1 0\n0 0 1\nvertices\n1 0 0 0\n' > "$tmp/b1.fe"
printf 'STRING\nSPACE_DIMENSION 2\nMETRIC\n1 0\n0 x+\nvertices\n1 0 0\n' > "$tmp/b2.fe"
printf 'STRING\nSPACE_DIMENSION 2\nMETRIC\n1 0 0 1\nMETRIC 1 0 0 1\nvertices\n1 0 0\n' > "$tmp/b3.fe"
for spec in "b1:1: METRIC on a soapfilm surface is not supported yet (the string model has it: give STRING and SPACE_DIMENSION before METRIC)" \
            "b2:5: METRIC component 2,2: expression 'x+': unexpected end of expression at column 3" \
            "b3:5: METRIC given twice"; do
  f=${spec%%:*}
  want="$tmp/$f.fe:${spec#*:}"
  got=$("$TDS" -q "$tmp/$f.fe" -e '' 2>&1 < /dev/null)
  status=$?
  if [ "$status" -eq 1 ] && [ "$got" = "$want" ]; then echo "PASS metric/bad-$f"
  else echo "FAIL metric/bad-$f: status $status, '$got', want '$want'"; fi
done
