#!/bin/sh
# commands.sh: Evolver command files run unchanged in tds and in Surface
# Evolver (`tds FILE.fe -f CMDS` vs `evolver-nox-d -f CMDS FILE.fe`).
#
# * Every example datafile tds loads runs its read section at load with no
#   error (they define gogo & co.; nothing there is unsupported).
# * Each file's `gogo` runs; where it reaches a command tds does not have
#   (t, o, lagrange) the error must name that command and its
#   line in the datafile, as listed in UNSUPPORTED below.
# * Printed numbers are compared: counts exactly; energies, volumes and
#   pressures after iterating to 1e-3 relative, because `g` takes the same
#   number of steps but its line search differs in detail (the per-step
#   energies agree to about 1e-4 after a refinement and converge to the same
#   minimum, see converge.sh); numbers that involve no iteration (element
#   attributes, aggregates, formulas) to 1e-12.
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# -- every loadable example: the read section runs at load
for f in cube mound qmound cat catman catbody column quad octa sphere tankex; do
  if "$TDS" -q "$EXAMPLES/$f.fe" -e 'assert(true)' > "$tmp/out" 2>&1 && [ ! -s "$tmp/out" ]; then
    echo "PASS commands/read/$f"
  else
    echo "FAIL commands/read/$f: $(head -n 3 "$tmp/out" | tr '\n' ' ')"
  fi
done

# -- gogo: runs to the end, or stops at a command tds does not have (named)
UNSUPPORTED=""
for f in cube mound qmound cat catman catbody column quad octa sphere; do
  want=$(for u in $UNSUPPORTED; do [ "${u%%:*}" = "$f" ] && echo "${u#*:}"; done)
  printf 'gogo\n' > "$tmp/gogo.cmd"
  (cd "$tmp" && "$TDS" -q "$EXAMPLES/$f.fe" -f gogo.cmd) > "$tmp/out" 2>&1
  rc=$?
  if [ -z "$want" ]; then
    if [ $rc -eq 0 ]; then echo "PASS commands/gogo/$f"
    else echo "FAIL commands/gogo/$f: $(tail -n 2 "$tmp/out" | tr '\n' ' ')"; fi
  elif [ $rc -ne 0 ] && grep -q "^$EXAMPLES/$f.fe:[0-9]*: $want: not supported yet" "$tmp/out"; then
    echo "PASS commands/gogo/$f (stops at unsupported '$want')"
  else
    echo "FAIL commands/gogo/$f: expected '$f.fe:LINE: $want: not supported yet', got: $(tail -n 2 "$tmp/out" | tr '\n' ' ')"
  fi
done

# compare NAME FILE TOL COMMANDS: run COMMANDS in both programs; every line
# "K v1 v2 ..." that Evolver prints must be printed by tds with the same
# key and the same values (integers exactly, reals to TOL relative).
compare() {
  name=$1 fe=$2 tol=$3 cmds=$4
  ev=$(evolver_run "$fe" "$cmds")
  printf '%s\n' "$cmds" > "$tmp/c.cmd"
  cp "$fe" "$tmp/in.fe"
  (cd "$tmp" && "$TDS" -q in.fe -f c.cmd) > "$tmp/tds.out" 2> "$tmp/tds.err"
  rc=$?
  printf '%s\n' "$ev" | grep '^K[A-Za-z0-9_]* ' > "$tmp/ev.k"
  grep '^K[A-Za-z0-9_]* ' "$tmp/tds.out" > "$tmp/tds.k"
  if [ $rc -ne 0 ]; then
    echo "FAIL commands/$name: tds exit $rc: $(head -n 2 "$tmp/tds.err" | tr '\n' ' ')"
    return
  fi
  if [ ! -s "$tmp/ev.k" ]; then
    echo "FAIL commands/$name: Evolver printed no K lines"
    return
  fi
  "$TDS" -q -e "
local function lines(p) local t = {} for l in io.lines(p) do t[#t + 1] = l end return t end
local ev, td = lines('$tmp/ev.k'), lines('$tmp/tds.k')
local bad
if #ev ~= #td then bad = ('%d lines from Evolver, %d from tds'):format(#ev, #td) end
for i = 1, math.min(#ev, #td) do
  local a, b = {}, {}
  for w in ev[i]:gmatch('%S+') do a[#a + 1] = w end
  for w in td[i]:gmatch('%S+') do b[#b + 1] = w end
  if a[1] ~= b[1] or #a ~= #b then bad = bad or ('line %d: %s vs %s'):format(i, ev[i], td[i]) end
  for j = 2, math.min(#a, #b) do
    local x, y = tonumber(a[j]), tonumber(b[j])
    if not x or not y then
      if a[j] ~= b[j] then bad = bad or ('%s: %s vs %s'):format(a[1], a[j], b[j]) end
    elseif not a[j]:find('[.eE]') and not b[j]:find('[.eE]') then
      if x ~= y then bad = bad or ('%s: %s vs %s'):format(a[1], a[j], b[j]) end
    elseif math.abs(x - y) > $tol * math.max(1, math.abs(x)) then
      bad = bad or ('%s value %d: Evolver %s, tds %s (tolerance $tol)'):format(a[1], j - 1, a[j], b[j])
    end
  end
end
if bad then print('FAIL commands/$name: ' .. bad) else print('PASS commands/$name') end
"
}

# Whole gogo scripts that tds runs to the end, taking Evolver's steps
# (the datafile's default search): measured 5.7e-6 (sphere) and 7.3e-6
# (catman) apart, steps on converged surfaces deciding on the last bit
# (see evolver-search below), so 1e-4.
compare gogo-sphere "$EXAMPLES/sphere.fe" 1e-4 'gogo; printf "K %d %d %d %.15g\n", vertex_count, edge_count, facet_count, total_energy'
compare gogo-catman "$EXAMPLES/catman.fe" 1e-4 'gogo; printf "K %d %d %d %.15g\n", vertex_count, edge_count, facet_count, total_energy'
# The tutorial's first steps on cube.fe (tutorial.md section 1).
compare tutorial-cube "$EXAMPLES/cube.fe" 1e-3 'g 5; printf "K1 %.15g\n", total_energy
v
printf "K2 %.15g %.15g\n", body[1].volume, body[1].pressure
r
printf "K3 %d %d %d\n", vertex_count, edge_count, facet_count
g 10
printf "K4 %.15g %.15g\n", total_energy, body[1].volume'
# mound.fe's gogo up to its first hessian: re (a user command with a
# generator and where), r, g (tutorial.md section 2 counts).
compare tutorial-mound "$EXAMPLES/mound.fe" 1e-3 're; printf "K1 %d %d %d\n", vertex_count, edge_count, facet_count
g 5; r; g 5; r; g 100
printf "K2 %d %d %d %.15g %.15g\n", vertex_count, edge_count, facet_count, total_energy, body[1].volume
angle := 45; recalc; g 200
printf "K3 %.15g %.15g\n", total_energy, max(vertex, z)'
# column.fe's force commands after the evolution of its gogo without
# hessian: set vertex y ..., recalc, user variables, body attributes.
# The forces are differences of energies at a shape that is converged
# only to the line search's accuracy, hence 1e-2.
compare forces-column "$EXAMPLES/column.fe" 1e-2 'u; g 5; r; g 5; r; g 5
printf "K1 %.15g %.15g\n", total_energy, body[1].pressure
do_yforce; do_zforce
printf "K2 %.15g %.15g\n", yforce, zforce'
# The language without iteration: exact to 1e-12.
compare language-cube "$EXAMPLES/cube.fe" 1e-12 'printf "K1 %d %d %d %d\n", vertex_count, edge_count, facet_count, body_count
printf "K2 %.15g %.15g %.15g\n", sum(facet, area), max(edge, length), min(vertex, x+y+z)
printf "K3 %d %d\n", count(edge where length > 0.5, 1), count(vertex where z > 0.9, 1)
foreach vertex vv where vv.id <= 3 do printf "K4 %d %g %g %g\n", vv.id, vv.x, vv.y, vv.z
printf "K5 %.15g %.15g\n", body[1].volume, body[1].target
set body[1] target 2; printf "K6 %g\n", body[1].target
set facet tension 2 where id < 3; recalc; printf "K7 %.15g\n", total_energy
nn := 0; foreach facet ff do { if ff.tension > 1 then nn += 1 }; printf "K8 %d\n", nn
printf "K9 %.15g\n", avg(vertex, x^2 + y^2)
procedure pr(real aa) { printf "K10 %g\n", aa*2 }; pr(3.5)
function real cube3(real aa) { return aa^3 }; printf "K11 %g\n", cube3(3)
ii := 0; while ii < 10 do { ii += 1; if ii == 7 then break }; printf "K12 %d\n", ii
define arr real[3]; arr[1] := 2; arr[3] := arr[1]^3^2; printf "K13 %g %g\n", arr[3], -2^2
ss := sprintf "%d-%d", 3, 4; printf "K14 %s\n", ss
set vertex z z*2 where z > 0.5; recalc; printf "K15 %.15g %.15g\n", body[1].volume, max(vertex, z)
printf "K16 %d %d\n", sum(vertex where on_constraint 1, 1), sum(vertex where fixed, 1)
unset body[1] target; set body[1] pressure 1; printf "K17 %g\n", body[1].pressure'
# Sub-elements are oriented as Evolver orients them: a facet's edges as it
# traverses them (negative oid = reversed), a vertex's edges pointing away.
compare oriented-cube "$EXAMPLES/cube.fe" 1e-12 'foreach facet[1].edge ee do printf "K1 %d %d %d %g\n", ee.oid, ee.vertex[1].id, ee.vertex[2].id, ee.x
foreach facet[5].edge ee do printf "K2 %d %d %d %g %g\n", ee.oid, ee.vertex[1].id, ee.vertex[2].id, ee.y, ee.z
printf "K3 %d %d\n", facet[2].edge[3].vertex[2].id, edge[-4].vertex[1].id'
# sphere.fe's `section` (do/while, foreach over vertex[n].edge, break,
# element attributes) prints the same cross-section as Evolver.
printf 'section\n' > "$tmp/s.cmd"
cp "$EXAMPLES/sphere.fe" "$tmp/sphere.fe"
evolver_run "$EXAMPLES/sphere.fe" 'section' > "$tmp/ev.out"
(cd "$tmp" && "$TDS" -q sphere.fe -f s.cmd) > "$tmp/tds.out" 2>&1
"$TDS" -q -e "
dofile('$ROOT/tests/evolver/numcmp.lua')
local pat = '^ *%-?%d+%.%d+ +%-?%d+%.%d+ +%-?%d+%.%d+ *$'
numcmp('commands/section-sphere', lines_of('$tmp/ev.out', pat), lines_of('$tmp/tds.out', pat), 1e-12)"
# In the string model total_area is the total length (in the metric with
# METRIC), as in Evolver.
compare total-area-popstr "$EXAMPLES/popstr.fe" 1e-12 'printf "K %.15g %.15g\n", total_area, total_length'
compare total-area-metric "$EXAMPLES/metric.fe" 1e-12 'printf "K %.15g %.15g\n", total_area, total_length'
# Named quantities' attributes, and parameters assigned from commands.
compare quantity-qmound "$EXAMPLES/qmound.fe" 1e-12 'printf "K1 %.15g %.15g\n", vol.value, vol.target
angle := 60; printf "K2 %g\n", angle'
# list in Evolver's layout (exact text and numbers).
printf 'list vertex where id < 4\nlist edge where id < 4\nlist facet where id < 4\n' > "$tmp/l.cmd"
cp "$EXAMPLES/cube.fe" "$tmp/cube.fe"
evolver_run "$EXAMPLES/cube.fe" "$(cat "$tmp/l.cmd")" > "$tmp/ev.out"
(cd "$tmp" && "$TDS" -q cube.fe -f l.cmd) > "$tmp/tds.out" 2>&1
"$TDS" -q -e "
dofile('$ROOT/tests/evolver/numcmp.lua')
local pat = '^ *//? *[%dI]'
numcmp('commands/list-cube', lines_of('$tmp/ev.out', pat), lines_of('$tmp/tds.out', pat), 0)"
# evcmp NAME FILE EVOLVER_CMDS TDS_LUA TOL: run EVOLVER_CMDS in Evolver and
# the Lua TDS_LUA in tds (both end by printing $K) on FILE; the K lines
# must agree (numcmp.lua: integers exactly, reals to TOL relative).
evcmp() {
  evolver_run "$2" "$3; $K" | grep '^K ' > "$tmp/ev.k"
  "$TDS" -q "$2" -e "$4; evolver [[ $K ]]" 2>&1 | grep '^K ' > "$tmp/tds.k"
  "$TDS" -q -e "
dofile('$ROOT/tests/evolver/numcmp.lua')
numcmp('commands/$1', lines_of('$tmp/ev.k', '^K'), lines_of('$tmp/tds.k', '^K'), $5)"
}
# A datafile takes Evolver's line search, so tds takes Evolver's steps
# and each gogo ends on Evolver's energy: the counts exact, the energies
# measured 1e-12 apart and closer where no step starts on a converged
# surface (the same steps, summed in another order: cat, mound, qmound,
# catbody, quad, metric, popstr, slidestr, twointor, phelanc; cat's gogo
# pinches its neck in 120 steps, where any difference in a step would
# grow), so 1e-10. Where a step starts on a converged surface, whether a
# trial lowers the energy is decided by the last bit of the sums
# (doc/commands.md): cube (its fifth step: 8e-8 apart at the end) and
# column (5e-7), so 1e-5. (cat's gogo pops its neck: tests/evolver/topo.sh.)
K='printf "K %d %d %d %.15g\n", vertex_count, edge_count, facet_count, total_energy'
for f in cat mound qmound catbody quad metric popstr slidestr twointor phelanc; do
  evcmp "evolver-search/$f" "$EXAMPLES/$f.fe" gogo "pcall(gogo)" 1e-10
done
for f in cube column; do
  evcmp "gogo-compare/$f" "$EXAMPLES/$f.fe" gogo "pcall(gogo)" 1e-5
done
# The search after a step whose scale fell to 0 starts from 1e-6 of the
# limit, as Evolver's: cube.fe's g 12 (its last six steps at scale 0),
# then r and g 10, measured 1e-13 apart.
evcmp evolver-search/cube-restart "$EXAMPLES/cube.fe" "g 12; r; g 10" "g(12); r(); g(10)" 1e-10
# knotty.fe's gogo (g 50; U; g 50) from a length 2.7 off its target:
# measured 9e-9 apart (its long trials are projected exactly where
# Evolver's restoring moves are not known, doc/commands.md), so 1e-7.
K='printf "K %d %d %.15g\n", vertex_count, edge_count, total_energy'
evcmp evolver-search/knotty "$EXAMPLES/knotty.fe" gogo "gogo()" 1e-7
# tankex.fe, g 10; r; g 2000: tds ends where Evolver does (measured
# 1.1e-7 apart: over 2000 steps near a stall on a folded facet the
# rounding differences grow), so 1e-6; tds's own search (a .tds script's
# default) stalls 3e-4 higher (doc/commands.md), checked to fail here.
K='printf "K %.15g\n", total_energy'
evcmp evolver-search/tankex "$EXAMPLES/tankex.fe" "g 10; r; g 2000" "g(10); r(); g(2000)" 1e-6
evolver_run "$EXAMPLES/tankex.fe" "g 10; r; g 2000; $K" | grep '^K ' > "$tmp/ev.k"
"$TDS" -q "$EXAMPLES/tankex.fe" -e "tds.setting('evolver_line_search', false); g(10); r(); g(2000); evolver [[ $K ]]" 2>&1 | grep '^K ' > "$tmp/tds.k"
"$TDS" -q -e "
local e = tonumber(io.open('$tmp/ev.k'):read('a'):match('K (%S+)'))
local t = tonumber(io.open('$tmp/tds.k'):read('a'):match('K (%S+)'))
if t - e > 1e-4 then print('PASS commands/tds-search/tankex-differs')
else print(('FAIL commands/tds-search/tankex-differs: tds %.10g, Evolver %.10g'):format(t, e)) end"
# list with constraints and flags (mound.fe, after setting some).
cat > "$tmp/l2.cmd" <<'CMDS'
set vertex[1] fixed; set edge[1] fixed; set edge[2] no_refine; set edge[5] constraint 1; set edge[6] fixed; set edge[6] constraint 1; set edge[6] no_refine
list vertex where id < 4 or id > 14
list edge where id < 7 or id > 36
set facet[2] fixed; set facet[3] tension 2; set facet[4] color red; set facet[5] no_refine
list facet where id < 6
CMDS
cp "$EXAMPLES/mound.fe" "$tmp/mound.fe"
evolver_run "$EXAMPLES/mound.fe" "$(cat "$tmp/l2.cmd")" > "$tmp/ev.out"
(cd "$tmp" && "$TDS" -q mound.fe -f l2.cmd) > "$tmp/tds.out" 2>&1
"$TDS" -q -e "
dofile('$ROOT/tests/evolver/numcmp.lua')
local pat = '^ *//? *[%dI]'
numcmp('commands/list-mound', lines_of('$tmp/ev.out', pat), lines_of('$tmp/tds.out', pat), 0)"
