-- tests/lua/test_failed_calls.lua — a call that raises leaves the world
-- exactly as it was: of two twin worlds, the call is made on one and raises;
-- then both must have the same hash and counts, hand out the same handles
-- to the same calls, and keep the same hash 10 steps later.
package.path = "tests/lua/?.lua;" .. package.path
local T = require "harness"
local tether = require "tether"

-- a handle without its world's tag (bits 49…40, tether/base.h)
local function untag(h) return h - T.shl(T.shr(h, 40) % 1024, 40) end

-- A world with a past: particles made and removed (free slots to hand out
-- again) and, with `constraints`, collisions on and constraints made and
-- removed; without, neither is set up yet. Returns the world, its four
-- live particles and its live constraint (nil without).
local function lived_in(constraints)
  local w = tether.world {}
  local ps, kept = {}, nil
  for i = 0, 5 do ps[#ps + 1] = w:particle(0.3 * i, 1 + 0.2 * i, { radius = 0.1 }) end
  if constraints then
    w:set_collision {}
    local gone = w:distance(ps[1], ps[3])
    kept = w:distance(ps[3], ps[4])
    w:remove_constraint(gone)
  end
  w:remove(ps[5])
  w:remove(ps[2])
  return w, { ps[1], ps[3], ps[4], ps[6] }, kept
end

-- The handles of a shape, two particles, a constraint, a rope and a spring
-- made now (the shape first: anything left registered by a failed call
-- would then be swept in another order in one twin only).
local function next_handles(w)
  local s = w:circle(0, -2, 0.5)
  local p, q = w:particle(0.5, 2), w:particle(1, 2.5)
  local c = w:distance(p, q)
  local r = w:rope { start = { -1, 3 }, finish = { 1, 3 }, segments = 4 }
  local k = w:spring(p, q)
  return { untag(s), untag(p), untag(q), untag(c), untag(r), untag(k) }
end

local function counts(w)
  return ("%d particles, %d constraints, %d composites, %d shapes, %d springs"):format(
    w:count(), w:constraint_count(), w:composite_count(), w:shape_count(), w:spring_count())
end

-- call(w, live, constraint) must raise on one twin and leave the two twins alike; on a
-- fresh world and on one with collisions and constraints. Returns the error.
local function fails_cleanly(what, call)
  local message
  for _, constraints in ipairs { false, true } do
    local a, live, kept = lived_in(constraints)
    local b = lived_in(constraints)
    local ok, err = pcall(call, a, live, kept)
    if not T.ok(not ok, what .. ": raised nothing") then return end
    message = tostring(err)
    T.eq(a:hash(), b:hash(), what .. ": hash right after")
    T.eq(counts(a), counts(b), what .. ": counts")
    local na, nb = next_handles(a), next_handles(b)
    for i = 1, #na do T.eq(na[i], nb[i], what .. ": next handle " .. i) end
    a:step(1 / 60, 10)
    b:step(1 / 60, 10)
    T.eq(a:hash(), b:hash(), what .. ": hash 10 steps later")
  end
  return message
end

local EDGE = 1e12 -- the largest coordinate

T.test("a cloth past the largest coordinate raises and changes nothing", function()
  local err = fails_cleanly("cloth", function(w)
    w:cloth { origin = { EDGE - 0.5, 0 }, width = 1, columns = 4, rows = 4 }
  end)
  T.ok(err and err:find("cloth: ", 1, true), "names the call: " .. tostring(err))
end)

T.test("a ragdoll, soft body, lattice or rope past it raises and changes nothing", function()
  fails_cleanly("ragdoll", function(w) w:ragdoll { position = { EDGE, 0 } } end)
  fails_cleanly("soft body", function(w) w:soft_body { center = { 0, EDGE - 0.5 }, ring_radius = 1, segments = 8 } end)
  fails_cleanly("lattice", function(w) w:lattice { center = { EDGE - 0.5, 0 }, width = 2, columns = 3 } end)
  -- both ends fit, but start + (finish - start)·1 rounds 1.2e-4 past the edge
  fails_cleanly("rope", function(w) w:rope { start = { -152580229995.33337, 0 }, finish = { EDGE, 0 }, segments = 9 } end)
end)

T.test("a lattice refuses collinear or repeated points, as a polygon shape does", function()
  local err = fails_cleanly("lattice on a line", function(w) w:lattice { points = { 0, 0, 1, 0, 2, 0 } } end)
  T.eq(err and err:match("lattice: .*"), "lattice: points must make a polygon with no repeated or collinear points (at point 1)",
    "message")
  err = fails_cleanly("lattice with a point twice", function(w) w:lattice { points = { 0, 0, 1, 0, 1, 0, 0, 1 } } end)
  T.ok(err and err:find("no repeated or collinear points (at point 1)", 1, true), tostring(err))
  -- the same point again, neither neighbour of the first: two triangles touching
  err = fails_cleanly("lattice meeting itself", function(w)
    w:lattice { points = { 0, 0, 2, -1, 2, 1, 0, 0, -2, 1, -2, -1 } }
  end)
  T.ok(err and err:find("(at point 3)", 1, true), tostring(err))
  local w = tether.world {}
  T.noerror(w.lattice, w, { points = { 0, 0, 2, 0, 2, 2, 1, 1, 0, 2 } }) -- concave is fine: every pair is braced
  T.checkerror("polygon must be convex with no repeated or collinear points (at point 1)", w.polygon, w, { 0, 0, 1, 0, 2, 0 })
end)

T.test("shapes that raise change nothing", function()
  fails_cleanly("polygon", function(w) w:polygon { 0, 0, 1, 0, 2, 0 } end)
  fails_cleanly("polygon, bad option", function(w) w:polygon({ 0, 0, 1, 0, 0, 1 }, { friction = -1 }) end)
  fails_cleanly("chain of one point", function(w) w:chain { 0, 0 } end)
  fails_cleanly("chain through inf", function(w) w:chain { 0, 0, 1, 0, math.huge, 0 } end)
  fails_cleanly("circle", function(w) w:circle(0, 0, -1) end)
end)

T.test("constraints, springs and settings that raise change nothing", function()
  fails_cleanly("area", function(w, p) w:area { p[1], p[2], p[1] } end)
  fails_cleanly("bounds", function(w, p) w:bounds(0, 0, 1, 1, { particles = { p[1], p[2] + T.shl(1, 24) } }) end)
  fails_cleanly("distance", function(w, p) w:distance(p[1], p[2], { stiffness = 2 }) end)
  fails_cleanly("angle", function(w, p) w:angle(p[1], p[2], p[3], { min = 1 }) end)
  fails_cleanly("spring", function(w, p) w:spring(p[1], p[1]) end)
  fails_cleanly("set_positions", function(w, p) w:set_positions({ p[1], p[2] }, { 5, 5, 0, 1 / 0 }) end)
  fails_cleanly("set_constraint", function(w, _, c) w:set_constraint(c, { stiffness = 0.5, box = { 0, 0, 1, 1 } }) end)
  fails_cleanly("set_collision", function(w) w:set_collision { friction = 0.2, events = { "begin", "never" } } end)
end)

T.test("an option that raises when read leaves no particle behind", function()
  -- the 'user' option was read after the particle was made
  local raising = setmetatable({}, { __index = function(_, k) if k == "user" then error("no user today") end end })
  fails_cleanly("particle with a raising option", function(w) w:particle(0, 0, raising) end)
end)

T.done()
