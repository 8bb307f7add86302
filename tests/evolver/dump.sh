#!/bin/sh
# dump.sh: datafiles written by tds, read by Surface Evolver and by tds.
# For each example: tds loads it and dumps it; Evolver loading the dump
# must find the same element counts and total_energy (1e-12 relative) as
# Evolver loading the original, and tds loading its own dump must find its
# own counts and energy again. The other way round, tds must read the
# dumps Evolver writes (view_matrix, *_predicted, forward declarations,
# lagrange_multiplier, original ...) to Evolver's counts and energy.
. "$(dirname "$0")/lib.sh"
FILES="cube mound qmound cat catman catbody column quad octa sphere tankex"
PRINT='printf "C0 %d %d %d %d\n", vertex_count, edge_count, facet_count, body_count; printf "E0 %.17g\n", total_energy;'

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for f in $FILES; do
  fe=$EXAMPLES/$f.fe
  ev=$(evolver_run "$fe" "$PRINT dump \"$tmp/ev_$f.dmp\";")
  c=$(echo "$ev" | grab C0)
  e=$(echo "$ev" | grab E0)

  # tds writes the dump; Evolver reads it.
  out=$("$TDS" -q "$fe" -e "
dofile('$ROOT/tests/evolver/compare.lua')
local ok, msg = dump('$tmp/$f.dmp')
if not ok then error(msg) end
print(('T0 %s %.17g'):format(counts(), total_energy))" 2>&1)
  if [ ! -s "$tmp/$f.dmp" ]; then
    echo "FAIL dump/$f: tds wrote no dump: $(echo "$out" | tail -n 1)"
    continue
  fi
  evd=$(evolver_run "$tmp/$f.dmp" "$PRINT")
  if echo "$evd" | grep -q 'ERROR'; then
    echo "FAIL dump/$f/evolver-reads: $(echo "$evd" | grep -m1 -A1 'ERROR' | tr '\n' ' ')"
  else
    echo "PASS dump/$f/evolver-reads"
  fi
  "$TDS" -q "$ROOT/tests/evolver/compare.lua" -e "
report('dump/$f/evolver-counts', '$(echo "$evd" | grab C0)' == '$c', '$(echo "$evd" | grab C0)', '$c')
same('dump/$f/evolver-energy', tonumber('$(echo "$evd" | grab E0)') or 0/0, $e, 1e-12)"

  # tds reads its own dump back.
  t=$(echo "$out" | grab T0)
  tc=$(echo "$t" | cut -d' ' -f1-4)
  te=$(echo "$t" | cut -d' ' -f5)
  "$TDS" -q "$tmp/$f.dmp" -e "
dofile('$ROOT/tests/evolver/compare.lua')
report('dump/$f/tds-counts', counts() == '$tc', counts(), '$tc')
same('dump/$f/tds-energy', total_energy, $te, 1e-12)
" 2>/dev/null || echo "FAIL dump/$f/tds-reads: $("$TDS" -q "$tmp/$f.dmp" -e '' 2>&1 | tail -n 1)"

  # tds reads Evolver's dump.
  "$TDS" -q "$tmp/ev_$f.dmp" -e "
dofile('$ROOT/tests/evolver/compare.lua')
report('dump/$f/evolver-dump-counts', counts() == '$c', counts(), '$c')
same('dump/$f/evolver-dump-energy', total_energy, $e, 1e-12)
" 2>/dev/null || echo "FAIL dump/$f/evolver-dump: $("$TDS" -q "$tmp/ev_$f.dmp" -e '' 2>&1 | tail -n 1)"

  # A dump Evolver writes after evolving carries state lines (TOTAL_TIME,
  # SCALE, ...): tds reads it to Evolver's counts and energy. 1e-11: the
  # dump rounds coordinates to 15 digits, which moves the energy by ~1e-14.
  evg=$(evolver_run "$fe" "g 2; $PRINT dump \"$tmp/evg_$f.dmp\";")
  "$TDS" -q "$tmp/evg_$f.dmp" -e "
dofile('$ROOT/tests/evolver/compare.lua')
report('dump/$f/evolved-dump-counts', counts() == '$(echo "$evg" | grab C0)', counts(), '$(echo "$evg" | grab C0)')
same('dump/$f/evolved-dump-energy', total_energy, $(echo "$evg" | grab E0), 1e-11)
" 2>/dev/null || echo "FAIL dump/$f/evolved-dump: $("$TDS" -q "$tmp/evg_$f.dmp" -e '' 2>&1 | tail -n 1)"
done
