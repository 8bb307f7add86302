#!/bin/sh
# run.sh: export round trips. Each case script (tds) writes the surface
# in every format and variant plus the values tds reports; check.py reads
# the files back with meshio, VTK and its own readers and compares.
# Run from the project root with $TDS set (tests/run.sh does both).
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cases=""
for c in cube mound bubble random column; do
  if EXPORT_DIR=$dir "$TDS" -q "tests/export/$c.tds" > "$dir/$c.log" 2>&1; then
    cases="$cases $c"
  else
    echo "FAIL export/$c: $(tail -n 3 "$dir/$c.log" | tr '\n' ' ')"
  fi
done
[ -n "$cases" ] || exit 0
# shellcheck disable=SC2086
/usr/bin/python3 tests/export/check.py "$dir" $cases 2> "$dir/stderr" ||
  echo "FAIL export/check.py: exit status $? $(tail -n 3 "$dir/stderr" | tr '\n' ' ')"
