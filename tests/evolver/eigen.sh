#!/bin/sh
# eigen.sh: the eigenvalue tutorial (Evolver's html/eigentut.htm) in tds
# and in Evolver. square.fe (a flat square of side pi with fixed sides,
# reconstructed from the tutorial) refined twice: ritz(0,10) with the
# identity metric, with linear_metric at linear_metric_mix 0, 0.5 and 1,
# and the counts of eigenprobe 0 with hessian_normal off (50 zero
# eigenvalues: in-plane motions do not change a flat film's area).
# Eigenvalues agree with Evolver's to 1e-9 relative (Evolver prints 13-15
# digits of values converged to about 1e-13); one more anchor is exact:
# the lowest eigenvalue of the twice-refined square with the identity
# metric is 2 - sqrt(2) (the tutorial's 0.585786437626905) to 1e-12.
# The cube (eigentut: `r; r; g 5; eigenprobe 1`, from Evolver's dump of
# that state) must count 18 eigenvalues below 1 as the tutorial says.
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
SQ=$ROOT/tests/evolver/data/square.fe
ev=$(evolver_run "$SQ" 'r; r; ritz(0,10); linear_metric; linear_metric_mix := 0; ritz(0,10);
linear_metric_mix := 0.5; ritz(0,10); linear_metric_mix := 1; ritz(0,10);
linear_metric; hessian_normal off; eigenprobe 0')
# the eigenvalue lines, in order, and the Eigencounts lines
echo "$ev" | grep -E '^ +[0-9]+\. +-?[0-9][0-9.]*(e[-+]?[0-9]+)? *$' | awk '{print $2}' > "$tmp/ev.vals"
echo "$ev" | grep '^Eigencounts' | tr -dc '0-9 \n' | tr -s ' ' > "$tmp/ev.counts"
"$TDS" -q "$SQ" -e "
dofile('$ROOT/tests/evolver/compare.lua')
local want, counts = {}, {}
for l in io.lines('$tmp/ev.vals') do want[#want + 1] = tonumber(l) end
for l in io.lines('$tmp/ev.counts') do counts[#counts + 1] = l:gsub('^ +', ''):gsub(' +$', '') end
r() r()
local got = {}
local function run(name)
  local vals, b, e, a = tds.ritz(0, 10)
  local k = #got
  for i = 1, #vals do got[#got + 1] = vals[i] end
  local worst = 0
  for i = 1, 10 do
    local w = want[k + i]
    worst = math.max(worst, w and math.abs((got[k + i] or math.huge) - w) / math.max(1, math.abs(w)) or math.huge)
  end
  report('eigen/square/' .. name, #vals == 10 and worst <= 1e-9,
         table.concat(vals, ' ', 1, 3) .. ' ... worst ' .. worst, 'Evolver to 1e-9')
  return vals, ('%d %d %d'):format(b, e, a)
end
local v, c = run('identity')
same('eigen/square/lowest-exact', v[1], 2 - math.sqrt(2), 1e-12)
report('eigen/square/counts', c == counts[1], c, counts[1])
tds.hessian_setting('linear_metric', true)
for _, mix in ipairs { 0, 0.5, 1 } do
  tds.hessian_setting('linear_metric_mix', mix)
  run('linear-metric-mix-' .. mix)
end
tds.hessian_setting('linear_metric', false)
tds.hessian_setting('hessian_normal', false)
local b, e, a = tds.eigenprobe(0)
local c0 = ('%d %d %d'):format(b, e, a)
report('eigen/square/normal-off-counts', c0 == counts[#counts] and e == 50, c0, counts[#counts])
" 2>&1 | grep -v '^Eigencounts\|^ *[0-9]*\.  \|^Iterations' || echo "FAIL eigen/square: tds exited with an error"

# the cube of the tutorial: Evolver's state after r; r; g 5
# eigenprobe(c, n), inverse iteration towards the eigenvalue nearest c,
# from the same state: the converged value (Evolver's last "k  ev = ..."
# line) agrees to 1e-9 relative (both converge to about 1e-13; the starts
# differ, so the iteration counts do), with the identity and the linear
# metric; with a limit of 3 iterations both print the lines of iterations
# 0 and 3 (the values there depend on the start vector).
ev=$(evolver_run "$EXAMPLES/cube.fe" "r; r; g 5; dump \"$tmp/cube.dmp\"; eigenprobe 1;
eigenprobe(1, 20); eigenprobe(0.3, 100); eigenprobe(0.3, 3); linear_metric; eigenprobe(0.3, 100)")
counts=$(echo "$ev" | grep '^Eigencounts' | head -n 1 | tr -dc '0-9 ' | tr -s ' ' | sed 's/^ //; s/ $//')
# per eigenprobe(c, n): the last ev value and the iteration numbers printed
echo "$ev" | awk '/^Eigencounts/ { if (n++ > 1) print last, its; its = ""; last = "" }
  / ev = / { last = $4; its = its $1 "," } END { print last, its }' > "$tmp/invit"
"$TDS" -q "$tmp/cube.dmp" -e "
dofile('$ROOT/tests/evolver/compare.lua')
local b, e, a = tds.eigenprobe(1)
local c = ('%d %d %d'):format(b, e, a)
report('eigen/cube/eigenprobe-1', c == '$counts' and b == 18, c, '$counts (tutorial: 18 0 175)')
local want = {}
for l in io.lines('$tmp/invit') do
  local v, its = l:match('^(%S+) (%S*)')
  want[#want + 1] = { v = tonumber(v), its = its }
end
local function probe(c, n)
  local b, e, a, v = tds.eigenprobe(c, n)
  return v
end
local v = probe(1, 20)
same('eigen/cube/invit-1', v, want[1].v, 1e-9)
same('eigen/cube/invit-last-eigenvalue', tds.hessian_setting('last_eigenvalue'), v, 0)
local r = tds.ritz(1, 1)
same('eigen/cube/invit-ritz', v, r[1], 1e-10)
v = probe(0.3, 100)
same('eigen/cube/invit-0.3', v, want[2].v, 1e-9)
tds.hessian_setting('linear_metric', true)
v = probe(0.3, 100)
same('eigen/cube/invit-linear-metric', v, want[4].v, 1e-9)
" 2>&1 | grep -v '^Eigencounts\|^Gravity\|ev = \|^ *[0-9]*\.  \|^Iterations\|^Linear' || echo "FAIL eigen/cube: tds exited with an error"
its=$("$TDS" -q "$tmp/cube.dmp" -e "tds.quiet(false) eigenprobe(0.3, 3)" 2>&1 | awk '/ ev = /{ printf "%s,", $1 }')
want=$(sed -n 3p "$tmp/invit" | cut -d' ' -f2)
if [ "$its" = "$want" ] && [ "$its" = "0,3," ]; then echo "PASS eigen/cube/invit-limit"
else echo "FAIL eigen/cube/invit-limit: iterations printed $its, Evolver $want"; fi

# eigenneg, eigenzero, eigenpos: the counts of the last hessian,
# hessian_seek, eigenprobe or ritz (0 before any), the same commands from
# the tutorial cube's state in both programs; integers, equal exactly
# (hessian's are at its start, where Evolver counts them; hessian_seek
# starts where hessian took the surface)
cmds='print eigenneg; eigenprobe 1; print eigenneg; print eigenzero; print eigenpos;
ritz(0.5, 3); print eigenneg; print eigenpos; eigenprobe(0.3, 5); print eigenneg;
hessian; print eigenneg; print eigenzero; print eigenpos; hessian_seek; print eigenpos'
ints() { grep -E '^ +-?[0-9]+$' | tr -s ' \n' ' ' | sed 's/^ //; s/ $//'; }
want=$(evolver_run "$tmp/cube.dmp" "$cmds" | ints)
got=$(printf '%s\n' "$cmds" | "$TDS" -q "$tmp/cube.dmp" -f /dev/stdin 2>&1 | ints)
if [ -n "$want" ] && [ "$got" = "$want" ]; then echo "PASS eigen/cube/eigencounts"
else echo "FAIL eigen/cube/eigencounts: tds '$got', Evolver '$want'"; fi
