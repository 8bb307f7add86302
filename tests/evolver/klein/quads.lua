-- quads.lua: seeded random quads near the Delaunay limit in the Klein
-- ball, for u under KLEIN_METRIC (tests/evolver/klein.sh). Globals: OUT
-- (path), SEED, NQ (the number of quads), SIZE (their size, default
-- 0.15), R0 (their centres lie in the ball of this radius, default 0.7).
-- Quad k is two facets on edge 5k-4 (a -> b) with third corners c and d,
-- all four vertices fixed, its corners jittered; the opposite angles at
-- c and d sum to about pi. OUT.euclid gets one line per quad: 1 if the
-- Euclidean angles of the coordinates would flip it (the cosines summing
-- below -5e-4, tds's u before KLEIN_METRIC was measured), else 0, so the
-- test can tell that the quads tell the two rules apart.
math.randomseed(SEED)
local function rnd(a, b) return a + (b - a) * math.random() end
local function dot(a, b) return a[1] * b[1] + a[2] * b[2] + a[3] * b[3] end
local function sub(a, b) return {a[1] - b[1], a[2] - b[2], a[3] - b[3]} end
local function ecos(p, q, r)
  local u, v = sub(q, p), sub(r, p)
  return dot(u, v) / math.sqrt(dot(u, u) * dot(v, v))
end
local V, E, F, euclid = {}, {}, {}, {}
local s, r0 = SIZE or 0.15, R0 or 0.7
for k = 1, NQ do
  local c0
  repeat c0 = {rnd(-r0, r0), rnd(-r0, r0), rnd(-r0, r0)} until dot(c0, c0) < r0 * r0
  local function pt(x, y)
    return {c0[1] + s * x + rnd(-.03, .03), c0[2] + s * y + rnd(-.03, .03), c0[3] + rnd(-.03, .03)}
  end
  -- a = (-1, 0), b = (1, 0), c = (~0, h1), d = (~0, -h2), h1 h2 near 1
  local h1 = rnd(.6, 1.4)
  local h2 = 1 / h1 * rnd(0.8, 1.25)
  local a, b, c, d = pt(-1, 0), pt(1, 0), pt(rnd(-.3, .3), h1), pt(rnd(-.3, .3), -h2)
  local n, ne = #V, #E
  V[n + 1], V[n + 2], V[n + 3], V[n + 4] = a, b, c, d
  E[ne + 1], E[ne + 2], E[ne + 3] = {n + 1, n + 2}, {n + 2, n + 3}, {n + 3, n + 1}
  E[ne + 4], E[ne + 5] = {n + 2, n + 4}, {n + 4, n + 1}
  F[#F + 1] = {ne + 1, ne + 2, ne + 3}           -- a b c
  F[#F + 1] = {-(ne + 1), -(ne + 5), -(ne + 4)}  -- b a d
  euclid[k] = ecos(c, a, b) + ecos(d, a, b) < -5e-4 and 1 or 0
end
local f = assert(io.open(OUT, "w"))
f:write("KLEIN_METRIC\nvertices\n")
for i, p in ipairs(V) do f:write(("%d %.17g %.17g %.17g fixed\n"):format(i, p[1], p[2], p[3])) end
f:write("edges\n")
for i, e in ipairs(E) do f:write(("%d %d %d\n"):format(i, e[1], e[2])) end
f:write("faces\n")
for i, t in ipairs(F) do f:write(("%d %d %d %d\n"):format(i, t[1], t[2], t[3])) end
f:close()
f = assert(io.open(OUT .. ".euclid", "w"))
f:write(table.concat(euclid, "\n"), "\n")
f:close()
