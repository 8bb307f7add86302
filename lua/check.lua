-- check.lua: the check mode (TDS_CHECK=1 in the environment; the test
-- suite sets it for every script). After every command it verifies that
-- no coordinate, parameter, pressure, volume, quantity or energy is NaN or
-- infinite; after a command that failed, that the surface is exactly as
-- before it (a snapshot is taken before and compared after). An
-- interrupted command may keep its completed steps, so it is only checked
-- for finiteness. A violation prints "TDS_CHECK: ..." and ends the process
-- with status 3, so no pcall can hide it. doc/reliability.md.
local tds = tds
local snapshot, same, finite = tds.check_snapshot, tds.check_same, tds.check_finite
local release = tds.check_release

-- Captured now, so a script that replaces io or os cannot silence a report.
local stderr, exit = io.stderr, os.exit
local function violation(what, msg)
  stderr:write(("TDS_CHECK: after %s: %s\n"):format(what, msg))
  stderr:flush()
  exit(3)
end

-- `derived`: the command evaluates the energy and succeeds only if it is
-- finite, so energy, area, volumes and quantity values are checked too.
local function after(what, snap, ok, err, derived)
  if ok or (type(err) == "string" and err:find("interrupted", 1, true)) then
    local fine, msg = finite(ok and derived)
    if not fine then violation(what, msg) end
  elseif snap then
    local unchanged, msg = same(snap)
    if not unchanged then violation(what .. " (which failed: " .. tostring(err) .. ")", msg) end
  end
  if snap then release(snap) end
end

local function pack(ok, ...) return ok, select("#", ...), { ... } end

-- Wrap tds[name]: with `heavy` (a function of the arguments, or true) a
-- snapshot is taken first, so a failure can be compared with it.
local function guard(name, heavy, derived)
  local f = tds[name]
  if type(f) ~= "function" then return end
  tds[name] = function(...)
    local snap = (heavy == true or (heavy and heavy(...))) and snapshot() or nil
    local ok, n, res = pack(pcall(f, ...))
    after("tds." .. name, snap, ok, res[1], derived)
    if not ok then error(res[1], 0) end
    return table.unpack(res, 1, n)
  end
end

local function setting(_, ...) return select("#", ...) > 0 end -- a write
for _, name in ipairs { "iterate", "refine", "equiangulate", "vertex_average", "pg",
                        "edgeweed", "areaweed", "edge_divide", "skinny", "notch", "delete",
                        "edgeswap", "pop", "jiggle", "pop_edge_to_tri", "pop_tri_to_edge", "pop_quad_to_quad",
                        "dissolve", "reverse_orientation",
                        "totals" } do
  guard(name, true, true)
end
for _, name in ipairs { "pressures", "scale", "optimize", "gravity" } do
  guard(name, true)
end
guard("param", setting)
guard("setting", setting)
-- declarations and model: finiteness after (no snapshot: they only add)
for _, name in ipairs { "decl_vertex", "decl_edge", "decl_face", "decl_body", "constraint",
                        "boundary", "quantity", "load_datafile" } do
  guard(name, false)
end

-- element setters (vertex[i].x = ...): they check their value before
-- changing anything, so finiteness after is the check
for _, kind in ipairs { "vertex", "edge", "facet", "body" } do
  local mt = tds.metatables[kind] -- the surface's own (src/lua_elem.c)
  local set = mt and mt.__newindex
  if set then
    mt.__newindex = function(h, k, v)
      local ok, err = pcall(set, h, k, v)
      after(kind .. "." .. tostring(k) .. " = " .. tostring(v), nil, ok, err)
      if not ok then error(err, 0) end
    end
  end
end
return true
