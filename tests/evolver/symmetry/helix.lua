-- helix.lua: a tube round the z axis in SYMMETRY_GROUP "quarter_turn",
-- one period high: N columns round (N a multiple of 4), K rows in
-- z = 0 .. P (exclusive); the top row's edges reach the bottom row's copy
-- under the generator z (a quarter turn and the lift P: torus code 4096),
-- so column j meets column j - N/4 there. Radius R, vertices moved by a
-- seeded pseudo-random offset of size AMP. Set OUT, N, K, P, R, SEED, AMP,
-- then dofile this.
math.randomseed(SEED)
local L = {'// helix.lua: a tube in the quarter_turn group (seed ' .. SEED .. ')',
  ('parameter quarter_turn_period = %.17g'):format(P), 'SYMMETRY_GROUP "quarter_turn"', '', 'vertices'}
local function vid(j, k) return k * N + (j % N) + 1 end
for k = 0, K - 1 do
  for j = 0, N - 1 do
    local th = 2 * math.pi * j / N + AMP * (2 * math.random() - 1)
    local r = R + AMP * (2 * math.random() - 1)
    local z = P * k / K + AMP * (2 * math.random() - 1)
    L[#L + 1] = ('%d %.17g %.17g %.17g'):format(vid(j, k), r * math.cos(th), r * math.sin(th), z)
  end
end
L[#L + 1] = '\nedges'
local ne, h, v, d = 0, {}, {}, {}
local function edge(a, b, wrap)
  ne = ne + 1
  L[#L + 1] = ('%d %d %d%s'):format(ne, a, b, wrap and ' wrap 4096' or '')
  return ne
end
-- the vertex dj columns on and one row up from (j, k), and whether the
-- edge to it crosses the top
local function up(j, k, dj)
  if k + 1 < K then return vid(j + dj, k + 1), false end
  return vid(j + dj - N // 4, 0), true
end
for k = 0, K - 1 do
  for j = 0, N - 1 do
    h[vid(j, k)] = edge(vid(j, k), vid(j + 1, k), false)
    local b, w = up(j, k, 0)
    v[vid(j, k)] = edge(vid(j, k), b, w)
    b, w = up(j, k, 1)
    d[vid(j, k)] = edge(vid(j, k), b, w)
  end
end
L[#L + 1] = '\nfaces'
local nf = 0
for k = 0, K - 1 do
  for j = 0, N - 1 do
    local top = k + 1 < K and vid(j, k + 1) or vid(j - N // 4, 0)
    nf = nf + 1
    L[#L + 1] = ('%d %d %d %d'):format(nf, h[vid(j, k)], v[vid(j + 1, k)], -d[vid(j, k)])
    nf = nf + 1
    L[#L + 1] = ('%d %d %d %d'):format(nf, d[vid(j, k)], -h[top], -v[vid(j, k)])
  end
end
local f = assert(io.open(OUT, 'w'))
f:write(table.concat(L, '\n'), '\n')
f:close()
