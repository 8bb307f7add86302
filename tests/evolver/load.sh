#!/bin/sh
# load.sh: Evolver's example datafiles loaded by tds and by Surface Evolver.
# After loading, the element counts must be identical and total_energy
# equal to 1e-12 relative. Evolver runs a datafile's read section while
# loading, tds keeps it unrun: for these files the read section only
# defines commands, which is checked by loading each file into Evolver
# once more without its read section (same counts and energy).
# The same for tests/datafile/good/features.fe (most supported datafile
# features in one file). And tests/datafile/good/lexical.fe, whose vertex
# coordinates exercise the lexical rules, must give Evolver's exactly.
. "$(dirname "$0")/lib.sh"
FILES="cube mound qmound cat catman catbody column quad octa sphere tankex"
PRINT='printf "C0 %d %d %d %d\n", vertex_count, edge_count, facet_count, body_count; printf "E0 %.17g\n", total_energy;'

# The file without its read section (the read keyword alone on a line).
strip_read() {
  awk 'tolower($0) ~ /^[ \t]*read[ \t]*(\/\/.*)?$/ { exit } { print }' "$1"
}

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for f in $FILES features; do
  fe=$EXAMPLES/$f.fe
  [ "$f" = features ] && fe=$ROOT/tests/datafile/good/features.fe
  ev=$(evolver_run "$fe" "$PRINT")
  strip_read "$fe" > "$tmp/$f.fe"
  ev0=$(evolver_run "$tmp/$f.fe" "$PRINT")
  c=$(echo "$ev" | grab C0)
  e=$(echo "$ev" | grab E0)
  if [ -n "$c" ] && [ "$c" = "$(echo "$ev0" | grab C0)" ] &&
     [ "$e" = "$(echo "$ev0" | grab E0)" ]; then
    echo "PASS load/$f/read-section-inert"
  else
    echo "FAIL load/$f/read-section-inert: Evolver with read section '$c' $e," \
         "without '$(echo "$ev0" | grab C0)' $(echo "$ev0" | grab E0)"
  fi
  "$TDS" -q "$fe" -e "
dofile('$ROOT/tests/evolver/compare.lua')
report('load/$f/counts', counts() == '$c', counts(), '$c')
same('load/$f/energy', total_energy, $e, 1e-12)
" 2>/dev/null || echo "FAIL load/$f: tds exited with an error: $("$TDS" -q "$fe" -e '' 2>&1 | tail -n 1)"
done

# Lexical rules: every coordinate as Evolver reads it.
lex=$ROOT/tests/datafile/good/lexical.fe
ev=$(evolver_run "$lex" 'foreach vertex vv do printf "V %d %.17g %.17g %.17g\n", vv.id, vv.x, vv.y, vv.z;
printf "P %.17g %.17g %.17g %.17g\n", cc, dd, ee, ff;')
want=$(echo "$ev" | grep '^[VP] ' | cut -d' ' -f2- | tr '\n' ';')
"$TDS" -q "$lex" -e "
dofile('$ROOT/tests/evolver/compare.lua')
local t = {}
for v in vertices() do t[#t + 1] = ('%d %.17g %.17g %.17g'):format(v.id, v.x, v.y, v.z) end
t[#t + 1] = ('%.17g %.17g %.17g %.17g'):format(cc, dd, ee, ff)
local got = table.concat(t, ';') .. ';'
report('load/lexical/values', got == '$want', got, '$want')
" 2>/dev/null || echo "FAIL load/lexical: tds exited with an error"
