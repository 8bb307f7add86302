#!/bin/sh
# multiplicate.sh: Evolver's shipped multiplicate.cmd (a datafile of the
# surface copied by every view transform, written with printf) run by
# Surface Evolver and tds on data/views.fe: with the datafile's view
# transforms, and after transform_expr "a" (the identity and the first
# generator, listed in that order by both). The element sections of the
# written files (from "Vertices" on: coordinates with %f, ids) must be the
# same text; the top sections differ (each program's dump header).
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cp "$ROOT/tests/evolver/data/views.fe" "$EXAMPLES/multiplicate.cmd" "$tmp/"
for case in file:'' expr:'transform_expr "a"'; do
  name=${case%%:*} pre=${case#*:}
  printf '%s\nread "multiplicate.cmd"\nmultiplicate >>> "ev.fe"\nq\n' "$pre" > "$tmp/ev.cmd"
  printf '%s\nread "multiplicate.cmd"\nmultiplicate >>> "tds.fe"\n' "$pre" > "$tmp/tds.cmd"
  (cd "$tmp" && rm -f ev.fe tds.fe && "$EVOLVER" -f ev.cmd views.fe < /dev/null > /dev/null 2>&1)
  if ! (cd "$tmp" && "$TDS" -q views.fe -f tds.cmd > tds.out 2>&1); then
    echo "FAIL multiplicate/$name: tds failed: $(tail -n 2 "$tmp/tds.out" | tr '\n' ' ')"
    continue
  fi
  sed -n '/^Vertices/,$p' "$tmp/ev.fe" > "$tmp/ev.el"
  sed -n '/^Vertices/,$p' "$tmp/tds.fe" > "$tmp/tds.el"
  if [ ! -s "$tmp/ev.el" ]; then
    echo "FAIL multiplicate/$name: Evolver wrote no elements"
  elif cmp -s "$tmp/ev.el" "$tmp/tds.el"; then
    echo "PASS multiplicate/$name"
  else
    echo "FAIL multiplicate/$name: the element sections differ: $(diff "$tmp/ev.el" "$tmp/tds.el" | head -n 4 | tr '\n' ' ')"
  fi
done
