-- tests/lua/test_box2d.lua — the tether_box2d module: Box2D worlds beside a
-- tether world, the shared scenes as tables, the cross-check's rows, and
-- errors that name the function and the argument.
package.path = "tests/lua/?.lua;" .. package.path
-- the module built for this Lua: build/ for 5.4, build/luajit/ for LuaJIT
package.cpath = (os.getenv("BUILD") or "build") .. (type(jit) == "table" and "/luajit" or "") .. "/?.so;" .. package.cpath
local T = require "harness"
local tether = require "tether"
local b2 = require "tether_box2d"

T.test("a Box2D world runs beside a tether world from one scene table", function()
  local s = b2.scene("fall")
  T.eq(#s.bodies, 2, "two boxes")
  T.eq(s.bodies[2].vy, 8, "the thrown one")
  local w = b2.build(s, { sleep = false })
  local tw = tether.world{ gravity = s.gravity }
  local p = tw:particle(s.bodies[1].x, s.bodies[1].y)
  for _ = 1, s.steps do w:step(s.dt); tw:step(s.dt) end
  local _, y = w:state(1)
  local _, ty = tw:position(p)
  T.near(y, 10 - 10 / 3600 * 60 * 61 / 2, 1e-4, "Box2D: symplectic Euler")
  T.near(ty, 5, 1e-9, "tether: Verlet, exact under constant gravity")
  local ke, m = w:energy()
  T.ok(ke > 0 and math.abs(m - 2) < 1e-6, "energy and mass of the two 1 x 1 boxes")
  T.ok(tostring(w):match("^tether_box2d.world{2 bodies}"), tostring(w))
end)

T.test("bodies and joints by hand: a pendulum on a revolute joint keeps its length", function()
  local w = b2.world{ gravity = {0, -10}, sleep = false }
  local bob = w:body{ shape = "circle", dynamic = true, x = 1, y = 2, radius = 0.1 }
  T.eq(bob, 1, "bodies count from 1")
  w:joint("revolute", 0, bob, 0, 2)
  for _ = 1, 120 do w:step(1 / 60) end
  local x, y = w:state(bob)
  T.near(math.sqrt(x * x + (y - 2) ^ 2), 1, 1e-3, "arm length")
  T.eq(w:count(), 1, "count")
  w:destroy()
  T.checkerror("destroyed", w.step, w, 1 / 60)
end)

T.test("every named scene is a table both engines can build", function()
  for _, name in ipairs{ "fall", "pendulum", "bounce", "slope", "spin", "pyramid", "discs", "pour" } do
    local s = b2.scene(name, true)
    local w = b2.build(s)
    T.eq(w:count(), #s.bodies, name)
  end
  T.eq(#b2.scene("pour").bodies, 10003, "the reference pour: 10 000 circles, floor, two walls")
end)

T.test("a body with fixed_rotation does not turn where one without it rolls", function()
  local spins = {}
  for _, fixed in ipairs{false, true} do
    local w = b2.world{ gravity = {0, -10}, sleep = false }
    -- a 15 degree slope, mu 0.3 > tan 15: the free disc rolls, the fixed one holds
    local a = math.rad(15)
    w:body{ shape = "box", x = 0.5 * math.sin(a), y = -0.5 * math.cos(a), hx = 20, hy = 0.5, angle = a }
    local d = w:body{ shape = "circle", dynamic = true, x = -0.5 * math.sin(a), y = 0.5 * math.cos(a), fixed_rotation = fixed }
    for _ = 1, 60 do w:step(1 / 60) end
    local x, y, _, _, _, spin = w:state(d)
    -- along the slope, downhill (the disc also settles Box2D's 5 mm slop into it, along the normal)
    local down = -((x + 0.5 * math.sin(a)) * math.cos(a) + (y - 0.5 * math.cos(a)) * math.sin(a))
    spins[#spins + 1] = spin
    if fixed then T.ok(math.abs(down) < 1e-3, "the fixed disc stays: " .. down) else T.ok(down > 0.8, "the free disc rolls: " .. down) end
  end
  T.ok(spins[1] > 1 and spins[2] == 0, "spin: " .. spins[1] .. ", " .. spins[2])
  T.checkerror_plain("bad option 'fixed_rotation'", function() b2.world{}:body{ shape = "circle", fixed_rotation = 1 } end)
end)

T.test("errors name the function and the argument", function()
  -- option tables read as every tether binding reads them (tl_opt, src/lua/lua_options.c)
  T.checkerror("tether_box2d.world: unknown option 'slep' (expected one of: 'gravity', 'velocity_iterations', 'position_iterations', 'sleep', 'continuous')", b2.world, { slep = true })
  T.checkerror("tether_box2d.world: bad option 'sleep' (boolean expected, got number)", b2.world, { sleep = 1 })
  T.checkerror("tether_box2d.world: bad option 'velocity_iterations' (integer in [1, 1000] expected, got 0)", b2.world, { velocity_iterations = 0 })
  T.checkerror("tether_box2d.world: bad option 'position_iterations' (integer in [1, 1000] expected, got 1.5)", b2.world, { position_iterations = 1.5 })
  T.checkerror("tether_box2d.world: bad option 'gravity' (index 2: finite number expected, got nan)", b2.world, { gravity = { 0, 0 / 0 } })
  T.checkerror("tether_box2d.build: unknown option 'slep'", b2.build, b2.scene("fall", true), { slep = true })
  local w = b2.world()
  T.checkerror("tether_box2d.world:body: invalid shape 'blob', expected one of: 'circle', 'box', 'polygon', 'edge'", w.body, w, { shape = "blob" })
  T.checkerror("tether_box2d.world:body: bad option 'shape' (one of 'circle', 'box', 'polygon', 'edge' expected, got no value)", w.body, w, { dynamic = true })
  T.checkerror("tether_box2d.world:body: unknown option 'rad'", w.body, w, { shape = "circle", rad = 1 })
  T.checkerror("tether_box2d.world:body: tb_body_create: radius must be in", w.body, w, { shape = "circle", radius = 0 })
  T.checkerror("tether_box2d.world:body: bad option 'x' (finite number expected, got nan)", w.body, w, { shape = "circle", x = 0 / 0 })
  T.checkerror("tether_box2d.world:body: bad option 'points' (x1, y1, x2, y2, ... of at most 8 points expected, got 3 numbers)", w.body, w, { shape = "polygon", points = { 0, 0, 1 } })
  T.checkerror("bad argument #2 to 'tether_box2d.world:body' (table expected, got nil)", w.body, w, nil)
  T.checkerror("tb_body_create: polygon points must be convex", w.body, w, { shape = "polygon", points = { 0, 0, 0, 1, 1, 0 } })
  w:body{ shape = "circle", dynamic = true }
  T.checkerror("tether_box2d.world:joint: bad argument #4 (body b must be another existing body)", w.joint, w, "weld", 0, 7, 0, 0)
  T.checkerror("tether_box2d.world:joint: bad argument #2 (kind must be", w.joint, w, "hinge", 0, 1, 0, 0)
  T.checkerror("tether_box2d.world:joint: bad argument #5 (ax must be a number, got string)", w.joint, w, "weld", 0, 1, "x", 0)
  T.checkerror("tether_box2d.world:step: bad argument #2 (dt must be in (0, 10] s)", w.step, w, -1)
  T.checkerror("tether_box2d.world:state: bad argument #2 (body must be an integer, got no value)", w.state, w)
  T.checkerror("tether_box2d.scene: bad argument #1 (unknown scene 'nope'", b2.scene, "nope")
  T.checkerror("tether_box2d.build: the scene's 'bodies' must be a list", b2.build, {})
  T.checkerror("tether_box2d.crosscheck: unknown scene", b2.crosscheck, "nope", { quick = true })
  T.checkerror("tether_box2d.crosscheck: unknown option 'fast'", b2.crosscheck, "fall", { fast = true })
  T.checkerror("tether_box2d.crosscheck: bad option 'runs' (integer in [1, 50] expected, got 1.5)", b2.crosscheck, "fall", { runs = 1.5 })
  T.checkerror("tether_box2d.crosscheck: bad option 'quick' (boolean expected, got number)", b2.crosscheck, "fall", { quick = 1 })
end)

T.test("the cross-check's rows come back as tables", function()
  local rows, costs = b2.crosscheck("fall", { quick = true, runs = 1 })
  T.eq(rows[1].scene, "fall")
  T.near(rows[1].box2d / rows[1].expected - 1, 1 / 60, 1e-4, "Box2D's fall 1.7 % long at 1 s")
  T.ok(math.abs(rows[1].tether / rows[1].expected - 1) < 1e-3, "tether within 0.1 %")
  T.ok(costs[1].box2d_ms > 0 and costs[1].tether_ms > 0, "both timed")
end)

T.test("lua/tether_box2d.d.lua annotates every function of the module", function()
  local f = io.open("lua/tether_box2d.d.lua", "r")
  T.ok(f, "lua/tether_box2d.d.lua readable (tests run from the repository root)")
  if not f then return end
  local ann = f:read("*a")
  f:close()
  for name, v in pairs(b2) do
    local seen = type(v) == "function" and ann:find("function tether_box2d." .. name .. "(", 1, true)
      or ann:find("---@field " .. name .. " ", 1, true)
    T.ok(seen, "annotations: tether_box2d." .. name)
  end
  local methods = getmetatable(b2.world()).__index
  for name in pairs(methods) do
    T.ok(ann:find("function world:" .. name .. "(", 1, true), "annotations: world:" .. name)
  end
end)

T.done()
