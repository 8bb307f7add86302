-- prelude.lua: the friendly tds API, built on the raw primitives in `tds`.
-- Loaded into every surface's namespace (its _ENV: the global table for
-- the tds program's surface, or the table tds.new() returns;
-- src/lua_surface.c). Declarations raise their errors at the user's line
-- (the line that called vertices{...} etc.).

local tds = tds
-- Where names the namespace does not define come from (nil when the
-- namespace is the global table itself).
local base = tds.env_base
-- The namespace's __index below calls these: kept as locals, since in a
-- private namespace a global name is itself looked up through __index.
-- The raw parameter reader too: the check mode wraps tds.param with Lua
-- code whose own global lookups would come back here.
local type, rawset, rawget, error, rawparam = type, rawset, rawget, error, tds.param
local KIND = { vertex = tds.vertex, edge = tds.edge, facet = tds.facet, body = tds.body }
local NAME = { [tds.vertex] = "vertex", [tds.edge] = "edge", [tds.facet] = "face",
               [tds.body] = "body" }
local PLURAL = { [tds.vertex] = "vertices", [tds.edge] = "edges", [tds.facet] = "faces",
                 [tds.body] = "bodies" }
local DECL = { [tds.vertex] = tds.decl_vertex, [tds.edge] = tds.decl_edge,
               [tds.facet] = tds.decl_face, [tds.body] = tds.decl_body }

-- The ids of a declaration table: its positive integer keys, in order.
-- `level` is the caller's level as seen from declare.
local function sorted_ids(kind, t, level)
  local ids = {}
  for k in pairs(t) do
    if math.type(k) ~= "integer" or k < 1 then
      error(("%s{}: key %s is not an id (use a list, or [id] = {...})")
            :format(PLURAL[kind], tostring(k)), level + 1)
    end
    ids[#ids + 1] = k
  end
  table.sort(ids)
  return ids
end

local function declare(kind, t)
  local level = 4 -- declare <- pcall <- generator function <- user's line
  local ids = sorted_ids(kind, t, level)
  if kind == tds.facet and #ids > 0 then
    -- Facets split off polygons are appended after every declared id.
    local ok, err = tds.reserve(tds.facet, ids[#ids], #ids)
    if not ok then error(err, level) end
  end
  local decl = DECL[kind]
  for _, id in ipairs(ids) do
    local entry = t[id]
    if type(entry) ~= "table" then
      error(("%s %d: expected a table, got %s"):format(NAME[kind], id, type(entry)), level)
    end
    local h, err = decl(id, entry)
    if not h then error(err, level) end
  end
end

-- vertices{...} declares; vertices() and vertices(filter) iterate.
local function generator(kind)
  return function(arg)
    if type(arg) == "table" then
      -- All or nothing: a failing entry takes back the ones before it.
      local snap = tds.check_snapshot()
      local ok, err = pcall(declare, kind, arg)
      if not ok then
        tds.check_restore(snap)
        error(err, 0)
      end
      tds.check_release(snap)
      if kind == tds.body then tds.body_warnings() end
      return
    end
    if arg ~= nil and type(arg) ~= "function" then
      error("expected a declaration table or a filter function", 2)
    end
    local filter, i = arg, 0
    return function()
      while true do
        local id, h = tds.next(kind, i)
        if not id then return nil end
        i = id
        if not filter or filter(h) then return h end
      end
    end
  end
end

vertices = generator(tds.vertex)
edges = generator(tds.edge)
faces = generator(tds.facet)
facets = faces
bodies = generator(tds.body)

-- vertex[i], edge[i], facet[i], body[i]: handles by id (nil if absent).
local function indexer(kind)
  return setmetatable({}, {
    __index = function(_, i)
      if math.type(i) ~= "integer" then return nil end
      return tds.get(kind, i)
    end,
    __newindex = function() error("elements are created by declarations", 2) end,
    __len = function() return tds.count(kind) end,
  })
end
vertex, edge, facet, body = indexer(tds.vertex), indexer(tds.edge),
                            indexer(tds.facet), indexer(tds.body)
face = facet

-- Parameters: parameter{ name = value } creates live parameters; reading
-- or assigning the global afterwards reads or sets the engine's value.
function parameter(t)
  if type(t) ~= "table" then error("parameter{ name = value, ... } expected", 2) end
  for k, v in pairs(t) do
    if type(k) ~= "string" or type(v) ~= "number" then
      error(("parameter %s: expected name = number"):format(tostring(k)), 2)
    end
    rawset(_G, k, nil)
    tds.param(k, v)
  end
end

-- Option tables: an unknown key, or a value whose type is not among those
-- `known` lists for it ("number|string"), is an error naming the key at
-- the caller's caller's line (level counts as for error()); nothing the
-- user typed is ignored.
function tds.check_options(t, what, known, level)
  for k, v in pairs(t) do
    if type(k) == "string" then
      local want = known[k]
      if not want then
        local names = {}
        for name in pairs(known) do names[#names + 1] = name end
        table.sort(names)
        error(("%s: unknown key '%s' (known: %s)"):format(what, k, table.concat(names, ", ")),
              level + 1)
      end
      if not ("|" .. want .. "|"):find("|" .. type(v) .. "|", 1, true) then
        error(("%s: %s must be a %s, not a %s"):format(what, k, want:gsub("|", " or "), type(v)),
              level + 1)
      end
    end
  end
end
local check_options = tds.check_options

-- constraint(n, {...}), boundary(n, {...}), quantity{...}: the model.
local function raise_at_caller(ok, err)
  if not ok then error(err, 3) end
end
local INTEGRAND = "string|number"
local CONSTRAINT_KEYS = { formula = "string", energy = "table", content = "table",
  nonnegative = "boolean", nonpositive = "boolean", convex = "boolean", global = "boolean" }
function constraint(n, t)
  if math.type(n) ~= "integer" or type(t) ~= "table" then
    error("constraint(number, { formula = ... }) expected", 2)
  end
  check_options(t, "constraint " .. n, CONSTRAINT_KEYS, 2)
  if t.nonnegative and t.nonpositive then
    error(("constraint %d: nonnegative and nonpositive contradict each other"):format(n), 2)
  end
  raise_at_caller(tds.constraint(n, t))
end
local BOUNDARY_KEYS = { parameters = "number", x = INTEGRAND, y = INTEGRAND, z = INTEGRAND,
  energy = "table", content = "table", convex = "boolean" }
function boundary(n, t)
  if math.type(n) ~= "integer" or type(t) ~= "table" then
    error("boundary(number, { parameters = 1, x = ..., y = ..., z = ... }) expected", 2)
  end
  check_options(t, "boundary " .. n, BOUNDARY_KEYS, 2)
  raise_at_caller(tds.boundary(n, t))
end
local METHOD_KEYS = { method = "string", modulus = "number", vector_integrand = "table",
  scalar_integrand = INTEGRAND }
local QUANTITY_KEYS = { name = "string", fixed = "number", energy = "boolean",
  info_only = "boolean", modulus = "number", methods = "table", method = "string",
  vector_integrand = "table", scalar_integrand = INTEGRAND }
function quantity(t)
  if type(t) ~= "table" then error("quantity{ name = ..., method = ... } expected", 2) end
  local what = "quantity " .. tostring(t.name)
  check_options(t, what, QUANTITY_KEYS, 2)
  for i, m in ipairs(type(t.methods) == "table" and t.methods or {}) do
    if type(m) == "table" then check_options(m, what .. " method " .. i, METHOD_KEYS, 2) end
  end
  raise_at_caller(tds.quantity(t))
end

function gravity_constant(value)
  if type(value) ~= "number" then error("gravity_constant(number) expected", 2) end
  tds.gravity(value)
end

-- attribute{ vertex = { weight = "real" }, facet = { flags = "integer[3]" } }:
-- user attributes, columns of the attribute registry (doc/language.md).
-- Every kind, name and type is checked before any is defined.
local ATTR_KINDS = { vertex = "table", edge = "table", facet = "table", face = "table",
                     body = "table" }
function attribute(t)
  if type(t) ~= "table" then error('attribute{ vertex = { name = "real" }, ... } expected', 2) end
  check_options(t, "attribute", ATTR_KINDS, 2)
  local list = {}
  for kind, names in pairs(t) do
    for name, ty in pairs(names) do
      if type(name) ~= "string" or type(ty) ~= "string"
         or not (ty:match("^real[%[%]%d]*$") or ty:match("^integer[%[%]%d]*$")) then
        error(("attribute: %s %s: expected name = \"real\" or \"integer\" (with dimensions "
              .. "such as \"real[3]\")"):format(kind, tostring(name)), 2)
      end
      list[#list + 1] = { kind, name, ty }
    end
  end
  table.sort(list, function(a, b) return a[1] .. " " .. a[2] < b[1] .. " " .. b[2] end)
  for _, a in ipairs(list) do -- clashes with what exists, before anything is defined
    for _, have in ipairs(tds.attributes(KIND[a[1]] or tds.facet)) do
      local shape = have.type
      for _, d in ipairs(have.dims or {}) do shape = shape .. "[" .. d .. "]" end
      if have.name == a[2] and (not have.user or shape ~= a[3]) then
        error(("attribute: %s %s is %s"):format(a[1], a[2], have.user
              and "already defined as " .. shape or "a built-in attribute"), 2)
      end
    end
  end
  for _, a in ipairs(list) do tds.define_attribute(a[1], a[2], a[3]) end
end

-- Commands, with Evolver's single letters and long names.
function g(n)
  if n ~= nil and (math.type(n) ~= "integer" or n < 0) then
    error("g(n): n must be a whole number of iterations", 2)
  end
  tds.iterate(n or 1)
end
iterate, go = g, g

-- The counts are printed; these return nothing so the REPL stays quiet.
function r(set) tds.refine(set) end
refine = r

-- u(set, opts) / u(opts): opts is a table of named options (it has a
-- string key and no [1], unlike a list of handles).
local function set_and_options(a, b, what, known)
  if b == nil and type(a) == "table" and getmetatable(a) == nil and a[1] == nil
      and next(a) ~= nil then
    a, b = nil, a
  end
  b = b or {}
  if type(b) ~= "table" then error(what .. ": options must be a table", 3) end
  check_options(b, what, known, 3)
  return a, b
end

-- u() is Evolver's one pass; u{delaunay = true} flips until no edge is
-- left that fails the Delaunay test.
function u(set, opts)
  set, opts = set_and_options(set, opts, "u", { delaunay = "boolean" })
  tds.equiangulate(set, opts.delaunay)
end
equiangulate = u

-- V() is Evolver's V; V{rule = "centroid"} is tds's earlier full-step
-- centroid rule, rule = "raw" / "rawest" Evolver's rawv / rawestv, and
-- sequential = true moves each vertex before the next (Evolver's
-- vertex_average on a generator). doc/commands.md.
function V(set, opts)
  set, opts = set_and_options(set, opts, "V", { rule = "string", sequential = "boolean" })
  local rules = { V = true, raw = true, rawest = true, centroid = true }
  if opts.rule ~= nil and not rules[opts.rule] then
    error(('V: rule must be "V", "raw", "rawest" or "centroid", not "%s"'):format(opts.rule), 2)
  end
  tds.vertex_average(set, opts.rule, opts.sequential)
end
function rawv(set) tds.vertex_average(set, "raw") end
function rawestv(set) tds.vertex_average(set, "rawest") end
-- The torus model (doc/torus.md, src/lua_torus.c).
function periods() return tds.periods() end
function wrap_vertex(v, w) tds.wrap_vertex(v, w) end
-- (not `rewrap`: Evolver's rewrap.cmd defines that command itself)
function torus_rewrap() return tds.rewrap() end
function detorus() tds.detorus() end
-- torus_display([mode]): "raw", "connected" or "clipped", how pictures,
-- exports and detorus draw a torus surface; returns the previous mode.
function torus_display(mode) return tds.torus_display(mode) end
-- display_origin[i]: Evolver's array, the clip box's lower corner (0 until
-- set; tds.display_origin(false) unsets it).
display_origin = setmetatable({}, {
  __index = function(_, i)
    local o = tds.display_origin()
    return math.type(i) and i >= 1 and i <= 3 and (o and o[i] or 0.0) or nil
  end,
  __newindex = function(_, i, v)
    if not (math.type(i) and i >= 1 and i <= 3) then
      error(("display_origin[%s]: the index is 1, 2 or 3"):format(tostring(i)), 2)
    end
    if type(v) ~= "number" then error("display_origin: a coordinate is a number", 2) end
    local o = tds.display_origin() or {0.0, 0.0, 0.0}
    o[i] = v
    tds.display_origin(o)
  end,
  __len = function() return 3 end,
})
-- facet_crosscut(f, tail, head): split a string-model cell (doc/string.md)
function facet_crosscut(f, t, h) return tds.facet_crosscut(f, t, h) end
vertex_average = V

-- Mesh maintenance (doc/commands.md): each prints Evolver's line and
-- returns the count. Sets are a handle, a list of handles or an iterator.
local function list_of(set, what)
  if type(set) == "function" then
    local l = {}
    for h in set do l[#l + 1] = h end
    return l
  end
  if set == nil then error(what .. " needs a set of elements (nil given)", 3) end
  return set
end
local function need(x, what, name)
  if type(x) ~= "number" then error(("%s: the %s must be a number"):format(name, what), 3) end
  return x
end
function t(len) return tds.edgeweed(need(len, "edge length", "t(len)")) end
edgeweed = t
function w(area) return tds.areaweed(need(area, "facet area", "w(area)")) end
areaweed = w
-- l(len), or l(set): split those edges, each splitting its facets in two
function l(x)
  local k = type(x)
  if k == "number" or k == "table" or k == "userdata" or k == "function" then return tds.edge_divide(x) end
  need(x, "edge length", "l(len)")
end
edge_divide = l
function K(angle) return tds.skinny(need(angle, "angle", "K(angle)")) end
function n(angle) return tds.notch(need(angle, "angle", "n(angle)")) end
notch = n
function delete(set) return tds.delete(list_of(set, "delete")) end
-- o() pops edges then vertices; o(set) pops the set's edges or vertices;
-- O() pops edges only.
-- In the string model both are Evolver's o for strings (tds.string_pop,
-- doc/string.md), as in the command language.
function o(set)
  if type(set) == "function" then set = list_of(set) end
  if tds.dimensions() == 1 then return tds.string_pop(set) end
  return tds.pop(set)
end
pop = o
function O()
  if tds.dimensions() == 1 then return tds.string_pop() end
  return tds.pop_edges(nil)
end
-- renumber_all(): ids 1, 2, ... for the live elements of each kind, in
-- order (after deletions); returns how many ids changed.
function renumber_all() return tds.renumber_all() end
-- rebody(): each body cut into pieces becomes one body per piece.
function rebody() return tds.rebody() end
-- vertex_merge(v1, v2): vertex v2 (a handle or an id) joins v1.
function vertex_merge(a, b)
  local function vx(v)
    if type(v) == "number" then
      local h = math.tointeger(v) and vertex[math.tointeger(v)]
      if h == nil then error(("vertex_merge: vertex %s does not exist"):format(v), 3) end
      return h
    end
    return v
  end
  return tds.vertex_merge(vx(a), vx(b))
end
pop_edges = O
function pop_edge_to_tri(set) return tds.pop_edge_to_tri(list_of(set, "pop_edge_to_tri")) end
function pop_tri_to_edge(set) return tds.pop_tri_to_edge(list_of(set, "pop_tri_to_edge")) end
function pop_quad_to_quad(set) return tds.pop_quad_to_quad(list_of(set, "pop_quad_to_quad")) end
function dissolve(set) return tds.dissolve(list_of(set, "dissolve")) end
function reverse_orientation(set) return tds.reverse_orientation(list_of(set, "reverse_orientation")) end
-- new_vertex(x, y, z), new_edge(tail, head), new_facet(e1, e2, e3, ...)
-- (signed edge ids that chain head to tail), new_body(): Evolver's
-- element constructors; each declares the element at the next free id
-- and returns that id.
local function next_id(kind)
  local i, last = 0, 0
  while true do
    local id = tds.next(kind, i)
    if not id then return last + 1 end
    last, i = id, id
  end
end
local function construct(kind, entry)
  local id = next_id(kind)
  local ok, err = pcall(({ [tds.vertex] = vertices, [tds.edge] = edges, [tds.facet] = faces,
                           [tds.body] = bodies })[kind], { [id] = entry })
  if not ok then error(err, 3) end
  return id
end
-- (not tail calls: construct raises at its caller's caller)
function new_vertex(x, y, z)
  if type(x) ~= "number" or type(y) ~= "number" or type(z) ~= "number" then
    error("new_vertex(x, y, z): three numbers expected", 2)
  end
  local id = construct(tds.vertex, { x, y, z })
  return id
end
function new_edge(t, h) local id = construct(tds.edge, { t, h }) return id end
function new_facet(...) local id = construct(tds.facet, { ... }) return id end
function new_body() local id = construct(tds.body, {}) return id end
function edgeswap(set) return tds.edgeswap(list_of(set, "edgeswap")) end
-- j(temperature [, set]): Evolver's jiggle (jiggle.h); seeded by
-- tds.setting("random_seed"), so a script repeats exactly.
function j(temperature, set)
  if type(temperature) ~= "number" then error("j(temperature [, set]): temperature must be a number", 2) end
  tds.jiggle(temperature, set)
end
jiggle = j

-- check_increase(on): with it on, a g step that would raise the energy is
-- taken back and g stops (Evolver's toggle). No argument toggles.
function check_increase(on)
  local was = tds.setting("check_increase")
  if on == nil then on = not was end
  tds.setting("check_increase", on and true or false)
  print(("Increase check %s. (was %s)"):format(on and "ON" or "OFF", was and "on" or "off"))
end

-- autopop(on), immediate_autopop(on), autochop(on [, length]): the mesh
-- maintenance g does before each step; area_normalization(on): g's motion
-- is force / (vertex area) (doc/commands.md). No argument
-- toggles.
local function gtoggle(name, what)
  return function(on, len)
    -- true, false, or nothing (toggle): 0 or "off" is an error, not on
    if on ~= nil and type(on) ~= "boolean" then
      error(("%s(on): on must be true or false, not %s"):format(name, type(on) == "string" and ("'" .. on .. "'") or tostring(on)), 2)
    end
    local was = tds.setting(name)
    if on == nil then on = not was end
    if len ~= nil then tds.setting("autochop_length", len) end
    tds.setting(name, on and true or false)
    print(("%s %s. (was %s)"):format(what, on and "ON" or "OFF", was and "on" or "off"))
  end
end
autopop = gtoggle("autopop", "Autopopping")
immediate_autopop = gtoggle("immediate_autopop", "Immediate autopop mode")
autochop = gtoggle("autochop", "Autochopping")
area_normalization = gtoggle("area_normalization", "Area normalization")
-- pop_to_edge(on), pop_to_face(on): how o pops the cone over a triangular
-- prism frame (doc/commands.md); turning one on turns the other off.
pop_to_edge = gtoggle("pop_to_edge", "pop_to_edge")
pop_to_face = gtoggle("pop_to_face", "pop_to_face")
-- pop_enjoin(on): o widens two cones meeting at a vertex into a neck
-- instead of splitting them (doc/commands.md).
pop_enjoin = gtoggle("pop_enjoin", "pop_enjoin")

-- recalc(): after assigning parameters, put boundary vertices where their
-- parameters say and constrained vertices back on their constraints (g, r
-- and pg do this first by themselves).
function recalc() tds.recalc() end

-- m(scale): fixed scale factor; m() returns to the optimizing scale.
function m(scale)
  if scale == nil then
    tds.optimize()
    print("Optimizing scale.")
  else
    tds.scale(scale)
    print(("Fixed scale %g."):format(scale))
  end
end
function optimize(limit) tds.optimize(limit) end

-- U(): toggle conjugate gradient directions; U(2) keeps it on and starts
-- a fresh history (Evolver's `U 2`).
function U(n)
  local on = tds.setting("conj_grad")
  if n == 2 then on = false end
  tds.setting("conj_grad", not on)
  print(("Conjugate gradient %s."):format(on and "OFF" or "ON"))
end
conj_grad = U

-- G(value) sets the gravitational constant and turns gravity on;
-- G() toggles gravity.
function G(value)
  if value == nil then
    local gval, on = tds.gravity()
    tds.gravity(gval, not on)
    print(("Gravity is %s, G = %g."):format(on and "off" or "on", gval))
  else
    tds.gravity(value, true)
  end
end

-- v(): bodies' target volume, actual volume and pressure, like Evolver.
function v()
  tds.totals()
  print("Body          target volume           actual volume          pressure")
  for b in bodies() do
    local target = b.target and ("%.15g"):format(b.target) or "-"
    print(("%3d  %22s  %22.15g  %16.15g"):format(b.id, target, b.volume, b.pressure))
  end
end
show_vol = v

function q(code)
  if code ~= nil and math.type(code) ~= "integer" then
    error("q(code): code must be an integer", 2)
  end
  error({ tds_quit = code or 0 }, 0)
end
quit, bye, exit = q, q, q

function check() return tds.check() end

-- help(): the commands at a glance; doc/ has the full manual.
local HELP = [[
Declarations  vertices{} edges{} faces{} bodies{}  parameter{}  constraint(n, {})
              boundary(n, {})  quantity{}  gravity_constant(g)
Evolving      g(n) iterate    r() refine    u() equiangulate    V() vertex_average
              m(scale) / m()  optimize(limit)   U() conjugate gradient   G(g) gravity
              recalc() after changing parameters
              pg(n) / pg() projected-gradient method (doc/method.md)
Reporting     v()  total_energy  total_area  vertex_count ... body_count
              vertex[i] edge[i] facet[i] body[i]   vertices(filter) ...
              quality()  curvature{}  check()
Files         tds file.fe (load a datafile)  dump("out.fe")
              export("out.ply" | .obj .stl .off .vtu .vtk .msh, {...})  mark()
Pictures      snapshot("s.png", {color=, view=})  plot("c.png")  quality{png=}
              verbose(on)  show() live 3-D view in the browser  (doc/output.md)
Leaving       q()  (at the prompt: q, or Ctrl-D)
Evolver text  at the prompt (g 5; r; u   angle := 45   print total_area),
              tds file.fe -f cmds, evolver(text) in Lua (doc/command-language.md)
The manual: doc/language.md, doc/commands.md, doc/expressions.md, doc/repl.md,
doc/evolver.md (coming from Surface Evolver), doc/method.md, doc/output.md.]]
function help() print(HELP) end

-- near(a, b, tol): |a - b| <= tol * max(1, |b|), for self-checking scripts.
function near(a, b, tol)
  if type(a) ~= "number" or type(b) ~= "number" or (tol ~= nil and type(tol) ~= "number") then
    error("near(a, b [, tol]) expects numbers", 2)
  end
  tol = tol or 1e-9
  return math.abs(a - b) <= tol * math.max(1, math.abs(b))
end

-- Values that read live from the surface as globals.
local live = {
  total_energy = function() return (tds.totals()) end,
  total_area = function() local _, a = tds.totals(); return a end,
  vertex_count = function() return tds.count(tds.vertex) end,
  edge_count = function() return tds.count(tds.edge) end,
  facet_count = function() return tds.count(tds.facet) end,
  body_count = function() return tds.count(tds.body) end,
  scale = function() return (tds.scale()) end,
  iteration_counter = function() return tds.setting("iterations") end,
}

setmetatable(_G, {
  __index = function(_, k)
    local f = live[k]
    if f then return f() end
    if type(k) == "string" then
      local p = rawparam(k)
      if p ~= nil then return p end
    end
    -- rawget: another surface's parameters and live values (the global
    -- table's own __index) are not this surface's
    if base then return rawget(base, k) end
  end,
  __newindex = function(t, k, val)
    if type(k) == "string" and tds.param(k) ~= nil then
      if type(val) ~= "number" then
        error(("parameter %s must be a number"):format(k), 2)
      end
      tds.param(k, val)
    elseif live[k] then
      error(("%s is read-only"):format(k), 2)
    else
      rawset(t, k, val)
    end
  end,
})

-- export(path, options) and mark(): doc/output.md (src/lua_export.c).
export, mark = tds.export, tds.mark
dump = tds.dump_raise

-- load_datafile(path): read a Surface Evolver datafile into this surface
-- (which must still be empty) and run its read section.
function load_datafile(path)
  if type(path) ~= "string" then error("load_datafile(path) expected", 2) end
  tds.load_datafile(path)
end

-- In a namespace of its own (tds.new()), chunks loaded by its code get
-- the namespace as their environment unless told otherwise, so a script
-- run with s.dofile(path) declares into s. (A safe surface's library does
-- this already, and loads text only.)
if base then
  local lload, lloadfile = base.load, base.loadfile
  function load(...)
    if select("#", ...) >= 4 then return lload(...) end
    local chunk, name, mode = ...
    return lload(chunk, name, mode, _ENV)
  end
  function loadfile(...)
    if select("#", ...) >= 3 then return lloadfile(...) end
    local path, mode = ...
    return lloadfile(path, mode, _ENV)
  end
  function dofile(path)
    local f, err = loadfile(path)
    if not f then error(err, 2) end
    return f()
  end
end
tds.props.vertex.gauss_curvature = function(h) return tds.vertex_gauss_curvature(h) end

-- Newton steps and Hessian eigenvalues (doc/newton.md; src/lua_newton.c).
function hessian() return tds.hessian() end
function hessian_seek(maxscale) return tds.hessian_seek(maxscale) end
function saddle(maxscale) return tds.saddle(maxscale) end
function eigenprobe(c, n) return tds.eigenprobe(c or 0, n) end
function ritz(shift, n) return tds.ritz(shift or 0, n or 5) end
function lanczos(shift, n) return tds.ritz(shift or 0, n or 15) end
function move(t) return tds.move(t) end
local function newton_toggle(name, msg)
  return function(on)
    if on == nil then on = true end
    local was = tds.hessian_setting(name)
    tds.hessian_setting(name, on)
    print(msg:format(on and "ON" or "OFF", was and "on" or "off"))
  end
end
hessian_normal = newton_toggle("hessian_normal", "hessian_normal %3s. (was %s)")
linear_metric = newton_toggle("linear_metric", "Linear interpolation metric with Hessian %s.(was %s)")
hessian_diff = newton_toggle("hessian_diff", "hessian_diff %s. (was %s)")
hessian_special_normal = newton_toggle("hessian_special_normal", "hessian_special_normal %3s. (was %s)")
hessian_normal_one = newton_toggle("hessian_normal_one", "hessian_normal_one %3s. (was %s)")
hessian_normal_perp = newton_toggle("hessian_normal_perp", "hessian_normal_perp %3s. (was %s)")

-- Evolver's command language: the runtime (tds.E, evolver [[...]]), read
-- sections run at load, and the prompt's Lua/Evolver rule.
require("evorun")
tds.on_load = function(path) tds.E.run_read(path) end
require("evolver")

-- The projected-gradient method and mesh metrics (lua/pg.lua).
require("pg")
require("live")
require("pictures")

-- The check mode: every command verified (lua/check.lua, doc/reliability.md).
if os.getenv("TDS_CHECK") == "1" then require("check") end

-- Evolver text cannot redefine the names above (lua/evorun.lua).
tds.E.protect()

return true

