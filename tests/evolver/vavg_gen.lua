-- vavg_gen.lua: seeded random datafiles for tests/evolver/vavg.sh, loaded
-- with dofile() from a tds -e chunk. Each writes many independent
-- patches into one datafile: a free vertex with fixed neighbours, so
-- every free vertex's move under V depends only on its own patch.
--   stars(path, seed, zs): closed fans of 3..8 facets around a vertex
--     (zs: height spread; 1 folds some fans over, where the order in which
--     V sums the facet normals shows);
--   fans(path, seed): open fans of 1..5 facets (the vertex on a border);
--   triples(path, seed): a vertex on a triple line of three fins;
--   contact(path, seed): vertices on a plane and on a sphere constraint,
--     with their facets on it or not (a contact line), or some on it (a
--     film standing on a triangulated floor).

local origin, centre = {0, 0}, {0, 0, 0}
-- the patch about to be written starts at (ox, oy): with KLEIN, pick its
-- place in the ball
local function patch(ox, oy)
  origin = {ox, oy or 0}
  if not KLEIN then return end
  repeat
    centre = {1.2 * math.random() - .6, 1.2 * math.random() - .6, 1.2 * math.random() - .6}
  until centre[1]^2 + centre[2]^2 + centre[3]^2 < .6^2
end

local function writer(path, top)
  local V, E, F = {}, {}, {}
  local index = {}
  if KLEIN then top = "KLEIN_METRIC\n" .. (top or "") end
  local function vertex(x, y, z, extra)
    if KLEIN then
      x, y, z = centre[1] + .15 * (x - origin[1]), centre[2] + .15 * (y - origin[2]), centre[3] + .15 * z
    end
    V[#V + 1] = ("%d %.17g %.17g %.17g %s"):format(#V + 1, x, y, z, extra or "")
    return #V
  end
  local function edge(a, b, extra)
    local k = a .. ":" .. b
    if index[k] then return index[k] end
    local r = index[b .. ":" .. a]
    if r then return -r end
    E[#E + 1] = ("%d %d %d %s"):format(#E + 1, a, b, extra or "")
    index[k] = #E
    return #E
  end
  local function facet(a, b, c, extra, eextra)
    local e = eextra or {}
    F[#F + 1] = ("%d %d %d %d %s"):format(#F + 1, edge(a, b, e[1]), edge(b, c, e[2]),
      edge(c, a, e[3]), extra or "")
  end
  local function close()
    local f = assert(io.open(path, "w"))
    f:write(top or "", "\nvertices\n", table.concat(V, "\n"), "\nedges\n",
      table.concat(E, "\n"), "\nfaces\n", table.concat(F, "\n"), "\n")
    f:close()
  end
  return vertex, edge, facet, close
end

local function uniform(a, b) return a + (b - a) * math.random() end

function stars(path, seed, zs)
  math.randomseed(seed)
  local vertex, _, facet, close = writer(path)
  for k = 1, 40 do
    local n = math.random(3, 8)
    local ox, oy = 4 * (k % 8), 4 * (k // 8)
    patch(ox, oy)
    local c = vertex(ox + uniform(-.3, .3), oy + uniform(-.3, .3), uniform(-zs, zs))
    local rim = {}
    for i = 0, n - 1 do
      local t, r = 2 * math.pi * i / n + uniform(-.3, .3), uniform(.6, 1.4)
      rim[#rim + 1] = vertex(ox + r * math.cos(t), oy + r * math.sin(t), uniform(-zs, zs), "fixed")
    end
    for i = 1, n do facet(c, rim[i], rim[i % n + 1]) end
  end
  close()
end

function fans(path, seed)
  math.randomseed(seed)
  local vertex, _, facet, close = writer(path)
  for k = 1, 30 do
    local n = (k - 1) % 5 + 1
    local ox = 4 * k
    patch(ox)
    local c = vertex(ox + uniform(-.2, .2), uniform(-.2, .2), uniform(-.2, .2))
    local nb = {}
    for j = 0, n do
      local a = math.pi * j / n * 0.9 + uniform(-.2, .2)
      nb[#nb + 1] = vertex(ox + math.cos(a), math.sin(a), uniform(-.3, .3), "fixed")
    end
    for j = 1, n do facet(c, nb[j], nb[j + 1]) end
  end
  close()
end

function triples(path, seed)
  math.randomseed(seed)
  local vertex, _, facet, close = writer(path)
  for k = 1, 20 do
    local ox = 5 * k
    patch(ox)
    local c = vertex(ox + uniform(-.2, .2), uniform(-.2, .2), uniform(-.2, .2))
    local t1 = vertex(ox - 1 + uniform(-.4, .4), uniform(-.4, .4), uniform(-.4, .4), "fixed")
    local t2 = vertex(ox + 1.5 + uniform(-.4, .4), uniform(-.4, .4), uniform(-.4, .4), "fixed")
    for _, a in ipairs { 0, 2.1, 4.2 } do
      local dy, dz = math.cos(a), math.sin(a)
      local function j() return uniform(-.2, .2) end
      local p = vertex(ox - 1 + j(), dy + j(), dz + j(), "fixed")
      local q = vertex(ox + j(), 1.1 * dy + j(), 1.1 * dz + j(), "fixed")
      local r = vertex(ox + 1.5 + j(), dy + j(), dz + j(), "fixed")
      facet(t1, c, p); facet(c, q, p); facet(c, r, q); facet(c, t2, r)
    end
  end
  close()
end

function contact(path, seed)
  math.randomseed(seed)
  local top = "constraint 1\nformula: z = 0\n\nconstraint 2\nformula: x^2 + y^2 + z^2 = 100\n"
  local vertex, _, facet, close = writer(path, top)
  local function sv(x, y, extra, dz) -- a vertex on (or dz inside) the sphere
    return vertex(x, y, math.sqrt(100 - x * x - y * y) - (dz or 0), extra)
  end
  for k = 1, 12 do
    local ox = 1.2 * k - 7.8 -- patches overlap in space: no matter
    -- a contact line on the plane z = 0: the vertex and two neighbours on
    -- it, edges along it on the constraint, the film rising above
    local c = vertex(ox + uniform(-.2, .2), uniform(-.2, .2), 0, "constraint 1")
    local a = vertex(ox - 1, uniform(-.2, .2), 0, "fixed constraint 1")
    local b = vertex(ox + 1, uniform(-.2, .2), 0, "fixed constraint 1")
    local up = {}
    for i = 1, 3 do
      up[i] = vertex(ox - 1 + 0.5 * i + uniform(-.2, .2), uniform(-.2, .3), uniform(.6, 1.2), "fixed")
    end
    facet(c, a, up[1], nil, { "constraint 1" })
    facet(c, up[1], up[2]); facet(c, up[2], up[3])
    facet(c, up[3], b, nil, { nil, nil, "constraint 1" })
    -- the same on the sphere of radius 10 (a curved contact line)
    local sy = 3
    local c2 = sv(ox + uniform(-.2, .2), sy + uniform(-.2, .2), "constraint 2")
    local a2 = sv(ox - 1, sy + uniform(-.2, .2), "fixed constraint 2")
    local b2 = sv(ox + 1, sy + uniform(-.2, .2), "fixed constraint 2")
    local u2 = {}
    for i = 1, 3 do
      u2[i] = sv(ox - 1 + 0.5 * i + uniform(-.2, .2), sy + uniform(.6, 1.2), "fixed", uniform(.3, .8))
    end
    facet(c2, a2, u2[1], nil, { "constraint 2" })
    facet(c2, u2[1], u2[2]); facet(c2, u2[2], u2[3])
    facet(c2, u2[3], b2, nil, { nil, nil, "constraint 2" })
    -- a star lying on the sphere, its facets on the constraint too
    local sy3 = -3
    local c3 = sv(ox + uniform(-.3, .3), sy3 + uniform(-.3, .3), "constraint 2")
    local n = math.random(4, 7)
    local rim = {}
    for i = 0, n - 1 do
      local t, r = 2 * math.pi * i / n + uniform(-.3, .3), uniform(.6, 1.2)
      rim[#rim + 1] = sv(ox + r * math.cos(t), sy3 + r * math.sin(t), "fixed constraint 2")
    end
    for i = 1, n do facet(c3, rim[i], rim[i % n + 1], "constraint 2",
      { "constraint 2", "constraint 2", "constraint 2" }) end
    -- a film standing on a floor that is triangulated on constraint 1:
    -- the vertex at its foot has facets on the constraint and off it
    local c4 = vertex(ox + uniform(-.2, .2), 5 + uniform(-.1, .1), 0, "constraint 1")
    local a4 = vertex(ox - 1, 5 + uniform(-.1, .1), 0, "fixed constraint 1")
    local b4 = vertex(ox + 1, 5 + uniform(-.1, .1), 0, "fixed constraint 1")
    local f1 = vertex(ox - .5 + uniform(-.2, .2), 4 + uniform(-.2, .2), 0, "fixed constraint 1")
    local f2 = vertex(ox + .5 + uniform(-.2, .2), 4 + uniform(-.2, .2), 0, "fixed constraint 1")
    local w1 = vertex(ox - .5 + uniform(-.2, .2), 5 + uniform(0, .3), 1 + uniform(-.2, .2), "fixed")
    local w2 = vertex(ox + .5 + uniform(-.2, .2), 5 + uniform(0, .3), 1 + uniform(-.2, .2), "fixed")
    local on = { "constraint 1", "constraint 1", "constraint 1" }
    facet(c4, f1, a4, "constraint 1", on); facet(c4, f2, f1, "constraint 1", on)
    facet(c4, b4, f2, "constraint 1", on)
    facet(c4, a4, w1); facet(c4, w1, w2); facet(c4, w2, b4)
  end
  close()
end
