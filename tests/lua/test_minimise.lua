-- tests/lua/test_minimise.lua — the fuzz minimisers' shared reduction
-- (tests/fuzz/minimise_lib.lua) against a failure whose causes are known:
-- a run of 8000 calls that fails at its last call on a world made at call
-- 6000, after 6000 calls on another world. As in the Lua fuzzer, skipping
-- the call that made a world renumbers the worlds after it, so the failure
-- needs both worlds' making calls and two calls on the failing world. The
-- work of a try is the calls it still makes (a fuzz run's time).
package.path = "tests/lua/?.lua;tests/fuzz/?.lua;" .. package.path
local T = require "harness"
local R = require "minimise_lib"

local N, NEEDED = 8000, { 1, 6000, 6300, 7500 } -- 1 and 6000 make the worlds

local function case(with_worlds)
  local worlds, makes = {}, { [1] = true, [6000] = true }
  for c = 1, N do worlds[c] = { c < 6000 and 1 or 2 } end
  for c = 1, N, 7 do if c < 6000 then worlds[c] = {} end end -- module calls: no world
  local work, failures_seen = 0, 0
  local skip, kept, tried = R.reduce {
    ncalls = N, worlds = with_worlds and worlds or nil, makes = makes,
    fails = function(s)
      for c = 1, N do if not s[c] then work = work + 1 end end
      for _, c in ipairs(NEEDED) do if s[c] then return false end end
      failures_seen = failures_seen + 1
      return true
    end,
    keep = function() end, over = function() return false end, say = function() end,
  }
  return skip, kept, tried, work
end

T.test("ranges merge the skipped calls", function()
  T.eq(R.ranges({ [3] = true, [4] = true, [5] = true, [9] = true, [12] = true, [13] = true }), "3-5,9,12-13")
  T.eq(R.ranges({}), "")
end)

T.test("the failing world's calls are all that is left", function()
  local skip, kept = case(true)
  T.eq(kept, #NEEDED + 1, "calls left")
  for _, c in ipairs(NEEDED) do T.ok(not skip[c], "call " .. c .. " kept") end
  T.ok(not skip[N], "the failing call kept")
end)

T.test("dropping the other world first costs a fraction of chunks alone", function()
  local _, kept_w, tried_w, work_w = case(true)
  local _, kept_c, tried_c, work_c = case(false)
  T.eq(kept_w, kept_c, "the same calls left either way")
  -- measured: 19.7 k calls made over 61 runs with worlds, 82.8 k over 86 runs by chunks alone
  T.ok(work_w * 3 < work_c, string.format("work %d with worlds, %d by chunks alone", work_w, work_c))
  T.ok(tried_w < 200, "runs tried: " .. tried_w)
end)

T.done()
