-- evolang.lua: Surface Evolver command text -> Lua source.
--
-- translate(text [, line0]) returns Lua source, or nil and "LINE: message".
-- The source expects the runtime table (lua/evorun.lua) as its vararg and
-- keeps every statement on its Evolver line (line0 + line in text), so a
-- chunk loaded as "@CMDS" reports run-time errors as CMDS:LINE.
--
-- Semantics kept from Evolver (syntax.htm, ../doc/command-language.md):
-- `^`/`**` left associative and tighter than unary minus; comparisons
-- right associative returning 1/0; `not` below `==`; `and`/`or` give 0/1;
-- `=` compares; numbers are reals. Single-letter commands are
-- case-sensitive; other names are folded to lower case when assigned.
-- Statements end at `;`, `}` or a new line that starts a new statement.

local M = {}

---------------------------------------------------------------- lexer

local OPS3 = { [":::="] = true }
local OPS3b = { [">>>"] = true, ["::="] = true }
local OPS2 = { [":="] = true, ["+="] = true, ["-="] = true, ["*="] = true, ["/="] = true,
               ["=="] = true, ["!="] = true, ["<="] = true, [">="] = true, ["&&"] = true,
               ["||"] = true, ["**"] = true, [">>"] = true, ["++"] = true, ["--"] = true }

-- Tokens of text. A lexical error ends the list with an eof token that
-- carries it (lexerr), so the commands before it still run.
local function lex(text, line0)
  local toks, i, n, line, nl = {}, 1, #text, line0 or 1, true
  local function err(msg) error({ evo = true, line = line, msg = msg }, 0) end
  local ok, e = pcall(function()
  while true do
    -- whitespace, comments, line splices
    while i <= n do
      local c = text:sub(i, i)
      if c == "\n" then line = line + 1; nl = true; i = i + 1
      elseif c == " " or c == "\t" or c == "\r" or c == "\f" then i = i + 1
      elseif c == "\\" and text:match("^\\[ \t\r]*\n", i) then
        local j = text:find("\n", i, true); i = j + 1; line = line + 1
      elseif text:sub(i, i + 1) == "//" then
        local j = text:find("\n", i, true); i = j or n + 1
      elseif c == "#" and nl then -- Evolver's '#' comment lines
        local j = text:find("\n", i, true); i = j or n + 1
      elseif text:sub(i, i + 1) == "/*" then
        local j = text:find("*/", i + 2, true)
        if not j then err("comment /* not closed") end
        for _ in text:sub(i, j):gmatch("\n") do line = line + 1; nl = true end
        i = j + 2
      else break end
    end
    if i > n then break end
    local tok = { line = line, nl = nl, at = i }
    nl = false
    local c = text:sub(i, i)
    local num = text:match("^0[xX]%x+", i)
    if not num then
      num = text:match("^%d+%.?%d*[eE][-+]?%d+", i) or text:match("^%.%d+[eE][-+]?%d+", i)
            or text:match("^%d+%.?%d*", i) or text:match("^%.%d+", i)
    end
    if num then
      tok.t = "num"; tok.v = tonumber(num) + 0.0; i = i + #num
      if text:match("^[%a_]", i) then err("malformed number near '" .. num .. text:sub(i, i) .. "'") end
    elseif c:match("[%a_]") then
      local w = text:match("^[%a_][%w_]*", i)
      tok.t = "name"; tok.raw = w; tok.s = #w == 1 and w or w:lower(); i = i + #w
    elseif c == "'" and text:match("^'%a'", i) then
      -- 'r': the original single-letter command, even if redefined
      tok.t = "name"; tok.raw = text:sub(i + 1, i + 1); tok.s = tok.raw; tok.orig = true; i = i + 3
    elseif c == '"' then
      local buf, j = {}, i + 1
      while true do
        local d = text:sub(j, j)
        if d == "" or d == "\n" then err("string not closed") end
        if d == '"' then break end
        if d == "\\" then
          local e = text:sub(j + 1, j + 1)
          local map = { n = "\n", t = "\t", r = "\r", b = "\b", q = '"', ['"'] = '"', ["\\"] = "\\" }
          buf[#buf + 1] = map[e] or ("\\" .. e); j = j + 2
        else buf[#buf + 1] = d; j = j + 1 end
      end
      tok.t = "str"; tok.v = table.concat(buf); i = j + 1
    else
      local s4, s3, s2 = text:sub(i, i + 3), text:sub(i, i + 2), text:sub(i, i + 1)
      local op = OPS3[s4] and s4 or OPS3b[s3] and s3 or OPS2[s2] and s2 or c
      if not op:match("^[-+*/%%^<>=!&|(){}%[%],.;:?]") then err("unexpected character '" .. c .. "'") end
      tok.t = "op"; tok.v = op; i = i + #op
    end
    toks[#toks + 1] = tok
  end
  end)
  local eof = { t = "eof", line = line, nl = true, at = n + 1 }
  if not ok then
    if type(e) ~= "table" or not e.evo then error(e, 0) end
    eof.lexerr = e
  end
  toks[#toks + 1] = eof
  return toks
end

---------------------------------------------------------------- tables

local KINDS = { vertex = "vertex", vertices = "vertex", edge = "edge", edges = "edge",
                facet = "facet", facets = "facet", face = "facet", faces = "facet",
                body = "body", bodies = "body", facetedge = "facetedge", facetedges = "facetedge" }

-- Attribute names a bare name means inside a generator (element context),
-- and that are never element names after a generator.
local ATTRS = {}
for w in ([[id oid x y z fixed valence length area volume target pressure density
  tension color frontcolor backcolor frontbody backbody no_refine volconst original
  bare p1 p2 constraint constraints boundary on_constraint hit_constraint on_boundary
  mean_curvature dihedral orientation edge_vector facet_normal vertex_normal
  sqcurve no_display nodisplay show]]):gmatch("%S+") do ATTRS[w] = true end

local MATH1 = {}
for w in ("abs sqr sqrt sin cos tan asin acos atan log exp sinh cosh tanh asinh acosh atanh ceil floor ellipticK ellipticE"):gmatch("%S+") do MATH1[w:lower()] = true end
local MATH2 = { atan2 = true, pow = true, minimum = true, maximum = true,
                incompleteelliptice = true, incompleteellipticf = true,
                wrap_compose = true } -- wrap_inverse is in MATH1 (doc/torus.md)
MATH1.wrap_inverse = true
local AGG = { max = true, min = true, sum = true, avg = true, count = true }

-- Words that begin a statement of their own kind.
local STMT = {}
for w in ([[if while do for foreach return break continue abort local procedure
  function define print printf binary_printf errprintf eprint list set unset fix unfix refine
  equiangulate vertex_average delete dissolve pop edgeswap t1_edgeswap pop_edge_to_tri
  pop_tri_to_edge pop_quad_to_quad reverse_orientation read exec]]):gmatch("%S+") do
  STMT[w] = true
end

-- Single-letter commands (case-sensitive) that take an optional count.
local LETTERS = {}
for c in ("gruVvUmGqxtowlKnjJiCcAabfkMNpQWyZzdsPDFHhXeYBORT"):gmatch(".") do LETTERS[c] = true end

---------------------------------------------------------------- parser

local P = {}
P.__index = P

-- A Lua string literal on one line (so the translation keeps line numbers).
local function q(s) return (string.format("%q", s):gsub("\\\n", "\\n")) end

local function numlit(v)
  if v ~= v then return "(0/0)" end
  if v == math.huge then return "math.huge" end
  local s = string.format("%.17g", v)
  if not s:find("[.eEn]") then s = s .. ".0" end
  return s
end

function P:peek(k) return self.toks[self.i + (k or 0)] end
function P:next() local t = self.toks[self.i]; self.i = self.i + 1; return t end
function P:isop(v, k) local t = self:peek(k); return t.t == "op" and t.v == v end
function P:isname(w, k) local t = self:peek(k); return t.t == "name" and t.s == w end
function P:err(msg, tok)
  tok = tok or self:peek()
  if tok.lexerr then error(tok.lexerr, 0) end
  error({ evo = true, line = tok.line, msg = msg }, 0)
end
function P:desc(t)
  t = t or self:peek()
  if t.t == "eof" then return "end of input" end
  if t.t == "str" then return "string" end
  return "'" .. (t.raw or tostring(t.v)) .. "'"
end
function P:expect(v, what)
  if not self:isop(v) then self:err(("expected '%s'%s, found %s"):format(v, what and (" " .. what) or "", self:desc())) end
  return self:next()
end
function P:acceptop(v) if self:isop(v) then self:next(); return true end end
function P:acceptname(w) if self:isname(w) then self:next(); return true end end
function P:gensym(p) self.nsym = self.nsym + 1; return (p or "_t") .. self.nsym end
function P:mark(line) return "\0" .. line .. "\0" end

-- A token that may continue an expression: not at a new line at top level.
function P:cont(t) t = t or self:peek(); return not (t.nl and self.depth == 0) end

-- Scopes: Evolver names -> Lua locals (locals, parameters, element names).
function P:push() self.scopes[#self.scopes + 1] = {} end
function P:pop() self.scopes[#self.scopes] = nil end
function P:bind(name, lua, kind) self.scopes[#self.scopes][name] = { lua = lua, kind = kind } end
function P:lookup(name)
  for k = #self.scopes, 1, -1 do
    local b = self.scopes[k][name]
    if b then return b end
    if self.scopes[k].fence then break end
  end
end
-- The current element (innermost generator) for bare attribute names.
function P:current()
  for k = #self.elems, 1, -1 do return self.elems[k] end
end

---------------------------------------------------------------- expressions

local function asnum(c, k) if k == "b" then return "(" .. c .. " and 1 or 0)" end return c end
local function ascond(c, k) if k == "b" then return c end return "E.truth(" .. c .. ")" end

function P:expr()
  local c, k = self:ternary()
  while self:isop("=") and self:cont() do
    self:next()
    local r, rk = self:ternary()
    c, k = "(" .. asnum(c, k) .. " == " .. asnum(r, rk) .. ")", "b"
  end
  return c, k
end

function P:ternary()
  local c, k = self:orexpr()
  if self:isop("?") and self:cont() then
    self:next()
    local a, ak = self:expr()
    self:expect(":", "in a ? : expression")
    local b, bk = self:ternary()
    -- only the chosen branch is evaluated
    return "((" .. ascond(c, k) .. ") and {" .. asnum(a, ak) .. "} or {" .. asnum(b, bk) .. "})[1]", "a"
  end
  return c, k
end

function P:orexpr()
  local c, k = self:andexpr()
  while (self:isname("or") or self:isop("||")) and self:cont() do
    self:next()
    local r, rk = self:andexpr()
    c, k = "(" .. ascond(c, k) .. " or " .. ascond(r, rk) .. ")", "b"
  end
  return c, k
end

function P:andexpr()
  local c, k = self:notexpr()
  while (self:isname("and") or self:isop("&&")) and self:cont() do
    self:next()
    local r, rk = self:notexpr()
    c, k = "(" .. ascond(c, k) .. " and " .. ascond(r, rk) .. ")", "b"
  end
  return c, k
end

function P:notexpr()
  if self:isname("not") or self:isop("!") then
    self:next()
    local c, k = self:notexpr()
    return "(not " .. ascond(c, k) .. ")", "b"
  end
  return self:relexpr()
end

local RELOPS = { ["=="] = "==", ["!="] = "~=", ["<"] = "<", [">"] = ">", ["<="] = "<=", [">="] = ">=" }
function P:relexpr()
  local c, k = self:addexpr()
  local t = self:peek()
  if t.t == "op" and RELOPS[t.v] and self:cont() then
    self:next()
    local r, rk = self:relexpr() -- right associative
    return "(" .. asnum(c, k) .. " " .. RELOPS[t.v] .. " " .. asnum(r, rk) .. ")", "b"
  end
  return c, k
end

function P:addexpr()
  local c, k = self:mulexpr()
  while (self:isop("+") or self:isop("-") or self:isop("++") or self:isop("--")) and self:cont() do
    local op = self:next().v
    if op == "--" then op = "+" elseif op == "++" then op = "+" end -- a - -b, a + +b
    local r, rk = self:mulexpr()
    c, k = "E.arith(" .. q(op) .. ", " .. asnum(c, k) .. ", " .. asnum(r, rk) .. ")", "a"
  end
  return c, k
end

local MULOPS = { ["*"] = "*", ["/"] = "/", ["%"] = "%" }
function P:mulexpr()
  local c, k = self:unary()
  while true do
    local t = self:peek()
    local op
    if t.t == "op" and MULOPS[t.v] then op = t.v
    elseif t.t == "name" and (t.s == "mod" or t.s == "imod" or t.s == "idiv") then op = t.s end
    if not op or not self:cont() then break end
    self:next()
    local r, rk = self:unary()
    c, k = "E.arith(" .. q(op) .. ", " .. asnum(c, k) .. ", " .. asnum(r, rk) .. ")", "n"
  end
  return c, k
end

function P:unary()
  if self:isop("--") then -- two minus signs
    self:next()
    local c, k = self:unary()
    return "(" .. asnum(c, k) .. ")", "n"
  elseif self:isop("++") then
    self:next()
    return self:unary()
  end
  if self:isop("-") then
    self:next()
    local c, k = self:unary()
    return "(-" .. asnum(c, k) .. ")", "n"
  elseif self:isop("+") then
    self:next()
    return self:unary()
  end
  return self:powexpr()
end

function P:powexpr()
  local c, k = self:postfix()
  while (self:isop("^") or self:isop("**")) and self:cont() do
    self:next()
    local neg = self:acceptop("-")
    local r, rk = self:postfix()
    r = asnum(r, rk)
    if neg then r = "(-" .. r .. ")" end
    c, k = "E.pow(" .. asnum(c, k) .. ", " .. r .. ")", "n"
  end
  return c, k
end

-- Comma-separated expressions up to ')'; '(' already taken.
function P:args()
  local a = {}
  if not self:isop(")") then
    repeat
      local c, k = self:expr()
      a[#a + 1] = asnum(c, k)
    until not self:acceptop(",")
  end
  self:expect(")", "closing the argument list")
  return table.concat(a, ", ")
end

-- Element postfix chain on an element-valued expression: .attr, .kind[i],
-- .on_constraint n, and array indexes of vector attributes.
function P:elemchain(c)
  while self:isop(".") do
    local dot = self:next()
    local t = self:next()
    if t.t ~= "name" then self:err("expected an attribute name after '.'", t) end
    local w = t.s
    if KINDS[w] and self:isop("[") then
      self:next()
      local i, ik = self:expr()
      self:expect("]")
      c = "E.subelem(" .. c .. ", " .. q(KINDS[w]) .. ", " .. asnum(i, ik) .. ")"
    elseif w == "on_constraint" or w == "hit_constraint" or w == "on_boundary" then
      local n, nk = self:unary()
      return "E.pred(" .. c .. ", " .. q(w) .. ", " .. asnum(n, nk) .. ")", "b"
    elseif w == "value_of_constraint" then
      local n, nk = self:unary()
      return "E.pred(" .. c .. ", " .. q(w) .. ", " .. asnum(n, nk) .. ")", "n"
    else
      if KINDS[w] then self:err("'" .. t.raw .. "' here makes a generator; use it after foreach or in an aggregate", dot) end
      if w == "x" and self:isop("[") then w = "__x" end -- vv.x[2]: coordinate 2
      c = "E.attr(" .. c .. ", " .. q(w) .. ")"
      while self:isop("[") do
        self:next()
        local i, ik = self:expr()
        self:expect("]")
        c = "E.index(" .. c .. ", " .. asnum(i, ik) .. ")"
      end
    end
  end
  return c, "a"
end

function P:postfix()
  local t = self:peek()
  if t.t == "num" then self:next(); return numlit(t.v), "n" end
  if t.t == "str" then
    self:next()
    local parts = { q(t.v) }
    while self:peek().t == "str" or self:isname("sprintf") do
      if self:peek().t == "str" then parts[#parts + 1] = q(self:next().v)
      else parts[#parts + 1] = (self:postfix()) end
    end
    if #parts == 1 then return parts[1], "s" end
    return "(" .. table.concat(parts, " .. ") .. ")", "s"
  end
  if self:acceptop("(") then
    local c, k = self:expr()
    self:expect(")", "closing '('")
    return "(" .. c .. ")", k
  end
  if self:isop("{") then return self:initializer(), "a" end -- an array value {1, x, y}
  if t.t ~= "name" then self:err("expected an expression, found " .. self:desc()) end
  local w = t.s
  if w == "pi" then self:next(); return "math.pi", "n" end
  if (t.raw == "e" or t.raw == "E") then self:next(); return "math.exp(1)", "n" end
  if w == "sprintf" then
    self:next()
    local paren = self:acceptop("(")
    local f = asnum(self:expr())
    local a = { f }
    while self:acceptop(",") do a[#a + 1] = asnum(self:expr()) end
    if paren then self:expect(")") end
    return "E.sprintf(" .. table.concat(a, ", ") .. ")", "s"
  end
  if (MATH1[w] or MATH2[w]) and self:isop("(", 1) then
    self:next(); self:next()
    return "E.fn." .. w .. "(" .. self:args() .. ")", "n"
  end
  if AGG[w] and self:isop("(", 1) then
    self:next(); self:next()
    local g = self:generator()
    self:expect(",", "after the generator of " .. w .. "()")
    self:pushgen(g)
    local v, vk = self:expr()
    self:popgen()
    self:expect(")")
    local cond = g.cond and ("if " .. g.cond .. " then ") or "if true then "
    return ("E.agg(%s, %s, function(%s) %s return %s end end)"):format(q(w), g.arr, g.var, cond, asnum(v, vk)), "n"
  end
  if (w == "is_defined" or w == "sizeof" or w == "valid_element" or w == "valid_constraint"
      or w == "valid_boundary" or w == "matrix_inverse" or w == "matrix_multiply"
      or w == "matrix_determinant") and self:isop("(", 1) then
    self:next(); self:next()
    local a1, a2 = self:peek(), self:peek(1)
    if w == "sizeof" and a1.t == "name" and self.extra[a1.s] and not self:lookup(a1.s)
       and a2.t == "op" and a2.v == ")" then -- sizeof(extra_attribute): its values per element
      self:next(); self:next()
      return "E.attrsize(" .. q(a1.s) .. ")", "n"
    end
    if w == "valid_element" then
      local kt = self:next()
      if kt.t ~= "name" or not KINDS[kt.s] then self:err("valid_element(kind[id]) expected", kt) end
      self:expect("[")
      local i = asnum(self:expr())
      self:expect("]")
      self:expect(")")
      return "(E.getelem(" .. q(KINDS[kt.s]) .. ", " .. i .. ", true) and 1 or 0)", "n"
    end
    return "E.fn." .. w .. "(" .. self:args() .. ")", "n"
  end
  if KINDS[w] and self:isop("[", 1) then
    self:next(); self:next()
    local i, ik = self:expr()
    self:expect("]")
    return self:elemchain("E.getelem(" .. q(KINDS[w]) .. ", " .. asnum(i, ik) .. ")")
  end
  if (w == "on_constraint" or w == "hit_constraint" or w == "on_boundary" or w == "value_of_constraint") then
    local cur = self:current()
    if not cur then self:err(w .. " needs an element (use it in a where clause or foreach)") end
    self:next()
    local n, nk = self:unary()
    return "E.pred(" .. cur.var .. ", " .. q(w) .. ", " .. asnum(n, nk) .. ")", w == "value_of_constraint" and "n" or "b"
  end
  self:next()
  local b = self:lookup(w)
  local c
  if b then
    c = b.lua
    if b.kind then return self:elemchain(c) end
  elseif self:isop("(") and self:cont() then
    self:next()
    return "E.callf(" .. q(t.raw) .. (self:isop(")") and "" or ", ") .. self:args() .. ")", "a"
  else
    local cur = self:current()
    if cur and (ATTRS[w] or self.extra[w]) then
      c = "E.attr(" .. cur.var .. ", " .. q(w) .. ")"
    elseif cur then
      c = "E.getv(" .. q(t.raw) .. ", " .. cur.var .. ")"
    else
      c = "E.getv(" .. q(t.raw) .. ")"
    end
  end
  while self:isop("[") do
    self:next()
    local i, ik = self:expr()
    self:expect("]")
    c = "E.index(" .. c .. ", " .. asnum(i, ik) .. ")"
  end
  if self:isop(".") then return self:elemchain(c) end
  return c, "a"
end

---------------------------------------------------------------- generators

-- generator := kind [ '[' i ']' ] { '.' kind [ '[' i ']' ] } [name] [where cond]
--            | element-variable '.' kind ...
-- Returns { arr = Lua list expression, kind, var = Lua local, cond }.
function P:generator()
  local t = self:next()
  local base, arr, kind
  if t.t == "name" and KINDS[t.s] then
    kind = KINDS[t.s]
    if self:isop("[") then
      self:next()
      local i = asnum(self:expr())
      self:expect("]")
      base = "E.getelem(" .. q(kind) .. ", " .. i .. ")"
    else
      arr = "E.all(" .. q(kind) .. ")"
    end
  elseif t.t == "name" and self:lookup(t.s) and self:lookup(t.s).kind then
    base, kind = self:lookup(t.s).lua, self:lookup(t.s).kind
  else
    self:err("expected an element generator (vertex, edge, facet, body), found " .. self:desc(t), t)
  end
  while not arr and ((self:isop(".") and self:peek(1).t == "name" and KINDS[self:peek(1).s])
                     or (self:peek().t == "name" and KINDS[self:peek().s] and self:cont())) do
    if self:isop(".") then self:next() end -- `ff vertex` is an old spelling of ff.vertex
    local kt = self:next()
    kind = KINDS[kt.s]
    if self:isop("[") then
      self:next()
      local i = asnum(self:expr())
      self:expect("]")
      base = "E.subelem(" .. base .. ", " .. q(kind) .. ", " .. i .. ")"
    else
      arr = "E.subs(" .. base .. ", " .. q(kind) .. ")"
    end
  end
  if not arr then arr = "{" .. base .. "}" end
  local g = { arr = arr, kind = kind, var = self:gensym("_e") }
  local nt = self:peek()
  if nt.t == "name" and not ATTRS[nt.s] and not KINDS[nt.s] and nt.s ~= "where" and nt.s ~= "do"
     and not STMT[nt.s] and not self.extra[nt.s] and self:cont(nt)
     and not (#nt.raw == 1 and LETTERS[nt.raw])
     and not (self.setgen and self:peek(1).t ~= "name") then
    self:next()
    g.name = nt.s
  end
  if self:isname("where") and self:cont() then
    self:next()
    self:pushgen(g)
    local c, k = self:expr()
    self:popgen()
    g.cond = ascond(c, k)
  end
  return g
end

function P:pushgen(g)
  self:push()
  if g.name then self:bind(g.name, g.var, g.kind) end
  self.elems[#self.elems + 1] = g
end
function P:popgen() self.elems[#self.elems] = nil; self:pop() end

-- "for _, VAR in ipairs(ARR) do if COND then BODY end end"
local function genloop(g, body)
  return ("for _, %s in ipairs(%s) do if E.live(%s)%s then %s end end"):format(
    g.var, g.arr, g.var, g.cond and (" and " .. g.cond) or "", body)
end

---------------------------------------------------------------- statements

-- Can this token end a statement (so no argument follows)?
function P:atend(t)
  t = t or self:peek()
  if t.t == "eof" or t.nl and self.depth == 0 then return true end
  if t.t == "op" and (t.v == ";" or t.v == "}" or t.v == ">>" or t.v == ">>>" or t.v == "|"
                      or t.v == ")") then return true end
  if t.t == "name" and t.s == "else" then return true end
  return false
end

-- Evolver takes a ':' that ends a line or comes before '}' as the end of
-- the command (3ds.cmd has one); step over it.
function P:stray_colon()
  if not self:isop(":") then return false end
  local n = self:peek(1)
  if n.t == "eof" or n.nl or (n.t == "op" and n.v == "}") then self:next(); return true end
  return false
end

function P:block_until_brace()
  local parts = {}
  self.depth = self.depth + 1
  while true do
    while self:acceptop(";") or self:stray_colon() do end
    if self:isop("}") then break end
    if self:peek().t == "eof" then self:err("'{' not closed by '}'") end
    parts[#parts + 1] = self:statement()
    if not (self:isop(";") or self:isop("}") or self:stray_colon()) then
      local t = self:peek()
      if not t.nl then self:err("expected ';' or '}' after a command, found " .. self:desc()) end
    end
  end
  self.depth = self.depth - 1
  self:next()
  return table.concat(parts, " ")
end

-- A compound { ... } with an optional repetition count.
function P:compound()
  self:expect("{")
  self:push()
  local body = self:block_until_brace()
  self:pop()
  local t = self:peek()
  if not self:atend() and not (t.t == "name" and (t.s == "while" or t.s == "then" or t.s == "do")) then
    local n = asnum(self:expr())
    return "for _ = 1, E.count(" .. n .. ") do " .. body .. " end"
  end
  return "do " .. body .. " end"
end

-- Loops: continue/break labels.
function P:loop(fn)
  local id = self:gensym("")
  self.loops[#self.loops + 1] = id
  local body = fn()
  self.loops[#self.loops] = nil
  return body, id
end

function P:jump(what)
  local n = 1
  if not self:atend() then
    local t = self:next()
    if t.t ~= "num" or t.v < 1 or t.v % 1 ~= 0 then self:err(what .. " count must be a positive whole number", t) end
    n = math.floor(t.v)
  end
  local id = self.loops[#self.loops - n + 1]
  if not id then self:err(what .. (n > 1 and (" " .. n) or "") .. " outside a loop") end
  return "goto " .. (what == "break" and "_b" or "_c") .. id
end

local function loopbody(body, id) return "do " .. body .. " end ::_c" .. id .. "::" end

-- A definition body compiled as a function with its own scopes and loops.
-- The body of a definition (a Lua function body) and, for the outermost
-- definition, the Lua list of the command words in it that nothing in this
-- text defines: the runtime refuses the definition when one of them is not
-- a command, variable or function at that moment, as Evolver refuses
-- `gg := { nosuchcmd 5 }` when it reads it.
function P:funcbody(params, compound)
  local outer = not self.unknown
  if outer then self.unknown = {} end
  local saved_loops = self.loops
  self.loops = {}
  self:push()
  self.scopes[#self.scopes].fence = true
  for _, p in ipairs(params) do self:bind(p.name, p.lua) end
  local saved_elems = self.elems
  self.elems = {}
  local body
  if compound then
    self:expect("{")
    body = self:block_until_brace()
  else
    body = self:statement()
  end
  self.elems = saved_elems
  self:pop()
  self.loops = saved_loops
  local unknown = self.unknown
  if not outer then return body, "" end
  self.unknown = nil
  local words = {}
  for i, w in ipairs(unknown) do words[i] = q(w) end
  return body, #words > 0 and ", {" .. table.concat(words, ", ") .. "}" or ""
end

-- A definition: FN(name, function(PARAMS) BODY end[, unknown words]).
function P:defn(fn, name, params, compound, names)
  local body, words = self:funcbody(params, compound)
  return fn .. "(" .. q(name) .. ", function(" .. (names or "") .. ") " .. body .. " end" .. words .. ")"
end

-- Command word t, run by E.cmd: noted for its definition's check unless
-- the text itself defines it.
function P:note_cmd(t)
  if self.unknown and not self:lookup(t.s) and not self.names[t.s] and not self.names[t.raw]
     and not (self.usercmds and self.usercmds[t.s]) then
    self.unknown[#self.unknown + 1] = t.raw
  end
end

function P:params()
  local ps, names = {}, {}
  self:expect("(")
  if not self:isop(")") then
    repeat
      local ty = self:next()
      local nm = ty
      if ty.t == "name" and (ty.s == "real" or ty.s == "integer" or ty.s == "string"
         or ty.s == "element" or KINDS[ty.s]) then nm = self:next() end
      if nm.t ~= "name" then self:err("expected a parameter name", nm) end
      local lua = "L_" .. nm.s
      ps[#ps + 1] = { name = nm.s, lua = lua, int = ty.s == "integer" }
      names[#names + 1] = lua
    until not self:acceptop(",")
  end
  self:expect(")")
  return ps, table.concat(names, ", ")
end

local TYPES = { real = true, integer = true, string = true }

function P:statement()
  local t = self:peek()
  local code = self:statement1()
  -- Output redirection applies to the whole statement.
  local r = self:peek()
  if r.t == "op" and (r.v == ">>" or r.v == ">>>" or r.v == "|") and self:cont(r) then
    self:next()
    local f = asnum(self:postfix())
    code = ("E.redirect(%s, %s, function() %s end)"):format(q(r.v), f, code)
  end
  return self:mark(t.line) .. code
end

-- An lvalue's setter given a value expression, or nil if t is not one.
function P:assign_to(target, op, value)
  if op == ":=" or op == "=" then return target.set(value) end
  local bop = op:sub(1, 1)
  return target.set("E.arith(" .. q(bop) .. ", " .. target.get .. ", " .. value .. ")")
end

function P:statement1()
  local t = self:peek()
  if t.t == "op" and t.v == "{" then return self:compound() end
  if t.t ~= "name" then
    if t.t == "eof" then self:err("unexpected end of input") end
    self:err("expected a command, found " .. self:desc())
  end
  local w = t.s
  local nxt = self:peek(1)
  local isassign = nxt.t == "op" and (nxt.v == ":=" or nxt.v == "::=" or nxt.v == ":::=" or
                   nxt.v == "+=" or nxt.v == "-=" or nxt.v == "*=" or nxt.v == "/=")

  if not isassign and STMT[w] and not self:lookup(w) then return self["s_" .. w](self) end
  if w == "else" then self:err("'else' without 'if' (no ';' goes before else)") end
  if w == "then" then self:err("'then' without 'if'") end

  -- show / show_expr GEN [where ...]: display criteria, no effect without
  -- graphics (Evolver's default criteria are what `show` reads)
  if (w == "show" or w == "show_expr" or w == "showq") and nxt.t == "name" and KINDS[nxt.s] then
    self:next()
    local g = self:generator()
    return "do end"
  end

  -- histogram(gen, expr), loghistogram(gen, expr)
  if (w == "histogram" or w == "loghistogram") and nxt.t == "op" and nxt.v == "(" then
    self:next(); self:next()
    local g = self:generator()
    self:expect(",", "after the generator of " .. w .. "()")
    self:pushgen(g)
    local v, vk = self:expr()
    self:popgen()
    self:expect(")")
    local cond = g.cond and ("if " .. g.cond .. " then ") or "if true then "
    return ("E.histogram(%s, %s, function(%s) %s return %s end end)"):format(
      tostring(w == "loghistogram"), g.arr, g.var, cond, asnum(v, vk))
  end

  if t.orig then
    self:next()
    if self:atend() then return "E.orig(" .. q(t.raw) .. ")" end
    return "E.orig(" .. q(t.raw) .. ", " .. asnum(self:expr()) .. ")"
  end

  -- single-letter commands with glued counts: g10
  local letter, digits = t.raw:match("^(%a)(%d+)$")
  if letter and LETTERS[letter] and not isassign and not self:lookup(w)
     and not (nxt.t == "op" and (nxt.v == "[" or nxt.v == "." or nxt.v == "++" or nxt.v == "--")) then
    self:next()
    return "E.cmd(" .. q(letter) .. ", " .. numlit(tonumber(digits)) .. ")"
  end

  -- x++, x-- (statements)
  if nxt.t == "op" and (nxt.v == "++" or nxt.v == "--") then
    self:next(); self:next()
    local d = nxt.v == "++" and "1.0" or "-1.0"
    local b = self:lookup(w)
    if b then return b.lua .. " = E.arith('+', " .. b.lua .. ", " .. d .. ")" end
    if #t.raw == 1 and LETTERS[t.raw] then self:err("'" .. t.raw .. "' is a single-letter command", t) end
    return "E.setv(" .. q(w) .. ", E.arith('+', E.getv(" .. q(t.raw) .. "), " .. d .. "))"
  end

  if isassign then
    self:next()
    local op = self:next().v
    if #t.raw == 1 and LETTERS[t.raw] and op ~= ":::=" then
      self:err(("'%s' is a single-letter command and cannot be assigned (use %s :::= {...} to redefine it)"):format(t.raw, t.raw), t)
    end
    if op == ":::=" then
      if #t.raw ~= 1 then self:err(":::= redefines a single-letter command", t) end
      return self:defn("E.redefine", t.raw, {}, self:isop("{"))
    end
    -- name := {1, x, -y}: an array value when the braces hold a list of
    -- expressions separated by commas; otherwise a command definition.
    if op == ":=" and self:isop("{") then
      local save, saved_depth = self.i, self.depth
      local ok, init = pcall(self.initializer, self)
      local a1 = self.toks[save + 1]
      if ok and (a1.t == "num" or (a1.t == "op" and (a1.v == "{" or a1.v == "-"))
                 or init:find(",", 1, true)) and self:atend() then
        local b = self:lookup(w)
        if b and not b.kind then return b.lua .. " = " .. init end
        return "E.setarray(" .. q(w) .. ", " .. init .. ")"
      end
      if not ok and (type(init) ~= "table" or not init.evo) then error(init, 0) end
      self.i, self.depth = save, saved_depth
    end
    if (op == ":=" or op == "::=") and self:isop("{") and not self:lookup(w) then
      self.usercmds = self.usercmds or {}
      self.usercmds[w] = true -- a user command of that name is no unsupported command
      return self:defn("E.defcmd", w, {}, true)
    end
    -- name := command (no braces), as Evolver: `gg := g 5`, `few :=
    -- transforms off`, `all := show facet`, `rr := r`. The right side is
    -- a command when it starts with a name and does not read as a whole
    -- expression, or is a lone command word.
    local c = self:peek()
    if (op == ":=" or op == "::=") and c.t == "name" and not self:lookup(w) then
      local save, saved_depth = self.i, self.depth
      local ok = pcall(self.expr, self)
      local whole = ok and self:atend()
      -- (new_body alone is a value: the new body's id, `bd := new_body`)
      local lone = self.i == save + 1 and not self:lookup(c.s) and
        (#c.raw == 1 and LETTERS[c.raw] or STMT[c.s] or type(rawget(_G, c.s)) == "function"
         or self.usercmds and self.usercmds[c.s])
        and c.s ~= "new_body" -- Evolver's value without parentheses: bd := new_body
      self.i, self.depth = save, saved_depth
      if not whole or lone then
        self.usercmds = self.usercmds or {}
        self.usercmds[w] = true
        return self:defn("E.defcmd", w, {}, false)
      end
    end
    local v = asnum(self:expr())
    local b = self:lookup(w)
    if not b then self.names[w] = true end
    if b then
      if op == ":=" or op == "::=" then return b.lua .. " = E.assign(" .. b.lua .. ", " .. v .. ")" end
      return b.lua .. " = E.arith(" .. q(op:sub(1, 1)) .. ", " .. b.lua .. ", " .. v .. ")"
    end
    if op == ":=" or op == "::=" then return "E.setv(" .. q(w) .. ", " .. v .. ")" end
    return "E.setv(" .. q(w) .. ", E.arith(" .. q(op:sub(1, 1)) .. ", E.getv(" .. q(t.raw) .. "), " .. v .. "))"
  end

  -- element attribute or array element assignment: body[1].target += 1, a[2] := 3
  if (KINDS[w] and nxt.t == "op" and nxt.v == "[") or (nxt.t == "op" and (nxt.v == "[" or nxt.v == ".")) then
    local save = self.i
    local lv = self:lvalue()
    if lv then
      local op = self:next().v
      if op == "++" or op == "--" then return self:assign_to(lv, "+=", op == "++" and "1.0" or "-1.0") end
      local v = asnum(self:expr())
      return self:assign_to(lv, op, v)
    end
    self.i = save
  end

  -- toggles: name [on|off]
  self:next()
  if self:isname("on") or self:isname("off") then
    local on = self:next().s == "on"
    return "E.toggle(" .. q(w) .. ", " .. tostring(on) .. ")"
  end
  -- an Evolver command tds does not have (M.UNSUPPORTED, set by the
  -- runtime): whatever follows is its arguments; it is an error naming it
  -- when it runs (zoom 1 0.5, breakpoint gogo 12, exprint gogo)
  local U = M.UNSUPPORTED
  if U and (#t.raw == 1 and U[t.raw] or #t.raw > 1 and U[w]) and not self:lookup(w)
     and type(rawget(_G, w)) ~= "function" and not (self.usercmds and self.usercmds[w]) then
    local depth = 0
    while true do
      local x = self:peek()
      if x.t == "eof" or (depth == 0 and self:atend(x)) then break end
      self:next()
      if x.t == "op" and (x.v == "(" or x.v == "[" or x.v == "{") then depth = depth + 1
      elseif x.t == "op" and (x.v == ")" or x.v == "]" or x.v == "}") then depth = depth - 1 end
    end
    return "E.unsupported(" .. q(t.raw) .. ")"
  end
  -- procedure call: name(args)
  if self:isop("(") and not (#t.raw == 1 and LETTERS[t.raw]) then
    self:next()
    self:note_cmd(t)
    local a = self:args()
    return "E.cmd(" .. q(t.raw) .. (a ~= "" and (", " .. a) or "") .. ")"
  end
  -- command with an optional argument: g 5, G -5, m 0.1, gogo 3
  if self:atend() then
    local b = self:lookup(w)
    if b and not b.kind then return "E.cmdvalue(" .. b.lua .. ")" end
    self:note_cmd(t)
    return "E.cmd(" .. q(t.raw) .. ")"
  end
  self:note_cmd(t)
  local a = { asnum(self:expr()) }
  while self:acceptop(",") do a[#a + 1] = asnum(self:expr()) end
  return "E.cmd(" .. q(t.raw) .. ", " .. table.concat(a, ", ") .. ")"
end

-- lvalue := kind[i](.attr|.kind[i])* | name([i])* (.attr)*   followed by an assignment op
function P:lvalue()
  local t = self:next()
  local c
  local b = self:lookup(t.s)
  if KINDS[t.s] and self:isop("[") then
    self:next()
    local i = asnum(self:expr())
    self:expect("]")
    c = "E.getelem(" .. q(KINDS[t.s]) .. ", " .. i .. ")"
  elseif b then c = b.lua
  else c = "E.getv(" .. q(t.raw) .. ")" end
  local last -- { base, key, kind = "attr"|"index" } of the final access
  while true do
    if self:isop("[") then
      self:next()
      local i = asnum(self:expr())
      self:expect("]")
      if last then c = last.get end
      last = { base = c, key = i, how = "index", get = "E.index(" .. c .. ", " .. i .. ")" }
    elseif self:isop(".") and self:peek(1).t == "name" then
      self:next()
      local a = self:next()
      if last then c = last.get end
      if KINDS[a.s] and self:isop("[") then
        self:next()
        local i = asnum(self:expr())
        self:expect("]")
        c = "E.subelem(" .. c .. ", " .. q(KINDS[a.s]) .. ", " .. i .. ")"
        last = nil
      else
        last = { base = c, key = q(a.s), how = "attr", get = "E.attr(" .. c .. ", " .. q(a.s) .. ")" }
      end
    else break end
  end
  local op = self:peek()
  if not last or op.t ~= "op" or not (op.v == ":=" or op.v == "=" or op.v == "+=" or op.v == "-="
     or op.v == "*=" or op.v == "/=" or op.v == "++" or op.v == "--") then return nil end
  local base, key, how = last.base, last.key, last.how
  return {
    get = last.get,
    set = function(v)
      if how == "attr" then return "E.setattr(" .. base .. ", " .. key .. ", " .. v .. ")" end
      return "E.setindex(" .. base .. ", " .. key .. ", " .. v .. ")"
    end,
  }
end

function P:cond()
  local c, k = self:expr()
  return ascond(c, k)
end

function P:s_if()
  self:next()
  local c = self:cond()
  if not self:acceptname("then") then self:err("expected 'then' after the condition of if, found " .. self:desc()) end
  local a = self:statement()
  if self:isname("else") then
    self:next()
    local b = self:statement()
    return "if " .. c .. " then " .. a .. " else " .. b .. " end"
  end
  return "if " .. c .. " then " .. a .. " end"
end

function P:s_while()
  self:next()
  local c = self:cond()
  if not self:acceptname("do") then self:err("expected 'do' after the condition of while, found " .. self:desc()) end
  local body, id = self:loop(function() return self:statement() end)
  return "while " .. c .. " do " .. loopbody(body, id) .. " end ::_b" .. id .. "::"
end

function P:s_do()
  self:next()
  local body, id = self:loop(function() return self:statement() end)
  while self:acceptop(";") do end
  if not self:acceptname("while") then self:err("expected 'while' after the body of do, found " .. self:desc()) end
  local c = self:cond()
  return "repeat " .. loopbody(body, id) .. " until not (" .. c .. ") ::_b" .. id .. "::"
end

function P:s_for()
  self:next()
  self:expect("(", "after for")
  self.depth = self.depth + 1
  local init = self:isop(";") and "" or self:statement()
  self:expect(";", "after the first part of for (...)")
  local c = self:isop(";") and "true" or self:cond()
  self:expect(";", "after the condition of for (...)")
  local step = self:isop(")") and "" or self:statement()
  self:expect(")", "closing for (...)")
  self.depth = self.depth - 1
  local body, id = self:loop(function() return self:statement() end)
  return "do " .. init .. " while " .. c .. " do " .. loopbody(body, id) .. " " .. step ..
         " end ::_b" .. id .. ":: end"
end

function P:s_foreach()
  self:next()
  local g = self:generator()
  if not self:acceptname("do") then self:err("expected 'do' after the generator of foreach, found " .. self:desc()) end
  self:pushgen(g)
  local body, id = self:loop(function() return self:statement() end)
  self:popgen()
  return "do " .. genloop(g, loopbody(body, id)) .. " end ::_b" .. id .. "::"
end

function P:s_return()
  self:next()
  if self:atend() then return "do return end" end
  return "do return " .. asnum(self:expr()) .. " end"
end
function P:s_break() self:next(); return self:jump("break") end
function P:s_continue() self:next(); return self:jump("continue") end
function P:s_abort() self:next(); return "E.abort()" end

function P:s_local()
  self:next()
  local names = {}
  repeat
    local t = self:next()
    if t.t ~= "name" then self:err("expected a name after local", t) end
    local lua = "L_" .. t.s
    self:bind(t.s, lua)
    names[#names + 1] = lua
  until not self:acceptop(",")
  local zeros = {}
  for i = 1, #names do zeros[i] = "0" end
  return "local " .. table.concat(names, ", ") .. " = " .. table.concat(zeros, ", ")
end

function P:s_procedure()
  self:next()
  local nt = self:next()
  if nt.t ~= "name" then self:err("expected a procedure name", nt) end
  local ps, names = self:params()
  self.names[nt.s] = true -- callable in its own body (recursion) and after
  return self:defn("E.defproc", nt.s, ps, true, names)
end

function P:s_function()
  self:next()
  local ty = self:next()
  if ty.t ~= "name" or not TYPES[ty.s] then self:err("expected a return type (real, integer) after function", ty) end
  local nt = self:next()
  if nt.t ~= "name" then self:err("expected a function name", nt) end
  local ps, names = self:params()
  self.names[nt.s] = true -- callable in its own body (recursion) and after
  return self:defn("E.defproc", nt.s, ps, true, names)
end

-- define name type [dims] [= init]; define kind attribute name type [dims]
function P:s_define()
  self:next()
  local t = self:next()
  if t.t == "name" and KINDS[t.s] and self:isname("attribute") then
    self:next()
    local nt = self:next()
    local ty = self:next()
    if nt.t ~= "name" or ty.t ~= "name" or not TYPES[ty.s] then
      self:err("define " .. t.s .. " attribute NAME real|integer expected", nt)
    end
    local dims = {}
    while self:acceptop("[") do dims[#dims + 1] = asnum(self:expr()); self:expect("]") end
    self.extra[nt.s] = true
    return "E.defattr(" .. q(KINDS[t.s]) .. ", " .. q(nt.s) .. ", " .. q(ty.s) .. ", {" .. table.concat(dims, ", ") .. "})"
  end
  if t.t == "name" and (t.s == "constraint" or t.s == "boundary" or t.s == "quantity" or t.s == "method_instance") then
    -- a datafile declaration, to the end of the statement: a `;`, `}` or
    -- a line end that does not follow an operator (`x +` continues)
    local last = t
    while true do
      local nt = self:peek()
      local open = last.t == "op" and last.v ~= ")" and last.v ~= "]"
      if nt.t == "eof" or (nt.nl and not open) or (nt.t == "op" and (nt.v == ";" or nt.v == "}")) then
        break
      end
      last = self:next()
    end
    -- one logical line for the datafile reader (comments dropped first)
    local text = self.text:sub(t.at, self:peek().at - 1):gsub("//[^\n]*", ""):gsub("%s+", " ")
      :gsub(" $", "")
    return ("E.defmodel(%s, %d)"):format(q(text), t.line)
  end
  if t.t ~= "name" then self:err("expected a name after define", t) end
  local ty = self:next()
  if ty.t ~= "name" or not TYPES[ty.s] then
    self:err("define " .. (t.raw or "?") .. ": expected a type (real, integer, string)" ..
             "", ty)
  end
  local dims = {}
  while self:acceptop("[") do
    dims[#dims + 1] = self:isop("]") and "0" or asnum(self:expr())
    self:expect("]")
  end
  local init = "nil"
  if self:acceptop("=") or self:acceptop(":=") then init = self:initializer() end
  local b = self:lookup(t.s)
  if b and not b.kind then -- define of a local: a local array
    return ("%s = E.newvalue(%s, {%s}, %s)"):format(b.lua, q(ty.s), table.concat(dims, ", "), init)
  end
  self.names[t.s] = true
  return ("E.define(%s, %s, {%s}, %s)"):format(q(t.s), q(ty.s), table.concat(dims, ", "), init)
end

function P:initializer()
  if self:acceptop("{") then
    local items = {}
    if not self:isop("}") then
      repeat items[#items + 1] = self:initializer() until not self:acceptop(",")
    end
    self:expect("}")
    return "{" .. table.concat(items, ", ") .. "}"
  end
  return asnum(self:expr())
end

function P:s_print()
  self:next()
  if self:atend() then self:err("print needs an expression") end
  local t = self:peek()
  -- print of an element or generator: print vertex[1]
  return "E.print(" .. asnum(self:expr()) .. ")"
end

function P:printf_args()
  local a = { asnum(self:expr()) }
  while self:acceptop(",") do a[#a + 1] = asnum(self:expr()) end
  return table.concat(a, ", ")
end
function P:s_printf() self:next(); return "E.printf(" .. self:printf_args() .. ")" end
function P:s_binary_printf() self:next(); return "E.binary_printf(" .. self:printf_args() .. ")" end
function P:s_errprintf() self:next(); return "E.errprintf(" .. self:printf_args() .. ")" end
function P:s_eprint() self:next(); return "E.eprint(" .. asnum(self:expr()) .. ")" end
function P:s_exec() self:next(); return "E.exec(" .. asnum(self:expr()) .. ")" end
function P:s_read()
  self:next()
  if self:atend() then self:err("read needs a file name: read \"file.cmd\"") end
  return "E.readfile(" .. asnum(self:expr()) .. ")"
end

function P:s_list()
  self:next()
  local t = self:peek()
  if t.t == "name" and (KINDS[t.s] or (self:lookup(t.s) and self:lookup(t.s).kind)) then
    local g = self:generator()
    self:pushgen(g)
    local body = "E.list(" .. g.var .. ", " .. q(g.kind) .. ", " .. g.var .. "__first)"
    self:popgen()
    return ("do local %s__first = true; %s end"):format(g.var,
      genloop(g, body .. "; " .. g.var .. "__first = false"))
  end
  if self:atend() then self:err("list needs a generator: list vertex, list edge where ...") end
  local w = self:next()
  if w.s == "topinfo" then return "E.listtop()" end
  local what = "list " .. (w.s or tostring(w.v))
  while not self:atend() do self:next() end -- list constraint 1, list boundary 2
  return "E.unsupported(" .. q(what) .. ")"
end

-- set gen attr [value] [where cond]; set gen.attr value
function P:s_set()
  self:next()
  self.setgen = true
  if self:peek().t == "name" and not KINDS[self:peek().s] and not (self:lookup(self:peek().s) or {}).kind then
    -- set toggle/variable forms: set name value
    local nt = self:next()
    local v = self:atend() and "nil" or asnum(self:expr())
    return "E.setting(" .. q(nt.s) .. ", " .. v .. ")"
  end
  local g = self:generator()
  self.setgen = false
  self:acceptop(".")
  local at = self:next()
  if at.t ~= "name" then self:err("expected an attribute name after the generator of set", at) end
  self:pushgen(g)
  local idx = {}
  while self:isop("[") do
    self:next()
    idx[#idx + 1] = asnum(self:expr())
    self:expect("]")
  end
  local v = "true"
  if at.s == "constraint" or at.s == "boundary" then
    if self:atend() then self:err("set ... " .. at.s .. " needs a number", at) end
  end
  self:acceptop("=")
  if not self:atend() and not self:isname("where") then v = asnum(self:expr()) end
  local cond = g.cond
  if self:isname("where") and self:cont() then
    self:next()
    cond = ascond(self:expr())
    if g.cond then cond = "(" .. g.cond .. " and " .. cond .. ")" end
  end
  self:popgen()
  g.cond = cond
  if #idx > 0 then -- set vertex arr[2] value: one element of an array attribute
    local base = "E.attr(" .. g.var .. ", " .. q(at.s) .. ")"
    for i = 1, #idx - 1 do base = "E.index(" .. base .. ", " .. idx[i] .. ")" end
    return genloop(g, "E.setindex(" .. base .. ", " .. idx[#idx] .. ", " .. v .. ")")
  end
  return genloop(g, "E.setattr(" .. g.var .. ", " .. q(at.s) .. ", " .. v .. ", true)")
end

function P:s_unset()
  self:next()
  self.setgen = true
  local g = self:generator()
  self.setgen = false
  self:acceptop(".")
  local at = self:next()
  if at.t ~= "name" then self:err("expected an attribute name after the generator of unset", at) end
  self:pushgen(g)
  local v = "nil"
  if not self:atend() and not self:isname("where") then v = asnum(self:expr()) end
  local cond = g.cond
  if self:isname("where") and self:cont() then
    self:next()
    cond = ascond(self:expr())
    if g.cond then cond = "(" .. g.cond .. " and " .. cond .. ")" end
  end
  self:popgen()
  g.cond = cond
  return genloop(g, "E.unsetattr(" .. g.var .. ", " .. q(at.s) .. ", " .. v .. ")")
end

local function fixer(on)
  return function(self)
    local w = self:next()
    local t = self:peek()
    if t.t == "name" and not KINDS[t.s] and not (self:lookup(t.s) or {}).kind then
      -- a named quantity (known only when the command runs) or a parameter
      self:next()
      return "E.fixname(" .. q(t.s) .. ", " .. q(t.raw) .. ", " .. tostring(on) .. ")"
    end
    local g = self:generator()
    return genloop(g, "E.setattr(" .. g.var .. ", 'fixed', " .. tostring(on) .. ", true)")
  end
end
P.s_fix = fixer(true)
P.s_unfix = fixer(false)

-- refine/equiangulate/vertex_average/delete... on a generator: collect, then act.
local function oncollection(name)
  return function(self)
    self:next()
    if self:atend() then return "E.cmd(" .. q(name) .. ")" end
    local g = self:generator()
    local acc = self:gensym("_l")
    return ("do local %s = {}; %s; E.oncollection(%s, %s, %s) end"):format(
      acc, genloop(g, acc .. "[#" .. acc .. " + 1] = " .. g.var), q(name), q(g.kind), acc)
  end
end
for _, w in ipairs { "refine", "equiangulate", "vertex_average", "delete", "dissolve", "pop", "edgeswap",
                     "t1_edgeswap", "pop_edge_to_tri", "pop_tri_to_edge", "pop_quad_to_quad", "reverse_orientation" } do
  P["s_" .. w] = oncollection(w)
end
-- rawv / rawestv on a generator (src/topo_vavg_ev.c)
for _, w in ipairs { "raw_vertex_average", "rawest_vertex_average" } do
  STMT[w] = true
  P["s_" .. w] = oncollection(w)
end

---------------------------------------------------------------- driver

-- Replace statement line marks by newlines so each statement sits on its
-- source line.
local function place(code, line0)
  local out, line = {}, line0 or 1
  local pos = 1
  while true do
    local a, b, l = code:find("%z(%d+)%z", pos)
    if not a then out[#out + 1] = code:sub(pos); break end
    out[#out + 1] = code:sub(pos, a - 1)
    l = tonumber(l)
    if l > line then out[#out + 1] = string.rep("\n", l - line); line = l end
    out[#out + 1] = " "
    pos = b + 1
  end
  return table.concat(out)
end

-- The user attributes the surface has now (datafile DEFINEs, Lua's
-- attribute{}): attribute names, as those a text defines (a facetedge's
-- also without its "fe__").
local function user_attributes()
  local extra = {}
  if tds and tds.attributes then
    for _, k in ipairs { tds.vertex, tds.edge, tds.facet, tds.body } do
      for _, a in ipairs(tds.attributes(k)) do
        if a.user then extra[a.name] = true end
        if a.user and a.name:sub(1, 4) == "fe__" then extra[a.name:sub(5)] = true end
      end
    end
  end
  return extra
end

-- translate(text [, line0]) -> source | nil, "LINE: message", partial
-- partial: the source of the command lines before the error, which
-- Evolver would have run before meeting it.
function M.translate(text, line0)
  line0 = line0 or 1
  local parts
  local ok, res = pcall(function()
    local extra = user_attributes()
    local p = setmetatable({ text = text, toks = lex(text, line0), i = 1, nsym = 0, depth = 0, scopes = { {} },
                             elems = {}, loops = {}, extra = extra, names = {} }, P)
    -- Each input line (with its continuations) is one command for abort,
    -- as at Evolver's prompt: E.top runs it.
    local unit
    parts = {}
    local function close()
      if unit then parts[#parts + 1] = "E.top(function() " .. table.concat(unit, "; ") .. " end)" end
      unit = nil
    end
    while true do
      while p:acceptop(";") or p:stray_colon() do end
      if p:peek().t == "eof" then
        if p:peek().lexerr then close(); p:err("") end
        break
      end
      if p:peek().nl then close() end
      unit = unit or {}
      unit[#unit + 1] = p:statement()
      local t = p:peek()
      if not (t.t == "eof" or t.nl or p:isop(";") or p:stray_colon()) then
        p:err("expected ';' or a new line after a command, found " .. p:desc(t))
      end
    end
    close()
    return "local E = ... or tds.E; " .. place(table.concat(parts, "; "), 1)
  end)
  if ok then return res end
  if type(res) == "table" and res.evo then
    local partial = parts and #parts > 0 and ("local E = ... or tds.E; " .. place(table.concat(parts, "; "), 1)) or nil
    return nil, res.line .. ": " .. res.msg, partial
  end
  error(res, 0)
end

-- dump_read(text, value) -> the read section a dump writes, as Evolver's
-- dump has it: the text's top-level definitions (name := { ... },
-- procedure, function, define of an array) verbatim, and each variable it
-- assigns at top level (name := expr) once, with its value now
-- (value(name): a number or a string, else it is left out). Its commands
-- (r, set, toggles, ...) have acted on the dumped surface already, so they
-- are left out: loading the dump does not do them twice. nil if the text
-- does not parse (the dump then keeps it whole).
function M.dump_read(text, value)
  local ok, res = pcall(function()
    local extra = user_attributes()
    local p = setmetatable({ text = text, toks = lex(text, 1), i = 1, nsym = 0, depth = 0, scopes = { {} },
                             elems = {}, loops = {}, extra = extra, names = {} }, P)
    local out, seen = {}, {}
    while true do
      while p:acceptop(";") or p:stray_colon() do end
      local t, t1, t2 = p:peek(), p:peek(1), p:peek(2)
      if t.t == "eof" then
        if t.lexerr then error(t.lexerr, 0) end
        break
      end
      p:statement()
      local src = text:sub(t.at, p:peek().at - 1):gsub("[%s;]+$", "")
      local assign = t.t == "name" and t1.t == "op" and (t1.v == ":=" or t1.v == "::=")
      if assign and t2.t == "op" and t2.v == "{" then
        out[#out + 1] = src                            -- a procedure
      elseif t.t == "name" and (t.s == "procedure" or t.s == "function") and not assign then
        out[#out + 1] = src
      elseif t.t == "name" and t.s == "define" and not assign and not KINDS[t1.s or ""] then
        out[#out + 1] = src                            -- an array (attributes are in the header)
      elseif assign and not seen[t.s] then
        seen[t.s] = true
        local v = value(t.raw)
        if type(v) == "number" then
          out[#out + 1] = ("%s := %.17g"):format(t.raw, v)
        elseif type(v) == "string" then
          out[#out + 1] = ("%s := \"%s\""):format(t.raw, v:gsub('[\\"]', "\\%0"):gsub("\n", "\\n"))
        end
      end
    end
    return #out > 0 and table.concat(out, "\n") .. "\n" or ""
  end)
  if ok then return res end
  return nil
end

M.lex = lex
M.LETTERS = LETTERS
M.STMT = STMT
return M
