-- tests/lua/test_atlas.lua — the speed/accuracy atlas at its quick size: every
-- point of every reference scene is in the CSV with finite numbers, the
-- Pareto front is marked, and the known answers hold where the method is
-- exact (Verlet's projectile) or accurate (RK4's orbit).
-- Runs under the runner, stock Lua 5.4 and LuaJIT, from the repository root.
package.path = "tests/lua/?.lua;lua/?.lua;" .. package.path
local T = require "harness"
local atlas = require "tether_atlas"
local scenes = require "tether_atlas_scenes"

local dir = os.tmpname()
os.remove(dir)

local function read_csv(path)
  local rows, header = {}, nil
  for line in io.lines(path) do
    local f = {}
    for v in (line .. ","):gmatch("([^,]*),") do f[#f + 1] = v end
    if not header then header = f else
      local r = {}
      for i, k in ipairs(header) do r[k] = f[i] end
      rows[#rows + 1] = r
    end
  end
  return rows, header
end

T.test("make atlas QUICK=1: every point, finite, with its front", function()
  local quiet = print
  print = function() end -- the summaries: the CSV is what is checked
  local ok, status = pcall(atlas.main, "--quick", "--out", dir)
  print = quiet
  T.ok(ok, tostring(status))
  T.eq(status, 0, "exit status")
  local want, names = 0, {}
  for _, s in ipairs(scenes.scenes(true)) do
    local n = #atlas.grid(s)
    want = want + n
    names[s.name] = n
  end
  local rows, header = read_csv(dir .. "/atlas.csv")
  T.eq(#header, 16, "columns")
  T.eq(#rows, want, "one row per point of every scene")
  local seen, fronts = {}, {}
  for _, r in ipairs(rows) do
    seen[r.scene] = (seen[r.scene] or 0) + 1
    for _, k in ipairs { "dt", "error", "ns_per_particle_step", "us_per_particle_second", "cost_min", "cost_max" } do
      local v = tonumber(r[k])
      T.ok(v and v == v and v < math.huge and v >= 0, ("%s %s: %s finite, >= 0"):format(r.scene, k, r[k]))
    end
    T.ok(tonumber(r.cost_min) <= tonumber(r.us_per_particle_second) + 1e-9, "min <= median")
    if r.pareto == "1" then fronts[r.scene] = true end
  end
  for name, n in pairs(names) do
    T.eq(seen[name], n, name .. " rows")
    T.ok(fronts[name], name .. " has a Pareto front")
  end
  for _, r in ipairs(rows) do
    local e = tonumber(r.error)
    if r.scene == "projectile" and r.integrator == "verlet" then T.ok(e < 1e-9, "Verlet is exact under gravity: " .. e) end
    if r.scene == "kepler" and r.integrator == "rk4" and tonumber(r.dt) < 0.003 then T.ok(e < 1e-6, "RK4 orbit: " .. e) end
    if r.scene == "kepler" and r.integrator == "euler" and tonumber(r.dt) > 0.05 then T.ok(e > 1, "Euler spirals out: " .. e) end
    if r.scene == "oscillator" and r.integrator == "rk4" and tonumber(r.dt) < 0.02 then T.ok(e < 1e-6, "RK4 oscillator: " .. e) end
    if r.scene == "landing" and r.substeps == "1" then -- measured 1.91 and 0.041 of a radius
      if tonumber(r.travel) == 0 then T.ok(e > 0.5, "a fixed substep lets the load sink into itself: " .. e) end
      if tonumber(r.travel) > 0 then T.ok(e < 0.1, "substeps by speed land it: " .. e) end
    end
  end
  os.execute("rm -rf '" .. dir .. "'")
end)

T.test("the Pareto front: no point on it is beaten on both counts", function()
  local rows = {
    { error = 1, us_per_s = 1 }, { error = 0.5, us_per_s = 2 }, { error = 0.7, us_per_s = 3 },
    { error = 0.1, us_per_s = 3 }, { error = math.huge, us_per_s = 0.1 }, { error = 1, us_per_s = 1.5 },
  }
  atlas.pareto(rows)
  local got = {}
  for i, r in ipairs(rows) do got[i] = r.pareto end
  T.eq(table.concat({ tostring(got[1]), tostring(got[2]), tostring(got[3]), tostring(got[4]), tostring(got[5]),
    tostring(got[6]) }, " "), "true true false true false false", "front")
  T.eq(atlas.median { 3, 1, 2 }, 2, "median odd")
  T.eq(atlas.median { 4, 1, 2, 3 }, 2.5, "median even")
end)

T.test("a user's scene: the example script sweeps and writes its CSV", function()
  local chunk = assert(loadfile("docs/atlas_example.lua"))
  local scene = chunk(true)
  local rows = atlas.sweep(scene, { repeats = 1, log = function() end })
  T.eq(#rows, 4, "points")
  local best, worst = math.huge, 0
  for _, r in ipairs(rows) do
    T.ok(r.error == r.error and r.error < 1, "stretch finite")
    best, worst = math.min(best, r.error), math.max(worst, r.error)
  end
  T.ok(best < worst, "the settings make a difference")
end)

T.done()
