-- tests/lua/test_sleep.lua — sleeping from Lua: the world options, w:sleep,
-- w:set_sleep, w:asleep, stats.sleeping, waking by a script call, and the
-- sleep state through a snapshot; refusals name the function and argument.
package.path = "tests/lua/?.lua;" .. package.path
local T = require "harness"
local tether = require "tether"

local R = 0.1
local function pile(opts)
  local w = tether.world(opts)
  w:set_collision()
  w:aabb(-2, -1, 2, 0); w:aabb(-2, 0, -1, 3); w:aabb(1, 0, 2, 3)
  local ps = {}
  for k = 0, 31 do
    local col, row = k % 8, T.idiv(k, 8)
    ps[#ps + 1] = w:particle(-0.85 + col * 2.2 * R + (row % 2) * 0.05, R + 0.02 + row * 2.2 * R, { radius = R })
  end
  return w, ps
end

local function settle(w, n, max)
  for s = 0, max do
    if w:stats().sleeping == n then return s end
    w:step(1 / 60)
  end
  return max + 1
end

T.test("sleeping is on by default (1 cm, 1 s), off with sleep = false; a settled pile sleeps", function()
  local w0 = pile()
  local on, speed, time = w0:sleep()
  T.eq(on, true); T.eq(speed, 0.01); T.eq(time, 1)
  on, speed, time = pile({ sleep = false }):sleep()
  T.eq(on, false); T.eq(speed, 0); T.eq(time, 0)
  local w, ps = pile { sleep = true, sleep_speed = 0.05, sleep_time = 0.5 }
  on, speed, time = w:sleep()
  T.eq(on, true); T.eq(speed, 0.05); T.eq(time, 0.5)
  T.ok(settle(w, #ps, 1200) <= 1200, "the pile sleeps")
  T.eq(w:asleep(ps[1]), true)
  local x, y = w:position(ps[#ps])
  for _ = 1, 30 do w:step(1 / 60) end
  local x2, y2 = w:position(ps[#ps])
  T.eq(x, x2); T.eq(y, y2)
  w:set_velocity(ps[3], 0, 1)
  T.eq(w:stats().sleeping, 0, "a script call wakes the island")
  T.eq(w:asleep(ps[1]), false)
end)

T.test("set_sleep turns it on and off; off wakes everything", function()
  local w, ps = pile { sleep = false }
  w:set_sleep(true)
  T.ok(settle(w, #ps, 1200) <= 1200)
  w:set_sleep(false)
  T.eq(w:stats().sleeping, 0)
  T.eq((w:sleep()), false)
end)

T.test("the sleep state goes through a snapshot", function()
  local w, ps = pile { sleep = true }
  T.ok(settle(w, #ps, 1200) <= 1200)
  local copy = tether.world { snapshot = w:snapshot() }
  T.eq(copy:stats().sleeping, #ps)
  T.eq(copy:hash(), w:hash())
  w:apply_impulse(ps[5], 0.01, 0); copy:apply_impulse(ps[5], 0.01, 0)
  for _ = 1, 30 do w:step(1 / 60); copy:step(1 / 60) end
  T.eq(copy:hash(), w:hash())
end)

T.test("sleep options and calls refuse bad input", function()
  T.checkerror("bad argument #2 to 'set_sleep' (boolean expected", tether.world().set_sleep, tether.world(), 1)
  local w = tether.world()
  T.checkerror("bad argument #3 to 'set_sleep'", w.set_sleep, w, true, -1)
  T.checkerror("bad argument #4 to 'set_sleep'", w.set_sleep, w, true, 0.1, 0 / 0)
  T.checkerror("sleep_speed", tether.world, { sleep = true, sleep_speed = -1 })
  T.checkerror("sleep", tether.world, { sleep = 1 })
  T.eq((w:sleep()), true, "a refused call changed nothing (on by default)")
  local p = w:particle(0, 0)
  w:remove(p)
  T.checkerror("bad argument #2 to 'asleep' (stale particle handle)", w.asleep, w, p)
end)

T.done()
