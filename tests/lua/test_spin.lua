-- tests/lua/test_spin.lua — particles that turn from Lua: the world option
-- spin, w:rotation, w:spin, w:set_spin; a disc rolling down a slope at
-- (2/3) g sin θ with r·ω = v; the spin through a snapshot; refusals.
package.path = "tests/lua/?.lua;" .. package.path
local T = require "harness"
local tether = require "tether"

local function slope(th)
  local w = tether.world { spin = true, sleep = false, iterations = 8 }
  w:segment(-100 * math.cos(th), -100 * math.sin(th), 100 * math.cos(th), 100 * math.sin(th), { friction = 1 })
  local p = w:particle(-0.5 * math.sin(th), 0.5 * math.cos(th), { radius = 0.5 })
  w:set_material(p, 0, 1)
  return w, p
end

T.test("a disc rolls down a slope at (2/3) g sin θ, turning at v / r", function()
  local th = 0.35
  local w, p = slope(th)
  for _ = 1, 120 do w:step(1 / 60) end
  local vx, vy = w:velocity(p)
  local down = -(vx * math.cos(th) + vy * math.sin(th))
  T.near(down / 2 / (2 / 3 * 9.81 * math.sin(th)), 1, 0.02)
  T.near(w:spin(p) * 0.5 / down, 1, 0.02)
  local a = w:rotation(p)
  T.ok(a >= -math.pi and a <= math.pi)
end)

T.test("the spin is in snapshots; set_spin changes the hash", function()
  local w, p = slope(0.3)
  for _ = 1, 20 do w:step(1 / 60) end
  local u = tether.world { snapshot = w:snapshot() }
  T.eq(u:hash(), w:hash())
  T.eq(u:rotation(p), w:rotation(p))
  local h = w:hash()
  w:set_spin(p, 3)
  T.eq(w:spin(p), 3)
  T.ok(w:hash() ~= h)
end)

T.test("refusals: a world without spin, a bad spin, a stale handle", function()
  local w = tether.world()
  local p = w:particle(0, 0)
  T.checkerror("do not turn", w.rotation, w, p)
  T.checkerror("do not turn", w.set_spin, w, p, 1)
  local s = tether.world { spin = true }
  local q = s:particle(0, 0)
  T.checkerror("bad argument #3 to 'set_spin'", s.set_spin, s, q, 1 / 0)
  T.checkerror("bad argument #3 to 'set_spin'", s.set_spin, s, q, "fast")
  s:remove(q)
  T.checkerror("bad argument #2 to 'spin' (stale particle handle)", s.spin, s, q)
end)

T.done()
