-- demos/fountain.lua — a particle fountain, with an explosion now and then.
--
--   build/tether demos/fountain.lua                       (a window)
--   build/tether --headless --frames 60 --every 10 --out build/demo demos/fountain.lua   (PNG frames)
--   build/tether --headless --steps 600 demos/fountain.lua [emit_per_step]
--   LUA_CPATH='build/?.so' lua5.4 demos/fountain.lua      (stock Lua: runs 600 steps itself)
--
-- Every second of simulated time it prints one summary line; at the end the
-- state hash, which is the same on every run (tests/run.sh checks it).
local tether = require "tether"

local FLOOR = -1.0          -- m: particles that fall below are removed
local MAX_PARTICLES = 3000
local EXPLODE_EVERY = 90    -- steps
local LOG_EVERY = 60        -- steps

local world
local emit_per_step = 6
local steps, emitted, removed, explosions = 0, 0, 0, 0
local handles, xy = {}, {}  -- reused by the bulk accessors: no garbage per frame

-- A small deterministic generator (the same fountain on every run).
local seed = 20240601
local function rnd()
  seed = seed * 48271 % 2147483647 -- MINSTD: exact in doubles, so LuaJIT draws the same numbers
  return (seed - 1) / 2147483646
end

local function emit()
  for _ = 1, emit_per_step do
    if world:count() >= MAX_PARTICLES then return end
    local angle = math.pi / 2 + (rnd() - 0.5) * 0.5
    local speed = 9 + rnd() * 3
    world:particle((rnd() - 0.5) * 0.2, 0, {
      vx = speed * math.cos(angle), vy = speed * math.sin(angle),
      mass = 0.05 + rnd() * 0.1, radius = 0.05,
    })
    emitted = emitted + 1
  end
end

-- Removes what fell below the floor; returns the highest particle's height.
local function sweep()
  local _, n = world:particles(handles)
  world:positions(xy)
  local top = FLOOR
  for i = 1, n do
    local y = xy[2 * i]
    if y < FLOOR then
      world:remove(handles[i])
      removed = removed + 1
    elseif y > top then
      top = y
    end
  end
  return top
end

function tether.load(args)
  emit_per_step = tonumber((args[1] or ""):match("^%d+$")) or emit_per_step
  world = tether.world { gravity = { 0, -9.81 }, damping = 0.02, integrator = "verlet", capacity = MAX_PARTICLES }
  print(("fountain: %d particles per step, floor at %.1f m, explosion every %d steps")
    :format(emit_per_step, FLOOR, EXPLODE_EVERY))
end

function tether.update(dt)
  emit()
  steps = steps + 1
  if steps % EXPLODE_EVERY == 0 then
    -- somewhere in the spray, a blast that pushes the particles around it away
    world:explode((rnd() - 0.5) * 2, 3 + rnd() * 3, 2.5, 0.4)
    explosions = explosions + 1
  end
  world:step(dt)
  local top = sweep()
  if steps % LOG_EVERY == 0 then
    local e = world:energy()
    print(("t=%6.2f s  particles %5d  emitted %6d  removed %6d  top %6.2f m  E %9.3f J  explosions %d")
      :format(world:stats().time, world:count(), emitted, removed, top, e.total, explosions))
  end
end

function tether.draw(g)
  g.fit(-5, FLOOR - 0.5, 5, 8.5)
  g.color(0.35, 0.38, 0.45)
  g.line(-5, FLOOR, 5, FLOOR)
  world:draw()
  g.hud(world, ("emitted %d  removed %d  explosions %d"):format(emitted, removed, explosions))
end

function tether.unload()
  print(("fountain: %d steps, %d particles, hash %s"):format(steps, world:count(), world:hash()))
  world:destroy()
end

-- Under stock Lua (no runner, so no tether.quit) run the loop here.
if not tether.quit then
  tether.load(arg or {})
  for _ = 1, 600 do tether.update(1 / 60) end
  tether.unload()
end
