-- tests/love/main.lua — a tiny LÖVE game that requires tether (the LuaJIT
-- module, found through LUA_CPATH), steps tests/love/scene.lua in
-- love.update, draws it with love.graphics into a canvas, and after
-- scene.FRAMES frames checks the world and the picture, saves the picture
-- (love_test.png in the save directory) and quits with exit code 0 or 1.
-- Run by tests/love/run.sh under Xvfb; TETHER_LOVE_HASH is the hash the
-- same scene reaches under plain luajit.
local tether = require "tether"
local S = require "scene"

local s, frames, canvas = nil, 0, nil
local xy, lines = {}, {}
local passed, failed = 0, 0

local function check(ok, what)
  if ok then passed = passed + 1 else failed = failed + 1; print("love: FAIL " .. what) end
end

function love.load()
  s = S.build(tether)
  canvas = love.graphics.newCanvas(320, 240)
end

-- One fixed step per frame, whatever the frame's dt: the same world as elsewhere.
function love.update()
  if frames < S.FRAMES then
    S.step(s)
    frames = frames + 1
  end
end

local function draw_world()
  local w = s.world
  love.graphics.push()
  love.graphics.translate(200, 230) -- world x in [-10, 6], y in [-0.5, 11.5]
  love.graphics.scale(20, -20)
  love.graphics.setLineWidth(0.08)
  love.graphics.setColor(0.6, 0.6, 0.7)
  love.graphics.line(-10, 0, 10, 0)
  love.graphics.setColor(0.9, 0.8, 0.5)
  local _, n = w:constraint_lines(lines)
  for i = 0, n - 1 do love.graphics.line(lines[4 * i + 1], lines[4 * i + 2], lines[4 * i + 3], lines[4 * i + 4]) end
  love.graphics.setColor(0.4, 0.7, 1.0)
  for _, b in ipairs(s.balls) do
    local x, y = w:position(b)
    love.graphics.circle("fill", x, y, 0.2, 16)
  end
  love.graphics.pop()
end

local function finish()
  local err = S.check(s)
  check(err == nil, "the world after " .. S.FRAMES .. " frames: " .. tostring(err))
  local want = os.getenv("TETHER_LOVE_HASH")
  check(want ~= nil and s.world:hash() == want,
        ("hash %s, plain luajit %s"):format(s.world:hash(), tostring(want)))
  local img = canvas:newImageData()
  local lit = 0
  for y = 0, img:getHeight() - 1, 2 do
    for x = 0, img:getWidth() - 1, 2 do
      local r, g, b = img:getPixel(x, y)
      if r + g + b > 0.6 then lit = lit + 1 end
    end
  end
  -- the balls alone cover about 24 * pi * 4^2 / 4 = 300 sampled pixels
  check(lit > 300 and lit < 5000, "pixels drawn by love.graphics: " .. lit)
  img:encode("png", "love_test.png")
  print(("love: %d frames, %d particles, hash %s, %d lit pixels, %s"):format(frames, s.world:count(),
        s.world:hash(), lit, love.filesystem.getSaveDirectory() .. "/love_test.png"))
  print(("%d passed, %d failed"):format(passed, failed))
  love.event.quit(failed == 0 and 0 or 1)
end

function love.draw()
  canvas:renderTo(function()
    love.graphics.clear(0.1, 0.1, 0.13)
    draw_world()
  end)
  love.graphics.setColor(1, 1, 1)
  love.graphics.draw(canvas)
  if frames == S.FRAMES and not s.done then
    s.done = true
    finish()
  end
end
