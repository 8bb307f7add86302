-- doccheck.lua: a doc example's shown output must be what it prints.
-- Returns check(block_file, output_file) -> true, or false and why.
-- A line `print(...)  --> EXPECTED` shows output: EXPECTED, less a
-- trailing "(comment)", must match a later line of the output than the
-- previous expectation's, with runs of blanks and tabs compared as one
-- space and `...` standing for any text.
local function norm(s)
  return (s:gsub("[ \t]+", " "):gsub("^ ", ""):gsub(" $", ""))
end

local function pattern(expected)
  expected = norm(expected:gsub("%s+%([^()]*%)%s*$", ""))
  local parts = {}
  for piece in (expected .. "..."):gmatch("(.-)%.%.%.") do
    parts[#parts + 1] = piece:gsub("%p", "%%%0")
  end
  return "^" .. table.concat(parts, ".*") .. (expected:sub(-3) == "..." and "" or "$")
end

return function(block, output)
  local out = {}
  for line in io.lines(output) do out[#out + 1] = norm(line) end
  local at, n = 1, 0
  for line in io.lines(block) do
    local want = line:match("^%s*print%b()%s*%-%->%s*(.-)%s*$")
    if want then
      n = n + 1
      local pat = pattern(want)
      while at <= #out and not out[at]:find(pat) do at = at + 1 end
      if at > #out then
        return false, ("shown output %d '%s' is not printed"):format(n, want)
      end
      at = at + 1
    end
  end
  return true
end
