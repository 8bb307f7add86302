-- foam.lua: seeded 2-D foams in the string model, written as datafiles
-- that Evolver and tds both read (tests/evolver/foam.sh, bench/string.sh).
--   voronoi_fe(n, seed): the Voronoi diagram of n random points (a
--     seeded linear congruential generator, the same numbers everywhere)
--     in the unit square, clipped to it. Every cell is a body whose area
--     is held at its Voronoi area (unless all its corners are fixed, and
--     but the last, whose area the fixed square decides); the walls on the square's sides and
--     their ends are fixed. Returns the text and the number of cells.
--   honeycomb_fe(nx, ny, jitter, seed): nx x ny hexagons of side 1 (odd
--     rows shifted), the vertices where fewer than three cells meet fixed,
--     the others moved by up to jitter in x and y; every cell a body with
--     the regular hexagon's area held (but the last: the fixed outline
--     decides it).
local M = {}

-- x' = (a x + c) mod 2^31, as floats in [0, 1): exact in doubles.
local function lcg(seed)
  local x = seed % 2147483648
  return function()
    x = (1103515245 * x + 12345) % 2147483648
    return x / 2147483648
  end
end

-- Clip polygon P (list of {x, y}) to the half-plane a x + b y <= c.
local function clip(P, a, b, c)
  local out = {}
  for i = 1, #P do
    local p, q = P[i], P[i % #P + 1]
    local fp, fq = a * p[1] + b * p[2] - c, a * q[1] + b * q[2] - c
    if fp <= 0 then out[#out + 1] = p end
    if (fp < 0 and fq > 0) or (fp > 0 and fq < 0) then
      local t = fp / (fp - fq)
      out[#out + 1] = {p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2])}
    end
  end
  return out
end

-- Vertices deduplicated by position (1e-9), edges by their two ends; a
-- cell's loop as signed edge ids. fixed(x, y) says whether a vertex is
-- fixed, fixed_edge(a, b) whether a wall is.
local function mesh()
  local m = {verts = {}, vid = {}, edges = {}, eid = {}, cells = {}}
  function m.vertex(x, y)
    local k = ("%.9f %.9f"):format(x, y):gsub("%-(0%.0+) ", "%1 "):gsub("%-(0%.0+)$", "%1")
    if not m.vid[k] then m.verts[#m.verts + 1] = {x, y, n = 0}; m.vid[k] = #m.verts end
    return m.vid[k]
  end
  function m.cell(ids, area)
    local loop = {}
    for i = 1, #ids do
      local a, b = ids[i], ids[i % #ids + 1]
      if a ~= b then
        local key = math.min(a, b) .. " " .. math.max(a, b)
        if not m.eid[key] then
          m.edges[#m.edges + 1] = {a, b, n = 0}
          m.eid[key] = #m.edges
        end
        local e = m.eid[key]
        m.edges[e].n = m.edges[e].n + 1
        loop[#loop + 1] = m.edges[e][1] == a and e or -e
      end
    end
    m.cells[#m.cells + 1] = {loop = loop, area = area}
  end
  function m.text(vfixed)
    local L = {"STRING", "SPACE_DIMENSION 2", "", "vertices"}
    local valence = {}
    for _, e in ipairs(m.edges) do
      for k = 1, 2 do valence[e[k]] = (valence[e[k]] or 0) + 1 end
    end
    for i, v in ipairs(m.verts) do
      L[#L + 1] = ("%d %.17g %.17g%s"):format(i, v[1], v[2], vfixed(i, v, valence[i]) and " fixed" or "")
    end
    L[#L + 1] = "edges"
    for i, e in ipairs(m.edges) do
      local fx = e.n == 1 and vfixed(e[1], m.verts[e[1]], valence[e[1]]) and
                 vfixed(e[2], m.verts[e[2]], valence[e[2]])
      L[#L + 1] = ("%d %d %d%s"):format(i, e[1], e[2], fx and " fixed" or "")
    end
    L[#L + 1] = "faces"
    for i, c in ipairs(m.cells) do L[#L + 1] = i .. " " .. table.concat(c.loop, " ") end
    L[#L + 1] = "bodies"
    for i, c in ipairs(m.cells) do
      -- a cell with no free corner cannot hold an area (its constraint
      -- would have no gradient): a body without a target
      local free = false
      for _, oe in ipairs(c.loop) do
        local e = m.edges[math.abs(oe)]
        for k = 1, 2 do free = free or not vfixed(e[k], m.verts[e[k]], valence[e[k]]) end
      end
      -- the last cell's area follows from the others' when the walls
      -- around the cluster are fixed (the areas sum to a constant)
      if m.closed and i == #m.cells then free = false end
      L[#L + 1] = free and ("%d %d volume %.17g"):format(i, i, c.area) or ("%d %d"):format(i, i)
    end
    return table.concat(L, "\n") .. "\n"
  end
  return m
end

local function polyarea(P)
  local a = 0
  for i = 1, #P do
    local p, q = P[i], P[i % #P + 1]
    a = a + p[1] * q[2] - q[1] * p[2]
  end
  return a / 2
end

function M.voronoi_fe(n, seed)
  local rnd = lcg(seed)
  local pts = {}
  for i = 1, n do pts[i] = {rnd(), rnd()} end
  local m = mesh()
  for i, p in ipairs(pts) do
    local P = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}
    for j, q in ipairs(pts) do
      if j ~= i then
        local a, b = q[1] - p[1], q[2] - p[2]
        P = clip(P, a, b, (q[1] * q[1] + q[2] * q[2] - p[1] * p[1] - p[2] * p[2]) / 2)
      end
    end
    local ids = {}
    for k, v in ipairs(P) do ids[k] = m.vertex(v[1], v[2]) end
    m.cell(ids, polyarea(P))
  end
  m.closed = true
  local function on_side(v) return v[1] < 1e-12 or v[1] > 1 - 1e-12 or v[2] < 1e-12 or v[2] > 1 - 1e-12 end
  return m.text(function(_, v) return on_side(v) end), #m.cells
end

function M.honeycomb_fe(nx, ny, jitter, seed)
  local rnd = lcg(seed)
  local s3 = math.sqrt(3)
  local m = mesh()
  for j = 0, ny - 1 do
    for i = 0, nx - 1 do
      local cx, cy = s3 * i + (j % 2) * s3 / 2, 1.5 * j
      local ids = {}
      for k = 0, 5 do
        local t = math.pi / 6 + k * math.pi / 3
        ids[#ids + 1] = m.vertex(cx + math.cos(t), cy + math.sin(t))
      end
      m.cell(ids, 3 * s3 / 2)
    end
  end
  local count = {}
  for _, c in ipairs(m.cells) do
    for _, oe in ipairs(c.loop) do
      local e = m.edges[math.abs(oe)]
      local v = oe > 0 and e[1] or e[2]
      count[v] = (count[v] or 0) + 1
    end
  end
  for i, v in ipairs(m.verts) do
    local dx, dy = (rnd() - 0.5) * 2 * jitter, (rnd() - 0.5) * 2 * jitter
    if count[i] == 3 then v[1], v[2] = v[1] + dx, v[2] + dy end
  end
  m.closed = true
  return m.text(function(i) return count[i] < 3 end), #m.cells
end

return M
