-- kelvin_gen.lua: writes kelvin.fe (stdout), one Kelvin cell (truncated
-- octahedron, the Voronoi cell of the body-centred cubic lattice) in the
-- torus of the bcc lattice's primitive periods (a skew cell of volume 1/2),
-- its six vertices moved by a seeded pseudo-random walk so that the file is
-- not symmetric. Run: tds -q kelvin_gen.lua > kelvin.fe
local P = {{-0.5, 0.5, 0.5}, {0.5, -0.5, 0.5}, {0.5, 0.5, -0.5}}
local function lat(x) return {x[2] + x[3], x[1] + x[3], x[1] + x[2]} end -- x = sum s_i P_i
local function key(x) return ("%.6f %.6f %.6f"):format(x[1] + 0, x[2] + 0, x[3] + 0) end

-- the 24 corners: permutations of (0, +-1/4, +-1/2)
local corners = {}
for z = 1, 3 do
  for h = 1, 3 do
    if h ~= z then
      local q = 6 - z - h
      for _, a in ipairs {-0.5, 0.5} do
        for _, b in ipairs {-0.25, 0.25} do
          local x = {0, 0, 0}
          x[h], x[q] = a, b
          corners[#corners + 1] = x
        end
      end
    end
  end
end

-- faces kept (the others are their translates, reversed): squares x_i = 1/2,
-- hexagons s . x = 3/4 with s_1 = 1; corners ordered anticlockwise seen
-- from outside
local faces = {}
local function face(normal, on)
  local pts, c = {}, {0, 0, 0}
  for _, x in ipairs(corners) do
    if on(x) then
      pts[#pts + 1] = x
      for i = 1, 3 do c[i] = c[i] + x[i] end
    end
  end
  for i = 1, 3 do c[i] = c[i] / #pts end
  local u = {pts[1][1] - c[1], pts[1][2] - c[2], pts[1][3] - c[3]}
  local w = {normal[2] * u[3] - normal[3] * u[2], normal[3] * u[1] - normal[1] * u[3],
             normal[1] * u[2] - normal[2] * u[1]}
  local function ang(x)
    local d = {x[1] - c[1], x[2] - c[2], x[3] - c[3]}
    return math.atan(d[1] * w[1] + d[2] * w[2] + d[3] * w[3], d[1] * u[1] + d[2] * u[2] + d[3] * u[3])
  end
  table.sort(pts, function(a, b) return ang(a) < ang(b) end)
  faces[#faces + 1] = pts
end
for i = 1, 3 do
  local n = {0, 0, 0}
  n[i] = 1
  face(n, function(x) return math.abs(x[i] - 0.5) < 1e-9 end)
end
for _, s2 in ipairs {-1, 1} do
  for _, s3 in ipairs {-1, 1} do
    face({1, s2, s3}, function(x) return math.abs(x[1] + s2 * x[2] + s3 * x[3] - 0.75) < 1e-9 end)
  end
end

-- torus vertices: each corner reduced into the cell {sum s_i P_i, 0 <= s_i < 1}
local verts, vid = {}, {}
local function reduce(x)
  local s = lat(x)
  local n = {}
  for i = 1, 3 do n[i] = math.floor(s[i] + 1e-9) end
  local r = {}
  for j = 1, 3 do r[j] = x[j] - n[1] * P[1][j] - n[2] * P[2][j] - n[3] * P[3][j] end
  local k = key(r)
  if not vid[k] then
    verts[#verts + 1] = r
    vid[k] = #verts
  end
  return vid[k], n
end
-- edges: (tail, head, wrap), a wrap being the lattice shift head - tail
local edges, eid = {}, {}
local function edge(p, q)
  local a, na = reduce(p)
  local b, nb = reduce(q)
  local w = {nb[1] - na[1], nb[2] - na[2], nb[3] - na[3]}
  local k = ("%d %d %d %d %d"):format(a, b, w[1], w[2], w[3])
  local kr = ("%d %d %d %d %d"):format(b, a, -w[1], -w[2], -w[3])
  if eid[k] then return eid[k] end
  if eid[kr] then return -eid[kr] end
  edges[#edges + 1] = {a, b, w}
  eid[k] = #edges
  return #edges
end
local flist = {}
for _, pts in ipairs(faces) do
  local l = {}
  for i = 1, #pts do l[#l + 1] = edge(pts[i], pts[i % #pts + 1]) end
  flist[#flist + 1] = l
end

-- a seeded random walk of the vertices (LCG: the same file every run)
local seed = 12345
local function rnd()
  seed = (seed * 1103515245 + 12345) % 2147483648
  return seed / 2147483648 - 0.5
end
for _, v in ipairs(verts) do
  for j = 1, 3 do v[j] = v[j] + 0.04 * rnd() end
end

local sign = {[-1] = "-", [0] = "*", [1] = "+"}
print("// kelvin.fe: one Kelvin cell in the bcc torus (written by kelvin_gen.lua)")
print("TORUS_FILLED\n\nPERIODS")
for i = 1, 3 do print(("%g %g %g"):format(P[i][1], P[i][2], P[i][3])) end
print("\nvertices")
for i, v in ipairs(verts) do print(("%d %.17g %.17g %.17g"):format(i, v[1], v[2], v[3])) end
print("\nedges")
for i, e in ipairs(edges) do
  print(("%d %d %d %s %s %s"):format(i, e[1], e[2], sign[e[3][1]], sign[e[3][2]], sign[e[3][3]]))
end
print("\nfaces")
for i, l in ipairs(flist) do print(i .. " " .. table.concat(l, " ")) end
local b = {}
for i = 1, #flist do b[#b + 1] = i; b[#b + 1] = -i end
print("\nbodies\n1 " .. table.concat(b, " ") .. " volume 0.5")
