-- tests/lua/test_constraints.lua — constraints and composites from Lua:
-- known answers (rest lengths, pendulum, areas), events, reads, errors.
package.path = "tests/lua/?.lua;" .. package.path
local T = require "harness"
local tether = require "tether"

T.test("options are named as in C: a rope's start and finish, a soft body's ring_radius", function()
  local w = tether.world()
  local r = w:rope { start = { 0, 0 }, finish = { 4, 0 }, segments = 4, pin_start = true, pin_finish = true }
  local ps = w:composite_particles(r)
  w:step(1 / 60, 30)
  T.eq(select(2, w:position(ps[5])), 0, "pin_finish holds the last particle")
  T.ok(select(2, w:position(ps[3])) < -0.01, "the middle sags")
  local s = w:soft_body { center = { 10, 0 }, ring_radius = 2, radius = 0.1, segments = 8 }
  local x = w:position(w:composite_particles(s)[1])
  T.near(x, 12, 1e-12, "ring_radius is the ring's, radius each particle's")
  T.checkerror("unknown option 'pin_end'", w.rope, w, { pin_end = true })
end)

T.test("a rope hangs at its rest lengths", function()
  local w = tether.world { iterations = 100, damping = 2 }
  local r = w:rope { start = { 0, 0 }, finish = { 4, 0 }, segments = 4 }
  local ps = w:composite_particles(r)
  T.eq(#ps, 5, "particles")
  T.eq(#w:composite_constraints(r), 4, "links")
  w:step(1 / 60, 900)
  for _, c in ipairs(w:composite_constraints(r)) do
    T.ok(w:constraint_error(c) < 1e-3, "link at rest length")
    T.eq(w:rest_length(c), 1, "rest length")
  end
  local x, y = w:position(ps[5])
  T.near(x, 0, 0.05, "hangs straight")
  T.ok(y < -3.99, "hangs down")
  T.eq(w:stats().iterations >= 1, true, "iterations reported")
end)

T.test("a compliant link stores its energy", function()
  local w = tether.world { gravity = { 0, 0 } }
  local a = w:particle(0, 0, { pinned = true })
  local b = w:particle(1.1, 0)
  w:distance(a, b, { length = 1, compliance = 1 / 144 })
  local e = w:energy()
  T.near(e.constraint, 0.5 * 0.01 * 144, 1e-9, "½ C²/α")
  T.near(e.total, e.constraint, 1e-12, "all of it in the link")
  w:step(1 / 60, 8)
  e = w:energy()
  T.ok(e.kinetic > 0 and e.total <= 0.72 + 1e-12, "into motion, never more than it was")
end)

T.test("pendulum period from a pin and a distance", function()
  local w = tether.world { iterations = 50, tolerance = 1e-12 }
  local top = w:particle(0, 0)
  local bob = w:particle(math.sin(0.05), -math.cos(0.05))
  w:pin(top)
  w:distance(top, bob)
  local dt, t, prev, first, last, n = 1 / 240, 0, select(1, w:position(bob)), nil, nil, 0
  for _ = 1, 240 * 10 do
    w:step(dt)
    t = t + dt
    local x = w:position(bob)
    if prev < 0 and x >= 0 then
      local tc = t - dt * x / (x - prev)
      if first then n = n + 1 else first = tc end
      last = tc
    end
    prev = x
  end
  local T0 = 2 * math.pi * math.sqrt(1 / 9.81)
  T.near((last - first) / n, T0, 0.01 * T0, "period")
end)

T.test("every constraint kind, its error and its particles", function()
  local w = tether.world { gravity = { 0, 0 } }
  local a, b, c = w:particle(0, 0), w:particle(1, 0.5), w:particle(2, 0)
  local d = w:distance(a, c, { length = 1, mode = "max" })
  T.eq(w:constraint_kind(d), "distance")
  T.near(w:constraint_error(d), 1, 1e-12, "distance error")
  local k = w:collinear(a, b, c, { stiffness = 0.5 })
  T.near(w:constraint_error(k), 0.5, 1e-12, "collinear error")
  local g = w:angle(a, b, c)
  T.eq(w:constraint_error(g), 0, "angle made at the angle now")
  local ar = w:area({ a, c, b })
  T.eq(w:constraint_kind(ar), "area")
  local p = w:pin(a, { anchor = { 0, 0 } })
  local bx = w:bounds(-5, -5, 5, 5, { particles = { a, b }, friction = 0.2 })
  T.eq(#w:constraint_particles(bx), 2)
  T.eq(w:constraint_count(), 6)
  w:step(1 / 60)
  T.ok(w:constraint_error(d) < 1, "the max distance pulled in (against the angle, area and pin)")
  w:set_constraint(p, { anchor = { 1, 1 } })
  T.eq(select(2, w:pin_anchor(p)), 1)
  w:remove_constraint(g)
  T.eq(w:constraint_is_valid(g), false)
  T.checkerror("bad argument #2 to 'constraint_error' (stale constraint handle)", w.constraint_error, w, g)
  T.checkerror("set_constraint: 'length' is for distance constraints", w.set_constraint, w, p, { length = 2 })
  T.checkerror("distance: invalid mode 'x', expected one of: 'rigid', 'max', 'min'", w.distance, w, a, b, { mode = "x" })
  T.checkerror("bad argument #5 to 'bounds' (ymax must be greater than ymin)", w.bounds, w, 0, 0, 1, 0)
  T.checkerror("angle: give both 'min' and 'max'", w.angle, w, a, b, c, { min = 0 })
  T.checkerror("bounds: bad option 'particles' (index 2: particle handle expected, got string)",
    w.bounds, w, 0, 0, 1, 1, { particles = { a, "x" } })
  T.checkerror("bounds: bad option 'particles' (table of particle handles expected)", w.bounds, w, 0, 0, 1, 1, { particles = 3 })
  T.checkerror("bad argument #2 to 'area' (3 to 65536 particle handles expected, got 2)", w.area, w, { a, b })
  local lines, n = w:constraint_lines()
  T.eq(n, 2, "one distance, one pin")
  T.eq(#lines, 8)
end)

T.test("a cloth tears and the script sees break events", function()
  local w = tether.world()
  local cl = w:cloth { columns = 8, rows = 8, break_strain = 0.3 }
  local ps = w:composite_particles(cl)
  local n0 = w:constraint_count()
  w:pin(ps[#ps], { anchor = { 0.5, -20 } })
  local torn = 0
  for _ = 1, 60 do
    w:step(1 / 60)
    for _, e in ipairs(w:break_events()) do
      torn = torn + 1
      T.ok(e.strain > 0.3, "strain past the threshold")
      T.eq(w:constraint_is_valid(e.constraint), false)
      T.ok(w:is_valid(e.a) and w:is_valid(e.b), "ends still live")
    end
  end
  T.ok(torn > 0, "tore")
  T.eq(w:constraint_count(), n0 + 1 - torn)
end)

T.test("lattice body: centre of mass and orientation", function()
  local w = tether.world { gravity = { 0, 0 } }
  local h = w:lattice { center = { 1, 2 }, width = 2, height = 1, columns = 3, rows = 2, angle = 0 }
  local x, y = w:composite_center(h)
  T.near(x, 1, 1e-12); T.near(y, 2, 1e-12)
  T.near(w:composite_angle(h), 0, 1e-12)
  -- spin it: tangential velocities ω × r about the centre
  for _, p in ipairs(w:composite_particles(h)) do
    local px, py = w:position(p)
    w:set_velocity(p, -(py - 2) * 1.0, (px - 1) * 1.0)
  end
  w:step(1 / 60, 30)
  local a = w:composite_angle(h)
  T.near(a, 0.5, 0.02, "turned by ω t")
  x, y = w:composite_center(h)
  T.near(x, 1, 1e-9); T.near(y, 2, 1e-9)
  w:remove_composite(h)
  T.eq(w:count(), 0)
  T.eq(w:constraint_count(), 0)
  T.eq(w:composite_count(), 0)
end)

T.test("ragdoll and soft body are built and stay finite on a floor", function()
  local w = tether.world { damping = 0.5 }
  local r = w:ragdoll { position = { 0, 3 } }
  local s = w:soft_body { center = { 3, 3 }, ring_radius = 0.5, pressure = 1.2, stiffness = 0.5 }
  w:bounds(-10, 0, 10, 20, { friction = 0.5 })
  T.eq(#w:composite_particles(r), 11)
  w:step(1 / 60, 300)
  for _, p in ipairs(w:particles()) do
    local x, y = w:position(p)
    T.ok(not T.nonfinite(x) and y >= -1e-9, "finite and above the floor")
  end
  local _, ry = w:composite_center(r)
  T.ok(ry < 1.5, "the ragdoll fell")
  T.eq(w:composite_count(), 2)
  T.ok(w:composite_is_valid(s))
end)

T.test("the same torn cloth twice gives the same hash", function()
  local hashes = {}
  for k = 1, 2 do
    local w = tether.world { substeps = 2 }
    local cl = w:cloth { columns = 12, rows = 12, break_strain = 0.25 }
    local ps = w:composite_particles(cl)
    w:pin(ps[#ps - 5], { anchor = { 2, -6 } })
    w:step(1 / 60, 120)
    hashes[k] = w:hash()
    T.ok(w:constraint_count() < 12 * 11 * 2 + 11 * 11 * 2 + 12 * 10 * 2 + 1, "it tore")
  end
  T.eq(hashes[1], hashes[2], "deterministic")
end)

T.test("a rope reeled in moves its load at the reel speed; max_rate makes a winch", function()
  for _, n in ipairs { 1, 4, 8 } do
    local w = tether.world { substeps = n }
    local top = w:particle(0, 0, { pinned = true })
    local bob = w:particle(0, -5)
    local c = w:distance(top, bob, { mode = "max" })
    local len = 5
    for _ = 1, 30 do -- reeled in at 1 m/s: 1 m/s after every step, whatever the substeps
      len = len - 1 / 60
      w:set_constraint(c, { length = len })
      w:step(1 / 60)
      local vx, vy = w:velocity(bob)
      T.near(math.sqrt(vx * vx + vy * vy), 1, 0.02, n .. " substeps: reel speed")
    end
    -- a winch: 2 m shorter at once, at most 1 m/s: 2 s (120 steps ± 1), never faster
    w:set_constraint(c, { length = len - 2, max_rate = 1 })
    T.eq(w:rest_length(c), len - 2, "the length set, at once")
    local steps, fastest = nil, 0
    for s = 1, 150 do
      w:step(1 / 60)
      local vx, vy = w:velocity(bob)
      fastest = math.max(fastest, math.sqrt(vx * vx + vy * vy))
      local x, y = w:position(bob)
      if not steps and math.sqrt(x * x + y * y) <= len - 2 + 1e-9 then steps = s end
    end
    T.ok(steps and steps >= 119 and steps <= 121, n .. " substeps: 2 m at 1 m/s in 2 s, took " .. tostring(steps))
    T.ok(fastest <= 1.02, n .. " substeps: never faster than the winch, got " .. fastest)
  end
  local w = tether.world()
  local b = w:bounds(-1, -1, 1, 1)
  T.checkerror("set_constraint: 'max_rate' is for distance constraints and pins", w.set_constraint, w, b, { max_rate = 1 })
  local p = w:pin(w:particle(0, 0), { max_rate = 2 })
  T.checkerror("max_rate", w.set_constraint, w, p, { max_rate = -1 })
end)

T.done()
