-- numcmp.lua: compare the lines two programs printed, number by number.
-- Usage (as a tds -e chunk): numcmp(name, evolver_lines, tds_lines, tol)
-- Lines pair up in order; words that are numbers must agree: integers
-- (no '.', 'e' in both) exactly, reals to tol relative (absolute below 1);
-- other words exactly. Prints PASS name or FAIL name: the first difference.
function numcmp(name, ev, td, tol)
  local bad
  if #ev == 0 then bad = "no lines to compare from Evolver" end
  if #ev ~= #td then bad = bad or ("%d lines from Evolver, %d from tds"):format(#ev, #td) end
  for i = 1, math.min(#ev, #td) do
    local a, b = {}, {}
    for w in ev[i]:gmatch("%S+") do a[#a + 1] = w end
    for w in td[i]:gmatch("%S+") do b[#b + 1] = w end
    if #a ~= #b then bad = bad or ("line %d: '%s' vs '%s'"):format(i, ev[i], td[i]) end
    for j = 1, math.min(#a, #b) do
      local x, y = tonumber(a[j]), tonumber(b[j])
      if not x or not y then
        if a[j] ~= b[j] then bad = bad or ("line %d word %d: '%s' vs '%s'"):format(i, j, a[j], b[j]) end
      elseif not a[j]:find("[.eE]") and not b[j]:find("[.eE]") then
        if x ~= y then bad = bad or ("line %d: %s vs %s"):format(i, a[j], b[j]) end
      elseif math.abs(x - y) > tol * math.max(1, math.abs(x)) then
        bad = bad or ("line %d word %d: Evolver %s, tds %s (tolerance %g)"):format(i, j, a[j], b[j], tol)
      end
    end
  end
  if bad then print("FAIL " .. name .. ": " .. bad) else print("PASS " .. name) end
end
function lines_of(path, pattern)
  local t = {}
  for l in io.lines(path) do if l:find(pattern) then t[#t + 1] = l end end
  return t
end
