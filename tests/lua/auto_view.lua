-- tests/lua/auto_view.lua — a script with no tether.draw still shows its worlds.
-- tests/run.sh runs it as PNG frames:
--   build/tether --headless --frames 2 --size 160x120 --out DIR tests/lua/auto_view.lua
-- and it reads its own first frame back: the pinned particle (red) and the
-- free ones (yellow) are on it. Prints "N passed, M failed".
package.path = "tests/lua/?.lua;" .. package.path
local T = require "harness"

local w = tether.world { gravity = { 0, 0 } }
w:particle(-2, 0, { radius = 0.3, pinned = true })
w:particle(2, 1, { radius = 0.3 })
local other = tether.world()
other:particle(0, -1, { radius = 0.3 })
local gone = tether.world()
gone:particle(50, 50)
gone:destroy() -- a destroyed world is skipped, and does not stretch the view

function tether.update(dt) w:step(dt) end

function tether.unload()
  T.test("the first frame shows every live world's particles", function()
    local img, msg = tether.gfx.load_image(tether.runner.out .. "/frame_00000.png")
    T.ok(img, tostring(msg))
    if not img then return end
    local W, H = img:size()
    local red, yellow = 0, 0
    for y = 0, H - 1 do
      for x = 0, W - 1 do
        local r, g, b = img:pixel(x, y)
        if r > 0.85 and g < 0.35 and b < 0.35 then red = red + 1 end
        if r > 0.85 and g > 0.7 and b < 0.45 then yellow = yellow + 1 end
      end
    end
    T.ok(red > 10, "the pinned particle is drawn (red pixels: " .. red .. ")")
    T.ok(yellow > 20, "the free particles of both worlds are drawn (yellow pixels: " .. yellow .. ")")
  end)
  local p, f = T.counts()
  print(("%d passed, %d failed"):format(p, f))
  if f > 0 then error("auto_view: failures") end
end
