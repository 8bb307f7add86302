-- generate.lua: seeded inputs the method was not tuned for (issue 13):
-- ten per experiment family, each of a different kind, so that a result
-- is judged by its worst input rather than by the hand-made one.
--
--   local G = dofile("scripts/paper/generate.lua")
--   local exp = G.experiment("hemisphere", 8)   -- for common.lua's C.run
--
-- Families (the paper's experiments, same models and targets as the
-- scripts in this folder): hemisphere, catenoid, schwarz_p, cmc (volume
-- 2.6, pi, 3.8 in turn), drop (odd cases the pendant drop, even ones the
-- sessile drop). Kinds, by case number:
--   1 random     uniform random points at least 0.3 h apart (h the mean
--                spacing), Delaunay
--   2 sliver     uniform random points, no minimum gap (slivers)
--   3 jitter     a hexagonal lattice jittered by 0.45 h
--   4 aniso      a lattice stretched 2.5:1 (facets with aspect ratio 2.5)
--   5 aniso_r    random points triangulated in coordinates stretched 3:1
--                (long thin Delaunay facets), across the first direction;
--                for Schwarz P a lattice stretched 6:1 (the stretched
--                Delaunay would cross the holes)
--   6 graded     random points whose density varies 1:9 across the domain
--   7 pole9      a jittered lattice with one vertex of valence 9
--   8 pole11     the same with valence 11 (at the hemisphere's pole)
--   9 perturbed  case 1's mesh with every free vertex moved 0.25 h in a
--                random direction (off the surface)
--  10 coarse     a coarse random mesh (1/16 of the points) refined twice
--                by edge midpoints: its vertices keep valences 3 to 9; for
--                the hemisphere an 11-gon pyramid refined three times (a
--                valence-11 pole), for Schwarz P the lattice with 20
--                vertices per circle (fixed edges 1.4 times the interior)
-- Every generator is deterministic: the seed is the family's and the case's
-- (and the optional salt's: G.experiment(family, case, salt) with a
-- positive integer salt gives another input of the same kind, for checks
-- on inputs nobody has looked at; the name then ends in "_sSALT").
local dir = debug.getinfo(1, "S").source:match("^@(.*/)") or "./"
local M = dofile(dir .. "meshes.lua")
local G = {}
local sqrt, cos, sin, pi, exp, log = math.sqrt, math.cos, math.sin, math.pi, math.exp, math.log

G.families = { "hemisphere", "catenoid", "schwarz_p", "cmc", "drop" }
G.kinds = { "random", "sliver", "jitter", "aniso", "aniso_r", "graded", "pole9",
            "pole11", "perturbed", "coarse" }
G.cases = #G.kinds

-- Point sets in a parameter domain. A domain has: area, bounds {u0, u1, v0,
-- v1}, inside(u, v, margin) (true when at least margin inside), period (of
-- u, or nil), and the boundary points (fixed or on a constraint) listed
-- first by the caller. Distances are measured in the domain's coordinates,
-- periodic in u when period is set.
local function d2(dom, a, b)
  local du = a[1] - b[1]
  if dom.period then
    du = du % dom.period
    if du > dom.period / 2 then du = du - dom.period end
  end
  return du * du + (a[2] - b[2])^2
end

-- A spatial hash for the gap test.
local function grid(cell)
  local g = {}
  local function key(u, v) return math.floor(u / cell) * 100003 + math.floor(v / cell) end
  return {
    add = function(p)
      local k = key(p[1], p[2])
      g[k] = g[k] or {}
      table.insert(g[k], p)
    end,
    near = function(dom, p, r)
      local iu, iv = math.floor(p[1] / cell), math.floor(p[2] / cell)
      local span = math.ceil(r / cell)
      for a = -span, span do
        for b = -span, span do
          for _, q in ipairs(g[(iu + a) * 100003 + iv + b] or {}) do
            if d2(dom, p, q) < r * r then return true end
          end
        end
      end
      if dom.period then -- across the seam
        local pp = { p[1] + (p[1] < dom.period / 2 and dom.period or -dom.period), p[2] }
        iu = math.floor(pp[1] / cell)
        for a = -span, span do
          for b = -span, span do
            for _, q in ipairs(g[(iu + a) * 100003 + iv + b] or {}) do
              if d2(dom, p, q) < r * r then return true end
            end
          end
        end
      end
      return false
    end,
  }
end

-- n random points, at least gap(u, v) apart and from the boundary points
-- `fixed`, and at least margin (default 0.3 gap) inside the domain (more
-- than the boundary polygon's sagitta, or a point would lie outside the
-- polygon); density(u, v) in (0, 1] thins them by rejection.
local function random_points(dom, n, rng, fixed, gapf, density, margin)
  local b = dom.bounds
  local cell = 0.2 * sqrt(dom.area / n)
  local gr = grid(cell)
  for _, p in ipairs(fixed) do gr.add(p) end
  local out, tries = {}, 0
  while #out < n do
    tries = tries + 1
    assert(tries < 1000 * n, "random_points: cannot place the points")
    local u, v = b[1] + (b[2] - b[1]) * rng(), b[3] + (b[4] - b[3]) * rng()
    local g = gapf(u, v)
    if dom.inside(u, v, margin or 0.3 * g) and (not density or rng() < density(u, v))
       and (g == 0 or not gr.near(dom, { u, v }, g)) then
      local p = { u, v }
      out[#out + 1] = p
      gr.add(p)
    end
  end
  return out
end

-- A hexagonal lattice of spacing h stretched by s (u by s, v by 1 / s),
-- jittered by jit * h, turned by angle rot, inside the domain (margin
-- 0.45 h); about n points (the spacing is adjusted).
local function lattice_points(dom, n, rng, o)
  local s, jit, rot = o.stretch or 1, o.jitter or 0.02, o.rot or 0
  local b = dom.bounds
  local h = sqrt(dom.area / (n * sqrt(3) / 2))
  local out
  for _ = 1, 8 do
    out = {}
    local cu, cv = (b[1] + b[2]) / 2, (b[3] + b[4]) / 2
    local R = sqrt((b[2] - b[1])^2 + (b[4] - b[3])^2)
    local nr = math.ceil(R / (h * sqrt(3) / 2 * math.min(s, 1 / s))) + 2
    local cr, sr = cos(rot), sin(rot)
    for j = -nr, nr do
      for i = -nr, nr do
        local x = (i + 0.5 * (j % 2)) * h * s
        local y = j * h * sqrt(3) / 2 / s
        local u = cu + cr * x - sr * y + jit * h * (rng() - 0.5)
        local v = cv + sr * x + cr * y + jit * h * (rng() - 0.5)
        if dom.period then u = b[1] + (u - b[1]) % dom.period end
        if u >= b[1] and u < b[2] and v >= b[3] and v <= b[4] and dom.inside(u, v, 0.45 * h) then
          out[#out + 1] = { u, v }
        end
      end
    end
    if dom.period then -- drop seam duplicates
      local keep, gr = {}, grid(0.5 * h)
      for _, p in ipairs(out) do
        if not gr.near(dom, p, 0.5 * h) then keep[#keep + 1] = p; gr.add(p) end
      end
      out = keep
    end
    if math.abs(#out - n) <= 0.02 * n then break end
    h = h * sqrt(#out / n)
  end
  return out, h
end

-- A vertex of valence k at c: the points within 1.5 rho of c (rho the
-- radius at which k points are h apart) are replaced by c and k points on
-- the circle of radius rho: the Delaunay triangulation joins c to all k.
local function add_pole(dom, pts, c, k, h)
  local rho = k * h / (2 * pi)
  local out = {}
  for _, p in ipairs(pts) do
    if d2(dom, p, c) > (1.5 * rho)^2 then out[#out + 1] = p end
  end
  out[#out + 1] = { c[1], c[2] }
  for i = 1, k do
    local a = 2 * pi * (i - 0.5) / k
    out[#out + 1] = { c[1] + rho * cos(a), c[2] + rho * sin(a) }
  end
  return out
end

-- The interior points of kind `kind` (not "coarse", "perturbed").
local function kind_points(dom, kind, n, rng, fixed, pole_at)
  local h = sqrt(dom.area / (n * sqrt(3) / 2))
  if kind == "random" or kind == "perturbed" then
    return random_points(dom, n, rng, fixed, function() return 0.3 * h end)
  elseif kind == "sliver" then
    return random_points(dom, n, rng, fixed, function() return 0 end, nil, 0.15 * h)
  elseif kind == "jitter" then
    return (lattice_points(dom, n, rng, { jitter = 0.45 }))
  elseif kind == "aniso" then
    return (lattice_points(dom, n, rng, { stretch = sqrt(2.5), jitter = 0.05, rot = 0.3 }))
  elseif kind == "aniso_r" then
    return random_points(dom, n, rng, fixed, function() return 0.3 * h end)
  elseif kind == "graded" then
    -- density from 1/9 at v0 to 1 at v1; the gap follows the local spacing
    local b = dom.bounds
    local function dens(_, v) local t = (v - b[3]) / (b[4] - b[3]); return (1 + 8 * t) / 9 end
    local hh = sqrt(dom.area / (n * sqrt(3) / 2)) * sqrt(5 / 9)
    return random_points(dom, n, rng, fixed, function(u, v) return 0.3 * hh / sqrt(dens(u, v)) end, dens)
  elseif kind == "pole9" or kind == "pole11" then
    local pts, hl = lattice_points(dom, n, rng, { jitter = 0.1 })
    return add_pole(dom, pts, pole_at, kind == "pole9" and 9 or 11, hl)
  end
  error("kind " .. tostring(kind))
end

-- Delaunay of the boundary points `fixed` and interior points `pts` in
-- the plane image img(u, v) -> x, y (the caller's conformal or stretched
-- map), keeping the triangles for which keep(tri) holds. Returns the
-- point list (fixed first) and the triangles.
local function triangulate(fixed, pts, img, keep)
  local all, plane = {}, {}
  for _, p in ipairs(fixed) do all[#all + 1] = p end
  for _, p in ipairs(pts) do all[#all + 1] = p end
  for i, p in ipairs(all) do plane[i] = { img(p[1], p[2]) } end
  local tris = {}
  for _, t in ipairs(M.delaunay(plane)) do
    if not keep or keep(t, all) then tris[#tris + 1] = t end
  end
  return all, tris
end

-- Refine a triangle list twice (or `times`) by edge midpoints in the plane
-- image: new points on a boundary edge (both ends in `isfixed`) are put
-- on the boundary by snap(x, y). pts are plane points here.
local function refine(pts, tris, nfixed, snap, times)
  local onb = {}
  for i = 1, nfixed do onb[i] = true end
  -- a boundary edge: both ends on the boundary and in one triangle only
  for _ = 1, times do
    local count = {}
    local function key(a, b) return a < b and a * 1000003 + b or b * 1000003 + a end
    for _, t in ipairs(tris) do
      for k = 1, 3 do
        local kk = key(t[k], t[k % 3 + 1])
        count[kk] = (count[kk] or 0) + 1
      end
    end
    local mid, nt = {}, {}
    local function m(a, b)
      local kk = key(a, b)
      if not mid[kk] then
        local x, y = (pts[a][1] + pts[b][1]) / 2, (pts[a][2] + pts[b][2]) / 2
        local bd = onb[a] and onb[b] and count[kk] == 1
        if bd then x, y = snap(x, y) end
        pts[#pts + 1] = { x, y }
        onb[#pts] = bd or nil
        mid[kk] = #pts
      end
      return mid[kk]
    end
    for _, t in ipairs(tris) do
      local a, b, c = t[1], t[2], t[3]
      local ab, bc, ca = m(a, b), m(b, c), m(c, a)
      nt[#nt + 1] = { a, ab, ca }; nt[#nt + 1] = { b, bc, ab }
      nt[#nt + 1] = { c, ca, bc }; nt[#nt + 1] = { ab, bc, ca }
    end
    tris = nt
  end
  return pts, tris, onb
end

-- Move every vertex without `fixed` (and not on a constraint) by amp in a
-- random direction.
local function perturb(t, amp, rng)
  for _, p in ipairs(t.vertices) do
    if not p.fixed and not p.constraint then
      local x, y, z
      repeat
        x, y, z = 2 * rng() - 1, 2 * rng() - 1, 2 * rng() - 1
      until x * x + y * y + z * z <= 1 and x * x + y * y + z * z > 0.01
      local l = sqrt(x * x + y * y + z * z)
      p[1], p[2], p[3] = p[1] + amp * x / l, p[2] + amp * y / l, p[3] + amp * z / l
    end
  end
end

local function seed_of(family, case, salt)
  local s = 0
  for i = 1, #family do s = s * 131 + family:byte(i) end
  return (s * 1000 + case + 7919 * (salt or 0)) % 2^52 + 12345
end

-- Disk surfaces (hemisphere, drops): unit disk, nrim boundary points,
-- nint interior, mapped by map(u, v, onrim) -> x, y, z.
local disk = {
  area = pi, bounds = { -1, 1, -1, 1 },
  inside = function(u, v, margin) return u * u + v * v < (1 - margin)^2 end,
}
local function disk_mesh(kind, nint, nrim, rng, map, pole_at, rimattr)
  local fixed = {}
  for i = 1, nrim do
    local a = 2 * pi * (i - 1) / nrim
    fixed[i] = { cos(a), sin(a) }
  end
  local pts, tris, onb
  if kind == "coarse" then
    local nc = math.max(8, math.floor(nrim / 4 + 0.5))
    local cfixed = {}
    for i = 1, nc do
      local a = 2 * pi * (i - 1) / nc
      cfixed[i] = { cos(a), sin(a) }
    end
    local inner = random_points(disk, math.max(4, nint // 16), rng, cfixed,
      function() return 0.5 * sqrt(pi / (nint / 16 * sqrt(3) / 2)) end)
    pts, tris = triangulate(cfixed, inner, function(u, v) return u, v end)
    pts, tris, onb = refine(pts, tris, nc, function(x, y)
      local l = sqrt(x * x + y * y); return x / l, y / l end, 2)
  elseif kind == "pyramid" then -- the 11-gon pyramid refined 3 times
    pts = { { 0, 0 } }
    tris = {}
    for i = 1, 11 do
      local a = 2 * pi * (i - 1) / 11
      pts[#pts + 1] = { cos(a), sin(a) }
      tris[#tris + 1] = { 1, 1 + i, 1 + i % 11 + 1 }
    end
    local on = {}
    for i = 2, 12 do on[i] = true end
    -- refine: mark the rim (indices 2..12) as the boundary
    local p2 = {}
    for i = 2, 12 do p2[#p2 + 1] = pts[i] end
    p2[#p2 + 1] = pts[1]
    local t2 = {}
    for _, t in ipairs(tris) do
      local f = function(k) return k == 1 and 12 or k - 1 end
      t2[#t2 + 1] = { f(t[1]), f(t[2]), f(t[3]) }
    end
    -- boundary midpoints stay on the polygon here, then every point is
    -- pushed radially from the polygon onto the disk
    pts, tris, onb = refine(p2, t2, 11, function(x, y) return x, y end, 3)
    local apo = cos(pi / 11)
    for _, p in ipairs(pts) do
      local r = sqrt(p[1]^2 + p[2]^2)
      if r > 0 then
        local a = math.atan(p[2], p[1]) % (2 * pi / 11) - pi / 11
        local rp = apo / cos(a) -- the polygon's radius in this direction
        local sc = (r / rp) / r
        p[1], p[2] = p[1] * sc, p[2] * sc
      end
    end
  else
    local inner = kind_points(disk, kind, nint, rng, fixed, pole_at)
    local img = function(u, v) return u, v end
    if kind == "aniso_r" then img = function(u, v) return 3 * u, v / 3 end end
    pts, tris = triangulate(fixed, inner, img)
    onb = {}
    for i = 1, nrim do onb[i] = true end
  end
  local V = {}
  for i, p in ipairs(pts) do
    local x, y, z = map(p[1], p[2], onb[i])
    V[i] = { x, y, z }
    if onb[i] then
      if rimattr then for k, v in pairs(rimattr) do V[i][k] = v end
      else V[i].fixed = true end
    end
  end
  return { vertices = V, facets = tris }
end

-- Cylinder surfaces (catenoid, cmc): (theta, z) in [0, 2 pi) x [z0, z1],
-- n fixed vertices per ring, triangulated in the conformal image.
local function cylinder_mesh(kind, n, nint, z0, z1, rng, caps)
  local dom = {
    area = 2 * pi * (z1 - z0), bounds = { 0, 2 * pi, z0, z1 }, period = 2 * pi,
    inside = function(_, z, margin) return z > z0 + margin and z < z1 - margin end,
  }
  local nr = kind == "coarse" and n // 4 or n
  local fixed = {}
  for j, z in ipairs { z0, z1 } do
    for i = 0, nr - 1 do fixed[#fixed + 1] = { 2 * pi * (i + 0.5 * (j - 1)) / nr, z } end
  end
  local stretch = kind == "aniso_r" and 3 or 1
  local img = function(th, z) local rho = exp(z * stretch); return rho * cos(th), rho * sin(th) end
  local keep = function(t) return t[1] > nr or t[2] > nr or t[3] > nr end -- not the hole
  local inner
  if kind == "coarse" then
    local hc = sqrt(dom.area / (nint / 16 * sqrt(3) / 2))
    inner = random_points(dom, math.max(4, nint // 16), rng, fixed, function() return 0.5 * hc end)
  elseif kind == "perturbed" then
    inner = kind_points(dom, "random", nint, rng, fixed)
  else
    inner = kind_points(dom, kind, nint, rng, fixed, { pi, (z0 + z1) / 2 })
  end
  local pts, tris = triangulate(fixed, inner, img, keep)
  local onb = {}
  for i = 1, 2 * nr do onb[i] = true end
  if kind == "coarse" then
    -- refine in the image of the unstretched map; ring midpoints go back
    -- onto their circle
    local plane = {}
    for i, p in ipairs(pts) do plane[i] = { img(p[1], p[2]) } end
    local r0, r1 = exp(z0), exp(z1)
    plane, tris, onb = refine(plane, tris, 2 * nr, function(x, y)
      local l = sqrt(x * x + y * y)
      local r = math.abs(l - r0) < math.abs(l - r1) and r0 or r1
      return x * r / l, y * r / l
    end, 2)
    pts = {}
    for i, q in ipairs(plane) do pts[i] = { math.atan(q[2], q[1]), log(sqrt(q[1]^2 + q[2]^2)) } end
  end
  local V, F = {}, {}
  for i, p in ipairs(pts) do
    V[i] = { cos(p[1]), sin(p[1]), p[2], fixed = onb[i] or nil }
  end
  for _, t in ipairs(tris) do F[#F + 1] = { t[1], t[3], t[2] } end
  if caps then -- fixed, tensionless end caps closing a body
    local ring = { {}, {} }
    for i = 1, #V do
      if V[i].fixed then
        local j = math.abs(V[i][3] - z0) < 1e-12 and 1 or 2
        ring[j][#ring[j] + 1] = i
      end
    end
    for j = 1, 2 do
      table.sort(ring[j], function(a, b) return math.atan(V[a][2], V[a][1]) < math.atan(V[b][2], V[b][1]) end)
      V[#V + 1] = { 0, 0, j == 1 and z0 or z1, fixed = true }
      local c = #V
      local rg = ring[j]
      for i = 1, #rg do
        local a, b = rg[i], rg[i % #rg + 1]
        F[#F + 1] = j == 1 and { c, b, a, tension = 0, fixed = true }
                           or { c, a, b, tension = 0, fixed = true }
      end
    end
  end
  return { vertices = V, facets = F }
end

-- Schwarz P: each face of the cube [-1,1]^3 with a hole of radius 0.5,
-- its interior points of this kind, pulled towards the centre.
local function schwarz_mesh(kind, rng, scale)
  local rho, h, shrink = 0.5, 0.16 * (scale or 1), 0.45
  local nc = math.floor((kind == "coarse" and 20 or 28) / (scale or 1) + 0.5)
  local ns = math.floor(2 / h + 0.5)
  local faces = {
    { {1,0,0}, {0,1,0}, {0,0,1} }, { {-1,0,0}, {0,0,1}, {0,1,0} },
    { {0,1,0}, {0,0,1}, {1,0,0} }, { {0,-1,0}, {1,0,0}, {0,0,1} },
    { {0,0,1}, {1,0,0}, {0,1,0} }, { {0,0,-1}, {0,1,0}, {1,0,0} } }
  local dom = {
    area = 4 - pi * rho * rho, bounds = { -1, 1, -1, 1 },
    inside = function(u, v, margin)
      return math.abs(u) < 1 - margin and math.abs(v) < 1 - margin and
             u * u + v * v > (rho + margin)^2
    end,
  }
  local nint = math.floor(dom.area / (h * h * sqrt(3) / 2) + 0.5)
  local V, F, index = {}, {}, {}
  local function vid(x, y, z, fixed)
    local key = ("%.9f %.9f %.9f"):format(x, y, z)
    if not index[key] then
      V[#V + 1] = { x, y, z, fixed = fixed or nil }
      index[key] = #V
    end
    return index[key]
  end
  for _, fa in ipairs(faces) do
    local fixed, circle = {}, {}
    for i = 1, nc do
      local a = 2 * pi * (i - 1) / nc
      fixed[#fixed + 1] = { rho * cos(a), rho * sin(a) }; circle[#fixed] = true
    end
    for s = 0, 3 do
      for i = 0, ns - 1 do
        local t = -1 + 2 * i / ns
        local u, v
        if s == 0 then u, v = t, -1 elseif s == 1 then u, v = 1, t
        elseif s == 2 then u, v = -t, 1 else u, v = -1, -t end
        fixed[#fixed + 1] = { u, v }
      end
    end
    local inner
    if kind == "coarse" then
      inner = (lattice_points(dom, nint, rng, { jitter = 0.02 }))
    elseif kind == "aniso_r" then
      -- Delaunay in stretched coordinates would not respect the hole:
      -- here a lattice stretched 6:1, turned by 1 radian, triangulated
      -- in the face's own coordinates
      inner = (lattice_points(dom, nint, rng, { stretch = sqrt(6), jitter = 0.05, rot = 1 }))
    elseif kind == "perturbed" then
      inner = kind_points(dom, "random", nint, rng, fixed)
    else
      inner = kind_points(dom, kind, nint, rng, fixed, { 0.62, 0.62 })
    end
    local img = function(u, v) return u, v end
    local pts, tris = triangulate(fixed, inner, img, function(t, all)
      local cu = (all[t[1]][1] + all[t[2]][1] + all[t[3]][1]) / 3
      local cv = (all[t[1]][2] + all[t[2]][2] + all[t[3]][2]) / 3
      return cu * cu + cv * cv > rho * rho
    end)
    local map = {}
    for i, p in ipairs(pts) do
      local x = fa[1][1] + p[1] * fa[2][1] + p[2] * fa[3][1]
      local y = fa[1][2] + p[1] * fa[2][2] + p[2] * fa[3][2]
      local z = fa[1][3] + p[1] * fa[2][3] + p[2] * fa[3][3]
      map[i] = vid(x, y, z, circle[i])
    end
    for _, t in ipairs(tris) do F[#F + 1] = { map[t[1]], map[t[2]], map[t[3]] } end
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

local function mean_edge_of(t)
  local s, n = 0, 0
  for _, f in ipairs(t.facets) do
    for k = 1, 3 do
      local a, b = t.vertices[f[k]], t.vertices[f[k % 3 + 1]]
      s = s + sqrt((a[1] - b[1])^2 + (a[2] - b[2])^2 + (a[3] - b[3])^2); n = n + 1
    end
  end
  return s / n
end

-- The experiment table (for common.lua's C.run) of case 1..10 of family;
-- salt (optional, a positive integer): another seed; size (optional, a
-- positive integer): the number of interior points instead of the
-- family's (309 hemisphere, 384 catenoid and CMC, 400 drops; Schwarz P
-- about 730, its spacing 0.16 scaled), with the border's vertex counts
-- scaled by the square root of the ratio, so that the border keeps its
-- spacing relative to the interior's (the name then ends in "_nSIZE").
-- Not for the hemisphere's coarse case (the 11-gon pyramid).
function G.experiment(family, case, salt, size)
  local kind = G.kinds[case] or error(("case %s: 1..%d expected"):format(tostring(case), G.cases))
  if salt ~= nil and (math.type(salt) ~= "integer" or salt < 1) then
    error(("salt %s: a positive integer expected"):format(tostring(salt)))
  end
  if size ~= nil and (math.type(size) ~= "integer" or size < 16) then
    error(("size %s: an integer of at least 16 expected"):format(tostring(size)))
  end
  if size and family == "hemisphere" and kind == "coarse" then
    error("size: not for the hemisphere's coarse case (the 11-gon pyramid)")
  end
  local rng = M.rng(seed_of(family, case, salt))
  local name = ("%s_%02d_%s"):format(family, case, kind) .. (salt and "_s" .. salt or "")
    .. (size and "_n" .. size or "")
  -- interior points and border vertices, scaled from the family's n0, b0
  local function sized(n0, b0)
    if not size then return n0, b0 end
    return size, math.max(3, math.floor(b0 * sqrt(size / n0) + 0.5))
  end
  local function finish(t)
    if kind == "perturbed" then perturb(t, 0.25 * mean_edge_of(t), rng) end
    return t
  end
  if family == "hemisphere" then
    return { name = name, target = "lambda", input = function()
      local ni, nb = sized(309, 41)
      local t = disk_mesh(kind == "coarse" and "pyramid" or kind, ni, nb, rng,
        M.cap_map(1, pi / 2), { 0, 0 })
      for _, f in ipairs(t.facets) do f.body = 1 end
      t.bodies = { { volume = 2 * pi / 3 } }
      return finish(t)
    end }
  elseif family == "catenoid" then
    return { name = name, target = 0, input = function()
      local ni, nb = sized(384, 48)
      return finish(cylinder_mesh(kind, nb, ni, -0.5, 0.5, rng))
    end }
  elseif family == "cmc" then
    local vol = ({ 2.6, pi, 3.8 })[(case - 1) % 3 + 1]
    return { name = name, target = "lambda", input = function()
      local ni, nb = sized(384, 48)
      local t = cylinder_mesh(kind, nb, ni, -0.5, 0.5, rng, true)
      for _, f in ipairs(t.facets) do f.body = 1 end
      t.bodies = { { volume = vol } }
      return finish(t)
    end }
  elseif family == "schwarz_p" then
    return { name = name, target = 0, input = function()
      return finish(schwarz_mesh(kind, rng, size and sqrt(730 / size)))
    end }
  elseif family == "drop" and case % 2 == 1 then -- pendant (pendant.tds)
    local a, R = 2.5, 2.8
    local thmax = pi - math.asin(a / R)
    return { name = name, target = "pressure",
      model = function() gravity_constant(9.806) end,
      input = function()
        local cap = M.cap_map(R, thmax)
        local zr = R * cos(thmax)
        local ni, nb = sized(400, 35)
        local t = disk_mesh(kind, ni, nb, rng, function(u, v, rim)
          local x, y, z = cap(u, v)
          return x, y, rim and 0 or zr - z
        end, { 0.3, 0 })
        for _, f in ipairs(t.facets) do f[2], f[3] = f[3], f[2]; f.body = 1 end
        t.bodies = { { volume = 75, density = 998 / 0.073 * 1e-6 } }
        return finish(t)
      end }
  elseif family == "drop" then -- sessile (sessile.tds)
    local theta = 3 * pi / 4
    local R = (100 * 3 / (pi * (2 - 3 * cos(theta) + cos(theta)^3)))^(1 / 3)
    return { name = name, target = "pressure", has_constraint = true,
      model = function()
        parameter { angle = 135 }
        constraint(1, { formula = "z = 0", energy = { "-(-cos(angle*pi/180)*y)", "0", "0" } })
        gravity_constant(9.806)
      end,
      fe_header = [[
PARAMETER angle = 135
constraint 1
formula: z = 0
energy:
e1: -(-cos(angle*pi/180)*y)
e2: 0
e3: 0]],
      input = function()
        local zc = -R * cos(theta)
        local cap = M.cap_map(R, theta, zc)
        local ni, nb = sized(400, 37)
        local t = disk_mesh(kind, ni, nb, rng, function(u, v, rim)
          local x, y, z = cap(u, v)
          return x, y, rim and 0 or z
        end, { 0.3, 0 }, { constraint = 1 })
        for _, f in ipairs(t.facets) do f.body = 1 end
        t.bodies = { { volume = 100, density = 998 / 0.073 * 1e-6 } }
        return finish(t)
      end }
  end
  error("family " .. tostring(family) .. ": " .. table.concat(G.families, ", ") .. " expected")
end

return G
