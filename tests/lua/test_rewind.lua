-- tests/lua/test_rewind.lua — tether.rewind: scrub back 2 s and forward
-- again gives the first pass's hashes; seeks with and without a driver;
-- bounds, bad arguments, a destroyed ring, a driver that misbehaves.
package.path = "tests/lua/?.lua;" .. package.path
local T = require "harness"
local tether = require "tether"

-- A scene whose inputs are a function of the step counter, so re-stepping
-- from a keyframe gives the same steps.
local function scene()
  local w = tether.world { substeps = 2 }
  w:set_collision { friction = 0.3 }
  w:segment(-10, 0, 10, 0)
  for i = 1, 80 do w:particle(-7 + (i % 14), 1 + math.floor(i / 14), { radius = 0.3 }) end
  local function drive(world)
    local n = world:stats().steps
    if n % 45 == 0 then world:explode(0, 0.5, 4, 3) end
    if n % 20 == 0 then world:particle(0, 8, { radius = 0.2 }) end
    world:step(1 / 60)
  end
  return w, drive
end

T.test("scrub back 2 s and forward again: the same hashes as the first pass", function()
  local w, drive = scene()
  local ring = tether.rewind { every = 10, seconds = 5 }
  local h = {}
  ring:record(w)
  h[0] = w:hash()
  for s = 1, 300 do
    drive(w)
    ring:record(w)
    h[s] = w:hash()
  end
  local first, last = ring:range()
  T.eq(last, 300)
  T.eq(first, 0, "5 s of history hold all 300 steps")
  for s = 300, 180, -3 do -- backwards, 3 steps a frame
    T.eq(ring:seek(w, s, drive), s)
    T.eq(w:hash(), h[s], "step " .. s)
  end
  for s = 181, 300 do
    drive(w)
    ring:record(w)
    T.eq(w:hash(), h[s], "forward again, step " .. s)
  end
  -- without a driver: the keyframe at or before the step
  T.eq(ring:seek(w, 257), 250)
  T.eq(w:stats().steps, 250)
  T.eq(w:hash(), h[250])
  T.ok(ring:memory() > 0 and ring:count() > 0)
  T.ok(tostring(ring):match("^tether.rewind %(%d+ keyframes, %d+ bytes%)"), tostring(ring))
end)

T.test("history is bounded: seconds, and steps outside are refused", function()
  local w, drive = scene()
  local ring = tether.rewind { every = 5, seconds = 1, dt = 1 / 60 }
  ring:record(w)
  for _ = 1, 200 do drive(w); ring:record(w) end
  local first, last = ring:range()
  T.eq(last, 200)
  T.ok(first <= 140 and first > 130, "first " .. first)
  T.checkerror("seek: step 100 is not in the ring (140 … 200)", ring.seek, ring, w, 100)
  T.checkerror("not in the ring", ring.seek, ring, w, 201)
  T.eq(w:stats().steps, 200, "a refused seek leaves the world")
end)

T.test("bad arguments, a destroyed ring, a driver that does not step", function()
  local w, drive = scene()
  T.checkerror("bad option 'every'", tether.rewind, { every = 0 })
  T.checkerror("unknown option 'evry'", tether.rewind, { evry = 3 })
  T.checkerror("bad option 'seconds'", tether.rewind, { seconds = -1 })
  local ring = tether.rewind()
  T.eq(ring:range(), nil)
  T.checkerror("empty", ring.seek, ring, w, 0)
  ring:record(w)
  for _ = 1, 25 do drive(w); ring:record(w) end
  T.checkerror("bad argument #2 to 'record' (tether.world expected", ring.record, ring, {})
  T.checkerror("bad argument #3 to 'seek'", ring.seek, ring, w, -1)
  T.checkerror("bad argument #4 to 'seek' (function expected, got number)", ring.seek, ring, w, 5, 42)
  T.checkerror("drive did not step the world", ring.seek, ring, w, 15, function() end)
  T.checkerror("bad argument #2 to 'seek'", ring.seek, ring, w, 15, function(x) x:destroy() end)
  ring:destroy()
  ring:destroy()
  T.checkerror("the ring was destroyed", ring.record, ring, scene())
  T.eq(tostring(ring), "tether.rewind (destroyed)")
end)

T.test("w:reverse(): a spring under gravity runs back to where it was; irreversible worlds refused", function()
  local w = tether.world { gravity = { 0, -8 }, integrator = "verlet", dt_hint = 1 / 64 }
  local a = w:particle(0, 0, { pinned = true })
  local b = w:particle(1, -1)
  w:spring(a, b, { stiffness = 40, damping = 0 })
  w:step(1 / 64)
  local x0, y0 = w:position(b)
  for _ = 1, 500 do w:step(1 / 64) end
  local x1, y1 = w:position(b)
  T.ok(math.abs(x1 - x0) + math.abs(y1 - y0) > 0.01, "it moved")
  w:reverse()
  for _ = 1, 500 do w:step(1 / 64) end
  w:reverse()
  local x, y = w:position(b)
  T.near(x, x0, 1e-12)
  T.near(y, y0, 1e-12)
  w:set_damping(0.1)
  local h = w:hash()
  T.checkerror("reverse: cannot run backwards: velocity damping", w.reverse, w)
  T.eq(w:hash(), h)
  local c = tether.world { integrator = "rk4" }
  T.checkerror("cannot run backwards: the integrator", c.reverse, c)
  local d = tether.world {}
  d:set_collision {}
  T.checkerror("cannot run backwards: collisions", d.reverse, d)
end)

T.test("fixed_point: the same spring runs back bit for bit; the option is checked and reported", function()
  local w = tether.world { gravity = { 0, -9.81 }, fixed_point = true }
  T.eq(w:fixed_point(), 2 ^ -32)
  T.eq(tether.world {}:fixed_point(), nil)
  local a = w:particle(0, 0, { pinned = true })
  local b = w:particle(1.1, -0.7)
  w:spring(a, b, { stiffness = 37, damping = 0 })
  w:step(1 / 60)
  local x0, y0 = w:position(b)
  local vx0, vy0 = w:velocity(b)
  for _ = 1, 1000 do w:step(1 / 60) end
  local x1 = w:position(b)
  T.ok(math.abs(x1 - x0) > 0.01, "it moved")
  w:reverse()
  for _ = 1, 1000 do w:step(1 / 60) end
  w:reverse()
  local x, y = w:position(b)
  local vx, vy = w:velocity(b)
  T.eq(x, x0) T.eq(y, y0) T.eq(vx, vx0) T.eq(vy, vy0)
  T.eq(tether.world { fixed_point = 2 ^ -10 }:fixed_point(), 2 ^ -10)
  T.eq(tether.world { fixed_point = false }:fixed_point(), nil)
  T.checkerror("fixed_point must be 0 (off) or a power of two", tether.world, { fixed_point = 0.001 })
  T.checkerror("fixed_point must be 0 (off) or a power of two", tether.world, { fixed_point = 0 / 0 })
  T.checkerror("bad option 'fixed_point' (boolean or number expected, got string)", tether.world, { fixed_point = "yes" })
  T.checkerror("fixed_point needs the 'verlet' integrator", tether.world, { fixed_point = true, integrator = "rk4" })
  local h = w:hash()
  T.checkerror("fixed-point range", w.set_position, w, b, 2 ^ 19 + 1, 0)
  T.checkerror("keeps the 'verlet' integrator", w.set_integrator, w, "euler")
  T.eq(w:hash(), h)
end)

T.done()
