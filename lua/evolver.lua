-- evolver.lua: the prompt's rule for Lua lines and Evolver lines.
--
-- tds.repl_classify(line) -> how, text
--   "lua", code      run code as Lua only (`.lua CODE`, or Lua mode)
--   "evolver", code  run code as Evolver text (`.evolver CODE`, Evolver
--                    mode, or a line that starts with an Evolver command
--                    and an argument: `g 5`, `G -5`, `gogo 2`, or with an
--                    Evolver statement word that is not Lua: `printf`,
--                    `foreach`, `set`, or is a bare built-in Evolver
--                    command (`U`, `v`, `r`) or one tds has no Lua global
--                    for: `C`, `i`, `hessian`, or a bare name that names
--                    nothing, which Evolver's runtime reports)
--   "auto", line     Lua if it compiles as Lua, else Evolver
--   "mode", message  a mode switch (`.lua`, `.evolver`, `.auto` alone)
-- tds.translate(text) -> Lua source | nil, message, incomplete
--   Evolver text to a Lua chunk for the prompt ("stdin" line numbers).

local evolang = require("evolang")
local E = require("evorun")

local mode = "auto"
local LUA_KEYWORDS = { ["if"] = true, ["while"] = true, ["for"] = true, ["do"] = true,
                       ["return"] = true, ["break"] = true, ["local"] = true, ["function"] = true }

local function trim(s) return (s:gsub("^%s+", ""):gsub("%s+$", "")) end

local function evolver_command(word)
  if E.B[word] or E.UNSUPPORTED[word] or E.UNSUPPORTED[word:lower()] then return true end
  if #word == 1 and evolang.LETTERS[word] then return true end
  local f = rawget(_G, word)
  return type(f) == "function"
end

function tds.repl_classify(line)
  local t = trim(line)
  local pre, rest = t:match("^%.(%a+)%s*(.*)$")
  if pre == "lua" or pre == "evolver" or pre == "auto" then
    if rest == "" then
      mode = pre
      return "mode", ({ lua = "Lua mode: lines run as Lua (.auto to go back).",
                        evolver = "Evolver mode: lines run as Evolver commands (.auto to go back).",
                        auto = "Auto mode: Lua lines run as Lua, other lines as Evolver commands." })[pre]
    end
    if pre == "auto" then return "auto", rest end
    return pre, rest
  end
  if mode ~= "auto" then return mode, line end
  local word, after = t:match("^([%a_][%w_]*)(.*)$")
  if word then
    -- `g 5`, `G -5`, `m 0.1`, `gogo 3`: a command and an argument.
    local g = rawget(_G, word)
    local arg = after:match("^%s+[%w_.\"]") or after:match("^%s+[-+][%d.]")
    if arg and evolver_command(word) and (g == nil or type(g) == "function")
       and not after:match("^%s+[%a_][%w_]*%s*=[^=]") then
      return "evolver", line
    end
    -- an Evolver statement word that is not Lua: printf, foreach, set, define
    if evolang.STMT[word] and not LUA_KEYWORDS[word] and rawget(_G, word) == nil then
      return "evolver", line
    end
    -- g10: a single-letter command with its count glued on
    local letter = word:match("^(%a)%d+$")
    if after == "" and letter and evolang.LETTERS[letter] and rawget(_G, word) == nil
       and tds.param(word) == nil then
      return "evolver", line
    end
    -- a bare built-in Evolver command (with Evolver's messages: U, m, v),
    -- or one without a Lua function of that name: C, i, hessian
    local gv = rawget(_G, word)
    if after == "" and (gv == nil or type(gv) == "function") and tds.param(word) == nil
       and (E.B[word] or gv == nil and evolver_command(word)) then
      return "evolver", line
    end
    -- a bare name that names nothing: Evolver's error naming it, not Lua's nil
    if after == "" and not LUA_KEYWORDS[word] and _G[word] == nil and tds.param(word) == nil then
      return "evolver", line
    end
  end
  return "auto", line
end

-- The prompt names the mode when it is not auto.
function tds.repl_prompt()
  if mode == "evolver" then return "evolver> " end
  if mode == "lua" then return "lua> " end
  return "tds> "
end

function tds.translate(text)
  local src, err = evolang.translate(text, 1)
  if src then return src end
  return nil, "stdin:" .. err, err:match("end of input") ~= nil or err:match("not closed") ~= nil
end

return tds.translate
