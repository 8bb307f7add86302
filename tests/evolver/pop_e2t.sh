#!/bin/sh
# pop_e2t.sh: pop_edge_to_tri on films with no bodies, as Evolver allows.
# Cones over seeded random triangular prism frames (height 0.6, corners
# and the cone's vertex moved up to 0.05, vertex ids, edge order and facet
# orientations shuffled) are popped to an edge by Evolver (pop_to_edge;
# o) and dumped; from the dump, in both programs, pop_edge_to_tri on the
# new edge (16) makes the triangle: the counts equal Evolver's exactly,
# and g relaxes both to the same films (on this flat prism the triangle
# is stable): area to 1e-5 relative. The new corners are where Evolver
# puts them; each film between two triple edges at one end follows the
# corner counterclockwise after the other about the edge's direction, as
# Evolver's films do within a session (tests/evolver/foam_t1_3d.sh), but
# from a state read back from its dump Evolver sometimes turns them the
# other way: on seeds 8 and 13 the areas agree to 1e-14, on 3 and 5 the
# triangulations differ and the relaxed areas were measured 1.5e-8 and
# 5.7e-6 apart (Evolver, given tds's triangulation, ends on tds's area).
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
LOOP='ii := 0; do { e0 := total_area; g 1; ii := ii + 1 } while (abs(total_area - e0) > 1e-14*abs(e0) and ii < 20000);'
for seed in 3 5 8 13; do
  "$TDS" -q -e "
local s = $seed * 104729
local function rnd() s = (s * 1103515245 + 12345) % 2147483648; return s / 2147483648 end
local function j() return 0.1 * (rnd() - 0.5) end
local function shuffle(t) for i = #t, 2, -1 do local r = 1 + math.floor(rnd() * i); t[i], t[r] = t[r], t[i] end return t end
local perm, pos = shuffle {1, 2, 3, 4, 5, 6}, {}
for z = 0, 1 do
  for k = 0, 2 do
    local t = 2 * math.pi * k / 3
    pos[perm[3 * z + k + 1]] = {math.cos(t) + j(), math.sin(t) + j(), 0.6 * z + j()}
  end
end
local out = {'vertices'}
for i = 1, 6 do out[#out + 1] = ('%d %.15g %.15g %.15g fixed'):format(i, pos[i][1], pos[i][2], pos[i][3]) end
out[#out + 1] = ('7 %.15g %.15g %.15g'):format(j(), j(), 0.3 + j())
local frame = shuffle {{1, 2}, {2, 3}, {3, 1}, {4, 5}, {5, 6}, {6, 4}, {1, 4}, {2, 5}, {3, 6}}
out[#out + 1] = 'edges'
for i, p in ipairs(frame) do out[#out + 1] = ('%d %d %d fixed'):format(i, perm[p[1]], perm[p[2]]) end
local order, spoke = shuffle {1, 2, 3, 4, 5, 6}, {}
for k = 1, 6 do out[#out + 1] = ('%d 7 %d'):format(9 + k, order[k]); spoke[order[k]] = 9 + k end
out[#out + 1] = 'faces'
for i, p in ipairs(frame) do
  local a, b = perm[p[1]], perm[p[2]]
  if rnd() < 0.5 then out[#out + 1] = ('%d %d %d %d'):format(i, spoke[a], i, -spoke[b])
  else out[#out + 1] = ('%d %d %d %d'):format(i, spoke[b], -i, -spoke[a]) end
end
local f = assert(io.open('$tmp/p$seed.fe', 'w')) f:write(table.concat(out, '\n') .. '\n') f:close()"
  evolver_dump pop_e2t "d$seed" "$tmp/p$seed.fe" "pop_to_edge on; o"
  kcompare "pop_e2t/prism$seed" "$tmp/d$seed.dmp" 1e-5 \
    "pop_edge_to_tri edge[16]; printf \"K %d %d %d\\n\", vertex_count, edge_count, facet_count; $LOOP printf \"K %.15g\\n\", total_area;"
done
