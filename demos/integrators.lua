-- demos/integrators.lua — the same spring oscillator under every integrator.
--
--   build/tether --headless --steps 600 demos/integrators.lua
--   LUA_CPATH='build/?.so' lua5.4 demos/integrators.lua   (stock Lua: 10 s of simulated time)
--
-- Five worlds side by side, one per integrator, each holding a bob on a
-- spring tied to a pinned anchor (no gravity, no damping: the energy should
-- stay constant). Every second of simulated time it prints the relative
-- energy drift (E - E0) / E0 of each: Euler gains energy, the symplectic
-- ones oscillate around zero, RK4 loses a little.
local tether = require "tether"

local K, MASS, REST, STRETCH = 100, 1, 1, 0.5  -- N/m, kg, m, m: period 2π/sqrt(K/MASS) ≈ 0.63 s

local worlds, e0 = {}, {}
local time, next_report = 0, 1

local function energy(w) return w:energy().total end

function tether.load()
  local head = { ("%7s"):format("t") }
  for i, name in ipairs(tether.integrators) do
    local w = tether.world { integrator = name, gravity = { 0, 0 } }
    local anchor = w:particle(0, 0, { pinned = true })
    local bob = w:particle(REST + STRETCH, 0, { mass = MASS })
    w:spring(anchor, bob, { stiffness = K, rest = REST })
    worlds[i], e0[i] = w, energy(w)
    head[#head + 1] = ("%17s"):format(name)
  end
  print(("integrators: bob of %g kg on a %g N/m spring, E0 = %g J; relative energy drift (E - E0)/E0")
    :format(MASS, K, e0[1]))
  print(table.concat(head))
end

function tether.update(dt)
  for _, w in ipairs(worlds) do w:step(dt) end
  time = time + dt
  if time >= next_report - 1e-9 then
    local row = { ("%5.1f s"):format(time) }
    for i, w in ipairs(worlds) do row[#row + 1] = ("%+17.3e"):format((energy(w) - e0[i]) / e0[i]) end
    print(table.concat(row))
    next_report = next_report + 1
  end
end

function tether.unload()
  local row = { "force evaluations per step:" }
  for i, w in ipairs(worlds) do
    row[#row + 1] = ("%s %d"):format(tether.integrators[i], w:stats().force_evaluations)
  end
  print(table.concat(row, "  "))
end

if not tether.quit then -- stock Lua: no runner, so run 10 s here
  tether.load()
  for _ = 1, 600 do tether.update(1 / 60) end
  tether.unload()
end
