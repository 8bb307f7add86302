-- sector.lua: one sector of a catenoid-like band between two fixed rings
-- (radius R at z = -H and z = H), for a SYMMETRY_GROUP that maps the
-- sector onto its neighbour: M columns at angles 0 .. ANGLE (exclusive),
-- K + 1 rows; the edges of the last column reach the first column's
-- copy under the group element of code W. FLIP: that element also
-- turns z -> -z, so row k meets the copy of row K - k. Interior vertices
-- are moved by a seeded pseudo-random offset of size AMP. BODY: the
-- facets as one body with that volume target (nil: no body). Set OUT,
-- GROUP, PARAMS (top-section lines), ANGLE, M, K, R, H, W, FLIP, SEED,
-- AMP, BODY, then dofile this.
math.randomseed(SEED)
local L = {'// sector.lua: a catenoid sector (seed ' .. SEED .. ')', PARAMS or '',
  GROUP and ('SYMMETRY_GROUP "%s"'):format(GROUP) or '', '', 'vertices'}
-- COPIES (default 1): that many sectors side by side with the same
-- offsets, the last reaching the first with no wrap: the whole surface,
-- without the group (GROUP nil), whose energy is COPIES times the
-- sector's.
local copies = COPIES or 1
local M0 = M
M = M0 * copies
local off = {}
for k = 0, K do
  for j = 0, M0 - 1 do
    off[k * M0 + j] = {AMP * (2 * math.random() - 1), AMP * (2 * math.random() - 1) / R,
      AMP * (2 * math.random() - 1)}
  end
end
local function vid(j, k) return k * M + j + 1 end
for k = 0, K do
  for j = 0, M - 1 do
    local th, z, r = ANGLE * j / M0, -H + 2 * H * k / K, R
    local fixed = (k == 0 or k == K)
    if not fixed then
      local o = off[k * M0 + j % M0]
      r = r * 0.8 + o[1]
      th = th + o[2]
      z = z + o[3]
    end
    L[#L + 1] = ('%d %.17g %.17g %.17g%s'):format(vid(j, k), r * math.cos(th), r * math.sin(th),
      z, fixed and ' fixed' or '')
  end
end
L[#L + 1] = '\nedges'
local ne, h, v, d = 0, {}, {}, {}
local function edge(a, b, wrap, fixed)
  ne = ne + 1
  L[#L + 1] = ('%d %d %d%s%s'):format(ne, a, b, wrap and (' wrap ' .. W) or '', fixed and ' fixed' or '')
  return ne
end
-- the head of an edge from column j, row k, one column on, dk rows up
local function ahead(j, k, dk)
  if j + 1 < M then return vid(j + 1, k + dk), false end
  return vid(0, FLIP and K - k - dk or k + dk), GROUP ~= nil
end
for k = 0, K do
  for j = 0, M - 1 do
    local hd, wr = ahead(j, k, 0)
    h[vid(j, k)] = edge(vid(j, k), hd, wr, k == 0 or k == K)
    if k < K then
      v[vid(j, k)] = edge(vid(j, k), vid(j, k + 1), false, false)
      hd, wr = ahead(j, k, 1)
      d[vid(j, k)] = edge(vid(j, k), hd, wr, false)
    end
  end
end
L[#L + 1] = '\nfaces'
local nf = 0
for k = 0, K - 1 do
  for j = 0, M - 1 do
    -- the vertical edge at the head of h(j, k), run upwards (-) or
    -- downwards (+) in the neighbour's copy
    local up
    if j + 1 < M then up = v[vid(j + 1, k)]
    elseif FLIP then up = -v[vid(0, K - k - 1)]
    else up = v[vid(0, k)] end
    nf = nf + 1
    L[#L + 1] = ('%d %d %d %d'):format(nf, h[vid(j, k)], up, -d[vid(j, k)])
    nf = nf + 1
    L[#L + 1] = ('%d %d %d %d'):format(nf, d[vid(j, k)], -h[vid(j, k + 1)], -v[vid(j, k)])
  end
end
if BODY then
  L[#L + 1] = '\nbodies'
  local b = {}
  for f = 1, nf do b[#b + 1] = tostring(f) end
  L[#L + 1] = '1 ' .. table.concat(b, ' ') .. (' volume %.17g'):format(BODY)
end
local f = assert(io.open(OUT, 'w'))
f:write(table.concat(L, '\n'), '\n')
f:close()
