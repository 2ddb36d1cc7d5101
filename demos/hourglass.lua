-- demos/hourglass.lua — thousands of grains run through the neck of an hourglass.
--
--   build/tether --headless --steps 1200 demos/hourglass.lua
--   LUA_CPATH='build/?.so' lua5.4 demos/hourglass.lua   (stock Lua: 20 s simulated)
--
-- The glass is two chains (left and right walls, floor); 3000 grains of
-- radius 0.1 m start stacked in the upper bulb and collide with each other
-- and with the glass. Every second it prints how many grains have passed
-- the neck and what a step costs; at the end the world's hash.
local tether = require "tether"

local GRAINS, R, NECK = 3000, 0.1, 0.35   -- count, grain radius (m), half-width of the neck (m)
local w, time, next_report = nil, 0, 1

local function below_neck()
  local xy, n = w:positions()
  local k = 0
  for i = 1, n do if xy[2 * i] < 0 then k = k + 1 end end
  return k
end

function tether.load()
  -- 4 substeps x 4 sweeps: piles settle without visible overlap (docs/collisions.md)
  w = tether.world { substeps = 4, iterations = 4 }
  w:set_collision { friction = 0.4 }
  w:chain({ -6, 24, -6, 6, -NECK, 0, -6, -6, -6, -12, 6, -12 }, { friction = 0.3 })
  w:chain({ 6, 24, 6, 6, NECK, 0, 6, -6, 6, -12 }, { friction = 0.3 })
  local cols, d = 50, 2.2 * R
  for i = 0, GRAINS - 1 do
    local row = math.floor(i / cols)
    local x = -5.4 + (i % cols) * d + (row % 2) * 0.5 * d
    w:particle(x, 7 + row * d, { radius = R * (0.9 + 0.2 * ((i * 37) % 11) / 10) })
  end
  print(("hourglass: %d grains (r = %.2f m), neck %.2f m wide"):format(GRAINS, R, 2 * NECK))
  print(("%6s %10s %12s"):format("t", "passed", "ms/step"))
end

function tether.update(dt)
  w:step(dt)
  time = time + dt
  if time >= next_report - 1e-9 then
    print(("%5.1fs %10d %12.3f"):format(time, below_neck(), w:stats().step_ms))
    next_report = next_report + 1
  end
end

function tether.draw(g)
  g.fit(-7, -13, 7, 25)
  w:draw()
  g.hud(w, ("%d grains"):format(GRAINS))
end

function tether.unload()
  local s = w:collision_stats()
  print(("hourglass: %d of %d grains passed the neck; %d particle pairs, %d shape contacts in the last substep")
    :format(below_neck(), GRAINS, s.pair_contacts, s.shape_contacts))
  print("hourglass: hash " .. w:hash())
end

if not tether.quit then -- stock Lua: no runner, so run 20 s here
  tether.load()
  for _ = 1, 1200 do tether.update(1 / 60) end
  tether.unload()
end
