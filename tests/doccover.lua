-- doccover.lua: every global name a tds script or the prompt can use (what
-- the program installs beyond standard Lua) must be documented in README.md
-- or doc/*.md (the files named in $DOCS), written in backticks as `name`, `name(`, `name{`, `name ` or
-- `name.`. Prints the undocumented names, one per line; nothing when all are.
local std = {}
for k in pairs(tds.base or {}) do std[k] = true end
for _, k in ipairs { "_G", "_VERSION", "assert", "collectgarbage", "coroutine",
  "debug", "dofile", "error", "getmetatable", "io", "ipairs", "load",
  "loadfile", "math", "next", "os", "package", "pairs", "pcall", "print",
  "rawequal", "rawget", "rawlen", "rawset", "require", "select",
  "setmetatable", "string", "table", "tonumber", "tostring", "type", "utf8",
  "warn", "xpcall" } do std[k] = true end
local text = {}
for path in os.getenv("DOCS"):gmatch("%S+") do
  local f = assert(io.open(path))
  text[#text + 1] = f:read("a")
  f:close()
end
text = table.concat(text, "\n")
local names = {}
for k in pairs(_G) do
  if type(k) == "string" and not std[k] then names[#names + 1] = k end
end
table.sort(names)
for _, k in ipairs(names) do
  local pat = "`" .. k:gsub("%p", "%%%0")
  if not (text:find(pat .. "[`({ .]")) then print(k) end
end
