#!/bin/sh
# popprism.sh: Evolver's toggles pop_to_edge and pop_to_face, which say how
# o pops the cone over a triangular prism frame (a free vertex joined by
# films to the nine edges of a fixed prism: six triple edges). Prisms of
# heights 0.6, 1.2 and 1.6 over a triangle of circumradius 1, every corner
# and the cone's vertex moved by a seeded random amount up to 0.05. With
# pop_to_edge the vertex becomes an edge joining the two triangles' sides
# (8 vertices, 19 edges, 12 facets), with pop_to_face a triangle between
# the two triangles' regions (9, 24, 16): the counts after o equal
# Evolver's exactly. Where the result is stable (the triangle on the flat
# prism, the edge on the tall ones) so does the area after g relaxes the
# films to convergence (both programs iterate until a step changes the
# area by at most 1e-14 relative; 1e-8 relative allowed, the minimum is
# strict); the other result shrinks its new film to nothing, a kink where
# g stalls at a place that depends on the path, so its area is not
# compared.
# The same after r (each film a fan of two facets), on two more seeds.
# Turning one toggle on turns the other off, in both programs.
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
LOOP='ii := 0; do { e0 := total_area; g 1; ii := ii + 1 } while (abs(total_area - e0) > 1e-14*abs(e0) and ii < 20000);'
for spec in "0.6 11 face" "1.2 12 edge" "1.6 13 edge" "0.6 21 face r" "1.2 22 edge r"; do
  set -- $spec
  h=$1 seed=$2 stable=$3 pre=${4:+"r; "}
  fe=$tmp/prism$seed.fe
  "$TDS" -q -e "
local s = $seed
local function rnd() s = (s * 1103515245 + 12345) % 2147483648; return s / 2147483648 - 0.5 end
local out = {'vertices'}
for z = 0, 1 do
  for k = 0, 2 do
    local t = 2 * math.pi * k / 3
    out[#out + 1] = ('%d %.15g %.15g %.15g fixed'):format(3 * z + k + 1, math.cos(t) + 0.1 * rnd(), math.sin(t) + 0.1 * rnd(), z * $h + 0.1 * rnd())
  end
end
out[#out + 1] = ('7 %.15g %.15g %.15g'):format(0.1 * rnd(), 0.1 * rnd(), $h / 2 + 0.1 * rnd())
local frame = {{1, 2}, {2, 3}, {3, 1}, {4, 5}, {5, 6}, {6, 4}, {1, 4}, {2, 5}, {3, 6}}
out[#out + 1] = 'edges'
for i, p in ipairs(frame) do out[#out + 1] = ('%d %d %d fixed'):format(i, p[1], p[2]) end
for k = 1, 6 do out[#out + 1] = ('%d 7 %d'):format(9 + k, k) end
out[#out + 1] = 'faces'
for i, p in ipairs(frame) do out[#out + 1] = ('%d %d %d %d'):format(i, 9 + p[1], i, -(9 + p[2])) end
local f = assert(io.open('$fe', 'w')) f:write(table.concat(out, '\n') .. '\n') f:close()"
  for mode in edge face; do
    name=popprism/${4:+r-}h$h/$mode
    cmds="${pre}pop_to_$mode on; o; printf \"C %d %d %d\\n\", vertex_count, edge_count, facet_count; $LOOP printf \"A %.17g\\n\", total_area;"
    ev=$(evolver_run "$fe" "$cmds")
    cp "$fe" "$tmp/in.fe"
    printf '%s\n' "$cmds" > "$tmp/c.cmd"
    out=$(cd "$tmp" && "$TDS" -q in.fe -f c.cmd 2>&1)
    "$TDS" -q -e "
dofile('$ROOT/tests/evolver/compare.lua')
local ec, tc = [[$(echo "$ev" | grab C)]], [[$(echo "$out" | grab C)]]
report('$name/counts', tc ~= '' and tc == ec, tc, ec)
if '$mode' == '$stable' then
  same('$name/area', tonumber([[$(echo "$out" | grab A)]]) or 0/0, tonumber([[$(echo "$ev" | grab A)]]) or 0/0, 1e-8)
end
" || echo "FAIL $name: tds exited with an error"
  done
done
# the two toggles exclude each other, as Evolver's
ev=$(evolver_run "$fe" 'pop_to_face on; pop_to_edge on; printf "T %d %d\n", pop_to_edge, pop_to_face;')
out=$("$TDS" -q "$fe" -e "evolver 'pop_to_face on; pop_to_edge on' print(('T %d %d'):format(tds.setting('pop_to_edge') and 1 or 0, tds.setting('pop_to_face') and 1 or 0))" 2>&1)
if [ "$(echo "$ev" | grab T)" = "1 0" ] && [ "$(echo "$out" | grab T)" = "1 0" ]; then
  echo "PASS popprism/toggles-exclusive"
else
  echo "FAIL popprism/toggles-exclusive: tds $(echo "$out" | grab T), Evolver $(echo "$ev" | grab T)"
fi
