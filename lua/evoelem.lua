-- evoelem.lua: elements for Evolver command text, part of the runtime
-- tds.E (lua/evorun.lua): element handles by id (negative ids reverse
-- edges), oriented sub-elements (a facet's edges, a vertex's edges, an
-- edge's facets ...), attributes with Evolver's meaning (x of an edge is
-- its vector, of a facet its area vector), run-time attributes (define
-- ... attribute), set/unset, aggregates, histograms and list.

local tds = tds
local E = tds.E
local fail, num = E.fail, E.num
local KINDNUM = { vertex = tds.vertex, edge = tds.edge, facet = tds.facet, body = tds.body }


-- An oriented element: a handle, or a reversed edge { h = handle } (as a
-- facet or a vertex sees it; Evolver's negative ids).
local REV = {}
local function reversed(h) return setmetatable({ h = h }, REV) end
local function unwrap(x)
  if getmetatable(x) == REV then return x.h, true end
  return x, false
end
local function ishandle(v) return type(v) == "userdata" and getmetatable(v) and getmetatable(v).__tds_kind ~= nil end
-- A facetedge: facet f's k-th side (its k-th edge as the facet traverses
-- it). Numbered 3 (f - 1) + k: tds's own numbering (Evolver's follows its
-- internal structures).
local FE = {}
local function isfe(v) return getmetatable(v) == FE end
local function facetedge(f, k) return setmetatable({ f = f, k = k }, FE) end
local function isel(v) return ishandle(v) or getmetatable(v) == REV or isfe(v) end
E.isel = isel
local KINDNAME = { [tds.vertex] = "vertex", [tds.edge] = "edge", [tds.facet] = "facet", [tds.body] = "body" }
local function kindof(x)
  if isfe(x) then return "facetedge" end
  return KINDNAME[getmetatable((unwrap(x))).__tds_kind]
end
E.unwrap = unwrap

function E.getelem(kind, i, soft)
  local id = num(i, kind .. "[]")
  if id % 1 ~= 0 then fail(("%s[%g]: the index must be a whole number"):format(kind, id)) end
  if kind == "facetedge" then
    local n = math.floor(math.abs(id))
    local f = n >= 1 and tds.get(tds.facet, (n - 1) // 3 + 1)
    if f then return facetedge(f, (n - 1) % 3 + 1) end
    if not soft then fail(("facetedge[%d] does not exist"):format(math.floor(id))) end
    return nil
  end
  local h = tds.get(KINDNUM[kind], math.floor(math.abs(id)))
  if not h and not soft then fail(("%s[%d] does not exist"):format(kind, math.floor(id))) end
  if h and id < 0 and kind == "edge" then return reversed(h) end
  return h
end

function E.all(kind)
  if kind == "facetedge" then
    local list = {}
    for _, f in ipairs(E.all("facet")) do
      for k = 1, 3 do list[#list + 1] = facetedge(f, k) end
    end
    return list
  end
  local list, i, k = {}, 0, KINDNUM[kind]
  while true do
    local id, h = tds.next(k, i)
    if not id then break end
    list[#list + 1] = h
    i = id
  end
  return list
end

-- Is h (a handle, reversed or not) still an element? Loops skip the
-- elements an earlier command in the loop deleted, as Evolver's do.
local function idof(h) return h.id end
function E.live(h)
  if getmetatable(h) == REV then h = h.h end
  if not ishandle(h) then return true end
  return (pcall(idof, h))
end

-- Adjacency of the current mesh, built in one pass when a generator
-- needs it and dropped whenever the topology may have changed (E.touch:
-- around every top-level command, after commands and Lua calls).
local adj
local USER -- user attributes, see userattr
local function adjacency()
  if adj then return adj end
  local a = { efacets = {}, vedges = {}, vfacets = {}, bfacets = {} }
  local function push(t, k, v) local l = t[k]; if not l then l = {}; t[k] = l end; l[#l + 1] = v end
  for _, e in ipairs(E.all("edge")) do
    push(a.vedges, e.tail.id, { e, false })
    push(a.vedges, e.head.id, { e, true })
    -- the facets around the edge in Evolver's order (src/ring.h)
    for _, fid in ipairs(tds.edge_ring(e.id) or {}) do
      push(a.efacets, e.id, { tds.get(tds.facet, math.abs(fid)), fid < 0 and -e.id or e.id })
    end
  end
  for _, f in ipairs(E.all("facet")) do
    for _, v in ipairs(f.vertices) do push(a.vfacets, v.id, f) end
    local fb, bb = f.frontbody, f.backbody
    if fb then push(a.bfacets, fb.id, f) end
    if bb and bb ~= fb then push(a.bfacets, bb.id, f) end
  end
  adj = a
  return a
end
function E.touch() adj = nil; USER = nil end

-- Elements around an element (sub-element generators).
local function around(x, kind)
  local from = kindof(x)
  if from == "facetedge" then
    if kind == "facet" then return { x.f } end
    if kind == "edge" then return { around(x.f, "edge")[x.k] } end
    if kind == "vertex" then return around(around(x.f, "edge")[x.k], "vertex") end
  end
  local h, rev = unwrap(x)
  if from == "facet" and kind == "edge" then
    local out = {}
    for _, id in ipairs(h.edges) do
      local e = tds.get(tds.edge, math.abs(id))
      out[#out + 1] = id < 0 and reversed(e) or e
    end
    return out
  elseif from == "facet" and kind == "vertex" then return h.vertices
  elseif from == "facet" and kind == "body" then
    local out = {}
    if h.frontbody then out[#out + 1] = h.frontbody end
    if h.backbody then out[#out + 1] = h.backbody end
    return out
  elseif from == "edge" and kind == "vertex" then
    if rev then return { h.head, h.tail } end
    return { h.tail, h.head }
  elseif from == "edge" and kind == "facet" then
    -- oriented like the edge: a facet that traverses it backwards is
    -- seen reversed (negative oid, opposite normal)
    local out = {}
    for _, fs in ipairs(adjacency().efacets[h.id] or {}) do
      out[#out + 1] = ((fs[2] < 0) ~= rev) and reversed(fs[1]) or fs[1]
    end
    return out
  elseif from == "vertex" and kind == "edge" then
    local out = {}
    for _, es in ipairs(adjacency().vedges[h.id] or {}) do -- oriented away from the vertex
      out[#out + 1] = es[2] and reversed(es[1]) or es[1]
    end
    return out
  elseif from == "vertex" and kind == "facet" then
    return { table.unpack(adjacency().vfacets[h.id] or {}) }
  elseif from == "body" and kind == "facet" then
    return { table.unpack(adjacency().bfacets[h.id] or {}) }
  elseif from == "vertex" and kind == "body" or from == "edge" and kind == "body" then
    local seen, out = {}, {}
    for _, f in ipairs(around(h, "facet")) do
      for _, b in ipairs(around(f, "body")) do
        if not seen[b.id] then seen[b.id] = true; out[#out + 1] = b end
      end
    end
    return out
  elseif from == "body" and (kind == "vertex" or kind == "edge") then
    local seen, out = {}, {}
    for _, f in ipairs(around(h, "facet")) do
      for _, x in ipairs(around(f, kind)) do
        if not seen[x.id] then seen[x.id] = true; out[#out + 1] = x end
      end
    end
    return out
  end
  fail(("%s.%s: not supported yet"):format(from, kind))
end

function E.subs(h, kind)
  if not isel(h) then fail("." .. kind .. " needs an element") end
  return around(h, kind)
end

function E.subelem(h, kind, i)
  if not isel(h) then fail("." .. kind .. "[] needs an element") end
  local list = around(h, kind)
  local k = math.floor(math.abs(num(i)))
  local x = list[k]
  if not x then fail(("%s %d has no %s[%d]"):format(kindof(h), unwrap(h).id, kind, k)) end
  return x
end

-- Element attributes come from tds's attribute registry (src/attr.h);
-- user attributes (define kind attribute ...) are columns of it, shared
-- with Lua (vertex[1].weight) and datafiles. USER[kind][name] = { type =,
-- user =, dims = } caches what tds.attributes reports, aliases included;
-- E.touch drops it.
local function attrinfo(kind, name)
  if not USER then
    USER = {}
    for k, n in pairs(KINDNUM) do
      local t = {}
      for _, a in ipairs(tds.attributes(n)) do
        t[a.name] = a
        for al in (a.alias or ""):gmatch("%S+") do t[al] = a end
      end
      USER[k] = t
    end
  end
  return USER[kind] and USER[kind][name]
end
local function userattr(kind, name)
  local a = attrinfo(kind, name)
  return a and a.user and a
end

-- Facetedge attributes (define facetedge attribute NAME type [dims]) are
-- kept on the facet, one value per side: the facet attribute fe__NAME of
-- shape [3][dims] (so they are copied with the facet by refine and the
-- snapshots of failing commands, and dump writes them as that facet
-- attribute, which a tds load of the dump gives back to the facetedges).
local FEPRE = "fe__"
E.FEPRE = FEPRE

function E.defattr(kind, name, ty, dims)
  local d = {}
  for i, n in ipairs(dims) do d[i] = num(n) end
  if kind == "facetedge" then
    if #name + #FEPRE >= 32 then fail(("facetedge attribute %s: name longer than %d characters"):format(name, 31 - #FEPRE)) end
    table.insert(d, 1, 3)
    kind, name = "facet", FEPRE .. name
  end
  for _, n in ipairs(d) do
    -- Evolver scripts free an attribute's storage by redefining it with a
    -- size 0 (multiplicate.cmd); tds keeps it as it is
    if n == 0 and userattr(kind, name) then USER = nil; return end
  end
  local ok, err = pcall(tds.define_attribute, kind, name, ty, d)
  USER = nil
  if not ok then fail(tostring(err):gsub("^.-:%d+: ", "")) end
end

local function setuser(h, name, u, v)
  if u.dims then
    if type(v) ~= "table" then -- a number assigned to an array sets every element
      local function fill(d)
        local t = {}
        for i = 1, u.dims[d] do t[i] = d < #u.dims and fill(d + 1) or num(v) end
        return t
      end
      v = fill(1)
    end
  else
    v = num(v)
  end
  local ok, err = pcall(function() h[name] = v end)
  if not ok then fail(tostring(err):gsub("^.-:%d+: ", "")) end
end

local function vec(x)
  local k = kindof(x)
  local h, rev = unwrap(x)
  if k == "edge" then
    local a, b = h.tail, h.head
    if rev then a, b = b, a end
    return b.x - a.x, b.y - a.y, b.z - a.z
  elseif k == "facet" then
    local v = h.vertices
    -- the cross product of the first two edges as the facet traverses them
    local ax, ay, az = v[2].x - v[1].x, v[2].y - v[1].y, v[2].z - v[1].z
    local bx, by, bz = v[3].x - v[2].x, v[3].y - v[2].y, v[3].z - v[2].z
    local sg = rev and -0.5 or 0.5
    return (ay * bz - az * by) * sg, (az * bx - ax * bz) * sg, (ax * by - ay * bx) * sg
  end
end

local ATTR = {
  id = function(h) return h.id + 0.0 end,
  oid = function(h, rev) return (rev and -h.id or h.id) + 0.0 end,
  frontbody = function(h) local b = h.frontbody; return b and b.id + 0.0 or 0.0 end,
  backbody = function(h) local b = h.backbody; return b and b.id + 0.0 or 0.0 end,
  target = function(h) return (h.target or 0) + 0.0 end,
  -- tds keeps one colour per facet: front and back are the same
  frontcolor = function(h) return h.color + 0.0 end,
  backcolor = function(h) return h.color + 0.0 end,
  valence = function(h)
    local k = kindof(h)
    if k == "facet" then return 3.0 end
    if k == "body" then return #around(h, "facet") + 0.0 end
    return h.valence + 0.0
  end,
  on_boundary = function(h) return h.boundary and 1.0 or 0.0 end,
  -- Evolver's default display criteria: facets unless nodisplay; edges
  -- that are fixed or not between exactly two facets.
  show = function(h)
    local k = kindof(h)
    if k == "facet" then return h.nodisplay and 0.0 or 1.0 end
    if k == "edge" then return (h.fixed or h.valence ~= 2) and 1.0 or 0.0 end
    return 1.0
  end,
}
ATTR.facet_normal = function(h, rev)
  if kindof(h) ~= "facet" then fail("facet_normal is a facet attribute") end
  local x, y, z = vec(rev and reversed(h) or h)
  return { x, y, z } -- the normal scaled by the area, as facet.x, .y, .z
end
ATTR.vertex_normal = function(h)
  if kindof(h) ~= "vertex" then fail("vertex_normal is a vertex attribute") end
  return { tds.vertex_normal(h) } -- the hessian normal (doc/newton.md)
end
ATTR.vertexnormal = ATTR.vertex_normal -- Evolver's old synonym
ATTR.edge_vector = function(h, rev)
  if kindof(h) ~= "edge" then fail("edge_vector is an edge attribute") end
  return { vec(rev and reversed(h) or h) }
end
ATTR.__x = function(h)
  if kindof(h) ~= "vertex" then fail("__x is a vertex attribute") end
  return { h.x, h.y, h.z }
end
for i, c in ipairs { "x", "y", "z" } do
  ATTR[c] = function(h)
    local k = kindof(h)
    if k == "vertex" then return unwrap(h)[c] end
    if k == "edge" or k == "facet" then return (select(i, vec(h))) end
    fail("body has no attribute " .. c)
  end
end

-- A facetedge's attributes: id, oid, the next and previous sides of its
-- facet, and the next and previous facets around its edge (in the edge's
-- ring of facets, tds's order).
local function feattr(o, name)
  local id = 3 * (o.f.id - 1) + o.k
  if name == "id" or name == "oid" then return id + 0.0 end
  if name == "nextedge" then return facetedge(o.f, o.k % 3 + 1) end
  if name == "prevedge" then return facetedge(o.f, (o.k + 1) % 3 + 1) end
  if name == "nextfacet" or name == "prevfacet" then
    local e = unwrap(around(o.f, "edge")[o.k])
    local ring = adjacency().efacets[e.id] or {}
    for i, fs in ipairs(ring) do
      if fs[1] == o.f then
        local nb = ring[(i + (name == "nextfacet" and 0 or #ring - 2)) % #ring + 1][1]
        for k, id2 in ipairs(nb.edges) do
          if math.abs(id2) == e.id then return facetedge(nb, k) end
        end
      end
    end
  end
  local u = userattr("facet", FEPRE .. name)
  if u then
    local v = o.f[FEPRE .. name][o.k]
    if type(v) == "number" then return v + 0.0 end
    return v -- a proxy of this side's array
  end
  if name == "edge" or name == "facet" then return around(o, name)[1] end
  fail(("facetedge %d has no attribute '%s'"):format(id, name))
end

local function fe_set(o, name, v)
  local u = userattr("facet", FEPRE .. name)
  local id = 3 * (o.f.id - 1) + o.k
  if not u then fail(("facetedge %d has no attribute '%s' to set"):format(id, name)) end
  local function fail_fe(err) -- the facet's column, named as the user knows it
    fail((tostring(err):gsub("^.-:%d+: ", ""):gsub("^facet %d+: " .. FEPRE, ("facetedge %d: "):format(id))))
  end
  local rows = o.f[FEPRE .. name]
  if #u.dims == 1 then
    local ok, err = pcall(function() rows[o.k] = num(v) end)
    if not ok then fail_fe(err) end
    return
  end
  local function fill(d) -- a number assigned to an array sets every element
    local r = {}
    for i = 1, u.dims[d] do r[i] = d < #u.dims and fill(d + 1) or num(v) end
    return r
  end
  local ok, err = pcall(function() rows[o.k] = type(v) == "table" and v or fill(2) end)
  if not ok then fail_fe(err) end
end

-- Element attributes of Evolver (elements.htm) tds does not have: reading
-- one is an error naming it as such.
local EV_ATTRS = {}
for w in ([[dihedral orientation sqcurve square_mean_curvature v_force
  v_velocity raw_velocity v_oldx v_constraint_list e_constraint_list f_constraint_list
  v_boundary e_boundary v_method_list e_method_list f_method_list on_quantity
  on_method_instance mid_edge mid_facet axial_point triple_point tetra_point midv wrap
  wrap_list no_transform phase f_next_vertex p_force p_velocity constraint_normal
  gauss_curvature node_charge]]):gmatch("%S+") do EV_ATTRS[w] = true end

function E.attr(o, name)
  if type(o) == "table" and o.__quantity then return E.qattr(o, name) end
  if not isel(o) then fail(("'.%s' needs an element, got %s"):format(name, type(o))) end
  if isfe(o) then return feattr(o, name) end
  if name == "x" or name == "y" or name == "z" then return ATTR[name](o) end
  local h, rev = unwrap(o)
  local u = userattr(kindof(h), name)
  if u then
    if u.dims then return h[name] end -- a proxy: a[i] reads, a[i] = x writes the element
    return h[name] + 0.0
  end
  local f = ATTR[name]
  if f then return f(h, rev) end
  local ok, v = pcall(function() return h[name] end)
  if not ok or v == nil then -- one of Evolver's that tds does not have is named as such
    if EV_ATTRS[name] then fail(("%s %d: attribute %s is not supported yet"):format(kindof(h), h.id, name)) end
  end
  if not ok then
    -- already positioned (the binding's message names the user's line)
    if type(v) == "string" and v:find("^[^\n]-:%d+: ") then error(v, 0) end
    fail(v)
  end
  if v == nil then
    if name == "pressure" or name == "volume" or name == "density" or name == "tension" then return 0.0 end
    fail(("%s %d has no attribute '%s'"):format(kindof(h), h.id, name))
  end
  if type(v) == "boolean" then return v and 1.0 or 0.0 end
  if type(v) == "function" then fail(("%s.%s is not an attribute"):format(kindof(h), name)) end
  return v
end

function E.pred(h, what, n)
  if not isel(h) then fail(what .. " needs an element") end
  h = unwrap(h)
  n = math.floor(num(n))
  if what == "value_of_constraint" then fail("value_of_constraint: not supported yet") end
  if what == "on_constraint" or what == "hit_constraint" then
    local cs = h.constraints or {}
    for _, c in ipairs(cs) do if c == n then return true end end
    return false
  end
  return h.boundary == n
end

local function has_con(h, n)
  for _, c in ipairs(h.constraints or {}) do if c == n then return true end end
end

-- set/unset of attributes; `fromset` marks Evolver's set command (no value
-- means a flag is switched on).
function E.setattr(h, name, v, fromset)
  if type(h) == "table" and h.__quantity then return E.setqattr(h, name, v) end
  if not isel(h) then fail(("cannot set '%s' of a %s"):format(name, type(h))) end
  if isfe(h) then return fe_set(h, name, v == true and 1 or v) end
  h = unwrap(h)
  local k = kindof(h)
  local u = userattr(k, name)
  if u then return setuser(h, name, u, v == true and 1 or v) end
  local info = attrinfo(k, name)
  if info and info.type == "boolean" then -- flags: fixed, no_refine, bare, nodisplay ...
    h[name] = E.truth(v == true and 1 or v)
  elseif name == "constraint" then
    local n = math.floor(num(v))
    if not has_con(h, n) then
      local cs = h.constraints or {}
      cs[#cs + 1] = n
      local ok, err = pcall(function() h.constraints = cs end)
      if not ok then fail(err) end
    end
  elseif (name == "frontcolor" or name == "backcolor") and k == "facet" then
    fail(("set facet %s: tds has one colour per facet; set color"):format(name))
  elseif name == "target" or name == "volume" then
    if k ~= "body" then fail(k .. " has no " .. name) end
    h.target = num(v)
  else
    if v == true then fail(("set %s %s needs a value"):format(k, name)) end
    local ok, err = pcall(function() h[name] = v end)
    if not ok then fail(tostring(err):gsub("^.-:%d+: ", "")) end
  end
end

-- `fix qname` / `unfix qname`: a named quantity becomes FIXED (its target
-- as declared or last set) or INFO_ONLY; parameters cannot be optimized.
function E.fixname(low, raw, on)
  if tds.quantity_info(low) == nil then
    fail(("%s %s: fixing parameters (optimizing_parameter) is not supported yet")
      :format(on and "fix" or "unfix", raw))
  end
  local ok, msg = tds.quantity_set(low, "fixed", on and 1 or 0)
  if not ok then fail(msg) end
end

function E.unsetattr(h, name, v)
  if isfe(h) then return fe_set(h, name, 0) end
  h = unwrap(h)
  local k = kindof(h)
  local info = attrinfo(k, name)
  if info and info.type == "boolean" then h[name] = false
  elseif name == "constraint" then
    local cs, out = h.constraints or {}, {}
    local n = v and math.floor(num(v))
    for _, c in ipairs(cs) do if n and c ~= n then out[#out + 1] = c end end
    h.constraints = out
  elseif name == "boundary" and (k == "vertex" or k == "edge") then
    -- `unset vertices boundary 1`: off that boundary (any without a number)
    if h.boundary ~= nil and (v == nil or h.boundary == math.floor(num(v))) then
      local ok, err = pcall(function() h.boundary = nil end)
      if not ok then fail(tostring(err):gsub("^.-:%d+: ", "")) end
    end
  elseif (name == "target" or name == "volume") and k == "body" then h.target = nil
  elseif name == "pressure" and k == "body" then h.pressure = nil
  elseif userattr(k, name) then h[name] = nil
  else fail(("unset %s %s: not supported"):format(k, name)) end
end

function E.agg(kind, list, f)
  local acc, n
  if kind == "sum" or kind == "count" or kind == "avg" then acc = 0.0 end
  n = 0
  for _, h in ipairs(list) do
    local v = f(h)
    if v ~= nil then
      v = num(v)
      n = n + 1
      if kind == "sum" or kind == "avg" then acc = acc + v
      elseif kind == "count" then acc = acc + 1
      elseif kind == "max" then acc = (acc == nil or v > acc) and v or acc
      else acc = (acc == nil or v < acc) and v or acc end
    end
  end
  if kind == "avg" then return n > 0 and acc / n or 0.0 end
  return acc or 0.0
end

-- histogram: 21 equal bins from the least to the greatest value;
-- loghistogram: 20 bins of equal ratio (positive values), as Evolver.
function E.histogram(log, list, f)
  local vals = {}
  for _, h in ipairs(list) do
    local v = f(h)
    if v ~= nil then vals[#vals + 1] = num(v) end
  end
  if log then
    for _, v in ipairs(vals) do
      if v <= 0 then fail(("loghistogram: value %g is not positive"):format(v)) end
    end
  end
  if #vals == 0 then E.out("No qualifying values.\n"); return end
  local lo, hi = math.huge, -math.huge
  for _, v in ipairs(vals) do lo = math.min(lo, v); hi = math.max(hi, v) end
  if lo == hi then
    E.out(("%10.5g - %10.5g     %d\n"):format(lo, hi, #vals))
    return
  end
  local nb = log and 20 or 21
  local counts = {}
  for i = 1, nb do counts[i] = 0 end
  for _, v in ipairs(vals) do
    local t = log and (math.log(v / lo) / math.log(hi / lo)) or ((v - lo) / (hi - lo))
    local b = math.min(nb, math.floor(t * nb) + 1)
    counts[b] = counts[b] + 1
  end
  for i = 1, nb do
    local a, b
    if log then a, b = lo * (hi / lo) ^ ((i - 1) / nb), lo * (hi / lo) ^ (i / nb)
    else a, b = lo + (hi - lo) * (i - 1) / nb, lo + (hi - lo) * i / nb end
    if i == nb then b = hi end
    E.out(("%10.5g - %10.5g     %d\n"):format(a, b, counts[i]))
  end
end


-- sizeof(name) of an extra attribute: its number of values per element
-- (a facetedge attribute's per side); an array variable of that name wins.
function E.attrsize(name)
  local v = rawget(_G, name)
  if type(v) == "table" then return #v + 0.0 end
  for _, k in ipairs { "vertex", "edge", "facet", "body" } do
    for _, n in ipairs { name, k == "facet" and FEPRE .. name or nil } do
      local u = userattr(k, n)
      if u then
        local size = 1
        for i, d in ipairs(u.dims or {}) do if not (n ~= name and i == 1) then size = size * d end end
        return size + 0.0
      end
    end
  end
  fail(("sizeof: '%s' is not an array or an extra attribute"):format(name))
end

function E.has_extra(h, name)
  if isfe(h) then return userattr("facet", FEPRE .. name) ~= nil end
  return E.isel(h) and userattr(kindof(h), name) ~= nil
end

-- list GEN in Evolver's layout.
local COLOR_NAME = { [-1] = "clear", [0] = "black", "blue", "green", "cyan", "red", "magenta",
  "brown", "lightgray", "darkgray", "lightblue", "lightgreen", "lightcyan", "lightred",
  "lightmagenta", "yellow", "white" }

-- The user attributes of h as list writes them: " name value", arrays
-- in braces ({1,2,3} for integers, {1.5, 2} for reals, as Evolver).
local function userlist(h, kind)
  local out = {}
  for _, a in ipairs(tds.attributes(KINDNUM[kind])) do
    if a.user and a.name:sub(1, #FEPRE) ~= FEPRE then
      local function fmt(v)
        if type(v) ~= "table" then return ("%.15g"):format(v) end
        local t = {}
        for i, x in ipairs(v) do t[i] = fmt(x) end
        return "{" .. table.concat(t, a.type == "integer" and "," or ", ") .. "}"
      end
      out[#out + 1] = " " .. a.name .. " " .. fmt(h[a.name])
    end
  end
  return table.concat(out)
end

-- list GEN in Evolver's layout: coordinates or ids, then the element's
-- constraints and flags, then its length or area (%g) in a comment.
function E.list(h, kind, first)
  if isfe(h) then
    -- Evolver's columns; neighbours around the edge are signed negative
    -- when they run the edge the other way
    if first then E.out("//    id       edge    facet  prevedge nextedge    prevfacet nextfacet\n") end
    local e = around(h, "edge")[1]
    local function around_id(name)
      local o = feattr(h, name)
      local oe = around(o, "edge")[1]
      local sign = (select(2, unwrap(oe)) == select(2, unwrap(e))) and 1 or -1
      return sign * feattr(o, "id")
    end
    local ex = {}
    for _, a in ipairs(tds.attributes(tds.facet)) do
      if a.user and a.name:sub(1, #FEPRE) == FEPRE then
        local v = feattr(h, a.name:sub(#FEPRE + 1))
        if type(v) == "number" then ex[#ex + 1] = ("%.15g"):format(v)
        else
          local vals = {}
          local function walk(x) if type(x) == "number" then vals[#vals + 1] = ("%.15g"):format(x) else for i = 1, #x do walk(x[i]) end end end
          walk(v)
          ex[#ex + 1] = "{" .. table.concat(vals, ",") .. "}"
        end
      end
    end
    local eid = select(2, unwrap(e)) and -unwrap(e).id or unwrap(e).id
    E.out(("%6d%11d%9d%10d%9d%13d%9d%s \n"):format(feattr(h, "id"), eid, h.f.id,
      feattr(feattr(h, "prevedge"), "id"), feattr(feattr(h, "nextedge"), "id"),
      around_id("prevfacet"), around_id("nextfacet"), table.concat(ex)))
    return
  end
  h = unwrap(h)
  local cons = kind ~= "body" and #h.constraints > 0 and table.concat(h.constraints, " ")
  if kind == "vertex" then
    if first then E.out("// Id               X                Y               Z\n") end
    E.out(("%3d  %17.15g %17.15g %17.15g%s%s%s\n"):format(h.id, h.x, h.y, h.z,
      cons and ("  constraints " .. cons .. " ") or "", h.fixed and " fixed " or "",
      userlist(h, kind)))
  elseif kind == "edge" then
    if first then E.out("// Id    endpoints\n") end
    E.out(("%3d    %4d %4d   %s%s%s  /*length %g*/ %s\n"):format(h.id, h.tail.id, h.head.id,
      cons and ("   constraints " .. cons) or "", h.fixed and " fixed" or "",
      h.no_refine and "  no_refine" or "", h.length, userlist(h, kind)))
  elseif kind == "facet" then
    if first then E.out("// Id    edges\n") end
    local ids = {}
    for i, e in ipairs(h.edges) do ids[i] = tostring(e) end
    local flags = (h.fixed and " fixed " or "") .. (h.tension ~= 1 and ("  density %g "):format(h.tension) or "")
      .. (h.color ~= 15 and (" color " .. (COLOR_NAME[h.color] or tostring(h.color)) .. " ") or "")
      .. (h.no_refine and " no_refine " or "")
    E.out(("%3d   %s%s /*area %g*/%s\n"):format(h.id, table.concat(ids, " "), flags, h.area,
      userlist(h, kind)))
  elseif kind == "body" then
    if first then E.out("// Id    facets\n") end
    local ids = {}
    for _, f in ipairs(around(h, "facet")) do ids[#ids + 1] = tostring(f.backbody == h and -f.id or f.id) end
    E.out(("%3d    %s  volume %.15g%s\n"):format(h.id, table.concat(ids, " "), h.volume,
      userlist(h, kind)))
  end
end

return true
