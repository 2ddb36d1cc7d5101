-- demos/stacks.lua — two pyramids of circles, without and with anchored friction.
--
--   build/tether demos/stacks.lua                        (a window)
--   build/tether --headless --frames 1 --every 300 --out build/demo demos/stacks.lua
--   LUA_CPATH='build/?.so' lua5.4 demos/stacks.lua   (stock Lua: 10 s simulated)
--
-- Two worlds side by side, each a pyramid of ten rows of circles (radius
-- 0.5 m, the bottom row 1.02 m apart, friction 0.3) on a floor, at 1
-- substep x 8 sweeps. These particles do not turn, so only friction between
-- them keeps the rows from sliding apart. On the left friction between
-- particles is the default one, bounded in the velocity pass substep by
-- substep: the pyramid spreads. On the right `anchored_friction = true`
-- holds each pair where it stuck (docs/collisions.md "Anchored friction"):
-- it stands, as in Box2D. At 3 s a 5 kg ball lands on each apex. Every
-- second it prints how far each base has spread; at the end the hashes.
local tether = require "tether"

local ROWS, R, GAP, MU = 10, 0.5, 1.02, 0.3
local OFFSET = 20 -- m: the right-hand world's pyramid is drawn this far right
local worlds, corners = {}, {}
local time, next_report = 0, 1

local function pyramid(anchored, x0)
  local w = tether.world { substeps = 1, iterations = 8 }
  w:set_collision { anchored_friction = anchored, friction = MU }
  w:aabb(x0 - 9.5, -1, x0 + 9.5, 0, { friction = MU })
  local dy = math.sqrt(4 * R * R - 0.25 * GAP * GAP)
  local left, right
  for r = 0, ROWS - 1 do
    for k = 0, ROWS - r - 1 do
      local p = w:particle(x0 + (k - 0.5 * (ROWS - r - 1)) * GAP, R + r * dy, { radius = R })
      if r == 0 and k == 0 then left = p end
      if r == 0 and k == ROWS - 1 then right = p end
    end
  end
  return w, { left, right }
end

local function spread(i)
  local w, c = worlds[i], corners[i]
  return select(1, w:position(c[2])) - select(1, w:position(c[1])) - (ROWS - 1) * GAP
end

function tether.load()
  worlds[1], corners[1] = pyramid(false, 0)
  worlds[2], corners[2] = pyramid(true, OFFSET)
  print(("stacks: %d rows of circles, friction %.1f; left: default friction, right: anchored_friction"):format(ROWS, MU))
  print(("%5s %16s %16s"):format("t", "spread left (m)", "spread right (m)"))
end

function tether.update(dt)
  for _, w in ipairs(worlds) do w:step(dt) end
  time = time + dt
  if math.abs(time - 3) < dt / 2 then
    for i, w in ipairs(worlds) do
      local p = w:particle((i - 1) * OFFSET + 0.2, 13, { radius = 0.6, mass = 5 })
      w:set_velocity(p, 0, -5)
    end
  end
  if time >= next_report - 1e-9 then
    print(("%5.1f %16.4f %16.4f"):format(time, spread(1), spread(2)))
    next_report = next_report + 1
  end
end

function tether.draw(g)
  g.fit(-10, -1.5, OFFSET + 10, 14)
  for _, w in ipairs(worlds) do w:draw() end
  g.hud(worlds[1], ("left: default friction, base spread %.2f m"):format(spread(1)))
  g.hud(worlds[2], ("right: anchored_friction = true, base spread %.3f m"):format(spread(2)))
end

function tether.unload()
  print(("stacks: base spread %.3f m (default) and %.4f m (anchored)"):format(spread(1), spread(2)))
  print("stacks: hashes " .. worlds[1]:hash() .. " " .. worlds[2]:hash())
end

if not tether.quit then -- stock Lua: no runner, so run 10 s here
  tether.load()
  for _ = 1, 600 do tether.update(1 / 60) end
  tether.unload()
end
