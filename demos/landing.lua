-- demos/landing.lua — a load of circles dropped fast, without and with substeps by speed.
--
--   build/tether demos/landing.lua                        (a window)
--   build/tether --headless --frames 1 --every 120 --out build/demo demos/landing.lua
--   LUA_CPATH='build/?.so' lua5.4 demos/landing.lua   (stock Lua: 5 s simulated)
--
-- Two worlds side by side, each a well 12 m wide, at 1 substep x 8 sweeps.
-- Into each falls a block of 11 x 30 circles (radius 0.5 m) thrown down at
-- 60 m/s: a metre a step, two radii. On the left every step runs its one
-- substep: the layers above run into the stopped ones before the sweeps can
-- hold them, and the block lands deep inside itself. On the right
-- `max_travel = 0.5` (docs/collisions.md "Substeps by speed") splits a step
-- wherever a circle would move more than half its radius in one: the block
-- lands in short substeps, and once it rests every step is one substep
-- again. Every half second it prints the deepest overlap so far in each well
-- (read every third step) and the substeps the right one ran; at the end
-- the hashes.
local tether = require "tether"

local COLS, ROWS, R, SPEED = 11, 30, 0.5, 60
local OFFSET = 18 -- m: the right-hand well is drawn this far right
local worlds, deepest, substeps = {}, { 0, 0 }, 0
local time, steps, next_report = 0, 0, 0.5

local function well(travel, x0)
  local w = tether.world { substeps = 1, iterations = 8, max_travel = travel }
  w:set_collision {}
  w:aabb(x0 - 7, -1, x0 + 7, 0)
  w:aabb(x0 - 7, 0, x0 - 6, 80)
  w:aabb(x0 + 6, 0, x0 + 7, 80)
  for r = 0, ROWS - 1 do
    for c = 0, COLS - 1 do
      -- a little stagger, so the layers do not stand exactly on one another
      w:particle(x0 + (c - 0.5 * (COLS - 1)) * 1.02 + (r % 2) * 0.02, 12 + r * 1.02, { radius = R, vy = -SPEED })
    end
  end
  return w
end

-- Deepest overlap of two circles, as a share of a radius (every pair: 330 circles).
local function overlap(w)
  local xy, worst = w:positions(), 0
  local n = math.floor(#xy / 2) -- (no // : the demos run under LuaJIT too)
  for i = 0, n - 1 do
    local xi, yi = xy[2 * i + 1], xy[2 * i + 2]
    for j = i + 1, n - 1 do
      local dx, dy = xy[2 * j + 1] - xi, xy[2 * j + 2] - yi
      local d2 = dx * dx + dy * dy
      if d2 < 4 * R * R then worst = math.max(worst, (2 * R - math.sqrt(d2)) / R) end
    end
  end
  return worst
end

function tether.load()
  worlds[1] = well(0, 0)
  worlds[2] = well(0.5, OFFSET)
  print(("landing: %d circles each, thrown down at %d m/s; left: 1 substep, right: max_travel = 0.5"):format(COLS * ROWS, SPEED))
  print(("%5s %18s %18s %16s"):format("t", "deepest left (%r)", "deepest right (%r)", "substeps right"))
end

function tether.update(dt)
  for _, w in ipairs(worlds) do w:step(dt) end
  substeps = substeps + worlds[2]:stats().substeps
  time, steps = time + dt, steps + 1
  if steps % 3 == 0 then -- every third step: a landing's deepest moment lasts longer
    for i = 1, 2 do deepest[i] = math.max(deepest[i], overlap(worlds[i])) end
  end
  if time >= next_report - 1e-9 then
    print(("%5.1f %18.1f %18.1f %16d"):format(time, 100 * deepest[1], 100 * deepest[2], worlds[2]:stats().substeps))
    next_report = next_report + 0.5
  end
end

function tether.draw(g)
  g.fit(-8, -1.5, OFFSET + 8, 46)
  for _, w in ipairs(worlds) do w:draw() end
  g.hud(worlds[1], ("left: 1 substep, deepest overlap %.0f %% of a radius"):format(100 * deepest[1]))
  g.hud(worlds[2], ("right: max_travel = 0.5, deepest %.0f %%, substeps this step %d"):format(100 * deepest[2],
    worlds[2]:stats().substeps))
end

function tether.unload()
  print(("landing: deepest overlap %.1f %% (1 substep) and %.1f %% (max_travel 0.5), %.2f substeps a step on the right")
    :format(100 * deepest[1], 100 * deepest[2], substeps / math.max(1, steps)))
  print("landing: hashes " .. worlds[1]:hash() .. " " .. worlds[2]:hash())
end

if not tether.quit then -- stock Lua: no runner, so run 5 s here
  tether.load()
  for _ = 1, 300 do tether.update(1 / 60) end
  tether.unload()
end
