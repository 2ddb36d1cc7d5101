-- tests/lua/test_reentry.lua — Lua code that runs in the middle of a binding
-- call: an __index of an option table, a __close, a finalizer run by an
-- allocation of the binding itself. However hostile it is (it destroys the
-- world, steps it, grows it), the call must finish without touching freed
-- memory (run under `make test SANITIZE=1`), with the answer of the world as
-- it was when the call began, and a world destroyed in the middle is freed
-- once the call returns.
package.path = "tests/lua/?.lua;" .. package.path
local T = require "harness"
local tether = require "tether"

-- A world with something of every kind in it; h holds the handles.
local function scene()
  local w = tether.world { gravity = { 0, 0 } }
  local h = {}
  h.a = w:particle(0, 0)
  h.b = w:particle(1, 0)
  h.c = w:particle(0, 1)
  h.s = w:spring(h.a, h.b)
  h.dc = w:distance(h.a, h.c)
  h.rope = w:rope { start = { 5, 0 }, finish = { 8, 0 }, segments = 3 }
  w:segment(-10, -5, 10, -5)
  for i = 1, 300 do w:particle(i * 0.01, 3) end
  return w, h
end

local function destroyed(w)
  return not pcall(w.count, w) and tostring(w):find("(destroyed)", 1, true) ~= nil
end

-- Every binding that reads an option table, with opts in its place.
local OPTION_CALLS = {
  { "particle", function(w, _, o) return w:particle(0, 0, o) end },
  { "spring", function(w, h, o) return w:spring(h.a, h.b, o) end },
  { "set_spring", function(w, h, o) return w:set_spring(h.s, o) end },
  { "distance", function(w, h, o) return w:distance(h.b, h.c, o) end },
  { "pin", function(w, h, o) return w:pin(h.a, o) end },
  { "bounds", function(w, _, o) return w:bounds(-20, -20, 20, 20, o) end },
  { "angle", function(w, h, o) return w:angle(h.a, h.b, h.c, o) end },
  { "area", function(w, h, o) return w:area({ h.a, h.b, h.c }, o) end },
  { "collinear", function(w, h, o) return w:collinear(h.a, h.b, h.c, o) end },
  { "set_constraint", function(w, h, o) return w:set_constraint(h.dc, o) end },
  { "rope", function(w, _, o) return w:rope(o) end },
  { "cloth", function(w, _, o) return w:cloth(o) end },
  { "ragdoll", function(w, _, o) return w:ragdoll(o) end },
  { "soft_body", function(w, _, o) return w:soft_body(o) end },
  { "lattice", function(w, _, o) return w:lattice(o) end },
  { "segment", function(w, _, o) return w:segment(0, 0, 1, 0, o) end },
  { "capsule", function(w, _, o) return w:capsule(0, 0, 1, 0, 0.1, o) end },
  { "aabb", function(w, _, o) return w:aabb(0, 0, 1, 1, o) end },
  { "box", function(w, _, o) return w:box(0, 0, 1, 1, o) end },
  { "circle", function(w, _, o) return w:circle(0, 0, 1, o) end },
  { "chain", function(w, _, o) return w:chain({ 0, 0, 1, 0, 2, 1 }, o) end },
  { "polygon", function(w, _, o) return w:polygon({ 0, 0, 1, 0, 0, 1 }, o) end },
  { "set_collision", function(w, _, o) return w:set_collision(o) end },
}

-- Ways for an __index to get rid of the world w.
local KILLS = {
  { "w:destroy()", function(w) w:destroy() end },
  -- collectgarbage() runs the pending finalizer planted below, which destroys w
  { "collectgarbage() and a finalizer", function() collectgarbage() end },
}
if not T.LUAJIT then -- the syntax is 5.4's (LuaJIT parses no <close>)
  table.insert(KILLS, 2, { "a <close> variable", load("local w = ...; do local _ <close> = w end") })
end

for _, kill in ipairs(KILLS) do
  T.test("an option table whose __index kills the world (" .. kill[1] .. ")", function()
    for _, case in ipairs(OPTION_CALLS) do
      local w, h = scene()
      local calls = 0
      local opts = setmetatable({}, { __index = function() calls = calls + 1; kill[2](w) end })
      collectgarbage("stop") -- the finalizer may run only inside the call
      T.finalized(function() w:destroy() end)
      local ok, err = pcall(case[2], w, h, opts)
      collectgarbage("restart")
      T.ok(calls > 0, case[1] .. ": the __index ran")
      T.ok(ok, case[1] .. ": the call finishes on the doomed world: " .. tostring(err))
      T.ok(destroyed(w), case[1] .. ": destroyed once the call returned")
    end
  end)
end

-- Calls fn(...) with the collector made to run a whole cycle at every
-- allocation check, and a finalizer armed to run hostile() at the first of
-- them. Nothing allocates between arming and the call, so it runs inside
-- fn, at the binding's first allocation. Returns whether it ran, then
-- pcall's first three results.
local function with_finalizer(hostile, fn, ...)
  local armed, fired = false, false
  local function plant()
    T.finalized(function()
      if armed then armed = false; fired = true; hostile() else plant() end
    end)
  end
  T.gc_eager() -- pause 1 %: the next check collects
  collectgarbage("collect")
  plant()
  armed = true
  local ok, r1, r2 = pcall(fn, ...)
  armed = false
  T.gc_default()
  collectgarbage("collect")
  return fired, ok, r1, r2
end

local function same(a, b)
  if type(a) ~= "table" or type(b) ~= "table" then return a == b end
  for k, v in pairs(a) do if not same(v, b[k]) then return false end end
  for k in pairs(b) do if a[k] == nil then return false end end
  return true
end

-- A world with contact events and broken links after one step.
local function busy_world()
  local w = tether.world()
  w:set_collision { events = { "begin", "persist", "end" } }
  w:aabb(-20, -1, 20, 0)
  for i = 1, 60 do w:particle(i * 0.3 - 10, 0.04, { radius = 0.05 }) end
  local cl = w:cloth { origin = { -5, 10 }, columns = 6, rows = 6, break_strain = 0.01 }
  local ps = w:composite_particles(cl)
  for i = 1, #ps, 2 do w:apply_impulse(ps[i], 50, 0) end
  local c = w:distance(w:particle(30, 30), w:particle(31, 30)) -- one that does not break
  w:step(1 / 60)
  assert(#w:contacts() > 0 and #w:break_events() > 0, "the scene has contact and break events")
  return w, cl, c
end

-- Every binding that fills a table (or makes one) from the world.
local FILL_CALLS = {
  { "particles", function(w) return w:particles() end },
  { "positions", function(w) return w:positions() end },
  -- the snapshot of handles is taken by w:each(), positions are read as the loop goes
  { "each", function(w) local it, t = w:each(), {}; for p in it do t[#t + 1] = p end; return t end, iterates = true },
  { "stats", function(w) local s = w:stats(); s.step_ms, s.stages = nil, nil; return s end },
  { "energy", function(w) return w:energy() end },
  { "memory", function(w) return w:memory() end },
  { "spring_info", function(w, h) return w:spring_info(h.s) end },
  { "constraint_particles", function(w, h) return w:constraint_particles(h.c) end },
  { "constraint_lines", function(w) return w:constraint_lines() end },
  { "break_events", function(w) return w:break_events() end },
  { "composite_particles", function(w, h) return w:composite_particles(h.cl) end },
  { "composite_constraints", function(w, h) return w:composite_constraints(h.cl) end },
  { "collision", function(w) return w:collision() end },
  { "collision_stats", function(w) local s = w:collision_stats(); s.broadphase_ms = nil; return s end },
  { "contacts", function(w) return w:contacts() end },
  { "raycast", function(w) return w:raycast(-15, 0.04, 15, 0.04) end },
  { "query_point", function(w) return w:query_point(-9.7, 0.04) end },
  { "query_aabb", function(w) return w:query_aabb(-20, -20, 20, 20) end },
}

-- What a finalizer may do to the world in the middle of a call.
local HOSTILE = {
  { "destroys it", function(w) w:destroy() end },
  { "steps it", function(w) w:step(1 / 60) end },
  { "grows it and reads it", function(w)
    for i = 1, 3000 do w:particle(i, 50) end
    w:positions(); w:particles(); w:contacts(); w:break_events()
  end },
}

for _, hostile in ipairs(HOSTILE) do
  T.test("a finalizer that " .. hostile[1] .. " while a binding fills its table", function()
    for _, case in ipairs(FILL_CALLS) do
      local w, cl, c = busy_world()
      local h = { cl = cl, c = c, s = w:spring(w:composite_particles(cl)[1], w:composite_particles(cl)[3]) }
      local want = case[2](w, h)
      local fired, ok, got = with_finalizer(function() hostile[2](w) end, case[2], w, h)
      local destroys = hostile[1] == "destroys it"
      T.ok(fired, case[1] .. ": the finalizer ran inside the call")
      if case.iterates and destroys then -- the loop goes on after w:each() has returned
        T.ok(not ok and tostring(got):find("attempt to use a destroyed world", 1, true), case[1] .. ": " .. tostring(got))
      else
        T.ok(ok, case[1] .. ": no error: " .. tostring(got))
        T.ok(same(got, want), case[1] .. ": the answer of the world as the call found it")
      end
      if destroys then T.ok(destroyed(w), case[1] .. ": destroyed once the call returned") end
    end
  end)
end

T.test("a world destroyed in the middle of a call is freed when the outermost call returns", function()
  local w = tether.world()
  local inner_ok, inner_err
  local opts = setmetatable({}, { __index = function(_, k)
    if k == "vx" then
      w:destroy()
      inner_ok, inner_err = pcall(w.particle, w, 0, 0) -- a nested call sees a destroyed world
    end
  end })
  local p = w:particle(1, 2, opts)
  T.ok(T.isint(p), "the outer call still made its particle")
  T.eq(inner_ok, false, "nested call refused")
  T.ok(tostring(inner_err):find("attempt to use a destroyed world", 1, true), tostring(inner_err))
  T.ok(destroyed(w), "destroyed now")
  w:destroy() -- still idempotent
end)

T.test("a world destroyed inside an iterator loop stops the loop with an error", function()
  local w = tether.world()
  for i = 1, 3 do w:particle(i, 0) end
  local n = 0
  T.checkerror_plain("attempt to use a destroyed world", function()
    for _ in w:each() do n = n + 1; w:destroy() end
  end)
  T.eq(n, 1, "one particle visited")
end)

T.done()
