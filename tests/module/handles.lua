-- handles.lua: element handles are interned per surface (so they work as
-- table keys) and know their surface. Run with the stock lua5.4.
local tds = require "tds"
local a, b = tds.new{quiet = true}, tds.new{quiet = true}
for _, s in ipairs{a, b} do
  s.vertices{ {0,0,0}, {1,0,0}, {0,1,0}, {0,0,1} }
  s.edges{ {1,2}, {2,3}, {3,1}, {1,4}, {2,4}, {3,4} }
  s.faces{ {1,2,3}, {4,-5,-1} }
  s.bodies{}
end

-- Interned: the same element is the same value while a handle is alive.
local v1 = a.vertex[1]
assert(rawequal(v1, a.vertex[1]), "vertex[1] is not interned")
assert(rawequal(a.edge[1].tail, v1), "edge.tail is another value")
assert(rawequal(a.facet[1].vertices[1], v1), "facet.vertices[1] is another value")
local seen = 0
for v in a.vertices() do if rawequal(v, v1) then seen = seen + 1 end end
assert(seen == 1, "vertices() gives another value for vertex 1")
-- ... so a table keyed by handles finds the entry again.
local t = {}
for v in a.vertices() do t[v] = v.id * 10 end
assert(t[a.vertex[3]] == 30 and t[a.edge[2].head] == 30)
local n = 0
for _ in pairs(t) do n = n + 1 end
assert(n == 4, "four vertices, four keys")

-- The same id in two surfaces: two elements, never equal.
assert(a.vertex[1] ~= b.vertex[1] and t[b.vertex[3]] == nil)
assert(tostring(a.vertex[2]) == "vertex 2" and tostring(b.facet[2]) == "facet 2")

-- A handle given to another surface is an error naming the element.
local function fails(f, want)
  local ok, err = pcall(f)
  assert(not ok, "expected an error: " .. want)
  assert(err:find(want, 1, true), ("got %q, want %q"):format(err, want))
  -- the message points at this file (the line of the call), not at tds
  assert(err:find("handles.lua:%d+:"), "no user position in: " .. err)
  return err
end
fails(function() b.V(a.vertex[1]) end, "vertex 1 belongs to another surface")
fails(function() b.r({ b.edge[1], a.edge[2] }) end, "edge 2 belongs to another surface")
fails(function() b.facet[1].frontbody = a.body and a.vertex[1] end, "body")
a.bodies{ {1, 2, volume = 0.1} }
fails(function() b.facet[1].frontbody = a.body[1] end, "body 1 belongs to another surface")
assert(b.facet[1].frontbody == nil, "the failed assignment changed b")
-- A wrong kind is still the usual Lua message.
fails(function() a.V(a.edge[1]) end, "vertex expected")

-- A handle keeps its surface alive: the surface is collected only when
-- neither it nor any of its handles is reachable.
local h = tds.new{quiet = true}
h.vertices{ {1, 2, 3} }
local kept = h.vertex[1]
h = nil
collectgarbage(); collectgarbage()
assert(kept.x == 1 and kept.y == 2 and kept.z == 3)
kept.z = 5
assert(kept.z == 5)
-- Handles no longer referenced are collected, and a new one is made.
local before = collectgarbage("count")
for _ = 1, 20000 do local _ = a.vertex[2].x end
for i = 1, 4 do t[a.vertex[i]] = nil end
v1 = nil
collectgarbage(); collectgarbage()
assert(a.vertex[1].x == 0 and a.vertex[2].x == 1)
assert(collectgarbage("count") < before + 1000, "handles accumulate")
print("module/handles: ok")
