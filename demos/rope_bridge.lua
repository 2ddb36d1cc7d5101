-- demos/rope_bridge.lua — a rope bridge between two cliffs: planks are small
-- lattice bodies hung under two sagging ropes, and two heavy boxes dropped on it.
--
--   build/tether --headless --steps 600 demos/rope_bridge.lua
--   LUA_CPATH='build/?.so' lua5.4 demos/rope_bridge.lua      (stock Lua: runs 600 steps itself)
--
-- Collisions are being built separately: until they land, the cliffs are
-- bounds constraints (solid blocks) and the boxes are tied to the deck by
-- slack (max-distance) links, so they fall until the link goes taut and then
-- hang from the deck instead of resting on the planks. Every second it prints
-- the sag and the largest link error; at the end the state hash.
local tether = require "tether"

local SPAN, PLANKS = 8.0, 16
local LOG_EVERY = 60
local world, ropes, planks, steps = nil, {}, {}, 0
local boxes = {}

function tether.load()
  world = tether.world { iterations = 30, substeps = 2, damping = 0.3 }
  -- two ropes pinned at both cliffs, 8 % longer than the span so they sag:
  -- made straight, then the pinned far end is moved in to the cliff edge
  for k, y in ipairs { 0.0, -0.02 } do
    ropes[k] = world:rope { start = { -SPAN / 2, y }, finish = { SPAN / 2 * 1.16, y }, segments = PLANKS * 2,
                            pin_start = true, pin_finish = true, mass = 0.5, radius = 0.03 }
    local ps = world:composite_particles(ropes[k])
    world:set_position(ps[#ps], SPAN / 2, y)
  end
  -- the deck: every second rope particle carries a plank (a rigid 2x2 lattice)
  local deck = world:composite_particles(ropes[1])
  for i = 2, #deck - 1, 2 do
    local x, y = world:position(deck[i])
    local pl = world:lattice { center = { x, y - 0.08 }, width = 0.35, height = 0.06, mass = 0.4 }
    local corners = world:composite_particles(pl)
    world:distance(deck[i], corners[3], { mode = "max" })   -- hangers that can go slack
    world:distance(deck[i], corners[4], { mode = "max" })
    planks[#planks + 1] = pl
  end
  -- the cliffs: solid blocks nothing can enter
  world:bounds(-SPAN / 2 - 3, -6, -SPAN / 2, 0, { outside = true, friction = 0.5 })
  world:bounds(SPAN / 2, -6, SPAN / 2 + 3, 0, { outside = true, friction = 0.5 })
  -- two heavy boxes dropped from above, hanging from deck particles by slack links
  for k, i in ipairs { 9, 21 } do
    local x = world:position(deck[i])
    local b = world:lattice { center = { x, 2 + k }, width = 0.5, height = 0.5, mass = 5 }
    world:distance(deck[i], world:composite_particles(b)[1], { mode = "max", length = 0.3 })
    boxes[k] = b
  end
  print(("rope_bridge: span %.1f m, %d planks, %d particles, %d constraints")
    :format(SPAN, #planks, world:count(), world:constraint_count()))
end

local function sag()
  local low = 0
  for _, p in ipairs(world:composite_particles(ropes[1])) do
    local _, y = world:position(p)
    if y < low then low = y end
  end
  return -low
end

local function worst_error()
  local e = 0
  for _, r in ipairs(ropes) do
    for _, c in ipairs(world:composite_constraints(r)) do e = math.max(e, world:constraint_error(c)) end
  end
  return e
end

function tether.update(dt)
  world:step(dt)
  steps = steps + 1
  if steps % LOG_EVERY == 0 then
    local st = world:stats()
    local bx, by = world:composite_center(boxes[1])
    print(("t=%5.2f s  sag %.3f m  rope error %.2e m  box at (%.2f, %.2f)  sweeps %d  solver error %.1e m")
      :format(st.time, sag(), worst_error(), bx, by, st.iterations, st.max_error))
  end
end

function tether.draw(g)
  g.fit(-SPAN / 2 - 1.5, -3, SPAN / 2 + 1.5, 5)
  g.color(0.35, 0.3, 0.25) -- the cliffs (bounds blocks are not drawn by w:draw)
  g.polygon { -SPAN / 2 - 3, -6, -SPAN / 2, -6, -SPAN / 2, 0, -SPAN / 2 - 3, 0 }
  g.polygon { SPAN / 2, -6, SPAN / 2 + 3, -6, SPAN / 2 + 3, 0, SPAN / 2, 0 }
  world:draw()
  g.hud(world, ("sag %.2f m"):format(sag()))
end

function tether.unload()
  print(("rope_bridge: %d steps, %d particles, hash %s"):format(steps, world:count(), world:hash()))
  world:destroy()
end

if not tether.quit then
  tether.load(arg or {})
  for _ = 1, 600 do tether.update(1 / 60) end
  tether.unload()
end
