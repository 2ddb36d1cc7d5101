-- demos/soft_bodies.lua — soft bodies (rings with an area constraint and
-- pressure) dropped into a funnel, next to a jelly made as a soft lattice.
--
--   build/tether --headless --steps 600 demos/soft_bodies.lua [count]
--   LUA_CPATH='build/?.so' lua5.4 demos/soft_bodies.lua      (stock Lua: runs 600 steps itself)
--
-- The box and the two ledges are static shapes; the bodies touch each other
-- through particle contacts, so they pile up, squashed by their fall and kept
-- round by pressure. Every second it prints each body's
-- area against its rest area; at the end the state hash.
local tether = require "tether"

local LOG_EVERY = 60
local world, bodies, rest, steps = nil, {}, {}, 0

local function area(ps)
  local a = 0
  for i = 1, #ps do
    local x1, y1 = world:position(ps[i])
    local x2, y2 = world:position(ps[i % #ps + 1])
    a = a + x1 * y2 - x2 * y1
  end
  return a / 2
end

function tether.load(args)
  local count = tonumber((args[1] or ""):match("^%d+$")) or 5
  world = tether.world { iterations = 20, substeps = 2, damping = 0.2 }
  world:set_collision { friction = 0.7 }
  world:aabb(-6, -1, 6, 0, { friction = 0.7 })                            -- floor
  world:aabb(-6, 0, -5, 40, { friction = 0.7 })                           -- walls
  world:aabb(5, 0, 6, 40, { friction = 0.7 })
  world:aabb(-5, 2, -2.5, 2.3, { friction = 0.7 })                        -- left ledge
  world:aabb(2.5, 3, 5, 3.3, { friction = 0.7 })                          -- right ledge
  for i = 1, count do
    local x = -4 + 8 * (i - 1) / math.max(count - 1, 1)
    local b = world:soft_body { center = { x, 6 + i }, ring_radius = 0.4 + 0.1 * (i % 3), segments = 20,
                                pressure = 1 + 0.1 * (i % 2), stiffness = 0.6, mass = 0.05, radius = 0.06 }
    bodies[#bodies + 1] = b
    rest[#rest + 1] = area(world:composite_particles(b))
  end
  -- a jelly block: a lattice with soft (compliant) links
  bodies[#bodies + 1] = world:lattice { center = { 0, 10 }, width = 1.2, height = 0.8, columns = 6, rows = 4,
                                        compliance = 2e-3, mass = 0.05 }
  print(("soft_bodies: %d bodies, %d particles, %d constraints"):format(#bodies, world:count(), world:constraint_count()))
end

function tether.update(dt)
  world:step(dt)
  steps = steps + 1
  if steps % LOG_EVERY == 0 then
    local parts = {}
    for i = 1, #rest do
      parts[#parts + 1] = ("%.2f"):format(area(world:composite_particles(bodies[i])) / rest[i])
    end
    local jx, jy = world:composite_center(bodies[#bodies])
    print(("t=%5.2f s  area/rest %s  jelly at (%.2f, %.2f) tilted %+.1f deg")
      :format(world:stats().time, table.concat(parts, " "), jx, jy, math.deg(world:composite_angle(bodies[#bodies]))))
  end
end

function tether.draw(g)
  g.fit(-6.5, -1.5, 6.5, 13)
  world:draw()
  g.hud(world)
end

function tether.unload()
  print(("soft_bodies: %d steps, %d particles, hash %s"):format(steps, world:count(), world:hash()))
  world:destroy()
end

if not tether.quit then
  tether.load(arg or {})
  for _ = 1, 600 do tether.update(1 / 60) end
  tether.unload()
end
