-- quadfoam.lua: six bubbles in a fixed square bipyramid, A above and B
-- below a quadrilateral film (corners (+-a, +-b, 0)) bounded by four
-- triple edges; C, D, E, F round it (C at -x, D at +y, E at +x, F at -y),
-- every film a four-sided datafile face (Evolver splits it round a centre
-- vertex). For pop_quad_to_quad (tests/evolver/quad.sh).
-- return function(o) -> the datafile text. o.a, o.b (default 0.6, 0.3);
-- o.seed, o.jit: every vertex moved by up to jit/2 per coordinate (seeded);
-- o.order "ba": B's side films listed first (their edges get the lower
-- numbers); o.shuf > 0: edge numbers and directions shuffled (seeded).
return function(o)
local a, b = o.a or 0.6, o.b or 0.3
local seed, jit = o.seed or 0, o.jit or 0
local zm = 1
local s = seed * 7919 + 1
local function rnd() s = (s * 1103515245 + 12345) % 2147483648; return s / 2147483648 - 0.5 end
local V, names = {}, {}
local function vert(name, x, y, z, fixed)
  if jit > 0 then x, y, z = x + jit * rnd(), y + jit * rnd(), z + jit * rnd() end
  V[#V + 1] = {x, y, z, fixed}; names[name] = #V
end
local px = {-a, a, a, -a}
local py = {b, b, -b, -b}
local Q = {{-2, 2}, {2, 2}, {2, -2}, {-2, -2}}
for k = 1, 4 do vert("p" .. k, px[k], py[k], 0, false) end
vert("N", 0, 0, 2 * zm, true); vert("S", 0, 0, -2 * zm, true)
for k = 1, 4 do vert("Q" .. k, Q[k][1], Q[k][2], 0, true) end
for k = 1, 4 do vert("M" .. k .. "u", Q[k][1] / 2, Q[k][2] / 2, zm, true) end
for k = 1, 4 do vert("M" .. k .. "d", Q[k][1] / 2, Q[k][2] / 2, -zm, true) end
local F = {} -- {verts, fixed, bodyX (front or back decided geometrically), bodyY}
local function face(vs, fixed, X, Y) F[#F + 1] = {vs = vs, fixed = fixed, X = X, Y = Y} end
local side = {"D", "E", "F", "C"}
local function n(k) return (k - 1) % 4 + 1 end
face({"p1", "p2", "p3", "p4"}, false, "A", "B")
for k = 1, 4 do
  local k1 = n(k + 1)
  if o.order == "ba" then
    face({"p" .. k, "p" .. k1, "M" .. k1 .. "d", "M" .. k .. "d"}, false, "B", side[k])
    face({"p" .. k, "p" .. k1, "M" .. k1 .. "u", "M" .. k .. "u"}, false, "A", side[k])
  else
    face({"p" .. k, "p" .. k1, "M" .. k1 .. "u", "M" .. k .. "u"}, false, "A", side[k])
    face({"p" .. k, "p" .. k1, "M" .. k1 .. "d", "M" .. k .. "d"}, false, "B", side[k])
  end
  face({"p" .. k, "M" .. k .. "u", "Q" .. k, "M" .. k .. "d"}, false, side[n(k - 1)], side[k])
  face({"N", "M" .. k .. "u", "M" .. k1 .. "u"}, true, "A")
  face({"S", "M" .. k .. "d", "M" .. k1 .. "d"}, true, "B")
  face({"M" .. k .. "u", "Q" .. k, "Q" .. k1, "M" .. k1 .. "u"}, true, side[k])
  face({"M" .. k .. "d", "Q" .. k, "Q" .. k1, "M" .. k1 .. "d"}, true, side[k])
end
local centre = {A = {0, 0, 0.8}, B = {0, 0, -0.8}, D = {0, 1.3, 0}, E = {1.3, 0, 0}, F = {0, -1.3, 0}, C = {-1.3, 0, 0}}
local bodyid = {}
local perm = "ABCDEF"
for i = 1, 6 do bodyid[perm:sub(i, i)] = i end
local out = {"vertices"}
for i, v in ipairs(V) do out[#out + 1] = ("%d %.15g %.15g %.15g%s"):format(i, v[1], v[2], v[3], v[4] and " fixed" or "") end
local E, eid = {}, {}
local function edge(i, j)
  local k = i < j and i .. "," .. j or j .. "," .. i
  if not eid[k] then E[#E + 1] = {i, j}; eid[k] = #E end
  local e = eid[k]
  return E[e][1] == i and e or -e
end
local faces, bodies = {}, {A = {}, B = {}, C = {}, D = {}, E = {}, F = {}}
for fi, f in ipairs(F) do
  local ids = {}
  for _, nm in ipairs(f.vs) do ids[#ids + 1] = names[nm] end
  local es = {}
  for i = 1, #ids do es[#es + 1] = edge(ids[i], ids[i % #ids + 1]) end
  faces[fi] = es
  -- normal and centroid
  local c, nn = {0, 0, 0}, {0, 0, 0}
  for i = 1, #ids do
    local p, q = V[ids[i]], V[ids[i % #ids + 1]]
    for d = 1, 3 do c[d] = c[d] + p[d] / #ids end
    nn[1] = nn[1] + (p[2] - q[2]) * (p[3] + q[3]); nn[2] = nn[2] + (p[3] - q[3]) * (p[1] + q[1]); nn[3] = nn[3] + (p[1] - q[1]) * (p[2] + q[2])
  end
  for _, X in ipairs({f.X, f.Y}) do
    local cc = centre[X]
    local d = (c[1] - cc[1]) * nn[1] + (c[2] - cc[2]) * nn[2] + (c[3] - cc[3]) * nn[3]
    table.insert(bodies[X], d > 0 and fi or -fi)
  end
end
-- optional shuffle of edge ids and directions
local map, flip = {}, {}
for i = 1, #E do map[i] = i; flip[i] = false end
local sh = o.shuf or 0
if sh > 0 then
  local t = sh * 104729 + 7
  local function r() t = (t * 1103515245 + 12345) % 2147483648; return t / 2147483648 end
  for i = #E, 2, -1 do local j = 1 + math.floor(r() * i); map[i], map[j] = map[j], map[i] end
  for i = 1, #E do flip[i] = r() < 0.5 end
end
local inv = {}
for i = 1, #E do inv[map[i]] = i end -- map[old] = new id
out[#out + 1] = "edges"
for nid = 1, #E do
  local i = inv[nid]
  local e = E[i]
  local fx = V[e[1]][4] and V[e[2]][4]
  local a, b = e[1], e[2]
  if flip[i] then a, b = b, a end
  out[#out + 1] = ("%d %d %d%s"):format(nid, a, b, fx and " fixed" or "")
end
out[#out + 1] = "faces"
for i, es in ipairs(faces) do
  local t = {}
  for _, e in ipairs(es) do
    local o = math.abs(e)
    local sg = (e > 0) ~= flip[o] and 1 or -1
    t[#t + 1] = tostring(sg * map[o])
  end
  out[#out + 1] = ("%d %s%s"):format(i, table.concat(t, " "), F[i].fixed and " fixed" or "")
end
out[#out + 1] = "bodies"
for i = 1, 6 do local X = perm:sub(i, i)
  local t = {}
  for _, f in ipairs(bodies[X]) do t[#t + 1] = tostring(f) end
  out[#out + 1] = ("%d %s"):format(bodyid[X], table.concat(t, " "))
end
return table.concat(out, "\n") .. "\n"
end
