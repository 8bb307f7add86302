-- evolver.lua: read a REPL line written with Surface Evolver habits as Lua.
-- Used only when the line does not compile as Lua. Returns Lua source, or
-- nil if the line is not recognisable Evolver command syntax either.
--
--   g 5            -> g(5)
--   r; u; g 5      -> r() u() g(5)
--   angle := 45    -> angle = 45
--   print total_area -> print(total_area)
--   gogo           -> gogo()

local function trim(s) return (s:gsub("^%s+", ""):gsub("%s+$", "")) end

-- Split at semicolons outside strings, parentheses and braces.
local function split(line)
  local parts, depth, quote, start = {}, 0, nil, 1
  for i = 1, #line do
    local c = line:sub(i, i)
    if quote then
      if c == quote and line:sub(i - 1, i - 1) ~= "\\" then quote = nil end
    elseif c == '"' or c == "'" then quote = c
    elseif c == "(" or c == "{" or c == "[" then depth = depth + 1
    elseif c == ")" or c == "}" or c == "]" then depth = depth - 1
    elseif c == ";" and depth == 0 then
      parts[#parts + 1] = line:sub(start, i - 1)
      start = i + 1
    end
  end
  parts[#parts + 1] = line:sub(start)
  return parts
end

local function one(cmd)
  cmd = trim(cmd)
  if cmd == "" then return "" end
  local name, rest = cmd:match("^([%a_][%w_]*)%s*:=%s*(.+)$")
  if name then return name .. " = " .. rest end
  rest = cmd:match("^print%s+(.+)$")
  if rest then return "print(" .. rest .. ")" end
  name, rest = cmd:match("^([%a_][%w_]*)%s+([-+]?[%d.][%w.+-]*)$")
  if name and tonumber(rest) then return name .. "(" .. rest .. ")" end
  name = cmd:match("^([%a_][%w_]*)$")
  if name and type(_G[name]) == "function" then return name .. "()" end
  if load(cmd) then return cmd end -- a Lua statement among Evolver ones
  return nil
end

return function(line)
  local out = {}
  for _, part in ipairs(split(line)) do
    local code = one(part)
    if not code then return nil end
    out[#out + 1] = code
  end
  return table.concat(out, "\n")
end
