#!/bin/sh
# language.sh: the command language test suite, each file in lang/ run
# unchanged in tds and in Surface Evolver; the lines starting with K must
# agree (numbers to 1e-10 relative: they are printed with %.12g or less
# and involve no iteration, so only the last printed digit may differ).
# errors.cmd stops at a run-time error in both programs (tds: exit 1),
# undefined.cmd at a definition naming an unknown command;
# histogram.cmd's lines are the histograms' (bins and counts); model.cmd's
# also the messages of linear, lagrange 1 and M 1; view.cmd's those of
# the transforms toggle; elemvar.cmd runs element commands on a loop
# variable (foreach edge ee ... do delete ee), skipping what an earlier
# pass deleted. Files in data/ (views.fe) are used before the
# examples of that name.
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for run in flow:cube elements:cube elemvar:cube elements:catbody errors:cube undefined:cube histogram:cube define:cube matrix:cube facetedge:cube facetedge:catbody named:cube model:cube feattr:cube feattr:catbody view:views resize:cube defcmd:cube phview:phelanc; do
  c=${run%%:*} fe=${run#*:}
  src=$EXAMPLES/$fe.fe
  [ -f "$ROOT/tests/evolver/data/$fe.fe" ] && src=$ROOT/tests/evolver/data/$fe.fe
  evolver_run "$src" "$(cat "$ROOT/tests/evolver/lang/$c.cmd")" > "$tmp/ev.out"
  cp "$src" "$tmp/in.fe"
  cp "$ROOT/tests/evolver/lang/$c.cmd" "$tmp/c.cmd"
  (cd "$tmp" && "$TDS" -q in.fe -f c.cmd) > "$tmp/tds.out" 2> "$tmp/tds.err"
  rc=$?
  want=0
  msg=
  [ "$c" = errors ] && msg="c.cmd:4: division by zero"
  [ "$c" = undefined ] && msg="c.cmd:11: 'nosuchcmd' is not a command, variable or function"
  [ -n "$msg" ] && want=1
  if [ $rc -ne $want ]; then
    echo "FAIL language/$c-$fe: exit status $rc, expected $want: $(head -n 2 "$tmp/tds.err" | tr '\n' ' ')"
    continue
  fi
  if [ -n "$msg" ] && ! grep -qF "$msg" "$tmp/tds.err"; then
    echo "FAIL language/$c-$fe: expected '$msg', got: $(cat "$tmp/tds.err")"
    continue
  fi
  pat='^K'
  [ "$c" = histogram ] && pat='^ *[-.0-9e]+ %- +[-.0-9e]+ +%d+$|^No qualifying'
  [ "$c" = model ] && pat='^K|^Changing|^Model already|^Converting'
  [ "$c" = view ] || [ "$c" = phview ] && pat='^K|^Transform showing|^ +%d+$'
  "$TDS" -q -e "
dofile('$ROOT/tests/evolver/numcmp.lua')
local function grab(p) local t = {} for l in io.lines(p) do
  for alt in ('$pat'):gmatch('[^|]+') do if l:find(alt) then t[#t + 1] = l; break end end end return t end
numcmp('language/$c-$fe', grab('$tmp/ev.out'), grab('$tmp/tds.out'), 1e-10)"
done
