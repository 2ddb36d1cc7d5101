-- tests/lua/test_clock.lua — tether.clock: steps from frame times, the
-- guard, pause, scale, single steps, and the refusals.
package.path = "tests/lua/?.lua;" .. package.path
local T = require "harness"
local tether = require "tether"

T.test("a clock turns frame times into fixed steps", function()
  local c = tether.clock { dt = 0.01, max_steps = 4 }
  T.eq(c:advance(0.025), 2)
  T.near(c:alpha(), 0.5, 1e-9)
  T.eq(c:advance(1.0), 4, "a long frame is capped")
  local i = c:info()
  T.ok(i.capped and i.dropped > 0.9, "the rest is dropped, and said so")
  T.near(i.time + i.acc + i.dropped, 1.025, 1e-12, "no time lost or made")
  c:set_paused(true)
  T.eq(c:advance(5), 0, "paused")
  c:step_once()
  T.eq(c:advance(5), 1, "a single step while paused")
  c:set_paused(false)
  c:set_scale(0.5)
  T.eq(c:scale(), 0.5)
  local n = 0
  for _ = 1, 100 do n = n + c:advance(0.01) end
  T.ok(n >= 49 and n <= 51, "half speed: half the steps")
end)

T.test("a world stepped by a clock", function()
  local w = tether.world()
  local p = w:particle(0, 0)
  local c = tether.clock { dt = 1 / 120 }
  for _ = 1, 60 do
    for _ = 1, c:advance(1 / 60) do w:step(c:dt()) end
  end
  T.eq(w:stats().steps, c:info().steps)
  T.near(w:stats().time, 1.0, 1e-9)
  local _, y = w:position(p)
  T.near(y, -0.5 * 9.81, 1e-9, "one second of free fall")
end)

T.test("a clock refuses bad input", function()
  T.checkerror("tether.clock: bad option 'dt' (number in [1e-09, 10] expected, got 0)", tether.clock, { dt = 0 })
  T.checkerror("unknown option 'speed'", tether.clock, { speed = 2 })
  T.checkerror("bad option 'max_steps'", tether.clock, { max_steps = 0 })
  local c = tether.clock()
  T.checkerror("bad argument #2 to 'advance' (number in [0, 1e+12] expected, got -1)", c.advance, c, -1)
  T.checkerror("bad argument #2 to 'advance' (finite number expected, got nan)", c.advance, c, 0 / 0)
  T.checkerror("bad argument #2 to 'set_scale'", c.set_scale, c, 1e4)
  T.checkerror("bad argument #1 to 'advance' (tether.clock expected, got table)", c.advance, {}, 1)
  T.checkerror("bad argument #2 to 'set_paused' (boolean expected, got number)", c.set_paused, c, 1)
  T.eq(c:info().steps, 0, "nothing changed")
  T.ok(tostring(c):find("tether.clock", 1, true))
  -- found by the fuzzer: the metamethod's error named '?'
  T.checkerror("bad argument #1 to '__tostring' (tether.clock expected, got number)", getmetatable(c).__tostring, 5)
end)

T.done()
