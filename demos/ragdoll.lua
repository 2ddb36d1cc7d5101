-- demos/ragdoll.lua — ragdolls tumbling down a staircase.
--
--   build/tether --headless --steps 600 demos/ragdoll.lua [count]
--   LUA_CPATH='build/?.so' lua5.4 demos/ragdoll.lua      (stock Lua: runs 600 steps itself)
--
-- Each stair is a static box shape, the ground a box, and the ragdolls
-- collide with each other (particle contacts). Every second it prints where each ragdoll is, how far it leans and the angle
-- limit errors; at the end the state hash.
local tether = require "tether"

local STEPS, RISE, TREAD = 6, 0.4, 0.8
local LOG_EVERY = 60
local world, dolls, limits, steps = nil, {}, {}, 0

function tether.load(args)
  local count = tonumber((args[1] or ""):match("^%d+$")) or 3
  world = tether.world { iterations = 20, substeps = 2, damping = 0.05 }
  -- the staircase: step k spans x in [k·TREAD, (k+1)·TREAD], top at (STEPS − k)·RISE
  world:set_collision { friction = 0.6 }
  for k = 0, STEPS - 1 do
    world:aabb(k * TREAD, -1, (k + 1) * TREAD, (STEPS - k) * RISE, { friction = 0.6 })
  end
  world:aabb(-2, -1, 12, 0, { friction = 0.8 })   -- ground
  world:aabb(-3, -1, -2, 30, { friction = 0.8 })  -- walls
  world:aabb(12, -1, 13, 30, { friction = 0.8 })
  for i = 1, count do
    local d = world:ragdoll { position = { 0.2 + 0.3 * i, STEPS * RISE + 1.2 + 1.5 * i }, height = 1.2,
                              mass = 2, radius = 0.05 }
    -- a shove toward the stairs, different for each doll
    for _, p in ipairs(world:composite_particles(d)) do world:set_velocity(p, 1.5 + 0.4 * i, 0) end
    dolls[i] = d
    for _, c in ipairs(world:composite_constraints(d)) do
      if world:constraint_kind(c) == "angle" then limits[#limits + 1] = c end
    end
  end
  print(("ragdoll: %d ragdolls, %d particles, %d constraints (%d angle limits), %d stairs")
    :format(count, world:count(), world:constraint_count(), #limits, STEPS))
end

function tether.update(dt)
  world:step(dt)
  steps = steps + 1
  if steps % LOG_EVERY == 0 then
    local parts, worst = {}, 0
    for i, d in ipairs(dolls) do
      local x, y = world:composite_center(d)
      parts[#parts + 1] = ("#%d (%5.2f, %5.2f) %+4.0f deg"):format(i, x, y, math.deg(world:composite_angle(d)))
    end
    for _, c in ipairs(limits) do worst = math.max(worst, world:constraint_error(c)) end
    print(("t=%5.2f s  %s  worst limit error %.3f rad"):format(world:stats().time, table.concat(parts, "  "), worst))
  end
end

function tether.draw(g)
  g.fit(-2.5, -0.5, 12.5, STEPS * RISE + 6)
  world:draw()
  g.hud(world)
end

function tether.unload()
  print(("ragdoll: %d steps, %d particles, hash %s"):format(steps, world:count(), world:hash()))
  world:destroy()
end

if not tether.quit then
  tether.load(arg or {})
  for _ = 1, 600 do tether.update(1 / 60) end
  tether.unload()
end
