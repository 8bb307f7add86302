-- pictures.lua: pictures, plots and the progress setting, friendly names
-- over the raw primitives of src/lua_render.c. Requiring it defines the
-- globals snapshot, plot, history and verbose. See doc/output.md.

local tds = tds

-- snapshot(path, { color =, view =, size =, edges =, range =, legend =,
-- lighting = }): the surface as a PNG picture. Returns the projection
-- (center, right, up, scale, cx, cy) and the colour range (lo, hi).
function snapshot(path, o)
  if type(path) ~= "string" then error("snapshot(path [, options]) expected", 2) end
  if o ~= nil and type(o) ~= "table" then error("snapshot: options must be a table", 2) end
  return tds.snapshot(path, o)
end

-- plot(path, { size = {w, h} }): energy and (for pg) r against iteration
-- over the iterations of this session.
function plot(path, o)
  if type(path) ~= "string" then error("plot(path [, options]) expected", 2) end
  if o ~= nil and type(o) ~= "table" then error("plot: options must be a table", 2) end
  return tds.plot(path, o)
end

-- history(): the iterations of this session, one record each:
-- { iteration =, kind = "g" | "pg", energy =, scale = (g) or r = (pg) }.
function history()
  local h, out = tds.history(), {}
  for i = 1, #h.iteration do
    local rec = { iteration = h.iteration[i], kind = h.kind[i], energy = h.energy[i] }
    if h.kind[i] == "pg" then rec.r = h.value[i] else rec.scale = h.value[i] end
    out[i] = rec
  end
  return out
end

-- verbose(on): Evolver's per-iteration lines even on a terminal (instead
-- of the live progress line). Returns the previous setting.
function verbose(on)
  if on == nil then return tds.verbose() end
  return tds.verbose(on and true or false)
end

return true
