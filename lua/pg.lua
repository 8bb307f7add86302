-- pg.lua: the projected-gradient method and the paper's metrics, friendly
-- names over the raw primitives of src/lua_pg.c. Requiring it defines the
-- globals pg, projected_gradient, quality, curvature, write_fe, trimesh and
-- the element attributes v.mean_curvature and f.min_angle.
-- See doc/method.md and doc/metrics.md.

local tds = tds

local function opts_of(arg, name)
  if arg == nil then return {} end
  if math.type(arg) == "integer" then
    if arg < 1 then error(name .. "(n): n must be at least 1", 3) end
    return { iterations = arg }
  end
  if type(arg) == "table" then return arg end
  error(name .. "(n) or " .. name .. "{ options } expected", 3)
end

-- pg(n): n iterations. pg(): until the termination criterion. pg{...}:
-- options iterations, max, nmax, s, plain, depth, flips, every, rtol,
-- threads, newton, probe, calm, momentum, momentum_size.
-- Returns { iterations, r, flips, lambda, energy, converged, ... }.
local PG_KEYS = { iterations = "number", n = "number", max = "number", nmax = "number",
  s = "number", plain = "boolean", depth = "number", flips = "boolean", every = "number",
  rtol = "number", threads = "number", newton = "boolean", probe = "boolean",
  calm = "boolean", momentum = "number", momentum_size = "number" }
function pg(arg)
  local o = opts_of(arg, "pg")
  tds.check_options(o, "pg", PG_KEYS, 2)
  local t = {}
  for k, v in pairs(o) do t[k] = v end
  if t.n and not t.iterations then t.iterations = t.n; t.n = nil end
  return tds.pg(t)
end
projected_gradient = pg

-- pg_polish{ rounds = 2, steps = 30, min_angle = degrees }: the curvature
-- polish after pg() (doc/method.md, Curvature polish): tangential steps
-- that make |grad V_i| equal Meyer's mixed area at every vertex, never
-- taking a facet's smallest angle below min_angle (default: the mesh's
-- smallest angle now) nor the mean smallest angle down by more than
-- max_loss degrees (default 1), each round followed by plain pg with no tangential
-- step (s = 0, no flips) to restore the normal equilibrium and the volumes.
-- Returns { phi0, phi, moved, iterations, r, r_relative, converged,
-- cpu_seconds }.
local POLISH_KEYS = { rounds = "number", steps = "number", min_angle = "number",
  max_loss = "number", max = "number" }
local function polish_rounds(rounds, steps, floor, mfloor, max)
  local out = { iterations = 0, converged = true }
  local c0 = os.clock()
  for round = 1, rounds do
    local p0, p1, n = tds.pg_polish(steps, floor, mfloor)
    if round == 1 then out.phi0 = p0 end
    out.phi, out.moved = p1, n
    -- Anderson mixing without Newton's preconditioning: with no
    -- tangential step the map's tangential modes are null, and the
    -- measured Jacobian is singular
    local r = tds.pg { s = 0, newton = false, probe = false, flips = false,
                       every = -1, max = max or 20000 }
    out.iterations = out.iterations + r.iterations
    out.r, out.r_relative, out.converged = r.r, r.r_relative, r.converged
    if not r.converged then break end
  end
  if rounds == 0 then out.phi0, out.phi, out.moved = tds.pg_polish(0, floor, mfloor) end
  out.cpu_seconds = os.clock() - c0
  return out
end

function pg_polish(o)
  o = o or {}
  if type(o) ~= "table" then error("pg_polish{ rounds =, steps =, min_angle =, max = } expected", 2) end
  tds.check_options(o, "pg_polish", POLISH_KEYS, 2)
  local rounds = o.rounds or 1
  local steps = o.steps or 20
  for _, k in ipairs { "rounds", "steps" } do
    local v = o[k] or 1
    if math.type(v) ~= "integer" or v < 0 then
      error(("pg_polish: option '%s' must be a whole number, 0 or more"):format(k), 2)
    end
  end
  -- refused, not silently read as something else: a NaN or out-of-range
  -- angle (the floor never binds, or always does), a negative max (pg's
  -- default cap)
  local function real(k, lo, hi)
    local v = o[k]
    if v ~= nil and not (v >= lo and v <= hi) then
      error(("pg_polish: option '%s' must be a number in [%g, %g], not %s"):format(k, lo, hi, v ~= v and "NaN" or tostring(v)), 3)
    end
  end
  real("min_angle", 0, 60)
  real("max_loss", 0, 60)
  if o.max ~= nil and (math.type(o.max) ~= "integer" or o.max < 1) then
    error("pg_polish: option 'max' must be a whole number, 1 or more", 2)
  end
  local q = tds.quality()
  local floor = o.min_angle or q.min
  if floor ~= floor then floor = 0 end
  local mfloor = q.mean == q.mean and q.mean - (o.max_loss or 1) or 0
  -- all or nothing: a round whose pg fails puts the surface back as it was
  local snap = tds.check_snapshot()
  local ok, out = pcall(function()
    return polish_rounds(rounds, steps, floor, mfloor, o.max)
  end)
  if not ok then
    tds.check_restore(snap)
    error(out, 0)
  end
  tds.check_release(snap)
  return out
end


local function pct(x) return ("%5.1f%%"):format(x) end

-- quality(): smallest facet angles; prints a table unless quality{quiet=true}.
-- quality{ png = "angles.png", size = {w, h} } also draws the histogram.
function quality(o)
  o = o or {}
  if type(o) ~= "table" then error("quality{ quiet =, png =, size = } expected", 2) end
  for k in pairs(o) do
    if k ~= "quiet" and k ~= "png" and k ~= "size" then
      error(("quality: option '%s' is unknown"):format(tostring(k)), 2)
    end
  end
  local q = tds.quality()
  if o.png ~= nil then
    if type(o.png) ~= "string" then error("quality: option 'png' must be a file name", 2) end
    q.picture = tds.histogram_png(o.png, q.histogram, 0, 60,
      ("Smallest angle of %d facets"):format(q.n), "degrees", { size = o.size })
  end
  if not o.quiet then
    print(("Mesh quality: smallest angle of %d facets"):format(q.n))
    if q.n > 0 then
      print(("  min %.2f  mean %.2f  std %.2f (degrees)"):format(q.min, q.mean, q.std))
      print(("  above 30: %s  40: %s  50: %s  55: %s"):format(
        pct(q.above30), pct(q.above40), pct(q.above50), pct(q.above55)))
      local most = 1
      for i = 1, 12 do most = math.max(most, q.histogram[i]) end
      for i = 1, 12 do
        local c = q.histogram[i]
        print(("  [%2d,%2d%s %6d %s"):format(5 * (i - 1), 5 * i, i == 12 and "]" or ")",
          c, ("#"):rep(math.floor(40 * c / most + 0.5))))
      end
    end
  end
  return q
end

-- curvature{ target = number | "lambda" | "pressure", measure = "meyer" |
-- "normal" }: Meyer et al. mean curvature (k1 + k2) at every measured
-- vertex and its error: by default |K| with the sign of K . n (the paper's),
-- measure = "normal" K . n. Both measures' statistics are in c.meyer and
-- c.normal, their RMS by valence in c.by_valence.
-- Default target: "pressure" when there are bodies, else 0.
function curvature(o)
  o = o or {}
  if type(o) == "number" or type(o) == "string" then o = { target = o } end
  if type(o) ~= "table" then error("curvature([target | { target =, quiet =, measure = }]) expected", 2) end
  tds.check_options(o, "curvature", { target = "number|string", quiet = "boolean",
    measure = "string" }, 2)
  local target = o.target
  if target == nil then target = (tds.count(tds.body) > 0) and "pressure" or 0 end
  local measure = o.measure or "meyer"
  if measure ~= "meyer" and measure ~= "normal" then
    error('curvature{ measure = "meyer" | "normal" } expected', 2)
  end
  local c
  if type(target) == "number" then
    c = tds.curvature("value", target, measure)
  elseif target == "lambda" or target == "pressure" then
    c = tds.curvature(target, 0, measure)
  else
    error('curvature{ target = number | "lambda" | "pressure" } expected', 2)
  end
  c.target = target
  if not o.quiet then
    print(("Mean curvature (Meyer et al., k1+k2) at %d vertices, target %s"):format(
      c.n, tostring(target)))
    if c.n > 0 then
      for _, k in ipairs { "meyer", "normal" } do
        local s = c[k]
        print(("  %-6s mean k1+k2 %.10g   error max %.3e  mean %.3e  rms %.3e%s"):format(
          k == "meyer" and "|K|" or "K.n", s.mean_curvature, s.max, s.mean, s.rms,
          k == measure and "  *" or ""))
      end
      local parts = {}
      for val, g in pairs(c.by_valence) do parts[#parts + 1] = val end
      table.sort(parts)
      for i, val in ipairs(parts) do
        local g = c.by_valence[val]
        parts[i] = ("%d: %d, %.2e/%.2e"):format(val, g.n, g.rms_meyer, g.rms_normal)
      end
      print("  rms |K|/K.n by valence: " .. table.concat(parts, "; "))
      print(("  worst vertex %d: k1+k2 %.10g, target %.10g"):format(
        c.worst, c.worst_value, c.worst_target))
    end
  end
  return c
end

-- Element attributes computed on demand: v.mean_curvature (K . n),
-- v.meyer_curvature (signed |K|), f.min_angle.
tds.props.vertex.mean_curvature = function(h) return tds.vertex_mean_curvature(h) end
tds.props.vertex.meyer_curvature = function(h) return tds.vertex_meyer_curvature(h) end
tds.props.facet.min_angle = function(h) return tds.facet_min_angle(h) end

-- trimesh{ vertices = {...}, facets = {...}, bodies = {...} }: declare a
-- surface from a triangle list. vertices[i] = { x, y, z, fixed = bool,
-- constraint = n }; facets[i] = { a, b, c, tension = t, fixed = bool,
-- body = b (front), backbody = b }; bodies[i] = { volume = V, density = d }.
-- Edges are made for every vertex pair; an edge of one facet whose ends
-- are both fixed is fixed, and one whose ends share a constraint is on it.
function trimesh(t)
  if type(t) ~= "table" then error("trimesh{ vertices = ..., facets = ... } expected", 2) end
  local V, F = t.vertices or error("trimesh{}: vertices expected", 2), t.facets or {}
  if type(V) ~= "table" or type(F) ~= "table" then
    error("trimesh{}: vertices and facets must be lists", 2)
  end
  local vdecl = {}
  for i, p in ipairs(V) do
    vdecl[i] = { p[1], p[2], p[3], fixed = p.fixed or nil, constraint = p.constraint }
  end
  vertices(vdecl)
  local key = function(a, b) return a < b and (a * 1000003 + b) or (b * 1000003 + a) end
  local eid, ends, count, edecl = {}, {}, {}, {}
  for _, f in ipairs(F) do
    for k = 1, 3 do
      local a, b = f[k], f[k % 3 + 1]
      local kk = key(a, b)
      if not eid[kk] then
        edecl[#edecl + 1] = { a, b }
        eid[kk] = #edecl
      end
      count[kk] = (count[kk] or 0) + 1
    end
  end
  for kk, e in pairs(eid) do
    local d = edecl[e]
    local va, vb = V[d[1]], V[d[2]]
    if count[kk] == 1 then
      if va.fixed and vb.fixed then d.fixed = true end
      if va.constraint and va.constraint == vb.constraint and not d.fixed then
        d.constraint = va.constraint
      end
    end
  end
  edges(edecl)
  local fdecl = {}
  for i, f in ipairs(F) do
    local loop = {}
    for k = 1, 3 do
      local a, b = f[k], f[k % 3 + 1]
      local e = eid[key(a, b)]
      loop[k] = (edecl[e][1] == a) and e or -e
    end
    loop.tension = f.tension
    loop.fixed = f.fixed or nil
    fdecl[i] = loop
  end
  faces(fdecl)
  if t.bodies then
    local bdecl = {}
    for b, bd in ipairs(t.bodies) do
      local list = {}
      for i, f in ipairs(F) do
        if f.body == b then list[#list + 1] = i end
        if f.backbody == b then list[#list + 1] = -i end
      end
      list.volume = bd.volume
      list.density = bd.density
      bdecl[b] = list
    end
    bodies(bdecl)
  end
end

-- write_fe(path, { header = text, read = text }): the current surface as a
-- Surface Evolver datafile: header first (parameters, constraint
-- declarations in Evolver syntax), then the gravity constant and the
-- elements exactly as dump writes them (tds.write_fe, src/dump.c: one
-- writer), then the read section. Written all or nothing; a failure is an
-- error at the caller's line.
function write_fe(path, o)
  if type(path) ~= "string" then error("write_fe(path [, options]): path must be a string", 2) end
  o = o or {}
  local ok, err = tds.write_fe(path, o.header, o.read)
  if not ok then error(err, 2) end
end

return true
