#!/bin/sh
# ports.sh: the hand-written .tds ports in scripts/ load to the same
# surface as Evolver's datafiles loaded directly: the same counts, and the
# same energy and body volumes after load and after two refinements (to
# 1e-12 relative: the same mesh, summed in the same order up to rounding).
. "$(dirname "$0")/lib.sh"
REPORT='
tds.quiet(true)
local function state()
  local s = ("%d %d %d %d %.15g"):format(vertex_count, edge_count, facet_count, body_count, total_energy)
  for b in bodies() do s = s .. (" %.15g"):format(b.volume) end
  return s
end
local t = { state() }
r() t[2] = state()
r() t[3] = state()
print("S " .. table.concat(t, " | "))'
for name in cube mound cat quad column; do
  a=$("$TDS" -q "$ROOT/scripts/$name.tds" -e "$REPORT" 2>&1 | grab S)
  b=$("$TDS" -q "$EXAMPLES/$name.fe" -e "$REPORT" 2>/dev/null | grab S)
  "$TDS" -q -e "
dofile('$ROOT/tests/evolver/compare.lua')
local a, b = '$a', '$b'
local na, nb = {}, {}
for w in a:gmatch('[^ |]+') do na[#na + 1] = tonumber(w) end
for w in b:gmatch('[^ |]+') do nb[#nb + 1] = tonumber(w) end
local ok = #na > 0 and #na == #nb
for i = 1, math.min(#na, #nb) do ok = ok and near(na[i], nb[i], 1e-12) end
report('ports/$name', ok, a, b .. ' (the .fe in tds)')
"
done
