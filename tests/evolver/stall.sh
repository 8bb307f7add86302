#!/bin/sh
# stall.sh: g's line search and its stall warning, against Surface Evolver
# on tankex.fe (a liquid in a cylindrical tank: gravity, contact energy,
# gap energy on a convex wall, one volume).
#
# 1. With tds.setting("evolver_line_search", true) the line search is
#    Evolver's (double or halve the last scale until a minimum is
#    bracketed, then the parabola's vertex): from Evolver's own
#    dumps of three evolved states (volume on target to 1e-14), tds's next
#    step chooses Evolver's scale (1e-6 relative: both compute the same
#    parabola from trial energies equal to rounding) and reaches its
#    energy to 1e-11 relative. One step only: earlier states (after 50
#    steps) have the volume 4e-10 off target, which Evolver restores by one
#    linear move and tds by projection, and a second step from the 213
#    state already chooses a scale 30% apart (energies 1e-7 apart), so the
#    whole trajectories are not expected to agree.
# 2. `g 10; r; g 2000` stalls in both programs on a facet squeezed flat
#    against the base (Evolver: "Zero area for facet", scale 0): tds says
#    so once, naming the facet and the remedies; the remedy it suggests
#    (u and V between runs of g) takes both programs well below where they
#    stalled (by more than 0.04, a hundred times the 5e-4 by which the two
#    stalled energies differ).
. "$(dirname "$0")/lib.sh"
FE=$EXAMPLES/tankex.fe
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cp "$FE" "$dir/tankex.fe"
for n in 213 600 1000; do
  printf 'g 10; r; g %s; dump "state.dmp"\nq\n' $n > "$dir/cmds"
  rm -f "$dir/state.dmp"
  (cd "$dir" && "$EVOLVER" -f cmds tankex.fe < /dev/null > /dev/null 2>&1)
  if [ ! -s "$dir/state.dmp" ]; then
    echo "FAIL stall/linesearch/$n: Evolver wrote no dump"
    continue
  fi
  ev=$(evolver_run "$dir/state.dmp" 'g 1; printf "S %.17g %.17g\n", scale, total_energy;')
  s1=$(echo "$ev" | grab S)
  "$TDS" -q "$dir/state.dmp" -e "
dofile('$ROOT/tests/evolver/compare.lua')
local sc, e = nums('$s1')
tds.setting('evolver_line_search', true)
g(1)
same('stall/linesearch/$n/scale', scale, sc, 1e-6)
same('stall/linesearch/$n/energy', total_energy, e, 1e-11)
" 2>/dev/null || echo "FAIL stall/linesearch/$n: tds exited with an error"
done

# 2. the stall, in both programs
ev=$(evolver_run "$FE" 'g 10; r; g 2000; printf "E %.17g %.17g\n", total_energy, scale;')
evstall=$(echo "$ev" | grab E)
evzero=$(echo "$ev" | grep -c 'Zero area for facet')
remedy='g 10; r; g 300; {u; V; g 100} 10'
ev=$(evolver_run "$FE" "$remedy; printf \"E %.17g\\n\", total_energy;")
evfixed=$(echo "$ev" | grab E)
out=$("$TDS" -q "$FE" -e "evolver 'g 10; r; g 2000'
print(('E %.17g %.17g'):format(total_energy, scale))" 2>&1)
n=$(echo "$out" | grep -c 'warning: g: a facet has degenerated')
f=$(echo "$out" | sed -n 's/^  worst facet \([0-9]*\): smallest angle.*/\1/p' | head -n 1)
"$TDS" -q "$FE" -e "
dofile('$ROOT/tests/evolver/compare.lua')
local evE, evS = nums('$evstall')
report('stall/tankex/evolver-stalls', $evzero > 0 and evS == 0, '', 'zero-area facet $evzero times, scale ' .. evS)
report('stall/tankex/warns-once', $n == 1, '$n warnings', 'one')
evolver 'g 10; r; g 2000'
local f = tonumber('$f')
-- the named facet is the flattest one: smallest angle below 1e-3 degrees
local worst, wa = nil, math.huge
for fa in facets() do
  local vs = fa.vertices
  local function ang(a, b, c)
    local u = {b.x - a.x, b.y - a.y, b.z - a.z}
    local w = {c.x - a.x, c.y - a.y, c.z - a.z}
    local d = u[1]*w[1] + u[2]*w[2] + u[3]*w[3]
    local cx = {u[2]*w[3]-u[3]*w[2], u[3]*w[1]-u[1]*w[3], u[1]*w[2]-u[2]*w[1]}
    return math.deg(math.atan(math.sqrt(cx[1]^2+cx[2]^2+cx[3]^2), d))
  end
  local m = math.min(ang(vs[1], vs[2], vs[3]), ang(vs[2], vs[3], vs[1]), ang(vs[3], vs[1], vs[2]))
  if m < wa then worst, wa = fa.id, m end
end
report('stall/tankex/names-flattest', f == worst and wa < 1e-3, tostring(f), 'facet ' .. tostring(worst) .. ' at ' .. wa .. ' degrees')
local stalled = total_energy
evolver 'g 10; r; g 300; {u; V; g 100} 10'
local fixed = tonumber('$evfixed')
report('stall/tankex/remedy', total_energy < stalled - 0.04 and total_energy < evE - 0.04,
       total_energy, 'below ' .. (math.min(stalled, evE) - 0.04) .. ' (Evolver with the remedy: ' .. fixed .. ')')
report('stall/tankex/evolver-remedy', fixed < evE - 0.04, fixed, 'below ' .. (evE - 0.04))
" 2>/dev/null || echo "FAIL stall/tankex: tds exited with an error"

# 3. The cube of volume 1 refined five times (24,576 facets): 400 steps of
#    g fold a facet flat (at about step 285) and g says so, once. With the
#    remedy it suggests for a fine mesh (conjugate gradient, u and V
#    between runs of g, then 20 steps) the area comes within the discretisation of the
#    sphere's, 4 pi (3/(4 pi))^(2/3) = 4.83598: the same remedy leaves the
#    cube refined four times 1.10e-3 above it, and the excess of an
#    inscribed mesh falls as the square of the edge length, so 2.8e-4 is
#    expected here; the test allows 4e-4 (the rest is the unconverged
#    tail), where the plain run stalls 0.37 above.
out=$("$TDS" -q "$ROOT/scripts/cube.tds" -e 'for i = 1, 5 do r() end g(400)' 2>&1)
n=$(echo "$out" | grep -c 'warning: g: a facet has degenerated')
if [ "$n" = 1 ]; then echo "PASS stall/cube/warns-once"; else echo "FAIL stall/cube/warns-once: $n warnings"; fi
"$TDS" -q "$ROOT/scripts/cube.tds" -e "
dofile('$ROOT/tests/evolver/compare.lua')
for i = 1, 5 do r() end
U()
evolver '{g 100; u; V} 3; g 20'
local S = 4 * math.pi * (3 / (4 * math.pi))^(2 / 3)
local ex = total_area - S
report('stall/cube/remedy-area', ex > 0 and ex < 4e-4, ('%.6g above the sphere'):format(ex), 'within 4e-4')
same('stall/cube/remedy-volume', body[1].volume, 1, 1e-9)
" 2>/dev/null | grep -v '^Conjugate' || echo "FAIL stall/cube: tds exited with an error"

# 4. No warning where nothing is wrong: the cube refined twice, 300 steps
#    with and without conjugate gradient, converges (the scale falls to 0
#    there too, with the force at rounding level).
for cg in "" "U()"; do
  out=$("$TDS" -q "$ROOT/scripts/cube.tds" -e "r() r() $cg g(300)" 2>&1)
  name=stall/cube/quiet-when-converged${cg:+-cg}
  if echo "$out" | grep -q warning; then echo "FAIL $name: $out"; else echo "PASS $name"; fi
done

# 5. check_increase (Evolver's toggle): a step that would raise the energy
#    is taken back and g stops. On cube.fe with the fixed scale 0.45 the
#    first step overshoots: both programs stop at once with the energy 6
#    of the start, exactly (the positions are restored, not recomputed).
#    With 0.3 both descend and stop on an increase at rounding level after
#    20-odd steps (the exact step differs with rounding), at energies equal
#    to 1e-11 relative. tds's positions after the undone step are those of
#    the last step done, bit for bit.
CUBE=$EXAMPLES/cube.fe
for sc in 0.45 0.3; do
  ev=$(evolver_run "$CUBE" "m $sc; check_increase on; g 30; printf \"E %.17g\\n\", total_energy;")
  e=$(echo "$ev" | grab E)
  warned=$(echo "$ev" | grep -c 'Motion would have increased energy')
  out=$("$TDS" -q "$CUBE" -e "evolver 'm $sc; check_increase on; g 30'
print(('E %.17g %d'):format(total_energy, iteration_counter))" 2>&1)
  set -- $(echo "$out" | grab E)
  tw=$(echo "$out" | grep -c 'motion would have increased the energy')
  "$TDS" -q -e "
dofile('$ROOT/tests/evolver/compare.lua')
report('stall/check_increase/$sc/stops', $tw == 1 and $warned == 1 and $2 < 30, '$tw warning, $2 steps', 'Evolver $warned warning, fewer than 30 steps')
same('stall/check_increase/$sc/energy', $1, nums('$e'), 1e-11)
" || echo "FAIL stall/check_increase/$sc: tds exited with an error"
done
POS='for v in vertices() do io.write(("P %.17g %.17g %.17g\n"):format(v.x, v.y, v.z)) end'
a=$("$TDS" -q "$CUBE" -e "m(0.3) check_increase(true) g(30) print('N ' .. iteration_counter) $POS" 2>/dev/null)
n=$(echo "$a" | grab N)
b=$("$TDS" -q "$CUBE" -e "m(0.3) g($n) print('N ' .. iteration_counter) $POS" 2>/dev/null)
if [ -n "$n" ] && [ "$n" -lt 30 ] && [ "$(echo "$a" | grep -c "^P ")" -gt 8 ] && [ "$(echo "$a" | grep "^P ")" = "$(echo "$b" | grep "^P ")" ]; then
  echo "PASS stall/check_increase/restores-exactly"
else
  echo "FAIL stall/check_increase/restores-exactly: positions after check_increase stopped at step $n differ from $n plain steps"
fi

# 6. Evolver's line search from a state off its volume target (tankex.fe
#    with the target 0.666 where the volume is 2/3), fixed scales 0.05 and
#    0.1: each trial adds the restoring motion to the projected force,
#    whose multipliers are the pressures (a restoring solve once
#    overwrote them, so the move was not tangent to the volume: energies
#    1.6e-3 and 5.6e-3 from Evolver's), and restores the volume as Evolver
#    does, leaving it off target by Evolver's amount. Energy and volume
#    equal Evolver's to 1e-12 (measured: to the printed digit).
sed 's/volume 0.6 /volume 0.666 /' "$FE" > "$dir/t666.fe"
for sc in 0.05 0.1; do
  ev=$(evolver_run "$dir/t666.fe" "m $sc; g 1; printf \"E %.17g %.17g\\n\", total_energy, body[1].volume;")
  e=$(echo "$ev" | grab E)
  "$TDS" -q "$dir/t666.fe" -e "
dofile('$ROOT/tests/evolver/compare.lua')
local e, v = nums('$e')
tds.setting('evolver_line_search', true)
m($sc) g(1)
same('stall/offtarget/$sc', total_energy, e, 1e-12)
same('stall/offtarget/$sc/volume', body[1].volume, v, 1e-12)
" 2>/dev/null | grep -v '^Fixed' || echo "FAIL stall/offtarget/$sc: tds exited with an error"
done
