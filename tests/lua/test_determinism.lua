-- tests/lua/test_determinism.lua — the same scene built twice gives the same
-- state, bit for bit (w:hash()). tests/run.sh adds the two-process check
-- (demos/fountain.lua run twice must print the same hash).
package.path = "tests/lua/?.lua;" .. package.path
local T = require "harness"
local tether = require "tether"

-- A non-trivial scene: a hanging chain of springs, a cloud of free particles,
-- per-step forces, explosions, removals and re-creations, integrator
-- switches. Deterministic by construction (its own LCG, no clock).
local function scene(integrators, steps)
  local rnd = T.minstd(2024) -- uniform in [0, 1)
  local w = tether.world { integrator = integrators[1], damping = 0.05, wind = { 0.3, 0 } }
  local chain = {}
  chain[1] = w:particle(0, 10, { pinned = true })
  for i = 2, 20 do
    chain[i] = w:particle(i * 0.5, 10, { mass = 0.5 + rnd() })
    w:spring(chain[i - 1], chain[i], { stiffness = 200 + 50 * rnd(), damping = 0.2, rest = 0.5 })
  end
  local cloud = {}
  for i = 1, 200 do
    cloud[i] = w:particle(rnd() * 20 - 10, rnd() * 20, { vx = rnd() - 0.5, vy = rnd() * 2, mass = 0.1 + rnd() })
  end
  for s = 1, steps do
    if s % 50 == 0 then
      w:set_integrator(integrators[T.idiv(s, 50) % #integrators + 1])
    end
    if s % 37 == 0 then w:explode(rnd() * 10 - 5, rnd() * 10, 6, 3) end
    if s % 11 == 0 then
      local i = 1 + math.floor(rnd() * #cloud)
      w:remove(cloud[i])
      cloud[i] = w:particle(rnd() * 4, 15, { vx = rnd() * 2 - 1 })
    end
    for i = 1, #cloud, 7 do w:apply_force(cloud[i], math.sin(s * 0.1) * 2, 1) end
    w:apply_impulse(chain[20], 0.01 * (rnd() - 0.5), 0)
    w:step(1 / 60)
  end
  local h = w:hash()
  local xy = w:positions()
  return h, xy
end

local ALL = tether.integrators

T.test("same scene twice, one process: identical hash", function()
  for _, list in ipairs { { "verlet" }, { "euler" }, { "symplectic_euler" }, { "leapfrog" }, { "rk4" }, ALL } do
    local h1, xy1 = scene(list, 400)
    local h2, xy2 = scene(list, 400)
    T.eq(h2, h1, "hash " .. table.concat(list, "+"))
    T.eq(#xy2, #xy1, "count")
    local same = true
    for i = 1, #xy1 do if xy1[i] ~= xy2[i] then same = false end end
    T.ok(same, "positions bit-identical " .. table.concat(list, "+"))
  end
end)

T.test("different scenes differ", function()
  local a = scene({ "verlet" }, 100)
  local b = scene({ "verlet" }, 101)
  local c = scene({ "rk4" }, 100)
  T.ok(a ~= b, "one more step changes the hash")
  T.ok(a ~= c, "another integrator changes the hash")
end)

T.test("interleaved worlds do not interfere", function()
  -- two worlds stepped alternately end where each would alone
  local alone = scene({ "leapfrog" }, 120)
  local w1 = tether.world { integrator = "leapfrog" }
  local w2 = tether.world { integrator = "rk4" }
  local p1 = w1:particle(0, 0, { vx = 1 })
  local p2 = w2:particle(0, 0, { vx = 2 })
  local q1 = w1:particle(1, 0)
  local q2 = w2:particle(1, 0)
  w1:spring(p1, q1); w2:spring(p2, q2)
  for _ = 1, 100 do w1:step(1 / 60); w2:step(1 / 60) end
  local h1 = w1:hash()
  local w3 = tether.world { integrator = "leapfrog" }
  local p3 = w3:particle(0, 0, { vx = 1 })
  local q3 = w3:particle(1, 0)
  w3:spring(p3, q3)
  w3:step(1 / 60, 100)
  T.eq(w3:hash(), h1, "w1 alone = w1 interleaved")
  T.eq(scene({ "leapfrog" }, 120), alone, "scene unchanged by other worlds")
end)

T.test("step(dt, n) equals n calls of step(dt)", function()
  local function build()
    local w = tether.world { integrator = "rk4" }
    local a = w:particle(0, 0, { vx = 1 })
    local b = w:particle(2, 0)
    w:spring(a, b, { stiffness = 30 })
    return w
  end
  local w1, w2 = build(), build()
  w1:step(0.01, 250)
  for _ = 1, 250 do w2:step(0.01) end
  T.eq(w1:hash(), w2:hash(), "hash")
end)

T.test("a -0 from the script is +0 in the world: one script, one world under Lua 5.4 and LuaJIT", function()
  -- LuaJIT has no integer zero: -i * d at i = 0 is -0 there, +0 in 5.4
  local nz = -1 * 0.0
  T.ok(1 / nz < 0, "the script holds a -0")
  local function build(z)
    local w = tether.world { gravity = { z, -9.81 } }
    local p = w:particle(z, 1, { vx = z, radius = 0.1 })
    w:segment(z, 0, 1, z)
    w:pin(p, { anchor = { z, 1 } })
    return w
  end
  local a, b = build(0.0), build(nz)
  T.eq(b:hash(), a:hash(), "hash before stepping")
  local x = b:position(b:particles()[1])
  T.ok(1 / x > 0, "the particle's x reads back as +0")
  a:step(1 / 60, 10); b:step(1 / 60, 10)
  T.eq(b:hash(), a:hash(), "hash after 10 steps")
end)

T.done()
