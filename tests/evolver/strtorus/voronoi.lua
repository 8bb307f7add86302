-- voronoi.lua: writes (stdout) a Surface Evolver datafile of the Voronoi
-- diagram of N seeded pseudo-random points in the unit torus (string
-- model, SPACE_DIMENSION 2, TORUS): one cell (facet) and one body per
-- point, each body's volume fixed at its cell's area (but the last's),
-- edges across the
-- cell boundary with wrap signs. Globals N (points) and SEED (the seed of
-- a 31-bit linear congruential generator, so the file is the same on
-- every machine) are set by the caller, e.g.
--   tds -q -e "N, SEED = 30, 7; dofile('voronoi.lua')" > foam.fe
local n, seed = N or 30, SEED or 1
local state = seed % 2147483647
if state == 0 then state = 1 end
local function rand() -- Park and Miller's minimal standard generator
  state = (state * 48271) % 2147483647
  return state / 2147483647
end
local pts = {}
for i = 1, n do pts[i] = {rand(), rand()} end

-- The Voronoi cell of point i: a square around it clipped by the
-- bisectors with every other point's nine nearest images.
local function clip(poly, q, c) -- keep x with (x - q) . c <= 0
  local out = {}
  for k = 1, #poly do
    local a, b = poly[k], poly[k % #poly + 1]
    local da = (a[1] - q[1]) * c[1] + (a[2] - q[2]) * c[2]
    local db = (b[1] - q[1]) * c[1] + (b[2] - q[2]) * c[2]
    if da <= 0 then out[#out + 1] = a end
    if (da < 0 and db > 0) or (da > 0 and db < 0) then
      local t = da / (da - db)
      out[#out + 1] = {a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])}
    end
  end
  return out
end
local cells = {}
for i = 1, n do
  local p = pts[i]
  local poly = {{p[1] - 1, p[2] - 1}, {p[1] + 1, p[2] - 1}, {p[1] + 1, p[2] + 1}, {p[1] - 1, p[2] + 1}}
  for j = 1, n do
    for a = -1, 1 do
      for b = -1, 1 do
        if j ~= i or a ~= 0 or b ~= 0 then
          local q = {pts[j][1] + a, pts[j][2] + b}
          poly = clip(poly, {(p[1] + q[1]) / 2, (p[2] + q[2]) / 2}, {q[1] - p[1], q[2] - p[2]})
        end
      end
    end
  end
  cells[i] = poly -- counterclockwise, as the square was
end

-- Vertices: the corners modulo the lattice, stored in [0, 1)^2; a corner
-- is its vertex plus an integer shift.
local M = 1e8
local vid, vx, nv = {}, {}, 0
local function vertex(x)
  local ix, iy = math.floor(x[1] * M + 0.5), math.floor(x[2] * M + 0.5)
  local key = (ix % M) .. " " .. (iy % M)
  if not vid[key] then
    nv = nv + 1
    vid[key] = nv
    vx[nv] = {(ix % M) / M, (iy % M) / M, x}
  end
  local id = vid[key]
  -- the shift from the stored vertex to this corner
  return id, {(ix - ix % M) / M, (iy - iy % M) / M}
end
-- Edges: (tail, head, wrap) with the reverse (head, tail, -wrap) the same.
local eid, ev, ne = {}, {}, 0
local function edge(a, sa, b, sb)
  local w = {sb[1] - sa[1], sb[2] - sa[2]}
  local key = ("%d %d %d %d"):format(a, b, w[1], w[2])
  if eid[key] then return eid[key] end
  local rkey = ("%d %d %d %d"):format(b, a, -w[1], -w[2])
  if eid[rkey] then return -eid[rkey] end
  ne = ne + 1
  eid[key] = ne
  ev[ne] = {a, b, w}
  return ne
end
local faces = {}
for i = 1, n do
  local poly, f = cells[i], {}
  for k = 1, #poly do
    local a, sa = vertex(poly[k])
    local b, sb = vertex(poly[k % #poly + 1])
    f[#f + 1] = edge(a, sa, b, sb)
  end
  faces[i] = f
end

local function area(poly)
  local s = 0
  for k = 1, #poly do
    local a, b = poly[k], poly[k % #poly + 1]
    s = s + a[1] * b[2] - a[2] * b[1]
  end
  return s / 2
end

local sign = {[-1] = "-", [0] = "*", [1] = "+"}
print(("// Voronoi foam of %d points in the unit torus, seed %d (voronoi.lua)"):format(n, seed))
print("STRING\nSPACE_DIMENSION 2\nTORUS\nPERIODS\n1 0\n0 1\n")
print("vertices")
for v = 1, nv do print(("%d %.17g %.17g"):format(v, vx[v][1], vx[v][2])) end
print("\nedges")
for e = 1, ne do
  local a, b, w = ev[e][1], ev[e][2], ev[e][3]
  print(("%d %d %d %s %s"):format(e, a, b, sign[w[1]], sign[w[2]]))
end
print("\nfaces")
for i = 1, n do print(i .. " " .. table.concat(faces[i], " ")) end
print("\nbodies")
-- the areas add up to the torus's: one body is left free (else the
-- volume constraints are dependent and both programs stop)
for i = 1, n - 1 do print(("%d %d volume %.17g"):format(i, i, area(cells[i]))) end
print(("%d %d"):format(n, n))
