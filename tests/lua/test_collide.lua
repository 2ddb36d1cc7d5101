-- tests/lua/test_collide.lua — collisions from Lua: shapes, settings,
-- bounce and rest, friction, bullets, queries and contact events (with the
-- world changed while reading them).
package.path = "tests/lua/?.lua;" .. package.path
local T = require "harness"
local tether = require "tether"

T.test("collisions are off until asked for", function()
  local w = tether.world()
  local c = w:collision()
  T.eq(c.particles, false, "particles off")
  local a = w:particle(0, 0, { radius = 1 }); local b = w:particle(0.5, 0, { radius = 1 })
  w:set_gravity(0, 0)
  w:step(1 / 60)
  T.near(select(1, w:position(b)) - select(1, w:position(a)), 0.5, 0, "no push without collisions")
  w:set_collision()
  T.eq(w:collision().particles, true, "particles on")
  w:step(1 / 60)
  T.near(select(1, w:position(b)) - select(1, w:position(a)), 2, 1e-9, "pushed apart to the radii sum")
  local st = w:collision_stats()
  T.eq(st.pair_contacts, 1, "one pair")
  T.ok(st.broadphase_ms > 0 and st.broadphase_ms <= w:stats().stages.collide, "grid time within detection's")
end)

T.test("every shape kind is made, typed and bounded", function()
  local w = tether.world()
  local s = {
    segment = w:segment(0, 0, 2, 0),
    chain = w:chain({ 0, 0, 1, 1, 2, 0 }, { loop = true }),
    aabb = w:aabb(0, 0, 1, 2),
    box = w:box(5, 5, 1, 0.5, { angle = math.pi / 2 }),
    circle = w:circle(3, 3, 0.5, { restitution = 0.5, friction = 0.1 }),
    capsule = w:capsule(0, 0, 1, 0, 0.25),
    polygon = w:polygon({ 0, 0, 1, 0, 0, 1 }, { sensor = true }),
  }
  T.eq(w:shape_count(), 7, "count")
  for kind, h in pairs(s) do T.eq(w:shape_type(h), kind, "type of " .. kind) end
  local x1, y1, x2, y2 = w:shape_aabb(s.box)
  T.near(x1, 4.5, 1e-12, "box x1"); T.near(y2, 6, 1e-12, "box y2")
  w:set_shape_transform(s.circle, 10, 10)
  local x, y = w:shape_transform(s.circle)
  T.eq(x, 10, "moved x"); T.eq(y, 10, "moved y")
  w:remove_shape(s.segment)
  T.eq(w:shape_is_valid(s.segment), false, "stale after removal")
  T.checkerror("bad argument #2 to 'shape_type' (stale shape handle)", w.shape_type, w, s.segment)
  T.checkerror("polygon must be convex", w.polygon, w, { 0, 0, 2, 0, 1, 0.5, 1, 2 })
  T.checkerror("circle: unknown option 'radius'", w.circle, w, 0, 0, 1, { radius = 2 })
  T.checkerror("option 'angle' is not valid", w.circle, w, 0, 0, 1, { angle = 2 })
  T.checkerror("bad argument #2 to 'chain' (an even number of coordinates expected, got 3)", w.chain, w, { 0, 0, 1 })
  T.checkerror("invalid event 'start'", w.set_collision, w, { events = { "start" } })
  T.checkerror("invalid broadphase 'tree'", w.set_collision, w, { broadphase = "tree" })
end)

T.test("stacking is a collision setting, off by default", function()
  local w = tether.world()
  w:set_collision()
  T.eq(w:collision().stacking, 0, "off")
  w:set_collision { stacking = 2 }
  T.eq(w:collision().stacking, 2, "set")
  w:set_collision { restitution = 0.1 }
  T.eq(w:collision().stacking, 2, "kept when unset")
  T.checkerror("set_collision: bad option 'stacking' (number in [0, 1e+12] expected, got -1)", w.set_collision, w, { stacking = -1 })
end)

T.test("anchored friction is a collision setting, off by default", function()
  local w = tether.world()
  w:set_collision()
  T.eq(w:collision().anchored_friction, false, "off")
  w:set_collision { anchored_friction = true }
  T.eq(w:collision().anchored_friction, true, "set")
  w:set_collision { stacking = 1 }
  T.eq(w:collision().anchored_friction, true, "kept when unset")
  T.checkerror("set_collision: bad option 'anchored_friction' (boolean expected, got number)", w.set_collision, w, { anchored_friction = 1 })
end)

T.test("warm start is a collision setting, off by default, a share in [0, 1]", function()
  local w = tether.world()
  w:set_collision()
  T.eq(w:collision().warm_start, 0, "off")
  w:set_collision { anchored_friction = true, warm_start = 0.75 }
  T.eq(w:collision().warm_start, 0.75, "set")
  w:set_collision { stacking = 2 }
  T.eq(w:collision().warm_start, 0.75, "kept when unset")
  T.checkerror("set_collision: bad option 'warm_start' (number in [0, 1] expected, got 1.5)", w.set_collision, w, { warm_start = 1.5 })
  T.eq(w:collision().warm_start, 0.75, "a refused call changes nothing")
end)

-- A pyramid of ten rows of circles (radius 0.5, the bottom row 1.02 m
-- apart, μ = 0.3) on a floor, 10 s at 1 × 8. These particles do not turn,
-- so only friction between them keeps the rows from sliding apart. Box2D
-- 2.4.1 (discs that do not turn) holds it: the base spreads 1.4 cm.
T.test("anchored friction holds a pyramid of circles that plain friction lets spread", function()
  local function spread(anchored)
    local w = tether.world { substeps = 1, iterations = 8 }
    w:set_collision { anchored_friction = anchored, friction = 0.3 }
    w:aabb(-30, -1, 30, 0, { friction = 0.3 })
    local rows, sp = 10, 1.02
    local dy = math.sqrt(1 - 0.25 * sp * sp)
    local left, right
    for r = 0, rows - 1 do
      for k = 0, rows - r - 1 do
        local p = w:particle((k - 0.5 * (rows - r - 1)) * sp, 0.5 + r * dy, { radius = 0.5 })
        if r == 0 and k == 0 then left = p end
        if r == 0 and k == rows - 1 then right = p end
      end
    end
    w:step(1 / 60, 600)
    return select(1, w:position(right)) - select(1, w:position(left)) - (rows - 1) * sp
  end
  local plain, held = spread(false), spread(true)
  T.ok(math.abs(held) < 0.014, "anchored: the base spreads " .. held .. " m, within Box2D's 1.4 cm")
  T.ok(plain > 1, "plain friction: the base spreads " .. plain .. " m")
end)

T.test("a dropped ball rebounds to e^2 of its height", function()
  local w = tether.world { substeps = 8 }
  w:aabb(-10, -1, 10, 0, { restitution = 0.8 })
  local p = w:particle(0, 1.1, { radius = 0.1 })
  w:set_material(p, 0.8, 0.6)
  local top, up = 0, false
  for _ = 1, 150 do
    w:step(1 / 60)
    local _, y = w:position(p)
    local _, vy = w:velocity(p)
    if vy > 0 then up = true end
    if up and vy < 0 and y < 0.12 then break end
    if up then top = math.max(top, y - 0.1) end
  end
  T.near(top / 0.64, 1, 0.02, "rebound / e^2")
end)

T.test("slope: sticks when tan < mu, slides when greater", function()
  for _, case in ipairs { { 0.4, false }, { 0.6, true } } do
    local w = tether.world()
    local th = math.atan(case[1])
    w:segment(-50 * math.cos(th), -50 * math.sin(th), 50 * math.cos(th), 50 * math.sin(th), { friction = 0.5 })
    local p = w:particle(-0.5 * math.sin(th), 0.5 * math.cos(th), { radius = 0.5 })
    w:set_material(p, 0, 0.5)
    w:step(1 / 60, 60)
    local x = w:position(p)
    T.eq(math.abs(x + 0.5 * math.sin(th)) > 1e-6, case[2], "slides for tan = " .. case[1])
  end
end)

-- A 5x3 lattice block resting on a slope of deg degrees, mu_s = 0.5 and mu_k = 0.4 on both sides.
local function block_on_slope(deg, world_opts)
  local MU, R, th = 0.5, 0.05, math.rad(deg)
  local w = tether.world(world_opts)
  w:set_collision { friction_static = MU, friction_kinetic = 0.4 }
  local c, s = math.cos(th), math.sin(th)
  w:segment(-20 * c, -20 * s, 20 * c, 20 * s, { friction_static = MU, friction_kinetic = 0.4 })
  local h = 0.25 + R
  local block = w:lattice { center = { -s * h, c * h }, width = 1, height = 0.5, columns = 5, rows = 3, angle = th, radius = R }
  return w, block, c, s
end

-- How far the block's centre goes in n steps of 1/60 s.
local function travel(w, block, n)
  local x0, y0 = w:composite_center(block)
  w:step(1 / 60, n)
  local x1, y1 = w:composite_center(block)
  return math.sqrt((x1 - x0) ^ 2 + (y1 - y0) ^ 2), x1 - x0, y1 - y0
end

T.test("a lattice block on a slope sticks when tan(slope) < mu_s and slides when greater", function()
  local function slide(deg)
    local w, block, c, s = block_on_slope(deg, { substeps = 4, iterations = 20 })
    local _, dx, dy = travel(w, block, 120)
    return -(dx * c + dy * s), w:composite_angle(block) -- the angle is relative to the rest pose
  end
  local still, turn1 = slide(20)
  local moved, turn2 = slide(35)
  T.ok(math.abs(still) < 0.01, ("20 deg: slid %.4f m"):format(still))
  T.ok(moved > 2.0, ("35 deg: slid only %.4f m"):format(moved))
  T.ok(math.abs(turn1) < 0.05 and math.abs(turn2) < 0.05, ("the block slides flat, it does not tumble (%.3f, %.3f rad)"):format(turn1, turn2))
end)

T.test("at the defaults a lattice block on a 15 deg slope with mu_s = 0.5 moves under 1 mm in 10 s", function()
  -- issue 21's creep target, at the settings the default figures use (1 substep, 10 sweeps);
  -- measured 0.13 mm, all of it while the block settles in its first steps
  for _, integ in ipairs { "verlet", "symplectic_euler" } do
    local w, block = block_on_slope(15, { integrator = integ })
    local moved = travel(w, block, 600)
    T.ok(moved < 1e-3, ("%s: moved %.2e m"):format(integ, moved))
  end
end)

T.test("with leapfrog and RK4 a lattice block on a 15 deg slope with mu_s = 0.5 settles and holds", function()
  -- Their shape friction is an impulse in the velocity pass, bounded by mu times the normal load.
  -- The load was the contact's own normal velocity change, which misses the weight the block's
  -- links bring down on its bottom row: the block slid 76 m in 10 s. Bounded by the normal
  -- correction the sweeps accumulated too, it slides 4.3 cm while it settles, then holds.
  for _, integ in ipairs { "leapfrog", "rk4" } do
    local w, block = block_on_slope(15, { integrator = integ })
    local settle, creep = travel(w, block, 120), travel(w, block, 480)
    T.ok(settle < 0.06, ("%s: slid %.3f m while settling"):format(integ, settle))
    T.ok(creep < 1e-3, ("%s: crept %.2e m from 2 s to 10 s"):format(integ, creep))
  end
end)

T.test("a bullet does not tunnel, a plain particle does", function()
  for _, bullet in ipairs { true, false } do
    local w = tether.world { gravity = { 0, 0 } }
    w:box(0.0025, 0, 0.0025, 10)
    local p = w:particle(-20, 0, { radius = 0.05, vx = 3000 }) -- 1000 radii per step
    w:set_bullet(p, bullet)
    T.eq(w:bullet(p), bullet, "flag")
    w:step(1 / 60, 5)
    local x = w:position(p)
    T.eq(x < 0, bullet, "stays on its side when a bullet")
  end
end)

T.test("queries find particles and shapes", function()
  local w = tether.world()
  local s = w:aabb(0, 0, 1, 1)
  local p = w:particle(5, 0.5, { radius = 0.5 })
  local hit = w:raycast(-1, 0.5, 10, 0.5)
  T.eq(hit.shape, s, "ray hits the box first"); T.near(hit.x, 0, 1e-12, "at x = 0"); T.eq(hit.nx, -1, "normal")
  hit = w:raycast(2, 0.5, 10, 0.5)
  T.eq(hit.particle, p, "then the particle"); T.near(hit.x, 4.5, 1e-12, "at its surface")
  T.eq(w:raycast(-1, 5, 10, 5), nil, "a miss is nil")
  local ps, ss = w:query_point(0.5, 0.5)
  T.eq(#ps, 0, "no particle there"); T.eq(ss[1], s, "the box")
  ps, ss = w:query_aabb(0.5, 0, 4.6, 1)
  T.eq(ps[1], p, "particle in the box query"); T.eq(ss[1], s, "shape in the box query")
end)

T.test("contact events arrive after the step; removing while reading is safe", function()
  local w = tether.world()
  w:set_collision { events = { "begin", "persist", "end" } }
  local ground = w:aabb(-20, -1, 20, 0)
  for i = 0, 99 do w:particle(-10 + (i % 20), 1 + T.idiv(i, 20), { radius = 0.4 }) end
  local begins, removed, moved, stale = 0, 0, 0, 0
  for _ = 1, 120 do
    w:step(1 / 60)
    for i, c in ipairs(w:contacts()) do
      if not w:is_valid(c.a) then stale = stale + 1
      elseif c.kind == "begin" then
        begins = begins + 1
        if i % 2 == 0 then w:remove(c.a); removed = removed + 1
        elseif c.b and w:is_valid(c.b) then w:set_position(c.b, 0, 30, "reset"); moved = moved + 1 end
        if c.shape then T.eq(c.shape, ground, "the ground"); T.near(c.ny, 1, 1e-9, "normal up") end
      end
    end
  end
  T.ok(begins > 50 and removed > 20 and moved > 5, ("begins %d removed %d moved %d"):format(begins, removed, moved))
  T.ok(stale > 0, "stale handles were seen and reported as such")
  T.eq(w:stats().diverged, 0, "nothing ran away")
end)

T.test("deterministic: same script, same hash", function()
  local function run()
    local w = tether.world()
    w:set_collision { restitution = 0.2 }
    w:aabb(-10, -1, 10, 0)
    for i = 0, 199 do w:particle(-8 + (i % 17) * 0.9, 1 + T.idiv(i, 17) * 0.9, { radius = 0.2 + 0.1 * (i % 3) }) end
    w:step(1 / 60, 120)
    return w:hash()
  end
  T.eq(run(), run(), "hash")
end)

T.test("a turning plank carries a resting particle with the point it rests on", function()
  -- The plank turns at 0.1 rad/s about its centre; the particle, 2 m out,
  -- must move with the plank's point under it (particles do not roll):
  -- v = ω × (contact point), at every substep count.
  for _, sub in ipairs { 1, 4, 8 } do
    local w = tether.world { substeps = sub }
    w:set_collision { friction = 1 }
    local b = w:box(0, 0, 5, 0.5, { friction = 1 })
    local p = w:particle(2, 0.6, { radius = 0.1 })
    w:step(1 / 60, 30)
    local worst = 0
    for s = 1, 120 do
      local a = 0.1 * s / 60
      w:set_shape_transform(b, 0, 0, a)
      w:step(1 / 60)
      if s > 30 then -- caught up with the plank
        local x, y = w:position(p)
        local vx, vy = w:velocity(p)
        local cx, cy = x + math.sin(a) * 0.1, y - math.cos(a) * 0.1
        local ex, ey = -0.1 * cy, 0.1 * cx
        worst = math.max(worst, math.sqrt((vx - ex) ^ 2 + (vy - ey) ^ 2) / math.sqrt(ex ^ 2 + ey ^ 2))
      end
    end
    T.ok(worst < 0.01, ("%d substeps: velocity off the plank's by %.2f %%"):format(sub, worst * 100))
  end
end)

T.done()
