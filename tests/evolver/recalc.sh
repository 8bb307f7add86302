#!/bin/sh
# recalc.sh: parameters are live. cat.fe's rings are widened and moved
# after load; Evolver and tds run the same commands and must agree on the
# energy and positions at every stage, to 1e-12 relative: with a fixed
# scale (m 0.05) a g step is the same arithmetic in both programs (seen to
# agree to 15 digits), so only rounding separates them. What is checked:
# recalc re-places the ring vertices; g after a change steps from the
# positions as they were and then re-places (Evolver's order); r makes new
# ring vertices from the old positions, then re-places; setting p1 moves a
# boundary vertex at once. (Evolver updates total_energy between command
# lines, so the assignment and the printf are on separate lines.)
. "$(dirname "$0")/lib.sh"
fe=$EXAMPLES/cat.fe
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
ev=$(evolver_run "$fe" '
RMAX := 1.7; recalc; printf "A %.17g\n", total_energy;
m 0.05; g 5; printf "B %.17g\n", total_energy;
r; RMAX := 1.8; g 1; printf "C %.17g\n", total_energy;
ZMAX := 0.9; r; printf "D %.17g %.17g %.17g\n", total_energy, vertex[1].x, vertex[1].z;
vertex[1].p1 := 0.3
printf "E %.17g %.17g %.17g\n", total_energy, vertex[1].x, vertex[1].y;')
"$TDS" -q "$fe" -e "
dofile('$ROOT/tests/evolver/compare.lua')
local function check(name, want, ...)
  local w = { nums(want) }
  if #w == 0 then report('recalc/' .. name, false, 'nothing', 'Evolver output') return end
  for i, got in ipairs({ ... }) do same('recalc/' .. name .. '/' .. i, got, w[i], 1e-12) end
end
local before = vertex[1].x
RMAX = 1.7
report('recalc/assignment-moves-nothing', vertex[1].x == before, vertex[1].x, before)
recalc()
check('A', '$(echo "$ev" | grab A)', total_energy)
tds.scale(0.05) g(5)
check('B', '$(echo "$ev" | grab B)', total_energy)
r() RMAX = 1.8 g(1)
check('C', '$(echo "$ev" | grab C)', total_energy)
ZMAX = 0.9 r()
check('D', '$(echo "$ev" | grab D)', total_energy, vertex[1].x, vertex[1].z)
vertex[1].p1 = 0.3
check('E', '$(echo "$ev" | grab E)', total_energy, vertex[1].x, vertex[1].y)
" > "$tmp/out" 2>&1 || echo "FAIL recalc: tds exited with an error: $(tail -n 1 "$tmp/out")"
cat "$tmp/out"

# A boundary formula that is not finite at the new parameter value: recalc
# and g refuse, naming the vertex, and nothing moves.
"$TDS" -q -e "
dofile('$ROOT/tests/evolver/compare.lua')
parameter { R = 1 }
boundary(1, { parameters = 1, x = 'sqrt(R) * cos(p1)', y = 'sqrt(R) * sin(p1)', z = '0' })
vertices { {0, boundary = 1, fixed = true}, {2, boundary = 1, fixed = true}, {4, boundary = 1, fixed = true}, {0, 0, 1} }
edges { {1, 2}, {2, 3}, {3, 1}, {1, 4}, {2, 4}, {3, 4} }
faces { {1, 5, -4}, {2, 6, -5}, {3, 4, -6} }
local x, e = vertex[1].x, total_energy
R = -1
local ok, msg = pcall(recalc)
report('recalc/refuses-nonfinite', not ok and msg:find('vertex 1 cannot be placed', 1, true) ~= nil
  and vertex[1].x == x and total_energy == e, tostring(msg), 'an error naming vertex 1, surface unchanged')
ok, msg = pcall(g, 1)
report('recalc/g-refuses-nonfinite', not ok and vertex[1].x == x and total_energy == e,
  tostring(msg), 'an error, surface unchanged')
R = 4
recalc()
same('recalc/after-refusal', vertex[1].x, 2, 1e-15)
" 2>&1 || echo "FAIL recalc/refusals: tds exited with an error"
