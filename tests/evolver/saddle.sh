#!/bin/sh
# saddle.sh: stability and the way off a saddle, against Evolver from its
# dumps.
# catman.fe (the manual's "saddle point due to triangulation
# arrangement"): after `g; u; r; g 50` the film is near a saddle in
# tangential directions. With hessian_normal off both programs must count
# the same negative eigenvalues (eigenprobe 0), find the two lowest
# eigenvalues (ritz(-1,2)) to 1e-8 relative, and `saddle` must lower the
# energy; then g 300 and three Newton steps must bring both to the same
# lower minimum, to 1e-10 relative (Newton converges quadratically there;
# the line searches of saddle and g differ between the programs, so the
# states in between are not compared), where the Hessian is positive
# definite (0 negative eigenvalues in both).
# cat.fe (radius 1.5089 at half-height 1: the critical separation)
# after `r; u; g 20` and three Newton steps sits on the unstable
# catenoid: both programs must count exactly one negative eigenvalue, and
# saddle must go downhill from it.
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
vals() { grep -E '^ +[0-9]+\. +-?[0-9][0-9.]*(e[-+]?[0-9]+)? *$' | awk '{print $2}' | tr '\n' ' '; }
counts() { grep '^Eigencounts' | sed -n "${1}p" | tr -dc '0-9 ' | tr -s ' ' | sed 's/^ //; s/ $//'; }

ev=$(evolver_run "$EXAMPLES/catman.fe" "g; u; r; g 50
dump \"$tmp/catman.dmp\"
hessian_normal off
printf \"E0 %.17g\\n\", total_energy
eigenprobe 0
ritz(-1,2)
saddle
printf \"S %.17g\\n\", total_energy
g 300
hessian
hessian
hessian
printf \"F %.17g\\n\", total_energy
eigenprobe 0")
e0=$(echo "$ev" | grab E0) s=$(echo "$ev" | grab S) f=$(echo "$ev" | grab F)
c0=$(echo "$ev" | counts 1) c1=$(echo "$ev" | counts 3) low=$(echo "$ev" | vals)
"$TDS" -q "$tmp/catman.dmp" -e "
dofile('$ROOT/tests/evolver/compare.lua')
tds.hessian_setting('hessian_normal', false)
local e0 = total_energy
same('saddle/catman/start', e0, $e0, 1e-12)
local b, z, a = tds.eigenprobe(0)
report('saddle/catman/eigenprobe', ('%d %d %d'):format(b, z, a) == '$c0' and b > 0, ('%d %d %d'):format(b, z, a), '$c0')
local v = tds.ritz(-1, 2)
local w = { nums('$low') }
report('saddle/catman/ritz', #w == 2 and near(v[1], w[1], 1e-8) and near(v[2], w[2], 1e-8),
       table.concat(v, ' '), '$low')
local lowest, moved = saddle()
report('saddle/catman/downhill', moved and total_energy < e0 and $s < e0, total_energy, $s)
g(300)
for i = 1, 3 do hessian() end
same('saddle/catman/minimum', total_energy, $f, 1e-10)
b, z, a = tds.eigenprobe(0)
report('saddle/catman/stable', ('%d %d %d'):format(b, z, a) == '$c1' and b == 0, ('%d %d %d'):format(b, z, a), '$c1')
" 2>&1 | grep -v '^ *1\. area\|^Eigencounts\|^Lowest\|^stepsize\|^Gravity\|^ *[0-9]*\.   \|^Iterations' \
  || echo "FAIL saddle/catman: tds exited with an error"

# hessian_seek at that saddle, every coordinate free (index 15): a plain
# Newton step may go uphill there; hessian_seek must not.
"$TDS" -q "$tmp/catman.dmp" -e "
dofile('$ROOT/tests/evolver/compare.lua')
tds.hessian_setting('hessian_normal', false)
local e0 = total_energy
local e, t, index = tds.hessian_seek()
report('saddle/catman/seek-downhill', index > 0 and e <= e0, e, '<= ' .. e0)
" 2>&1 | grep -v '^Gravity' || echo "FAIL saddle/catman/seek-downhill: tds exited with an error"

ev=$(evolver_run "$EXAMPLES/cat.fe" "r; u; g 20; hessian; hessian; hessian
dump \"$tmp/cat.dmp\"
printf \"E0 %.17g\\n\", total_energy
eigenprobe 0
saddle
printf \"S %.17g\\n\", total_energy")
e0=$(echo "$ev" | grab E0) s=$(echo "$ev" | grab S) c0=$(echo "$ev" | counts 1)
"$TDS" -q "$tmp/cat.dmp" -e "
dofile('$ROOT/tests/evolver/compare.lua')
local e0 = total_energy
same('saddle/cat/start', e0, $e0, 1e-12)
local b, z, a = tds.eigenprobe(0)
report('saddle/cat/one-negative', ('%d %d %d'):format(b, z, a) == '$c0' and b == 1, ('%d %d %d'):format(b, z, a), '$c0')
local lowest, moved = saddle()
report('saddle/cat/downhill', lowest < 0 and moved and total_energy < e0 and $s < e0, total_energy, $s)
" 2>&1 | grep -v '^ *1\. area\|^Eigencounts\|^Lowest\|^stepsize\|^Gravity' \
  || echo "FAIL saddle/cat: tds exited with an error"
