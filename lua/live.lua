-- live.lua: show(), the live 3-D view in the browser (doc/output.md).
-- The server and the snapshots are C (src/live.c, src/lua_live.c); this
-- checks the options and opens the browser.

local tds = tds
local OPTIONS = { port = true, open = true, color = true, stop = true }
local FIELDS = { none = true, mean_curvature = true, min_angle = true,
                 body = true, tension = true, color = true }
local color = "none" -- the page's initial field, kept across show() calls

local function stop()
  if tds.live_stop() then print("live view stopped") end
end

-- show() / show{ port = n, open = bool, color = field }: start (or
-- update) the live view and print its address; show(false) or
-- show{ stop = true } stops it.
function show(o)
  if o == false then return stop() end
  if o == nil then o = {} end
  if type(o) ~= "table" then
    error("show: expected a table of options, or false to stop", 2)
  end
  local keys = {}
  for k in pairs(o) do
    if not OPTIONS[k] then
      error(("show: unknown option '%s' (options: color, open, port, stop)")
            :format(tostring(k)), 2)
    end
    keys[#keys + 1] = k
  end
  if o.stop ~= nil and type(o.stop) ~= "boolean" then
    error("show: stop must be true or false", 2)
  end
  if o.stop then
    if #keys > 1 then error("show: stop = true takes no other option", 2) end
    return stop()
  end
  local port = o.port
  if port ~= nil and (math.type(port) ~= "integer" or port < 0 or port > 65535) then
    error("show: port must be an integer 0..65535 (0: any free port)", 2)
  end
  if o.open ~= nil and type(o.open) ~= "boolean" then
    error("show: open must be true or false", 2)
  end
  if o.color ~= nil then
    if not FIELDS[o.color] then
      error(("show: unknown color '%s' (mean_curvature, min_angle, body, "
             .. "tension, color, none)"):format(tostring(o.color)), 2)
    end
    color = o.color
  end
  local p, err = tds.live_start(port or 0, color)
  if not p then error("show: " .. err:gsub("^live view: ", ""), 2) end
  local url = ("http://127.0.0.1:%d/"):format(p)
  local opened = false
  if o.open ~= false and os.execute("command -v xdg-open >/dev/null 2>&1") then
    opened = os.execute("xdg-open '" .. url .. "' >/dev/null 2>&1 &") and true
  end
  print(("live view: %s%s"):format(url, opened and " (opening in a browser)" or ""))
end
