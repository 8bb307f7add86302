-- meshes.lua: input meshes of the paper's experiments, as triangle lists
-- for trimesh{} (lua/pg.lua). Load with dofile; returns the module table.
-- Every generator is deterministic (its own random generator, seeded).

local M = {}
local sqrt, cos, sin, pi = math.sqrt, math.cos, math.sin, math.pi

-- A small deterministic generator (xorshift), so meshes do not depend on
-- Lua's math.random implementation.
function M.rng(seed)
  local s = seed or 88172645463325252
  return function()
    s = s ~ (s << 13)
    s = s ~ (s >> 7)
    s = s ~ (s << 17)
    return ((s >> 11) & ((1 << 53) - 1)) / (1 << 53)
  end
end

-- Icosahedron subdivided n times, projected on the sphere of radius R.
function M.icosphere(n, R)
  R = R or 1
  local t = (1 + sqrt(5)) / 2
  local V = { {-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
              {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1} }
  local F = { {1,12,6}, {1,6,2}, {1,2,8}, {1,8,11}, {1,11,12}, {2,6,10}, {6,12,5},
              {12,11,3}, {11,8,7}, {8,2,9}, {4,10,5}, {4,5,3}, {4,3,7}, {4,7,9},
              {4,9,10}, {5,10,6}, {3,5,12}, {7,3,11}, {9,7,8}, {10,9,2} }
  for _ = 1, n do
    local mid, NF = {}, {}
    local function m(a, b)
      local k = a < b and a * 100000 + b or b * 100000 + a
      if not mid[k] then
        local p, q = V[a], V[b]
        V[#V + 1] = { (p[1] + q[1]) / 2, (p[2] + q[2]) / 2, (p[3] + q[3]) / 2 }
        mid[k] = #V
      end
      return mid[k]
    end
    for _, f in ipairs(F) do
      local a, b, c = f[1], f[2], f[3]
      local ab, bc, ca = m(a, b), m(b, c), m(c, a)
      NF[#NF + 1] = { a, ab, ca }; NF[#NF + 1] = { b, bc, ab }
      NF[#NF + 1] = { c, ca, bc }; NF[#NF + 1] = { ab, bc, ca }
    end
    F = NF
  end
  for _, p in ipairs(V) do
    local l = sqrt(p[1]^2 + p[2]^2 + p[3]^2)
    p[1], p[2], p[3] = R * p[1] / l, R * p[2] / l, R * p[3] / l
  end
  return { vertices = V, facets = F }
end


-- Delaunay triangulation of 2-D points (Bowyer-Watson). pts[i] = {u, v}.
-- Returns a list of counter-clockwise triangles {i, j, k}. Up to 4000
-- points: the simple version (every triangle tested per point, O(n^2);
-- the inputs of the paper's experiments and of generate.lua are built by
-- it, and stay bit for bit as they were); above: M.delaunay_fast.
function M.delaunay(pts)
  if #pts > 4000 then return M.delaunay_fast(pts) end
  local n = #pts
  local P = {}
  for i = 1, n do P[i] = pts[i] end
  local lo, hi = math.huge, -math.huge
  for i = 1, n do
    lo = math.min(lo, pts[i][1], pts[i][2]); hi = math.max(hi, pts[i][1], pts[i][2])
  end
  local c, d = (lo + hi) / 2, (hi - lo) * 20 + 1
  P[n + 1] = { c - d, c - d }; P[n + 2] = { c + d, c - d }; P[n + 3] = { c, c + d }
  local tris = {}
  local function add(a, b, cc)
    local A, B, C = P[a], P[b], P[cc]
    local ax, ay, bx, by, cx, cy = A[1], A[2], B[1], B[2], C[1], C[2]
    local D = 2 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
    local a2, b2, c2 = ax * ax + ay * ay, bx * bx + by * by, cx * cx + cy * cy
    local ux = (a2 * (by - cy) + b2 * (cy - ay) + c2 * (ay - by)) / D
    local uy = (a2 * (cx - bx) + b2 * (ax - cx) + c2 * (bx - ax)) / D
    tris[#tris + 1] = { a, b, cc, ux, uy, (ax - ux)^2 + (ay - uy)^2 }
  end
  add(n + 1, n + 2, n + 3)
  for i = 1, n do
    local px, py = P[i][1], P[i][2]
    local keep, edges = {}, {}
    for _, t in ipairs(tris) do
      if (px - t[4])^2 + (py - t[5])^2 < t[6] * (1 - 1e-12) then
        for k = 1, 3 do
          local a, b = t[k], t[k % 3 + 1]
          local key = a < b and a * 1000003 + b or b * 1000003 + a
          if edges[key] then edges[key] = false else edges[key] = { a, b } end
        end
      else
        keep[#keep + 1] = t
      end
    end
    tris = keep
    for _, e in pairs(edges) do
      if e then add(e[1], e[2], i) end
    end
  end
  local out = {}
  for _, t in ipairs(tris) do
    if t[1] <= n and t[2] <= n and t[3] <= n then
      local A, B, C = P[t[1]], P[t[2]], P[t[3]]
      local cr = (B[1] - A[1]) * (C[2] - A[2]) - (B[2] - A[2]) * (C[1] - A[1])
      if cr > 0 then out[#out + 1] = { t[1], t[2], t[3] }
      else out[#out + 1] = { t[1], t[3], t[2] } end
    end
  end
  return out
end

-- The same triangulation in O(n log n)-ish time (for 100k-point inputs):
-- points inserted in a serpentine order of a grid, the triangle holding
-- each found by walking from the last one, its cavity (the triangles whose
-- circumcircle holds the point, same test as M.delaunay) grown through the
-- neighbours. Same result as M.delaunay but for the order of the list and
-- for ties among cocircular points.
function M.delaunay_fast(pts)
  local n = #pts
  local X, Y = {}, {}
  local lo, hi = math.huge, -math.huge
  for i = 1, n do
    X[i], Y[i] = pts[i][1], pts[i][2]
    lo = math.min(lo, X[i], Y[i]); hi = math.max(hi, X[i], Y[i])
  end
  local c, d = (lo + hi) / 2, (hi - lo) * 20 + 1
  X[n + 1], Y[n + 1] = c - d, c - d
  X[n + 2], Y[n + 2] = c + d, c - d
  X[n + 3], Y[n + 3] = c, c + d
  -- triangles: vertices T1, T2, T3 (counter-clockwise); N1, N2, N3 the
  -- neighbours across the edges (T1, T2), (T2, T3), (T3, T1), or false;
  -- circumcircle CX, CY, R2
  local T1, T2, T3, N1, N2, N3, CX, CY, R2, dead = {}, {}, {}, {}, {}, {}, {}, {}, {}, {}
  local nt = 0
  local function circ(t)
    local a, b, cc = T1[t], T2[t], T3[t]
    local ax, ay, bx, by, cx, cy = X[a], Y[a], X[b], Y[b], X[cc], Y[cc]
    local D = 2 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
    local a2, b2, c2 = ax * ax + ay * ay, bx * bx + by * by, cx * cx + cy * cy
    local ux = (a2 * (by - cy) + b2 * (cy - ay) + c2 * (ay - by)) / D
    local uy = (a2 * (cx - bx) + b2 * (ax - cx) + c2 * (bx - ax)) / D
    CX[t], CY[t], R2[t] = ux, uy, (ax - ux)^2 + (ay - uy)^2
  end
  local function new(a, b, cc)
    nt = nt + 1
    T1[nt], T2[nt], T3[nt] = a, b, cc
    N1[nt], N2[nt], N3[nt] = false, false, false
    circ(nt)
    return nt
  end
  new(n + 1, n + 2, n + 3)
  -- insertion order: serpentine rows of a grid
  local m = math.max(1, math.floor(math.sqrt(n / 4)))
  local x0, x1, y0, y1 = math.huge, -math.huge, math.huge, -math.huge
  for i = 1, n do
    x0 = math.min(x0, X[i]); x1 = math.max(x1, X[i]); y0 = math.min(y0, Y[i]); y1 = math.max(y1, Y[i])
  end
  local order, key = {}, {}
  for i = 1, n do
    local r = math.min(m - 1, math.floor((Y[i] - y0) / (y1 - y0 + 1e-300) * m))
    local cc = math.min(m - 1, math.floor((X[i] - x0) / (x1 - x0 + 1e-300) * m))
    if r % 2 == 1 then cc = m - 1 - cc end
    key[i] = (r * m + cc) * (n + 1) + i
    order[i] = i
  end
  table.sort(order, function(a, b) return key[a] < key[b] end)
  local last = 1
  local incav, stack, cav, bnd = {}, {}, {}, {}
  local gen = 0
  local function orient(a, b, px, py)
    return (X[b] - X[a]) * (py - Y[a]) - (Y[b] - Y[a]) * (px - X[a])
  end
  for _, p in ipairs(order) do
    local px, py = X[p], Y[p]
    -- locate: walk
    local t = last
    while dead[t] do t = t - 1 end
    local steps = 0
    while true do
      steps = steps + 1
      local a, b, cc = T1[t], T2[t], T3[t]
      if orient(a, b, px, py) < 0 and N1[t] then t = N1[t]
      elseif orient(b, cc, px, py) < 0 and N2[t] then t = N2[t]
      elseif orient(cc, a, px, py) < 0 and N3[t] then t = N3[t]
      else break end
      assert(steps < 10 * n + 100, "walk")
    end
    -- cavity
    gen = gen + 1
    local ncav = 1
    cav[1] = t; incav[t] = gen
    local head = 1
    local nb = 0
    while head <= ncav do
      local u = cav[head]; head = head + 1
      for k = 1, 3 do
        local v
        if k == 1 then v = N1[u] elseif k == 2 then v = N2[u] else v = N3[u] end
        local ea = k == 1 and T1[u] or k == 2 and T2[u] or T3[u]
        local eb = k == 1 and T2[u] or k == 2 and T3[u] or T1[u]
        if v and incav[v] == gen then
          -- interior edge
        elseif v and (px - CX[v])^2 + (py - CY[v])^2 < R2[v] * (1 - 1e-12) then
          ncav = ncav + 1; cav[ncav] = v; incav[v] = gen
        else
          nb = nb + 1
          bnd[3 * nb - 2], bnd[3 * nb - 1], bnd[3 * nb] = ea, eb, v
        end
      end
    end
    -- the cavity's border edges (those recorded before their neighbour
    -- joined the cavity are skipped), each joined to p
    local startT, endT = {}, {}
    local newts = {}
    for i = 1, nb do
      local ea, eb, v = bnd[3 * i - 2], bnd[3 * i - 1], bnd[3 * i]
      if not (v and incav[v] == gen) then
        local tt = new(ea, eb, p)
        newts[#newts + 1] = tt
        N1[tt] = v or false
        if v then
          if T1[v] == eb then N1[v] = tt elseif T2[v] == eb then N2[v] = tt else N3[v] = tt end
        end
        startT[ea] = tt; endT[eb] = tt
      end
    end
    for i = 1, ncav do dead[cav[i]] = true end
    for _, tt in ipairs(newts) do
      local ea, eb = T1[tt], T2[tt]
      N2[tt] = startT[eb] -- edge (eb, p) shared with (eb, x, p)'s edge (p, eb)
      N3[tt] = endT[ea]   -- edge (p, ea) shared with (y, ea, p)'s edge (ea, p)
      assert(N2[tt] and N3[tt], "cavity not star-shaped")
    end
    last = newts[#newts]
  end
  local out = {}
  for t = 1, nt do
    if not dead[t] and T1[t] <= n and T2[t] <= n and T3[t] <= n then
      out[#out + 1] = { T1[t], T2[t], T3[t] }
    end
  end
  return out
end

-- Points of a hexagonal lattice of spacing h, sorted by distance from the
-- origin; jittered by `jit` * h (deterministic).
local function hex_lattice(h, R, jit, rng)
  local pts = {}
  local nr = math.ceil(R / (h * sqrt(3) / 2)) + 1
  for j = -nr, nr do
    local y = j * h * sqrt(3) / 2
    local off = (j % 2) * h / 2
    for i = -nr - 1, nr + 1 do
      local x = i * h + off
      if x * x + y * y < R * R then
        pts[#pts + 1] = { x + jit * h * (rng() - 0.5), y + jit * h * (rng() - 0.5), x * x + y * y }
      end
    end
  end
  table.sort(pts, function(a, b) return a[3] < b[3] end)
  return pts
end

-- Points in the unit disk: nint interior points (lattice or random) and
-- nrim points on the circle. Returns pts (rim first) and nrim.
function M.disk_points(nint, o)
  o = o or {}
  local rng = M.rng(o.seed or 12345)
  local pts = {}
  local h = o.h
  if not h then -- area per lattice point h^2 sqrt(3)/2 over the inner disk
    h = sqrt(pi / (nint * sqrt(3) / 2))
    for _ = 1, 5 do h = sqrt(pi * (1 - 0.45 * h)^2 / (nint * sqrt(3) / 2)) end
    h = h * 0.98
  end
  local nrim = o.nrim or math.floor(2 * pi / h + 0.5)
  for i = 1, nrim do
    local a = 2 * pi * (i - 1) / nrim
    pts[i] = { cos(a), sin(a) }
  end
  if o.random then
    local k = 0
    while k < nint do
      local x, y = 2 * rng() - 1, 2 * rng() - 1
      local r2 = x * x + y * y
      if r2 < (1 - 0.15 * h)^2 then k = k + 1; pts[#pts + 1] = { x, y } end
    end
  else
    local lat = hex_lattice(h, 1.5, o.jitter or 0.02, rng)
    local k = 0
    for _, p in ipairs(lat) do
      if k == nint then break end
      if p[1]^2 + p[2]^2 < (1 - 0.45 * h)^2 then k = k + 1; pts[#pts + 1] = { p[1], p[2] } end
    end
    assert(k == nint, "lattice too small")
  end
  return pts, nrim
end

-- A surface over the unit disk: map(u, v, rim) -> x, y, z. Rim vertices
-- are fixed unless o.rim is a table of vertex attributes.
function M.disk_surface(pts, nrim, map, o)
  o = o or {}
  local V = {}
  for i, p in ipairs(pts) do
    local x, y, z = map(p[1], p[2], i <= nrim)
    V[i] = { x, y, z }
    if i <= nrim then
      if o.rim then for k, v in pairs(o.rim) do V[i][k] = v end
      else V[i].fixed = true end
    end
  end
  local F = M.delaunay(pts)
  if o.flip then for _, f in ipairs(F) do f[2], f[3] = f[3], f[2] end end
  return { vertices = V, facets = F }
end

-- Equal-area map of the unit disk onto the spherical cap of polar angle
-- theta_max (measured from the pole (0, 0, 1)), radius R.
function M.cap_map(R, thmax, zc)
  local k = 1 - cos(thmax)
  return function(u, v)
    local r2 = u * u + v * v
    local c = 1 - r2 * k
    local th = math.acos(math.max(-1, math.min(1, c)))
    local phi = math.atan(v, u)
    local z = R * cos(th)
    if math.abs(z) < 1e-14 * R then z = 0 end
    return R * sin(th) * cos(phi), R * sin(th) * sin(phi), (zc or 0) + z
  end
end

-- An irregular spherical cap: the cap of the unit sphere around (0, 0, 1)
-- of polar angle thmax, with nrim vertices on its rim (first; at polar
-- angle exactly thmax) and nint points sampled uniformly at random on the
-- cap's area (seeded), at least o.gap (default 0.3) times the mean
-- spacing from each other and from the rim. Triangulated by Delaunay in
-- the stereographic image from (0, 0, -1), which is conformal: the
-- triangles are the sphere's own Delaunay triangles (the same idea as
-- M.random_cylinder). Returns { vertices, facets } on the unit sphere,
-- facets counter-clockwise seen from outside; the caller scales, moves
-- and fixes the rim.
function M.random_cap(thmax, nrim, nint, o)
  o = o or {}
  local rng = M.rng(o.seed or 2016)
  local k = 1 - cos(thmax)
  local h = sqrt(2 * pi * k / (nint * sqrt(3) / 2))
  local gap = (o.gap or 0.3) * h
  local V = {}
  for i = 1, nrim do
    local phi = 2 * pi * (i - 1) / nrim
    V[i] = { sin(thmax) * cos(phi), sin(thmax) * sin(phi), cos(thmax) }
  end
  local function near(x, y, z)
    for _, q in ipairs(V) do
      if (q[1] - x)^2 + (q[2] - y)^2 + (q[3] - z)^2 < gap * gap then return true end
    end
    return false
  end
  local n = 0
  while n < nint do
    local c = 1 - rng() * k -- uniform in area: cos(theta) uniform
    local s, phi = sqrt(1 - c * c), 2 * pi * rng()
    local x, y, z = s * cos(phi), s * sin(phi), c
    if math.acos(c) < thmax - 0.3 * h and not near(x, y, z) then
      n = n + 1
      V[#V + 1] = { x, y, z }
    end
  end
  local pts = {}
  for i, p in ipairs(V) do pts[i] = { p[1] / (1 + p[3]), p[2] / (1 + p[3]) } end
  return { vertices = V, facets = M.delaunay(pts) }
end

-- Staggered cylinder of radius 1 between z0 and z1 with n vertices per ring
-- and rows intervals; the two end rings are fixed. Facets face outwards.
function M.cylinder(n, rows, z0, z1, o)
  o = o or {}
  local V, F = {}, {}
  for j = 0, rows do
    local z = z0 + (z1 - z0) * j / rows
    for i = 0, n - 1 do
      local a = 2 * pi * (i + 0.5 * (j % 2)) / n
      V[#V + 1] = { cos(a), sin(a), z, fixed = (j == 0 or j == rows) or nil }
    end
  end
  local id = function(j, i) return j * n + (i % n) + 1 end
  for j = 0, rows - 1 do
    for i = 0, n - 1 do
      if j % 2 == 0 then
        F[#F + 1] = { id(j, i), id(j, i + 1), id(j + 1, i) }
        F[#F + 1] = { id(j, i + 1), id(j + 1, i + 1), id(j + 1, i) }
      else
        F[#F + 1] = { id(j, i), id(j + 1, i + 1), id(j + 1, i) }
        F[#F + 1] = { id(j, i), id(j, i + 1), id(j + 1, i + 1) }
      end
    end
  end
  if o.caps then -- fixed, tensionless end caps closing a body
    V[#V + 1] = { 0, 0, z0, fixed = true }
    local c0 = #V
    V[#V + 1] = { 0, 0, z1, fixed = true }
    local c1 = #V
    for i = 0, n - 1 do
      F[#F + 1] = { c0, id(0, i + 1), id(0, i), tension = 0, fixed = true }
      F[#F + 1] = { c1, id(rows, i), id(rows, i + 1), tension = 0, fixed = true }
    end
  end
  return { vertices = V, facets = F }
end

-- An irregular cylinder of radius 1 between z0 and z1: n fixed vertices on
-- each end ring and nint interior points sampled uniformly at random
-- (seeded), kept at least o.gap * h from each other and from the rings
-- (h the mean spacing; default gap 0.3, a random sampling with the worst
-- slivers removed). Triangulated by Delaunay in the conformal image of
-- the cylinder, the annulus (theta, z) -> e^z (cos theta, sin theta), so
-- the triangles are Delaunay on the cylinder up to the map's distortion.
-- Facets face outwards; o.caps as for M.cylinder.
function M.random_cylinder(n, nint, z0, z1, o)
  o = o or {}
  local rng = M.rng(o.seed or 2016)
  local h = sqrt(2 * pi * (z1 - z0) / (nint * sqrt(3) / 2))
  local gap = (o.gap or 0.3) * h
  local pts, cyl = {}, {}
  local function add(th, z, fixed)
    local rho = math.exp(z)
    pts[#pts + 1] = { rho * cos(th), rho * sin(th) }
    cyl[#cyl + 1] = { cos(th), sin(th), z, fixed = fixed or nil }
  end
  for j, z in ipairs { z0, z1 } do
    for i = 0, n - 1 do add(2 * pi * (i + 0.5 * (j - 1)) / n, z, true) end
  end
  local function near(x, y, z)
    for _, q in ipairs(cyl) do
      local d2 = (q[1] - x)^2 + (q[2] - y)^2 + (q[3] - z)^2
      if d2 < gap * gap then return true end
    end
    return false
  end
  local k = 0
  while k < nint do
    local th, z = 2 * pi * rng(), z0 + (z1 - z0) * rng()
    if not near(cos(th), sin(th), z) then k = k + 1; add(th, z) end
  end
  local F = {}
  for _, t in ipairs(M.delaunay(pts)) do -- drop the hole (inner ring only)
    if t[1] > n or t[2] > n or t[3] > n then F[#F + 1] = { t[1], t[3], t[2] } end
  end
  local V = cyl
  if o.caps then -- fixed, tensionless end caps closing a body
    V[#V + 1] = { 0, 0, z0, fixed = true }
    local c0 = #V
    V[#V + 1] = { 0, 0, z1, fixed = true }
    local c1 = #V
    for i = 0, n - 1 do
      local a, b = 1 + i, 1 + (i + 1) % n
      F[#F + 1] = { c0, b, a, tension = 0, fixed = true }
      F[#F + 1] = { c1, n + a, n + b, tension = 0, fixed = true }
    end
  end
  return { vertices = V, facets = F }
end

-- The surface of the cube [-1,1]^3 with a hole of radius rho in each face
-- (the circles fixed), interior points pulled towards the centre. The
-- circles have o.nc vertices (default: spacing h).
function M.schwarz_p(rho, h, shrink, o)
  o = o or {}
  local rng = M.rng(777)
  local faces = { -- normal, a, b with a x b = normal
    { {1,0,0}, {0,1,0}, {0,0,1} }, { {-1,0,0}, {0,0,1}, {0,1,0} },
    { {0,1,0}, {0,0,1}, {1,0,0} }, { {0,-1,0}, {1,0,0}, {0,0,1} },
    { {0,0,1}, {1,0,0}, {0,1,0} }, { {0,0,-1}, {0,1,0}, {1,0,0} } }
  local V, F, index = {}, {}, {}
  local function vid(x, y, z, fixed)
    local key = ("%.9f %.9f %.9f"):format(x, y, z)
    if not index[key] then
      V[#V + 1] = { x, y, z, fixed = fixed or nil }
      index[key] = #V
    end
    return index[key]
  end
  local nc = o.nc or math.floor(2 * pi * rho / h + 0.5)
  local ns = math.floor(2 / h + 0.5)
  for _, fa in ipairs(faces) do
    local pts, kind = {}, {}
    for i = 1, nc do
      local a = 2 * pi * (i - 1) / nc
      pts[#pts + 1] = { rho * cos(a), rho * sin(a) }; kind[#pts] = "circle"
    end
    for s = 0, 3 do
      for i = 0, ns - 1 do
        local t = -1 + 2 * i / ns
        local u, v
        if s == 0 then u, v = t, -1 elseif s == 1 then u, v = 1, t
        elseif s == 2 then u, v = -t, 1 else u, v = -1, -t end
        pts[#pts + 1] = { u, v }
      end
    end
    local lat = hex_lattice(h, 1.5, 0.02, rng)
    for _, p in ipairs(lat) do
      local u, v = p[1], p[2]
      if math.abs(u) < 1 - 0.45 * h and math.abs(v) < 1 - 0.45 * h and
         u * u + v * v > (rho + 0.45 * h)^2 then
        pts[#pts + 1] = { u, v }
      end
    end
    local tris = M.delaunay(pts)
    local map = {}
    for i, p in ipairs(pts) do
      local x = fa[1][1] + p[1] * fa[2][1] + p[2] * fa[3][1]
      local y = fa[1][2] + p[1] * fa[2][2] + p[2] * fa[3][2]
      local z = fa[1][3] + p[1] * fa[2][3] + p[2] * fa[3][3]
      map[i] = vid(x, y, z, kind[i] == "circle")
    end
    for _, t in ipairs(tris) do
      local cu = (pts[t[1]][1] + pts[t[2]][1] + pts[t[3]][1]) / 3
      local cv = (pts[t[1]][2] + pts[t[2]][2] + pts[t[3]][2]) / 3
      if cu * cu + cv * cv > rho * rho then
        F[#F + 1] = { map[t[1]], map[t[2]], map[t[3]] }
      end
    end
  end
  local r0, r1 = sqrt(1 + rho * rho), sqrt(3)
  for _, p in ipairs(V) do
    if not p.fixed then
      local r = sqrt(p[1]^2 + p[2]^2 + p[3]^2)
      local sc = 1 - shrink * (r - r0) / (r1 - r0)
      p[1], p[2], p[3] = p[1] * sc, p[2] * sc, p[3] * sc
    end
  end
  return { vertices = V, facets = F }
end

return M
