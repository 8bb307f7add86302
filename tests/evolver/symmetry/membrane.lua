-- membrane.lua: a periodic film in SYMMETRY_GROUP "torus": an N x N grid
-- over the cell's first two periods (PERIODS P, P[1] and P[2] in the
-- xy-plane), the wrap codes of Evolver's torus group (x: 1, y: 64, their
-- negatives 31 and 31*64) on the edges that cross the cell, heights
-- Z0 + a seeded pseudo-random bump of size AMP (and a sideways jitter of
-- AMP/4), one body below it with volume target VOL (VOL nil: none). The
-- film relaxes to the plane: area |P1 x P2| and, with a target, the
-- height VOL / area (Euclidean volume: the integral of z dx dy). Set OUT,
-- N, SEED, AMP, Z0, P, VOL, then dofile this.
math.randomseed(SEED)
local lines = {'// membrane.lua: a periodic film (seed ' .. SEED .. ')',
  'SYMMETRY_GROUP "torus"', 'PERIODS'}
for i = 1, 3 do lines[#lines + 1] = ('%.17g %.17g %.17g'):format(P[i][1], P[i][2], P[i][3]) end
lines[#lines + 1] = '\nvertices'
local function vid(i, j) return (j % N) * N + (i % N) + 1 end
for j = 0, N - 1 do
  for i = 0, N - 1 do
    local u, v = i / N + AMP / 4 * (2 * math.random() - 1), j / N + AMP / 4 * (2 * math.random() - 1)
    local x, y = u * P[1][1] + v * P[2][1], u * P[1][2] + v * P[2][2]
    lines[#lines + 1] = ('%d %.17g %.17g %.17g'):format(vid(i, j), x, y,
      Z0 + AMP * (2 * math.random() - 1))
  end
end
lines[#lines + 1] = '\nedges'
local edges, ne = {}, 0
-- edge from (i, j) to (i + di, j + dj): its wrap when the head crosses
local function edge(i, j, di, dj)
  local code = 0
  if i + di == N then code = code + 1 end
  if j + dj == N then code = code + 64 end
  ne = ne + 1
  lines[#lines + 1] = ('%d %d %d%s'):format(ne, vid(i, j), vid(i + di, j + dj),
    code ~= 0 and (' wrap ' .. code) or '')
  return ne
end
for j = 0, N - 1 do
  for i = 0, N - 1 do
    edges[vid(i, j)] = {edge(i, j, 1, 0), edge(i, j, 0, 1), edge(i, j, 1, 1)}
  end
end
lines[#lines + 1] = '\nfaces'
local nf = 0
for j = 0, N - 1 do
  for i = 0, N - 1 do
    local e = edges[vid(i, j)]
    local right = edges[vid(i + 1, j)] -- its vertical edge from (i+1, j)
    local up = edges[vid(i, j + 1)]    -- its horizontal edge from (i, j+1)
    nf = nf + 1
    lines[#lines + 1] = ('%d %d %d %d'):format(nf, e[1], right[2], -e[3])
    nf = nf + 1
    lines[#lines + 1] = ('%d %d %d %d'):format(nf, e[3], -up[1], -e[2])
  end
end
lines[#lines + 1] = '\nbodies'
local b = {}
for f = 1, nf do b[#b + 1] = tostring(f) end
lines[#lines + 1] = '1 ' .. table.concat(b, ' ') .. (VOL and (' volume ' .. ('%.17g'):format(VOL)) or '')
local f = assert(io.open(OUT, 'w'))
f:write(table.concat(lines, '\n'), '\n')
f:close()
