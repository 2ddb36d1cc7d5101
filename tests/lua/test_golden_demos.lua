-- tests/lua/test_golden_demos.lua — every demo, driven as the runner drives
-- it (tether.load, then tether.update(1/60) STEPS times), ends with these
-- positions (FNV-1a of their bits, read with w:positions(), apart from
-- w:hash()) and these world hashes. A change of results, or of what the
-- hash covers, changes the constants in a commit that says why. The
-- positions were recorded before the hash became the hash of the snapshot
-- stream and did not move with it.
package.path = "tests/lua/?.lua;" .. package.path
local T = require "harness"
local tether = require "tether"

local STEPS = 120
local golden = {
  cloth = { "bf95991b563e9272", "6525abdc094c4633" },
  fountain = { "6f5670ad6bc772f6", "8e2eb4be3075c5e7" },
  galton = { "8c6fcd0f80161128", "d53512656daf934c" },
  hourglass = { "c09cda5bf493f092", "0770fe70fadb78da" },
  integrators = { "72823523ba511575", "3621fcd6145aab93,26f29bf1c1082c37,95cb19c7b2324695,8ccc75868e811135,ea6678e9ca425f4c" },
  ragdoll = { "218a40738c049b9c", "44a768ea8a87c004" },
  rope_bridge = { "73fa3817e5c476a7", "1695e8d069c351f6" },
  soft_bodies = { "53b95d0bf05b10d2", "7be9a3697b1b1bbf" },
  spring_net = { "2a61a51d9d763317", "23f95701ff040468" },
  terrain = { "06cc662cfae0adc4", "a8faa1348f33a5c7" },
  worms = { "59c16f0720da8417", "5f2ea84f24227871" },
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
  "soft_bodies", "spring_net", "terrain", "worms" } do names[#names + 1] = n end

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
