-- demos/spring_net.lua — a net of springs hanging from a pinned top row,
-- pushed by gusts of wind and a blast now and then. Springs are drawn by
-- strain: blue compressed, grey at rest, red stretched. Force-based springs
-- only (no constraints, no collisions), so it runs on the core alone.
--
--   build/tether demos/spring_net.lua                         (a window: drag a knot with the mouse)
--   build/tether --headless --frames 60 --every 10 --out build/demo demos/spring_net.lua
--   build/tether --headless --steps 600 demos/spring_net.lua
local tether = require "tether"

local COLS, ROWS, GAP = 21, 13, 0.25   -- knots, m
local K, DAMP, MASS = 600, 0.4, 0.05   -- N/m, N·s/m, kg per knot
local SUB = 10                         -- substeps per frame: stiff springs need a small step

local world
local steps = 0
local seed = 7
local function rnd()
  seed = seed * 48271 % 2147483647 -- MINSTD: exact in doubles, so LuaJIT draws the same numbers
  return (seed - 1) / 2147483646
end

function tether.load()
  world = tether.world { gravity = { 0, -9.81 }, damping = 0.05, integrator = "verlet" }
  local knots = {}
  local x0 = -(COLS - 1) * GAP / 2
  for r = 0, ROWS - 1 do
    for c = 0, COLS - 1 do
      local pinned = r == 0 and c % 4 == 0
      knots[r * COLS + c] = world:particle(x0 + c * GAP, -r * GAP, { mass = MASS, radius = 0.03, pinned = pinned })
    end
  end
  for r = 0, ROWS - 1 do
    for c = 0, COLS - 1 do
      local k = knots[r * COLS + c]
      if c + 1 < COLS then world:spring(k, knots[r * COLS + c + 1], { stiffness = K, damping = DAMP }) end
      if r + 1 < ROWS then world:spring(k, knots[(r + 1) * COLS + c], { stiffness = K, damping = DAMP }) end
    end
  end
  print(("spring_net: %d knots, %d springs, k = %g N/m, %d substeps"):format(world:count(), world:spring_count(), K, SUB))
end

function tether.update(dt)
  steps = steps + 1
  local t = steps * dt
  -- gusts: a slow swell and a random flutter, sideways and a little up
  world:set_wind(0.07 * math.sin(t * 0.7) + 0.04 * (rnd() - 0.5), 0.02 * math.sin(t * 1.3))
  if steps % 240 == 120 then world:explode((rnd() - 0.5) * 3, -1.5 - rnd(), 1.5, 0.08) end
  world:step(dt / SUB, SUB)
end

function tether.draw(g)
  g.fit(-3.4, -(ROWS - 1) * GAP - 1.2, 3.4, 1.2)
  g.color(0.4, 0.4, 0.45)
  g.line(-3, 0.05, 3, 0.05)
  world:draw { min_radius = 2 }
  g.hud(world, "wind gusts, a blast every 4 s")
end

function tether.unload()
  local e = world:energy()
  print(("spring_net: %d steps, E %.4f J, hash %s"):format(steps, e.total, world:hash()))
end

if not tether.quit then -- stock Lua: run 10 s here
  tether.load()
  for _ = 1, 600 do tether.update(1 / 60) end
  tether.unload()
end
