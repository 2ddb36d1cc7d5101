-- tests/lua/test_world.lua — behaviour of the world API from Lua.
-- Runs under the runner (build/tether tests/lua/test_world.lua) and under
-- stock Lua (LUA_CPATH='build/?.so' lua5.4 tests/lua/test_world.lua), from
-- the repository root.
package.path = "tests/lua/?.lua;" .. package.path
local T = require "harness"
local tether = require "tether"

local G = -9.81

T.test("module", function()
  T.eq(type(tether.version), "string", "version type")
  T.ok(tether.version:match("^%d+%.%d+%.%d+"), "version looks like x.y.z")
  T.eq(#tether.integrators, 5, "integrator count")
  local want = { "euler", "symplectic_euler", "leapfrog", "verlet", "rk4" }
  for i, name in ipairs(want) do T.eq(tether.integrators[i], name, "integrators[" .. i .. "]") end
  T.eq(type(tether.world), "function", "tether.world")
end)

T.test("world defaults", function()
  local w = tether.world()
  local gx, gy = w:gravity()
  T.eq(gx, 0, "gravity x"); T.near(gy, G, 0, "gravity y")
  local wx, wy = w:wind()
  T.eq(wx, 0, "wind x"); T.eq(wy, 0, "wind y")
  T.eq(w:damping(), 0, "damping")
  T.eq(w:integrator(), "verlet", "integrator")
  T.eq(w:count(), 0, "count")
  T.eq(w:spring_count(), 0, "spring_count")
  T.eq(getmetatable(w).__name, "tether.world", "__name")
  T.ok(tostring(w):match("^tether%.world: 0x%x+ %(0 particles%)$"), "tostring: " .. tostring(w))
  w:particle(0, 0); w:particle(1, 1)
  T.ok(tostring(w):match("%(2 particles%)$"), "tostring counts: " .. tostring(w))
  w:destroy()
end)

T.test("world options", function()
  local w = tether.world { gravity = { 1, -2 }, integrator = "rk4", damping = 0.5, wind = { 3, 4 },
                           dt_hint = 1 / 120, capacity = 1000 }
  local gx, gy = w:gravity()
  T.eq(gx, 1, "gravity x"); T.eq(gy, -2, "gravity y")
  local wx, wy = w:wind()
  T.eq(wx, 3, "wind x"); T.eq(wy, 4, "wind y")
  T.eq(w:damping(), 0.5, "damping")
  T.eq(w:integrator(), "rk4", "integrator")
  T.ok(w:memory().capacity >= 1000, "capacity reserved")
  -- every integrator name is accepted
  for _, name in ipairs(tether.integrators) do
    T.eq(tether.world({ integrator = name }):integrator(), name, "integrator option " .. name)
  end
end)

T.test("particle read back", function()
  local w = tether.world()
  local p = w:particle(1.5, -2.5, { vx = 3, vy = -4, mass = 2, radius = 0.25, category = 4, mask = 0x00F0,
                                    user = "hello" })
  T.ok(T.isint(p), "handle is an integer")
  T.ok(w:is_valid(p), "is_valid")
  local x, y = w:position(p)
  T.eq(x, 1.5, "x"); T.eq(y, -2.5, "y")
  local vx, vy = w:velocity(p)
  T.near(vx, 3, 1e-12, "vx"); T.near(vy, -4, 1e-12, "vy")
  T.eq(w:mass(p), 2, "mass")
  T.eq(w:radius(p), 0.25, "radius")
  T.eq(w:pinned(p), false, "pinned")
  local c, m = w:filter(p)
  T.eq(c, 4, "category"); T.eq(m, 0x00F0, "mask")
  T.eq(w:user(p), "hello", "user")
  -- defaults
  local q = w:particle(0, 0)
  T.eq(w:mass(q), 1, "default mass")
  T.eq(w:radius(q), 0, "default radius")
  T.eq(w:pinned(q), false, "default pinned")
  c, m = w:filter(q)
  T.eq(c, 1, "default category"); T.eq(m, 0xFFFF, "default mask")
  T.eq(w:user(q), nil, "default user")
  local vx0, vy0 = w:velocity(q)
  T.eq(vx0, 0, "default vx"); T.eq(vy0, 0, "default vy")
  local r = w:particle(0, 0, { pinned = true })
  T.eq(w:pinned(r), true, "pinned option")
  T.eq(w:count(), 3, "count")
end)

T.test("substeps by speed", function()
  local w = tether.world { gravity = { 0, 0 }, max_travel = 0.5, max_substeps = 6, sleep = false }
  local t, most = w:travel()
  T.eq(t, 0.5, "max_travel"); T.eq(most, 6, "max_substeps")
  T.eq(w:stats().substeps, 0, "no step yet")
  w:particle(0, 0, { radius = 0.5, vy = 59 }) -- 0.98 m a step: 1.97 radii, 4 substeps of 0.5
  local other = w:particle(5, 0, { radius = 0.5, vy = 59 })
  w:step(1 / 60)
  T.eq(w:stats().substeps, 1, "nothing to collide with: the setting")
  w:set_collision() -- it is for contacts
  w:step(1 / 60)
  T.eq(w:stats().substeps, 1, "the two fly as one: nothing to meet")
  w:set_velocity(other, 0, 0)
  w:step(1 / 60)
  T.eq(w:stats().substeps, 4, "the count the speed relative to the other asks")
  w:set_travel(0.5, 3); w:step(1 / 60)
  T.eq(w:stats().substeps, 3, "capped")
  w:set_travel(0); w:step(1 / 60)
  t, most = w:travel()
  T.eq(t, 0, "off"); T.eq(most, 3, "the cap kept when left out")
  T.eq(w:stats().substeps, 1, "off: the setting")
  T.eq(tether.world():travel(), 0, "off by default")
  T.checkerror("max_travel", tether.world, { max_travel = -1 })
  T.checkerror("max_substeps", tether.world, { max_substeps = 0 })
end)

T.test("set/get round trips", function()
  local w = tether.world { integrator = "symplectic_euler" }
  local p = w:particle(0, 0)
  w:set_position(p, 7, -8)
  local x, y = w:position(p)
  T.eq(x, 7, "set_position x"); T.eq(y, -8, "set_position y")
  w:set_velocity(p, 1.25, -0.5)
  local vx, vy = w:velocity(p)
  T.near(vx, 1.25, 1e-12, "set_velocity x"); T.near(vy, -0.5, 1e-12, "set_velocity y")
  w:set_position(p, 1, 2, "keep")
  vx, vy = w:velocity(p)
  T.near(vx, 1.25, 1e-12, "keep keeps vx"); T.near(vy, -0.5, 1e-12, "keep keeps vy")
  w:set_position(p, 3, 4, "reset")
  vx, vy = w:velocity(p)
  T.eq(vx, 0, "reset vx"); T.eq(vy, 0, "reset vy")
  w:set_mass(p, 3.5); T.eq(w:mass(p), 3.5, "mass")
  w:set_radius(p, 0.75); T.eq(w:radius(p), 0.75, "radius")
  w:set_filter(p, 0x8000, 0x0001)
  local c, m = w:filter(p)
  T.eq(c, 0x8000, "category"); T.eq(m, 1, "mask")
  w:set_filter(p, 0, 0xFFFF)
  c, m = w:filter(p)
  T.eq(c, 0, "category 0"); T.eq(m, 0xFFFF, "mask max")
  local tbl = {}
  w:set_user(p, tbl); T.eq(w:user(p), tbl, "user table")
  w:set_user(p, 42); T.eq(w:user(p), 42, "user number")
  w:set_user(p, nil); T.eq(w:user(p), nil, "user cleared")
  w:set_pinned(p, true); T.eq(w:pinned(p), true, "pinned")
  w:set_pinned(p, false); T.eq(w:pinned(p), false, "unpinned")
  T.eq(w:mass(p), 3.5, "mass survives pin/unpin")
  w:set_gravity(1, 2)
  local gx, gy = w:gravity(); T.eq(gx, 1, "gx"); T.eq(gy, 2, "gy")
  w:set_wind(-3, 4)
  local wx, wy = w:wind(); T.eq(wx, -3, "wind x"); T.eq(wy, 4, "wind y")
  w:set_damping(0.25); T.eq(w:damping(), 0.25, "damping")
  for _, name in ipairs(tether.integrators) do
    w:set_integrator(name); T.eq(w:integrator(), name, "set_integrator " .. name)
  end
end)

T.test("removal makes handles stale", function()
  local w = tether.world()
  local a = w:particle(0, 0, { user = "a" })
  local b = w:particle(1, 0)
  local s = w:spring(a, b)
  w:remove(a)
  T.eq(w:is_valid(a), false, "is_valid after remove")
  T.eq(w:is_valid(b), true, "other still valid")
  T.eq(w:count(), 1, "count after remove")
  T.eq(w:spring_is_valid(s), false, "spring removed with its particle")
  T.eq(w:spring_count(), 0, "spring_count")
  T.checkerror("bad argument #2 to 'position' (stale particle handle)", w.position, w, a)
  T.checkerror("bad argument #2 to 'remove' (stale particle handle)", w.remove, w, a)
  T.checkerror("bad argument #2 to 'user' (stale particle handle)", w.user, w, a)
  -- a new particle may reuse the slot, never the handle, nor the user value
  local c = w:particle(5, 5)
  T.ok(c ~= a, "new handle differs from the stale one")
  T.eq(w:is_valid(a), false, "old handle still stale")
  T.eq(w:user(c), nil, "user value of a removed particle is gone")
  -- never-made handles
  local never = { 0, 1, 12345, -1, T.shl(1, 32), T.shl(7, 32) + 3 }
  if not T.LUAJIT then never[#never + 1] = math.maxinteger; never[#never + 1] = math.mininteger end
  for _, h in ipairs(never) do
    if h ~= b and h ~= c then T.eq(w:is_valid(h), false, "never-made " .. h) end
  end
end)

T.test("springs", function()
  local w = tether.world { gravity = { 0, 0 } }
  local a = w:particle(0, 0)
  local b = w:particle(3, 4)
  local s = w:spring(a, b)
  T.ok(T.isint(s), "spring handle is an integer")
  T.ok(w:spring_is_valid(s), "spring_is_valid")
  T.eq(w:spring_count(), 1, "spring_count")
  T.near(w:spring_length(s), 5, 1e-12, "length")
  local info = w:spring_info(s)
  T.eq(info.a, a, "info.a"); T.eq(info.b, b, "info.b")
  T.eq(info.stiffness, 100, "default stiffness")
  T.eq(info.damping, 0, "default damping")
  T.near(info.rest, 5, 1e-12, "default rest = current distance")
  w:set_spring(s, { stiffness = 250 })
  info = w:spring_info(s)
  T.eq(info.stiffness, 250, "stiffness changed")
  T.eq(info.damping, 0, "damping unchanged")
  T.near(info.rest, 5, 1e-12, "rest unchanged")
  w:set_spring(s, { damping = 1.5, rest = 2 })
  info = w:spring_info(s)
  T.eq(info.stiffness, 250, "stiffness unchanged")
  T.eq(info.damping, 1.5, "damping changed"); T.eq(info.rest, 2, "rest changed")
  w:set_spring(s, {})
  T.eq(w:spring_info(s).stiffness, 250, "empty table changes nothing")
  local s2 = w:spring(a, b, { stiffness = 10, damping = 0.5, rest = 1 })
  info = w:spring_info(s2)
  T.eq(info.stiffness, 10, "opt stiffness"); T.eq(info.damping, 0.5, "opt damping"); T.eq(info.rest, 1, "opt rest")
  -- a stretched spring pulls its ends together
  w:step(1 / 60)
  T.ok(w:spring_length(s) < 5, "spring contracts")
  w:remove_spring(s)
  T.eq(w:spring_is_valid(s), false, "removed spring stale")
  T.eq(w:spring_count(), 1, "one left")
  T.checkerror("bad argument #2 to 'spring_length' (stale spring handle)", w.spring_length, w, s)
  T.eq(w:spring_is_valid(0), false, "never-made spring")
  T.eq(w:spring_is_valid(999), false, "never-made spring 999")
end)

T.test("bulk accessors agree with per-particle reads", function()
  local w = tether.world()
  local made = {}
  for i = 1, 50 do made[i] = w:particle(i, -i * 0.5, { vx = i % 3, vy = i % 5 }) end
  for i = 1, 50, 7 do w:remove(made[i]) end
  w:step(1 / 60, 10)
  local hs, n = w:particles()
  local xy, m = w:positions()
  T.eq(n, w:count(), "particles n"); T.eq(m, n, "positions n")
  T.eq(#hs, n, "#handles"); T.eq(#xy, 2 * n, "#xy")
  for i = 1, n do
    local x, y = w:position(hs[i])
    T.eq(xy[2 * i - 1], x, "x of " .. i); T.eq(xy[2 * i], y, "y of " .. i)
  end
  -- each visits the same particles in the same order
  local i = 0
  for p, x, y in w:each() do
    i = i + 1
    T.eq(p, hs[i], "each handle " .. i)
    T.eq(x, xy[2 * i - 1], "each x " .. i); T.eq(y, xy[2 * i], "each y " .. i)
  end
  T.eq(i, n, "each count")
  -- reused tables are cleared past the new end
  local big = {}
  for k = 1, 500 do big[k] = k end
  local t2, n2 = w:particles(big)
  T.eq(t2, big, "particles reuses the table"); T.eq(n2, n, "n"); T.eq(#big, n, "leftovers cleared")
  T.eq(big[n + 1], nil, "nothing past n")
  local big2 = {}
  for k = 1, 500 do big2[k] = k end
  local t3, n3 = w:positions(big2)
  T.eq(t3, big2, "positions reuses the table"); T.eq(n3, n, "n"); T.eq(#big2, 2 * n, "leftovers cleared")
  -- set_positions moves exactly the given particles
  local moved = {}
  for k = 1, n do moved[2 * k - 1] = k * 10; moved[2 * k] = -k end
  w:set_positions(hs, moved, "reset")
  for k = 1, n do
    local x, y = w:position(hs[k])
    T.eq(x, k * 10, "set_positions x"); T.eq(y, -k, "set_positions y")
    local vx, vy = w:velocity(hs[k])
    T.eq(vx, 0, "reset vx"); T.eq(vy, 0, "reset vy")
  end
  w:set_positions({}, {})  -- nothing to do is fine
  -- removal during each is safe: removed particles are skipped
  local seen = 0
  for p in w:each() do
    seen = seen + 1
    for _, q in ipairs(hs) do if q ~= p and w:is_valid(q) then w:remove(q); break end end
  end
  T.ok(seen < n and seen > 0, "each skips particles removed during the loop (" .. seen .. " of " .. n .. ")")
  -- an empty world
  local e = tether.world()
  local eh, en = e:particles()
  T.eq(en, 0, "empty n"); T.eq(#eh, 0, "empty table")
  for _ in e:each() do T.ok(false, "each on an empty world") end
end)

T.test("stats, energy, memory, hash", function()
  local w = tether.world()
  local p = w:particle(0, 10, { mass = 2 })
  local e = w:energy()
  T.eq(e.kinetic, 0, "kinetic at rest")
  T.near(e.gravity, 2 * 9.81 * 10, 1e-9, "gravity energy = m g h")
  T.eq(e.spring, 0, "no springs")
  T.near(e.total, e.kinetic + e.gravity + e.spring, 1e-9, "total is the sum")
  w:step(1 / 60, 30)
  local s = w:stats()
  T.eq(s.steps, 30, "steps"); T.near(s.time, 0.5, 1e-12, "time")
  T.eq(s.particles, 1, "particles"); T.eq(s.springs, 0, "springs")
  T.ok(type(s.step_ms) == "number" and s.step_ms >= 0, "step_ms")
  T.ok(T.isint(s.force_evaluations) and s.force_evaluations >= 0, "force_evaluations")
  for _, k in ipairs { "forces", "integrate", "collide", "solve", "events" } do
    T.ok(type(s.stages[k]) == "number" and s.stages[k] >= 0, "stage " .. k)
  end
  e = w:energy()
  T.ok(e.kinetic > 0, "falling particle has kinetic energy")
  -- Verlet reports the backward-difference velocity (half a step behind),
  -- so kinetic energy lags by about m g^2 t dt / 2 = 0.8 J here.
  T.near(e.total, 2 * 9.81 * 10, 1.0, "energy roughly conserved in free fall")
  local m = w:memory()
  T.ok(m.total > 0 and m.particles > 0 and m.capacity >= 1, "memory fields")
  T.ok(m.total >= m.particles, "total >= particle arrays")
  T.ok(m.bytes_per_particle > 0, "bytes_per_particle")
  local h = w:hash()
  T.ok(type(h) == "string" and #h == 16 and h:match("^%x+$"), "hash is 16 hex digits: " .. tostring(h))
  T.eq(w:hash(), h, "hash is stable without a step")
  w:step(1 / 60)
  T.ok(w:hash() ~= h, "hash changes with the state")
  T.ok(w:is_valid(p), "particle alive")
end)

T.test("forces, impulses, explosions", function()
  local w = tether.world { gravity = { 0, 0 }, integrator = "symplectic_euler" }
  local p = w:particle(0, 0, { mass = 2 })
  w:apply_impulse(p, 4, -2)
  local vx, vy = w:velocity(p)
  T.near(vx, 2, 1e-12, "impulse vx = j/m"); T.near(vy, -1, 1e-12, "impulse vy")
  w:set_velocity(p, 0, 0)
  w:apply_force(p, 12, 0)
  w:step(0.5)
  vx = w:velocity(p)
  T.near(vx, 3, 1e-12, "force: dv = f/m dt")
  w:step(0.5)
  T.near((w:velocity(p)), 3, 1e-12, "force lasts one step only")
  -- explosion pushes away from the centre, less with distance
  local near = w:particle(1, 0)
  local far = w:particle(0, 3)
  local pinned = w:particle(-1, 0, { pinned = true })
  w:explode(0, 0, 4, 10)
  local nvx, nvy = w:velocity(near)
  local fvx, fvy = w:velocity(far)
  T.ok(nvx > 0 and math.abs(nvy) < 1e-12, "near pushed +x")
  T.ok(fvy > 0 and math.abs(fvx) < 1e-12, "far pushed +y")
  T.ok(nvx > fvy, "nearer gets more")
  local px, py = w:velocity(pinned)
  T.eq(px, 0, "pinned not pushed"); T.eq(py, 0, "pinned not pushed")
  w:step(1 / 60, 10)
  local x, y = w:position(pinned)
  T.eq(x, -1, "pinned stays"); T.eq(y, 0, "pinned stays")
  T.checkerror("set_velocity:", w.set_velocity, w, pinned, 1, 1)
end)

T.test("integrator switching keeps velocity", function()
  for _, from in ipairs(tether.integrators) do
    for _, to in ipairs(tether.integrators) do
      local w = tether.world { integrator = from, wind = { 0.5, 0 } }
      local a = w:particle(0, 0, { vx = 1, vy = 2 })
      local b = w:particle(1, 0, { vx = -1 })
      w:spring(a, b, { stiffness = 50, damping = 0.1, rest = 0.5 })
      w:step(1 / 60, 7)
      local ax, ay = w:velocity(a)
      local bx, by = w:velocity(b)
      w:set_integrator(to)
      local ax2, ay2 = w:velocity(a)
      local bx2, by2 = w:velocity(b)
      local what = from .. " -> " .. to
      T.near(ax2, ax, 1e-12, what .. " a.vx"); T.near(ay2, ay, 1e-12, what .. " a.vy")
      T.near(bx2, bx, 1e-12, what .. " b.vx"); T.near(by2, by, 1e-12, what .. " b.vy")
      w:step(1 / 60)
      for _, q in ipairs { a, b } do
        local x, y = w:position(q)
        T.ok(not T.nonfinite(x) and not T.nonfinite(y), what .. " finite after a step")
      end
    end
  end
end)

T.test("projectile under verlet", function()
  local x0, y0, vx0, vy0 = 1, 2, 3, 4
  local w = tether.world { integrator = "verlet" }
  local p = w:particle(x0, y0, { vx = vx0, vy = vy0 })
  w:step(1 / 60, 60)
  local t = 1
  local x, y = w:position(p)
  T.near(w:stats().time, t, 1e-12, "time")
  T.near(x, x0 + vx0 * t, 1e-9, "x = x0 + v0 t")
  T.near(y, y0 + vy0 * t + 0.5 * G * t * t, 1e-9, "y = y0 + v0 t + g t^2/2")
end)

T.test("every integrator runs a projectile", function()
  for _, name in ipairs(tether.integrators) do
    local w = tether.world { integrator = name }
    local p = w:particle(0, 0, { vx = 1, vy = 10 })
    w:step(1 / 60, 60)
    local x, y = w:position(p)
    T.near(x, 1, 1e-9, name .. " x")
    T.near(y, 10 + 0.5 * G, 0.1, name .. " y")
  end
end)

T.test("step counts", function()
  local w = tether.world()
  w:particle(0, 0)
  w:step(0.01)
  w:step(0.01, 99)
  T.eq(w:stats().steps, 100, "steps")
  T.near(w:stats().time, 1, 1e-12, "time")
end)

T.test("destroy, __close, __gc", function()
  local w = tether.world()
  local p = w:particle(0, 0)
  w:destroy()
  w:destroy() -- idempotent
  T.ok(tostring(w):match("destroyed"), "tostring of a destroyed world: " .. tostring(w))
  T.checkerror("attempt to use a destroyed world", w.position, w, p)
  T.checkerror("attempt to use a destroyed world", w.count, w)
  if T.LUAJIT then -- no <close> syntax there; the metamethod is the same
    local c = tether.world()
    c:particle(1, 1)
    getmetatable(c).__close(c)
    w = c
  else
    w = load("local tether = ...; do local c <close> = tether.world(); c:particle(1, 1); return c end")(tether)
  end
  T.checkerror("attempt to use a destroyed world", w.count, w)
  -- many worlds left to the collector
  for _ = 1, 200 do
    local g = tether.world()
    for i = 1, 10 do g:particle(i, i, { user = {} }) end
  end
  collectgarbage(); collectgarbage()
  T.ok(true)
end)

T.test("docs/lua-api.md and lua/tether.d.lua cover every function", function()
  local function slurp(path)
    local f = io.open(path, "r")
    if not f then return nil end
    local text = f:read("a")
    f:close()
    return text
  end
  local doc, ann = slurp("docs/lua-api.md"), slurp("lua/tether.d.lua")
  T.ok(doc, "docs/lua-api.md readable (tests run from the repository root)")
  T.ok(ann, "lua/tether.d.lua readable")
  if not (doc and ann) then return end
  local methods = getmetatable(tether.world()).__index
  for name in pairs(methods) do
    T.ok(doc:find("### `w:" .. name .. "(", 1, true) or doc:find("/ `w:" .. name .. "(", 1, true),
      "docs: w:" .. name)
    T.ok(ann:find("function world:" .. name .. "(", 1, true), "annotations: world:" .. name)
  end
  for name in pairs(tether) do
    T.ok(doc:find("### `tether." .. name, 1, true), "docs: tether." .. name)
    T.ok(ann:find("tether." .. name, 1, true) or ann:find("@field " .. name, 1, true), "annotations: tether." .. name)
  end
end)

T.test("each option class of lua/tether.d.lua names exactly the keys its function accepts", function()
  local f = io.open("lua/tether.d.lua", "r")
  T.ok(f, "lua/tether.d.lua readable")
  if not f then return end
  local ann = f:read("a")
  f:close()
  local function documented(class)
    local keys, body = {}, ann:match("%-%-%-@class tether%." .. class .. "\n(.-)\n\n")
    T.ok(body, class .. " found")
    for k in (body or ""):gmatch("%-%-%-@field ([%w_]+)") do keys[k] = true end
    return keys
  end
  -- the keys listed by the unknown-key error of a call given {zz_unknown = 1}
  local unpack = table.unpack or unpack -- LuaJIT has the global
  local function accepted(fn, ...)
    local args = { n = select("#", ...), ... }
    args[args.n + 1] = { zz_unknown = 1 }
    local ok, msg = pcall(fn, unpack(args, 1, args.n + 1))
    T.ok(not ok and msg:find("unknown option 'zz_unknown'", 1, true), tostring(msg))
    local keys = {}
    for k in tostring(msg):match("expected one of: (.*)%)$"):gmatch("'([%w_]+)'") do keys[k] = true end
    return keys
  end
  local w = tether.world()
  local a, b = w:particle(0, 0), w:particle(1, 0)
  local m = tether.mask.rect(4, 4)
  local cases = {
    { "world_options", tether.world },
    { "clock_options", tether.clock },
    { "rewind_options", tether.rewind },
    { "particle_options", w.particle, w, 0, 0 },
    { "spring_options", w.spring, w, a, b },
    { "distance_options", w.distance, w, a, b },
    { "shape_options", w.circle, w, 0, 0, 1 },
    { "collision_settings", w.set_collision, w },
    { "terrain_options", w.terrain, w, m },
    { "draw_options", w.draw, w },
    { "mask_chain_options", w.mask_chains, w, m },
  }
  for _, c in ipairs(cases) do
    local doc, got = documented(c[1]), accepted(unpack(c, 2))
    for k in pairs(got) do T.ok(doc[k], c[1] .. ": accepted key '" .. k .. "' is documented") end
    for k in pairs(doc) do T.ok(got[k], c[1] .. ": documented key '" .. k .. "' is accepted") end
  end
end)

T.test("a core refusal names the Lua function once", function()
  local w = tether.world()
  local p = w:particle(0, 0, { pinned = true })
  local ok, msg = pcall(w.set_velocity, w, p, 1, 2)
  T.ok(not ok)
  T.eq(msg, "set_velocity: the particle is pinned")
end)

T.test("handles carry their kind: the first of each kind differ, and a wrong kind is refused", function()
  local w = tether.world()
  local p, q = w:particle(0, 0), w:particle(1, 0)
  local h = {
    particle = p, spring = w:spring(p, q), constraint = w:distance(p, q),
    shape = w:circle(0, -5, 1), composite = w:rope { start = { 0, 2 }, finish = { 1, 2 }, segments = 2 },
  }
  local seen, keyed, n = {}, {}, 0
  for kind, v in pairs(h) do
    T.ok(T.isint(v), kind)
    T.ok(v > 0 and v < 2 ^ 53 and (v + 0.0) == v, kind .. " handle is exact as a double")
    T.ok(not seen[v], kind .. " handle equals another kind's")
    seen[v] = kind
    keyed[v] = kind
    n = n + 1
  end
  for v, kind in pairs(keyed) do T.eq(seen[v], kind, "handles as table keys") end
  T.eq(n, 5)
  T.checkerror("bad argument #2 to 'remove' (particle expected, got constraint)", w.remove, w, h.constraint)
  T.checkerror("bad argument #2 to 'position' (particle expected, got shape)", w.position, w, h.shape)
  T.checkerror("bad argument #2 to 'remove_shape' (shape expected, got particle)", w.remove_shape, w, h.particle)
  T.checkerror("bad argument #2 to 'remove_constraint' (constraint expected, got composite)",
               w.remove_constraint, w, h.composite)
  T.checkerror("bad argument #2 to 'is_valid' (particle expected, got spring)", w.is_valid, w, h.spring)
  T.eq(w:count(), 2 + 3) -- nothing was removed by the refused calls
  -- A handle that went through a float (LuaJIT, JSON, a saved game) still works.
  T.eq(w:position(p + 0.0), 0)
  T.eq(w:is_valid(0), false, "the null handle names nothing")
end)

T.test("handles carry their world: the next 1022 worlds refuse a world's handles", function()
  -- The promise of tether/base.h: worlds take tags 1…1023 in turn, so the
  -- 1023rd world made after `a` is the first that could take its handles.
  local a = tether.world()
  local pa = a:particle(1, 1)
  local sa = a:circle(0, 0, 1)
  local function tag(h) return T.shr(h, 40) % 1024 end
  local tags = { [tag(pa)] = true }
  a:destroy()
  for i = 1, 1022 do
    local w = tether.world()
    local p = w:particle(i, 2)
    local s = w:circle(0, 0, 1)
    T.eq(w:position(p), i)
    T.ok(not tags[tag(p)], "a tag came back before 1023 worlds")
    tags[tag(p)] = true
    if not T.ok(not w:is_valid(pa) and not w:shape_is_valid(sa), "world " .. i .. " took a's handles") then break end
    T.checkerror("stale particle handle", w.position, w, pa)
    T.ok(p < 2 ^ 53 and s < 2 ^ 53 and p + 0.0 == p, "handles are exact as doubles")
    w:destroy()
  end
end)

T.test("point attractor: a Kepler orbit closes, bad input changes nothing", function()
  local w = tether.world { gravity = { 0, 0 }, integrator = "rk4" }
  local p = w:particle(0.5, 0, { vx = 0, vy = math.sqrt(3) })  -- e = 0.5, a = 1, GM = 1: period 2π
  local h0 = w:hash()
  T.checkerror("bad argument #2 to 'set_attractor'", w.set_attractor, w, 0, 0, 0, 1)
  T.checkerror("bad argument #2 to 'set_attractor'", w.set_attractor, w, 9, 0, 0, 1)
  T.checkerror("bad argument #3 to 'set_attractor'", w.set_attractor, w, 1, 0 / 0, 0, 1)
  T.checkerror("bad argument #5 to 'set_attractor'", w.set_attractor, w, 1, 0, 0, math.huge)
  T.checkerror("bad argument #6 to 'set_attractor'", w.set_attractor, w, 1, 0, 0, 1, -1)
  T.checkerror("bad argument #2 to 'attractor'", w.attractor, w, "x")
  T.eq(w:hash(), h0, "failed calls leave the world as it was")
  w:set_attractor(1, 0, 0, 1)
  local x, y, s, e = w:attractor(1)
  T.eq(x, 0, "x"); T.eq(y, 0, "y"); T.eq(s, 1, "strength"); T.eq(e, 0, "softening")
  T.near(w:energy().attractor, -2, 1e-12, "potential at perihelion")
  T.near(w:energy().total, -0.5, 1e-12, "orbit energy -GM/2a")
  w:step(2 * math.pi / 4000, 4000)
  local px, py = w:position(p)
  T.near(px, 0.5, 1e-6, "back at perihelion x")
  T.near(py, 0, 1e-6, "back at perihelion y")
  w:set_attractor(1, 3, 3, 0, 1)
  T.eq(select(3, w:attractor(1)), 0, "strength 0 clears")
  w:destroy()
end)

T.done()
