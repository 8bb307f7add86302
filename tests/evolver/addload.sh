#!/bin/sh
# addload.sh: Evolver's addload and replace_load, the same command files
# run by Surface Evolver and tds. The lines starting with K must agree:
# counts, ids of the renumbered elements and their `original`, exactly;
# energies, volumes and coordinates to 1e-10 relative (printed with %.12g
# and computed without iteration, so only the last digit may differ).
# drops.fe's read section addloads itself three times (as Evolver's
# addload_example.fe does, with the contact angle a parameter; the example
# itself, with an edge attribute, is in xattr.sh) and moves each copy;
# cube.cmd addloads cube.fe into itself, replace_loads mound.fe and adds
# cube.fe again.
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cp "$EXAMPLES/cube.fe" "$EXAMPLES/mound.fe" "$ROOT/tests/evolver/data/drops.fe" "$tmp/"
for run in drops:drops cube:cube; do
  c=${run%%:*} fe=${run#*:}
  cp "$ROOT/tests/evolver/addload/$c.cmd" "$tmp/c.cmd"
  key=""
  if [ -n "$TDS_EVOLVER_CACHE" ]; then
    mkdir -p "$TDS_EVOLVER_CACHE"
    key=$TDS_EVOLVER_CACHE/$(cat "$tmp"/*.fe "$tmp/c.cmd" | md5sum | cut -d' ' -f1)-$fe
  fi
  if [ -n "$key" ] && [ -f "$key" ]; then
    cp "$key" "$tmp/ev.out"
  else
    (cd "$tmp" && printf 'read "c.cmd"\nq\n' > run.cmd && "$EVOLVER" -f run.cmd "$fe.fe" < /dev/null > ev.out 2>&1)
    [ -n "$key" ] && cp "$tmp/ev.out" "$key"
  fi
  (cd "$tmp" && "$TDS" -q "$fe.fe" -f c.cmd) > "$tmp/tds.out" 2> "$tmp/tds.err"
  rc=$?
  if [ $rc -ne 0 ]; then
    echo "FAIL addload/$c: exit status $rc: $(head -n 2 "$tmp/tds.err" | tr '\n' ' ')"
    continue
  fi
  "$TDS" -q -e "
dofile('$ROOT/tests/evolver/numcmp.lua')
numcmp('addload/$c', lines_of('$tmp/ev.out', '^K'), lines_of('$tmp/tds.out', '^K'), 1e-10)"
done
