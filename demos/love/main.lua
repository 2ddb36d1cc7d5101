-- demos/love/main.lua — tether inside LÖVE: a fountain of grains over pegs,
-- a cloth hanging by its top corners and a rope from a pin, all in one
-- tether world, drawn with love.graphics. Drag anything with the mouse;
-- R resets, Esc quits. Run (after `make luajit`, from the repository root):
--
--   LUA_CPATH="$PWD/build/luajit/?.so" love demos/love
--
-- or, with tether installed, just `love demos/love`. Extra arguments
-- `--frames N --shot F.png` run N frames, save the last into LÖVE's save
-- directory as F.png and quit (how docs/img/love.png is made).
local tether = require "tether"

local VIEW = { x0 = -9.6, y0 = -0.5, scale = 50 } -- world x in [-9.6, 9.6], y in [-0.5, 11.5]
local DT = 1 / 60
local MAX_GRAINS = 700

local world, grains, next_grain, cloth, rope, drag, steps, ms
local frames_wanted, shot, quit_after
local xy, lines = {}, {}

local function to_world(sx, sy)
  return sx / VIEW.scale + VIEW.x0, (love.graphics.getHeight() - sy) / VIEW.scale + VIEW.y0
end

local function reset()
  if world then world:destroy() end
  world = tether.world { substeps = 4, iterations = 6 }
  world:set_collision { restitution = 0.1 }
  world:segment(-9.5, 0, 9.5, 0)
  world:segment(-9.5, 0, -9.5, 11)
  world:segment(9.5, 0, 9.5, 11)
  for i = 0, 6 do world:circle(-6 + 2 * i + (i % 2) * 0.5, 4 + (i % 2) * 1.2, 0.3) end
  cloth = world:cloth { origin = { 2.5, 10.5 }, width = 5, height = 3.5, columns = 18, rows = 13, mass = 0.02,
                        shear_stiffness = 0, bend_stiffness = 0.02, radius = 0.1, collide = false }
  rope = world:rope { start = { -8, 10.5 }, finish = { -3, 10.5 }, segments = 24, mass = 0.05, radius = 0.1 }
  grains, next_grain, drag, steps, ms = {}, 1, nil, 0, 0
end

function love.load(args)
  for i = 1, #args - 1 do
    if args[i] == "--frames" then frames_wanted = tonumber(args[i + 1]) end
    if args[i] == "--shot" then shot = args[i + 1] end
  end
  love.graphics.setBackgroundColor(0.09, 0.1, 0.13)
  reset()
end

-- A grain from the spout every other step, up to MAX_GRAINS: then the oldest goes.
local function pour()
  if steps % 2 ~= 0 then return end
  if grains[next_grain] then world:remove(grains[next_grain]) end
  local t = steps * DT
  grains[next_grain] = world:particle(1 + 5 * math.sin(t * 0.5), 11.2,
                                      { radius = 0.08, mass = 0.01, vx = 2 * math.cos(t * 1.3), vy = -1 })
  next_grain = next_grain % MAX_GRAINS + 1
end

function love.update()
  pour()
  if drag then world:set_constraint(drag, { anchor = { to_world(love.mouse.getPosition()) } }) end
  local t0 = love.timer.getTime()
  world:step(DT) -- a fixed step: the same world at any frame rate
  ms = 0.9 * ms + 0.1 * (love.timer.getTime() - t0) * 1000
  steps = steps + 1
end

function love.mousepressed(x, y)
  local wx, wy = to_world(x, y)
  local found = world:query_aabb(wx - 0.3, wy - 0.3, wx + 0.3, wy + 0.3)
  if #found > 0 then drag = world:pin(found[1], { anchor = { wx, wy } }) end
end

function love.mousereleased()
  if drag then world:remove_constraint(drag); drag = nil end
end

function love.keypressed(key)
  if key == "escape" then love.event.quit() elseif key == "r" then reset() end
end

function love.draw()
  love.graphics.push()
  love.graphics.translate(-VIEW.x0 * VIEW.scale, love.graphics.getHeight() + VIEW.y0 * VIEW.scale)
  love.graphics.scale(VIEW.scale, -VIEW.scale)
  love.graphics.setLineWidth(2 / VIEW.scale)
  love.graphics.setColor(0.55, 0.58, 0.66)
  love.graphics.line(-9.5, 11, -9.5, 0, 9.5, 0, 9.5, 11)
  for i = 0, 6 do love.graphics.circle("fill", -6 + 2 * i + (i % 2) * 0.5, 4 + (i % 2) * 1.2, 0.3, 24) end
  local _, n = world:constraint_lines(lines)
  for i = 0, n - 1 do
    local k = 4 * i
    if drag and i == n - 1 then love.graphics.setColor(1, 0.4, 0.3) else love.graphics.setColor(0.95, 0.8, 0.45) end
    love.graphics.line(lines[k + 1], lines[k + 2], lines[k + 3], lines[k + 4])
  end
  love.graphics.setColor(0.45, 0.75, 1)
  for _, g in pairs(grains) do
    local x, y = world:position(g)
    love.graphics.circle("fill", x, y, 0.08, 8)
  end
  love.graphics.pop()
  love.graphics.setColor(1, 1, 1)
  love.graphics.print(("%d particles   %.2f ms/step   %d fps   drag with the mouse, R resets"):format(
    world:count(), ms, love.timer.getFPS()), 10, 10)
  if frames_wanted and steps >= frames_wanted then
    if shot then love.graphics.captureScreenshot(shot) end
    frames_wanted = nil
    quit_after = 2 -- the screenshot is written at the end of this frame
  elseif quit_after then
    quit_after = quit_after - 1
    if quit_after == 0 then
      print(("love demo: %d steps, %d particles, hash %s"):format(steps, world:count(), world:hash()))
      love.event.quit(0)
    end
  end
end
