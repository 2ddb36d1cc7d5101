-- tests/lua/test_golden_demos.lua — every demo, driven as the runner drives
-- it (tether.load, then tether.update(1/60) STEPS times), ends with these
-- positions (FNV-1a of their bits, read with w:positions(), apart from
-- w:hash()) and these world hashes. A change of results, or of what the
-- hash covers, changes the constants in a commit that says why. The
-- positions were recorded before the hash became the hash of the snapshot
-- stream and did not move with it. Sleeping on by default (issue 22) moved
-- every hash (the hash covers the sleep section) and no position: nothing
-- falls asleep within 120 steps. Pre-stabilisation of overlaps deeper than
-- a tenth of the radii sum (issue 21) moved galton, soft_bodies and worms,
-- whose particles spawn into or fall deep into one another. The speed cap
-- after the velocity pass (issue 21, contact_cap.c: no particle leaves its
-- pair contacts faster than the fastest of them came in) moved hourglass,
-- ragdoll and soft_bodies, whose particles pile and press on one another.
-- The rest test reading the particle's position smoothed over a few steps
-- (sleep_rest.c, its smoothed positions in the sleep section) moved every
-- hash but fountain's, and no position. stacks came with its pin (anchored
-- friction beside the default one), which moved when anchored friction
-- went into the batches' vector lanes (their order, not the pairs'), and
-- again when its rub took the pair's distance from the push and divided
-- by reciprocals (contact_batch.h tt__anchored_rub: the same physics,
-- other roundings). landing came with its pin (substeps by speed beside one
-- fixed substep, src/core/travel.c).
package.path = "tests/lua/?.lua;" .. package.path
local T = require "harness"
local tether = require "tether"

local STEPS = 120
local golden = {
  cloth = { "bf95991b563e9272", "73a31a0091afa103" },
  fountain = { "6f5670ad6bc772f6", "445dc6e166079fa7" },
  galton = { "f87c0e38649ae15d", "715dbdd6cb3e2712" },
  hourglass = { "654a2585bdea45e0", "42be60c7a612e2a4" },
  landing = { "569b6df26b7d9199", "671e4f0753023bb5,ed938c8f4b97d4c4" },
  integrators = { "72823523ba511575", "f2247ad90c3f894c,ddf0c7a2ba95667c,373b4cb2b329b35a,db9258f3acc7bed6,e35fe3ff1fc505ea" },
  ragdoll = { "1f6eff9f9b774ef4", "bc8e871ea995947e" },
  rope_bridge = { "73fa3817e5c476a7", "3defb6dcebf4f0d1" },
  soft_bodies = { "ec279600d165358c", "7bb2f58f82342a50" },
  spring_net = { "2a61a51d9d763317", "0463e3ebdfefda22" },
  stacks = { "d39b1544cdc9db51", "3161b57fd285ec75,7c2f001930b89397" },
  terrain = { "06cc662cfae0adc4", "f64d2ac4c14dd04c" },
  worms = { "a7fcec207a6ecc1b", "328b1cf988991979" },
}

local function digest(h, xy)
  for i = 1, #xy do T.fnv.add(h, T.double_bytes(xy[i])) end
  return h
end

local function run(path)
  local made = {}
  local make = tether.world
  tether.world = function(...)
    local w = make(...)
    made[#made + 1] = w
    return w
  end
  tether.load, tether.update, tether.draw = nil, nil, nil
  -- a demo runs its own loop under a plain Lua (no runner, so no tether.quit)
  local quit = tether.quit
  tether.quit = quit or function() end
  local real_print = print
  print = function() end -- the demos' own reports are not under test
  local ok, err = pcall(function()
    dofile(path)
    if tether.load then tether.load({}) end
    for _ = 1, STEPS do tether.update(1 / 60) end
  end)
  print, tether.world, tether.quit = real_print, make, quit
  if not ok then error(err, 0) end
  local pos, hashes = T.fnv.new(), {}
  for _, w in ipairs(made) do
    pos = digest(pos, w:positions())
    hashes[#hashes + 1] = w:hash()
  end
  return T.fnv.hex(pos), table.concat(hashes, ",")
end

local names = {}
for _, n in ipairs { "cloth", "fountain", "galton", "hourglass", "integrators", "ragdoll", "rope_bridge",
  "soft_bodies", "spring_net", "stacks", "terrain", "worms", "landing" } do names[#names + 1] = n end

T.test("every demo keeps its positions and hashes", function()
  for _, n in ipairs(names) do
    local pos, h = run("demos/" .. n .. ".lua")
    local g = golden[n]
    if not g or g[1] ~= pos or g[2] ~= h then
      T.ok(false, ("%s = { %q, %q },"):format(n, pos, h))
    end
  end
end)

T.done()
