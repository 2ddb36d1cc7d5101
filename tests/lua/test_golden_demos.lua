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
  cloth = { "bf95991b563e9272", "d23d5fcc63b71977" },
  fountain = { "25b1064dba2bae74", "5223328bbbf97f13" },
  galton = { "cef42891f80af0e6", "a29aedfc721296cb" },
  hourglass = { "91992223c1eeadff", "59af12d946385abe" },
  integrators = { "72823523ba511575", "1e25e20850840eca,4b2d6895ea62ff05,c3e389b7117092fb,cff93b3bacb89aa9,b82dc46bc0cd7f14" },
  ragdoll = { "74016491e8b45d88", "c007c6a2cc2810a1" },
  rope_bridge = { "73fa3817e5c476a7", "79f70505821e14b6" },
  soft_bodies = { "19d58e45566a5e66", "fba8f3e64323c161" },
  spring_net = { "dbb870a369c6c0a1", "55925ccf53a2d78c" },
  terrain = { "1db0fd03fee478a9", "e4b5efc4c4f822a0" },
}

local function digest(h, xy)
  for i = 1, #xy do
    local s = string.pack("<d", xy[i])
    for k = 1, #s do h = (h ~ s:byte(k)) * 0x100000001b3 end
  end
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
  local real_print = print
  print = function() end -- the demos' own reports are not under test
  local ok, err = pcall(function()
    dofile(path)
    if tether.load then tether.load({}) end
    for _ = 1, STEPS do tether.update(1 / 60) end
  end)
  print, tether.world = real_print, make
  if not ok then error(err, 0) end
  local pos, hashes = 0xcbf29ce484222325, {}
  for _, w in ipairs(made) do
    pos = digest(pos, w:positions())
    hashes[#hashes + 1] = w:hash()
  end
  return ("%016x"):format(pos), table.concat(hashes, ",")
end

local names = {}
for _, n in ipairs { "cloth", "fountain", "galton", "hourglass", "integrators", "ragdoll", "rope_bridge",
  "soft_bodies", "spring_net", "terrain" } do names[#names + 1] = n end

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
