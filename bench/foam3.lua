-- foam3.lua: writes (stdout) a Surface Evolver datafile of a periodic 3-D
-- foam: the Voronoi cells of the body-centred cubic lattice (Kelvin's
-- foam) of 2 N^3 points in the unit cube torus, each point moved by a
-- seeded pseudo-random amount (up to AMP of the lattice spacing) so the
-- cells are all different. TORUS_FILLED; every body's volume is held at
-- its cell's volume. Globals N, AMP and SEED are set by the caller:
--   tds -q -e "N, AMP, SEED = 4, 0.1, 1; dofile('foam3.lua')" > foam.fe
local n, amp, seed = N or 4, AMP or 0.1, SEED or 1
local state = seed % 2147483647
if state == 0 then state = 1 end
local function rand() -- Park and Miller's minimal standard generator
  state = (state * 48271) % 2147483647
  return state / 2147483647
end
local h = 1 / n
local pts = {}
for i = 0, n - 1 do
  for j = 0, n - 1 do
    for k = 0, n - 1 do
      for _, off in ipairs {0, 0.5} do
        local p = {}
        for c, base in ipairs {i, j, k} do p[c] = ((base + off) * h + amp * h * (2 * rand() - 1)) % 1 end
        pts[#pts + 1] = p
      end
    end
  end
end
local np = #pts

local function sub(a, b) return {a[1] - b[1], a[2] - b[2], a[3] - b[3]} end
local function dot(a, b) return a[1] * b[1] + a[2] * b[2] + a[3] * b[3] end
local function cross(a, b)
  return {a[2] * b[3] - a[3] * b[2], a[3] * b[1] - a[1] * b[3], a[1] * b[2] - a[2] * b[1]}
end

-- A convex polyhedron: faces {pts = polygon, lab = label}. Clip by the
-- half-space (x - q) . c <= 0; the cut face gets label lab.
local function clip(poly, q, c, lab)
  local out, cut = {}, {}
  for _, f in ipairs(poly) do
    local P, res = f.pts, {}
    for k = 1, #P do
      local a, b = P[k], P[k % #P + 1]
      local da, db = dot(sub(a, q), c), dot(sub(b, q), c)
      if da <= 0 then res[#res + 1] = a end
      if (da < 0 and db > 0) or (da > 0 and db < 0) then
        local t = da / (da - db)
        local x = {a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2]), a[3] + t * (b[3] - a[3])}
        res[#res + 1] = x
        cut[#cut + 1] = x
      end
    end
    if #res >= 3 then out[#out + 1] = {pts = res, lab = f.lab} end
  end
  if #cut >= 3 then -- the new face: the cut points by angle about their centre
    local m = {0, 0, 0}
    for _, x in ipairs(cut) do for i = 1, 3 do m[i] = m[i] + x[i] / #cut end end
    local u = sub(cut[1], m)
    local w = cross(c, u)
    table.sort(cut, function(a, b)
      local da, db = sub(a, m), sub(b, m)
      return math.atan(dot(da, w), dot(da, u)) < math.atan(dot(db, w), dot(db, u))
    end)
    -- drop repeats (a cut through a corner gives it twice)
    local uniq = {}
    for _, x in ipairs(cut) do
      local y = uniq[#uniq]
      if not y or math.abs(x[1] - y[1]) + math.abs(x[2] - y[2]) + math.abs(x[3] - y[3]) > 1e-12 then
        uniq[#uniq + 1] = x
      end
    end
    if #uniq >= 3 then out[#out + 1] = {pts = uniq, lab = lab} end
  end
  return out
end

local function box(p, r)
  local c = {}
  for s1 = 0, 1 do
    for s2 = 0, 1 do
      for s3 = 0, 1 do
        c[#c + 1] = {p[1] + (2 * s1 - 1) * r, p[2] + (2 * s2 - 1) * r, p[3] + (2 * s3 - 1) * r}
      end
    end
  end
  -- corner index = 4 s1 + 2 s2 + s3 + 1; faces counterclockwise from outside
  local F = {{1, 2, 4, 3}, {5, 7, 8, 6}, {1, 5, 6, 2}, {3, 4, 8, 7}, {1, 3, 7, 5}, {2, 6, 8, 4}}
  local poly = {}
  for _, f in ipairs(F) do poly[#poly + 1] = {pts = {c[f[1]], c[f[2]], c[f[3]], c[f[4]]}, lab = false} end
  return poly
end

local cells = {}
local reach = 2 * h -- Voronoi neighbours of a perturbed bcc point lie nearer
for i = 1, np do
  local p = pts[i]
  local poly = box(p, 1.5 * h)
  for j = 1, np do
    for a = -1, 1 do
      for b = -1, 1 do
        for c = -1, 1 do
          if j ~= i or a ~= 0 or b ~= 0 or c ~= 0 then
            local q = {pts[j][1] + a, pts[j][2] + b, pts[j][3] + c}
            local d = sub(q, p)
            if math.abs(d[1]) < reach and math.abs(d[2]) < reach and math.abs(d[3]) < reach then
              poly = clip(poly, {(p[1] + q[1]) / 2, (p[2] + q[2]) / 2, (p[3] + q[3]) / 2}, d, true)
            end
          end
        end
      end
    end
  end
  for _, f in ipairs(poly) do assert(f.lab, "a cell reached its bounding box") end
  cells[i] = poly
end

-- Vertices modulo the lattice, stored in [0, 1)^3.
local M = 1e8
local vid, vx, nv = {}, {}, 0
local function vertex(x)
  local ix = {}
  for i = 1, 3 do ix[i] = math.floor(x[i] * M + 0.5) end
  local key = (ix[1] % M) .. " " .. (ix[2] % M) .. " " .. (ix[3] % M)
  if not vid[key] then
    nv = nv + 1
    vid[key] = nv
    vx[nv] = {(ix[1] % M) / M, (ix[2] % M) / M, (ix[3] % M) / M}
  end
  local s = {}
  for i = 1, 3 do s[i] = (ix[i] - ix[i] % M) / M end
  return vid[key], s
end
local eid, ev, ne = {}, {}, 0
local function edge(a, sa, b, sb)
  local w = {sb[1] - sa[1], sb[2] - sa[2], sb[3] - sa[3]}
  local key = ("%d %d %d %d %d"):format(a, b, w[1], w[2], w[3])
  if eid[key] then return eid[key] end
  local rkey = ("%d %d %d %d %d"):format(b, a, -w[1], -w[2], -w[3])
  if eid[rkey] then return -eid[rkey] end
  ne = ne + 1
  eid[key] = ne
  ev[ne] = {a, b, w}
  return ne
end
local fid, faces, bodyf = {}, {}, {}
local vol = {}
for i = 1, np do
  bodyf[i] = {}
  local v = 0
  for _, f in ipairs(cells[i]) do
    local list, ids = {}, {}
    for k = 1, #f.pts do
      local a, sa = vertex(f.pts[k])
      local b, sb = vertex(f.pts[k % #f.pts + 1])
      local e = edge(a, sa, b, sb)
      list[#list + 1] = e
      ids[#ids + 1] = math.abs(e)
    end
    table.sort(ids)
    local key = table.concat(ids, " ")
    if fid[key] then
      bodyf[i][#bodyf[i] + 1] = -fid[key]
    else
      faces[#faces + 1] = list
      fid[key] = #faces
      bodyf[i][#bodyf[i] + 1] = #faces
    end
    -- the cell's volume: the cone from its point over the face
    local P = f.pts
    for k = 2, #P - 1 do v = v + dot(sub(P[1], pts[i]), cross(sub(P[k], pts[i]), sub(P[k + 1], pts[i]))) / 6 end
  end
  vol[i] = v
end

local sign = {[-1] = "-", [0] = "*", [1] = "+"}
print(("// periodic foam: %d perturbed bcc Voronoi cells (foam3.lua N=%d AMP=%g SEED=%d)"):format(np, n, amp, seed))
print("TORUS_FILLED\nPERIODS\n1 0 0\n0 1 0\n0 0 1\n")
print("vertices")
for v = 1, nv do print(("%d %.17g %.17g %.17g"):format(v, vx[v][1], vx[v][2], vx[v][3])) end
print("\nedges")
for e = 1, ne do
  local w = ev[e][3]
  print(("%d %d %d %s %s %s"):format(e, ev[e][1], ev[e][2], sign[w[1]], sign[w[2]], sign[w[3]]))
end
print("\nfaces")
for f = 1, #faces do print(f .. " " .. table.concat(faces[f], " ")) end
print("\nbodies")
for i = 1, np do print(("%d %s volume %.17g"):format(i, table.concat(bodyf[i], " "), vol[i])) end
