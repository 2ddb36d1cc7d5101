-- demos/terrain.lua — balls rolling and bouncing on a terrain polyline.
--
--   build/tether --headless --steps 600 demos/terrain.lua
--   LUA_CPATH='build/?.so' lua5.4 demos/terrain.lua   (stock Lua: 10 s simulated)
--
-- The ground is one chain through 201 points of a sum of sines (hills and
-- valleys); 150 balls of mixed sizes and bounciness fall on it, roll down
-- the slopes and gather in the valleys. Every two seconds it prints how many
-- balls are still moving; at the end how many rest in each valley.
local tether = require "tether"

local w, balls, time, next_report = nil, {}, 0, 2
local X0, X1 = -40, 40

local function ground(x) return 3 * math.sin(x * 0.25) + 1.2 * math.sin(x * 0.9 + 1) end

local function moving()
  local k = 0
  for _, p in ipairs(balls) do
    local vx, vy = w:velocity(p)
    if vx * vx + vy * vy > 0.01 then k = k + 1 end
  end
  return k
end

function tether.load()
  w = tether.world { substeps = 4, iterations = 4 }
  w:set_collision { friction = 0.5 }
  local pts = {}
  for i = 0, 200 do
    local x = X0 + (X1 - X0) * i / 200
    pts[#pts + 1] = x
    pts[#pts + 1] = ground(x)
  end
  w:chain(pts, { friction = 0.8, restitution = 0.2 })
  w:aabb(X0 - 1, -10, X0, 20)  -- end walls
  w:aabb(X1, -10, X1 + 1, 20)
  for i = 0, 149 do
    local r = 0.2 + 0.3 * ((i * 7) % 5) / 4
    local p = w:particle(X0 + 2 + (i % 50) * 1.5, 8 + math.floor(i / 50) * 2, { radius = r, mass = r * r })
    w:set_material(p, 0.1 + 0.5 * ((i * 3) % 4) / 3, 0.8)
    balls[#balls + 1] = p
  end
  print(("terrain: %d balls on a %d-point polyline from x = %d to %d"):format(#balls, #pts / 2, X0, X1))
end

function tether.update(dt)
  w:step(dt)
  time = time + dt
  if time >= next_report - 1e-9 then
    print(("%5.1fs  %3d balls still moving, max error %.2e m"):format(time, moving(), w:stats().max_error))
    next_report = next_report + 2
  end
end

function tether.draw(g)
  g.fit(X0 - 2, -8, X1 + 2, 22)
  w:draw()
  g.hud(w)
end

function tether.unload()
  -- valleys: local minima of the ground; each ball counts for the nearest one
  local valleys, count = {}, {}
  for i = 1, 799 do
    local x = X0 + (X1 - X0) * i / 800
    local dx = (X1 - X0) / 800
    if ground(x) < ground(x - dx) and ground(x) <= ground(x + dx) then valleys[#valleys + 1] = x end
  end
  for k = 1, #valleys do count[k] = 0 end
  for _, p in ipairs(balls) do
    local x = w:position(p)
    local best, bk = math.huge, 1
    for k, v in ipairs(valleys) do
      if math.abs(x - v) < best then best, bk = math.abs(x - v), k end
    end
    count[bk] = count[bk] + 1
  end
  local row = {}
  for k, v in ipairs(valleys) do row[#row + 1] = ("x=%.1f:%d"):format(v, count[k]) end
  print("terrain: balls per valley  " .. table.concat(row, "  "))
  print(("terrain: %d still moving; hash %s"):format(moving(), w:hash()))
end

if not tether.quit then -- stock Lua: no runner, so run 10 s here
  tether.load()
  for _ = 1, 600 do tether.update(1 / 60) end
  tether.unload()
end
