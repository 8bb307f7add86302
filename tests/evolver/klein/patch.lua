-- patch.lua: a seeded random film in the Klein ball (tests/evolver/klein.sh).
-- Globals: OUT (path), SEED, N (an N x N grid of squares, each cut into two
-- triangles along a random diagonal), BODY (true: a closed octahedron-like
-- body instead, N subdivisions per side, with a volume constraint), G2
-- (false, or true: SYMMETRY_GROUP "genus2" with the vertices stored in
-- random copies, below), NOWRAP (with G2: every copy the identity, the
-- same film as with G2 alone), NEAR (the centre as with G2, no group),
-- NOKLEIN (no KLEIN_METRIC), ROT (SYMMETRY_GROUP "rotate", order 4: each
-- vertex stored turned back by a random power of its element, edge u->v
-- wrapped by the difference of the powers), VOL (BODY: the target volume, as a factor of
-- the body's volume at load when below 2, read by the caller).
-- The grid is bent (z = c (u^2 - v^2)), its points perturbed by up to a
-- fifth of a cell, rotated at random and put at a random centre, all
-- inside the ball of radius 0.8; the boundary is fixed. Under genus2 each
-- vertex v is stored as h_v^-1(X_v), h_v the identity or G_k (one random
-- k per file), and edge u->v gets the wrap h_u^-1 h_v (0, G_k or G_k^-1),
-- so every facet gathers an isometric copy of the designed triangle.
math.randomseed(SEED)
local function rnd(a, b) return a + (b - a) * math.random() end
local lines = {}
if not NOKLEIN then lines[#lines + 1] = "KLEIN_METRIC" end
local k = math.random(0, 7)
if G2 then lines[#lines + 1] = 'SYMMETRY_GROUP "genus2"' end
if ROT then lines[#lines + 1] = 'SYMMETRY_GROUP "rotate"' end
-- a random rotation (QR of a random matrix, Gram-Schmidt)
local function unit(v) local n = math.sqrt(v[1]^2 + v[2]^2 + v[3]^2) return {v[1]/n, v[2]/n, v[3]/n} end
local a = unit({rnd(-1, 1), rnd(-1, 1), rnd(-1, 1)})
local b = {rnd(-1, 1), rnd(-1, 1), rnd(-1, 1)}
local d = a[1]*b[1] + a[2]*b[2] + a[3]*b[3]
b = unit({b[1] - d*a[1], b[2] - d*a[2], b[3] - d*a[3]})
local c = {a[2]*b[3] - a[3]*b[2], a[3]*b[1] - a[1]*b[3], a[1]*b[2] - a[2]*b[1]}
local R = 0.35                   -- the shape's radius
local ctr = unit({rnd(-1, 1), rnd(-1, 1), rnd(-1, 1)})
local cr = rnd(0, 0.8 - R)
if G2 or NEAR then cr = cr * 0.3 / (0.8 - R) end -- copies by G_k stay inside
local function place(p)
  local q = {}
  for i = 1, 3 do q[i] = cr * ctr[i] + R * (p[1]*a[i] + p[2]*b[i] + p[3]*c[i]) end
  return q
end
-- G_k as in symgroup_g2.c (boost by cosh d = 5 + 4 sqrt 2 towards 135 k deg)
local ch = 5 + 4 * math.sqrt(2)
local sh = math.sqrt(ch * ch - 1)
local function boost(kk, p, sign)
  local t = math.rad(135 * kk)
  local u = {math.cos(t), math.sin(t), 0}
  local ux = u[1]*p[1] + u[2]*p[2]
  local w = ch + sign * sh * ux
  local q = {}
  for i = 1, 3 do q[i] = (p[i] + (ch - 1) * ux * u[i] + sign * sh * u[i]) / w end
  return q
end
local V, F, fixed = {}, {}, {}
if BODY then
  -- an octahedron's faces subdivided N times, pushed out to a sphere
  local O = {{1,0,0},{-1,0,0},{0,1,0},{0,-1,0},{0,0,1},{0,0,-1}}
  local faces = {{1,3,5},{3,2,5},{2,4,5},{4,1,5},{3,1,6},{2,3,6},{4,2,6},{1,4,6}}
  local key = {}
  local function vid(p)
    local s = ("%.9f %.9f %.9f"):format(p[1], p[2], p[3])
    if not key[s] then
      local n = unit(p)
      local r = 1 + rnd(-0.1, 0.1)
      V[#V + 1] = place({n[1]*r, n[2]*r, n[3]*r})
      key[s] = #V
    end
    return key[s]
  end
  for _, f in ipairs(faces) do
    local A, B, C = O[f[1]], O[f[2]], O[f[3]]
    local function P(i, j) local l = N - i - j
      return {(l*A[1] + i*B[1] + j*C[1])/N, (l*A[2] + i*B[2] + j*C[2])/N, (l*A[3] + i*B[3] + j*C[3])/N} end
    for i = 0, N - 1 do
      for j = 0, N - 1 - i do
        F[#F + 1] = {vid(P(i, j)), vid(P(i + 1, j)), vid(P(i, j + 1))}
        if i + j < N - 1 then F[#F + 1] = {vid(P(i + 1, j)), vid(P(i + 1, j + 1)), vid(P(i, j + 1))} end
      end
    end
  end
else
  local cb = rnd(-0.5, 0.5)
  local id = {}
  for i = 0, N do
    id[i] = {}
    for j = 0, N do
      local u, v = 2 * i / N - 1, 2 * j / N - 1
      local edge = i == 0 or j == 0 or i == N or j == N
      if not edge then u, v = u + rnd(-0.2, 0.2) * 2 / N, v + rnd(-0.2, 0.2) * 2 / N end
      V[#V + 1] = place({u, v, cb * (u * u - v * v)})
      id[i][j] = #V
      fixed[#V] = edge
    end
  end
  for i = 0, N - 1 do
    for j = 0, N - 1 do
      local p, q, r, s = id[i][j], id[i + 1][j], id[i + 1][j + 1], id[i][j + 1]
      if math.random() < 0.5 then F[#F + 1] = {p, q, r} F[#F + 1] = {p, r, s}
      else F[#F + 1] = {p, q, s} F[#F + 1] = {q, r, s} end
    end
  end
end
local h = {}
for v = 1, #V do h[v] = math.random() < 0.4 and G2 and not NOWRAP or false end
local rot = {} -- ROT: the power of rotate's element (clockwise quarter turns)
for v = 1, #V do rot[v] = ROT and math.random(0, 3) or 0 end
lines[#lines + 1] = "vertices"
for v, p in ipairs(V) do
  if h[v] then p = boost(k, p, -1) end -- G_k^-1 (the boost backwards)
  for _ = 1, rot[v] do p = {-p[2], p[1], p[3]} end -- undo rot[v] clockwise turns
  lines[#lines + 1] = ("%d %.17g %.17g %.17g%s"):format(v, p[1], p[2], p[3], fixed[v] and " fixed" or "")
end
local code = {[false] = {[false] = 0, [true] = k + 16 * ((k + 1) % 8)},
              [true] = {[false] = (k + 4) % 8 + 16 * ((k + 5) % 8), [true] = 0}}
lines[#lines + 1] = "edges"
local E, ne = {}, 0
local function edge(u, v)
  local key1, key2 = u .. " " .. v, v .. " " .. u
  if E[key1] then return E[key1] end
  if E[key2] then return -E[key2] end
  ne = ne + 1
  E[key1] = ne
  local w = ROT and (rot[v] - rot[u]) % 4 or code[h[u]][h[v]]
  lines[#lines + 1] = ("%d %d %d%s"):format(ne, u, v, (G2 or ROT) and " wrap " .. w or "")
  return ne
end
local fl = {}
for i, f in ipairs(F) do
  fl[i] = ("%d %d %d %d"):format(i, edge(f[1], f[2]), edge(f[2], f[3]), edge(f[3], f[1]))
end
lines[#lines + 1] = "faces"
for _, l in ipairs(fl) do lines[#lines + 1] = l end
if BODY then
  local all = {}
  for i = 1, #F do all[i] = i end
  lines[#lines + 1] = "bodies"
  lines[#lines + 1] = "1 " .. table.concat(all, " ") .. " volume " .. VOL
end
local f = assert(io.open(OUT, "w"))
f:write(table.concat(lines, "\n"), "\n")
f:close()
