#!/bin/sh
# foam_t1.sh: a T1 in seeded random 2-D foams (tests/evolver/string/foam.lua:
# the Voronoi diagram of n random points, each cell holding its area), as
# Evolver does it. Relaxed by g, the shortest wall between two cells A and
# B (free ends) is made to vanish: A and B shrink to 0.7 of their areas,
# the cells C and D at its ends grow by 1.4 (tds picks the cells). Evolver
# relaxes that (the wall goes to ~1e-12) and dumps; from the dump, in both
# programs, `t 0.01` deletes the short walls (vertices where four meet,
# some on the fixed outer wall), `o` pops them into triple junctions, and
# g relaxes. The relaxation to a vanishing wall ends at a kink where g
# stalls at a place that depends on the path (4e-4 apart in energy), so
# the programs start from Evolver's dump. Checked: the counts after t and
# after o (exact); then either the new foam is regular and its relaxed
# energy (1e-10 relative: both converge to 1e-14 per step; measured 1e-13)
# and its sorted wall lengths (1e-6: first order in the position error)
# equal Evolver's, and the T1 happened (tds: C and D share a wall, A and B
# do not, the energy fell), or, as on three of the five seeds, the wall
# a pop made vanishes again in Evolver and then must in tds too (below
# 1e-6; their energies there differ like any two stalls at a kink).
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
LOOP='ii := 0; do { e0 := total_energy; g 1; ii := ii + 1 } while (abs(total_energy - e0) > 1e-14*abs(e0) and ii < 100000);'
for spec in "30 12345" "40 1" "40 3" "40 777" "50 7"; do
  set -- $spec
  name=foam_t1/voronoi$1-$2
  fe=$tmp/v$1.fe
  "$TDS" -q -e "local F = dofile('$ROOT/tests/evolver/string/foam.lua')
local f = assert(io.open('$fe', 'w')) f:write((F.voronoi_fe($1, $2))) f:close()"
  # the cells: A, B share the shortest wall with free ends; C, D at its ends
  cells=$("$TDS" -q "$fe" -e "
dofile('$ROOT/tests/evolver/compare.lua')
converge(1e-14, 100000)
local function cells_of(id)
  local c = {}
  for f in facets() do for _, oe in ipairs(f.edges) do if math.abs(oe) == id then c[#c + 1] = f.id end end end
  return c
end
local best, bl = nil, math.huge
for e in edges() do
  if e.length < bl and #cells_of(e.id) == 2 and not e.tail.fixed and not e.head.fixed then best, bl = e, e.length end
end
local c, ends = cells_of(best.id), {}
for _, v in ipairs({best.tail, best.head}) do
  for f in facets() do
    if f.id ~= c[1] and f.id ~= c[2] then
      for _, oe in ipairs(f.edges) do
        local e = edge[math.abs(oe)]
        if e.tail.id == v.id or e.head.id == v.id then ends[#ends + 1] = f.id break end
      end
    end
  end
end
print(('CELLS %d %d %d %d'):format(c[1], c[2], ends[1], ends[2]))" | grab CELLS)
  set -- $cells
  if [ $# -ne 4 ]; then echo "FAIL $name: no wall found ($cells)"; continue; fi
  A=$1 B=$2 C=$3 D=$4
  SET="body[$A].target := body[$A].target*0.7; body[$B].target := body[$B].target*0.7; body[$C].target := body[$C].target*1.4; body[$D].target := body[$D].target*1.4;"
  # Evolver drives the wall to ~0 and dumps: both programs go on from there
  rm -f "$tmp/pre.dmp"
  evolver_run "$fe" "$LOOP $SET $LOOP dump \"$tmp/pre.dmp\";" > /dev/null
  if [ ! -s "$tmp/pre.dmp" ]; then echo "FAIL $name: Evolver wrote no dump"; continue; fi
  CNT='vertex_count, edge_count, facet_count'
  cmds="t 0.01; printf \"T %d %d %d\\n\", $CNT; o; printf \"O %d %d %d\\n\", $CNT; $LOOP printf \"H %.17g\\n\", total_energy; foreach edge ee do printf \"L %.12f\\n\", ee.length;"
  evolver_run "$tmp/pre.dmp" "$cmds" > "$tmp/ev.out"
  cp "$tmp/pre.dmp" "$tmp/in.dmp"
  printf '%s\n' "$cmds" > "$tmp/c.cmd"
  (cd "$tmp" && "$TDS" -q in.dmp -f c.cmd) > "$tmp/tds.out" 2>&1
  "$TDS" -q "$tmp/pre.dmp" -e "
dofile('$ROOT/tests/evolver/compare.lua')
local ev = io.open('$tmp/ev.out'):read('a')
local tds = io.open('$tmp/tds.out'):read('a')
local function line(s, k) return s:match('\n' .. k .. ' ([^\n]*)') or s:match('^' .. k .. ' ([^\n]*)') end
report('$name/counts-after-t', line(tds, 'T') ~= nil and line(tds, 'T') == line(ev, 'T'), line(tds, 'T'), line(ev, 'T'))
report('$name/counts-after-o', line(tds, 'O') ~= nil and line(tds, 'O') == line(ev, 'O'), line(tds, 'O'), line(ev, 'O'))
local h, he = tonumber(line(tds, 'H')), tonumber(line(ev, 'H'))
local tl, el = {}, {}
for x in tds:gmatch('\nL (%S+)') do tl[#tl + 1] = tonumber(x) end
for x in ev:gmatch('\nL (%S+)') do el[#el + 1] = tonumber(x) end
table.sort(tl)
table.sort(el)
if (el[1] or 0) < 1e-6 then
  -- the popped junction's new wall vanished again: a kink where g stalls
  report('$name/reforms', (tl[1] or 1) < 1e-6, tl[1], 'a wall below 1e-6 as in Evolver (' .. el[1] .. ')')
  return
end
same('$name/energy', h or 0/0, he or 0/0, 1e-10)
local worst = #tl == #el and 0 or math.huge
for i = 1, math.min(#tl, #el) do worst = math.max(worst, math.abs(tl[i] - el[i])) end
report('$name/wall-lengths', worst <= 1e-6, worst, '<= 1e-6 (' .. #el .. ' walls)')
-- the T1 (tds): C and D share a wall, A and B do not, the energy fell
local before = total_energy
evolver 't 0.01; o'
converge(1e-14, 100000)
local function share(a, b)
  local s = {}
  for _, oe in ipairs(facet[a].edges) do s[math.abs(oe)] = true end
  for _, oe in ipairs(facet[b].edges) do if s[math.abs(oe)] then return true end end
  return false
end
report('$name/t1', share($C, $D) and not share($A, $B) and total_energy < before - 1e-3,
       ('C-D %s, A-B %s, energy %.10g from %.10g'):format(tostring(share($C, $D)), tostring(share($A, $B)), total_energy, before),
       'C-D walled, A-B not, energy lower')
" 2>/dev/null | grep -v '^Deleted\|^Vertices popped\|^Gravity' || echo "FAIL $name: tds exited with an error"
done
