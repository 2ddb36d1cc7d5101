-- tests/lua/test_render.lua — the drawing API (tether.gfx, world:draw).
-- Two runs (tests/run.sh does both):
--   build/tether tests/lua/test_render.lua
--       outside a frame: every drawing call raises "nothing to draw on"
--   build/tether --headless --frames 2 --size 200x150 --out DIR tests/lua/test_render.lua
--       inside tether.draw(g): camera, fit, conversions, argument errors
-- Pixels are checked by the C tests (tests/render/test_render.c), which read frames back.
package.path = "tests/lua/?.lua;" .. package.path
local T = require "harness"
local tether = require "tether"
local g = tether.gfx

local function outside_frame()
  T.test("gfx exists and lists its functions", function()
    for _, name in ipairs { "color", "clear", "circle", "line", "polygon", "text", "line_width", "layer",
      "camera", "fit", "size", "to_world", "to_screen", "hud", "new_image", "image", "load_image" } do
      T.eq(type(g[name]), "function", "tether.gfx." .. name)
    end
    T.eq(type(tether.world().draw), "function", "world:draw")
  end)

  T.test("drawing outside a frame raises, naming the function", function()
    T.checkerror_plain("tether.gfx.circle: nothing to draw on", g.circle, 0, 0, 1)
    T.checkerror_plain("tether.gfx.size: nothing to draw on", g.size)
    local w = tether.world()
    w:particle(0, 0)
    T.checkerror_plain("draw: nothing to draw on", w.draw, w)
  end)

  T.test("load_image and the image metamethods name themselves in errors", function()
    T.checkerror_plain("bad argument #1 to 'tether.gfx.load_image' (string expected, got table)", g.load_image, {})
    T.checkerror_plain("bad argument #1 to 'tether.gfx.load_image' (string expected, got no value)", g.load_image)
    local mt = getmetatable(g.new_image(1, 1))
    T.checkerror_plain("bad argument #1 to '__tostring' (tether.image expected, got number)", mt.__tostring, 42)
    T.checkerror_plain("bad argument #1 to '__close' (tether.image expected, got number)", mt.__close, 42)
    T.checkerror_plain("bad argument #1 to '__gc' (tether.image expected, got table)", mt.__gc, {})
  end)

  T.test("world:draw checks its world and options before it needs a canvas", function()
    local w = tether.world()
    T.checkerror_plain("unknown option 'partcles'", w.draw, w, { partcles = true })
    w:destroy()
    T.checkerror_plain("attempt to use a destroyed world", w.draw, w)
    T.checkerror("tether.world expected", tether.world().draw, 42)
  end)
end

local function inside_frame()
  local w = tether.world { gravity = { 0, 0 } }
  local a = w:particle(-1, 0, { radius = 0.2 })
  local b = w:particle(1, 0, { radius = 0.2, pinned = true })
  w:spring(a, b)
  local frames = 0

  function tether.draw(gg)
    frames = frames + 1
    if frames > 1 then -- the same checks once are enough; the second frame checks state persists
      local x, y, z = gg.camera()
      T.test("the camera persists between frames", function()
        T.eq(x, 1, "x"); T.eq(y, 2, "y"); T.eq(z, 10, "zoom")
      end)
      T.test("load_image reads the PNG of the first frame", function()
        local img, msg = gg.load_image(tether.runner.out .. "/frame_00000.png")
        T.ok(img, "loaded: " .. tostring(msg))
        if not img then return end
        local W, H = img:size()
        T.eq(W, 200, "width"); T.eq(H, 150, "height")
        local r, g2, b, a = img:pixel(0, 0) -- frame 1 ended with g.clear(0, 0, 0): opaque black
        T.eq(r + g2 + b, 0, "black"); T.eq(a, 1, "opaque")
        T.noerror(gg.image, img, -1, -1, 1, 1)
        local none, why = gg.load_image("no/such/file.png")
        T.eq(none, nil, "missing file: nil")
        T.ok(type(why) == "string" and why:find("no/such/file.png", 1, true), "message names the file: " .. tostring(why))
      end)
      T.test("an image closed right after it was drawn is in the frame", function()
        local img = gg.load_image(tether.runner.out .. "/frame_00000.png")
        if not T.ok(img, "frame 1 loaded") then return end
        local r, g2, b, a = img:pixel(189, 139) -- inside the square drawn with the closed image
        T.eq(r, 1, "red"); T.eq(g2 + b, 0, "red only"); T.eq(a, 1, "opaque")
      end)
      return
    end
    T.test("gfx is the argument of tether.draw", function() T.eq(gg, g, "g") end)

    T.test("world:draw{alpha=} draws between the last two steps; alpha is checked", function()
      local m = tether.world { gravity = { 0, 0 } }
      m:particle(0, 0, { vx = 1 })
      m:step(1 / 60)
      T.eq(m:interpolation(), false, "off until asked")
      T.noerror(m.draw, m) -- alpha 1 (the runner's headless frames): nothing kept
      T.eq(m:interpolation(), false, "alpha 1 needs nothing kept")
      T.noerror(m.draw, m, { alpha = 0.5 })
      T.eq(m:interpolation(), true, "alpha < 1 keeps the previous positions from now on")
      T.noerror(m.draw, m, { alpha = 0 })
      for _, bad in ipairs { 0 / 0, -0.01, 1.5, math.huge } do
        T.checkerror("bad option 'alpha'", m.draw, m, { alpha = bad })
      end
      T.checkerror("bad option 'alpha'", m.draw, m, { alpha = "half" })
      m:set_interpolation(false)
      T.eq(m:interpolation(), false, "off again")
      T.checkerror("bad argument #2 to 'set_interpolation' (boolean expected", m.set_interpolation, m, 1)
    end)

    T.test("size is --size", function()
      local W, H = gg.size()
      T.eq(W, 200, "width"); T.eq(H, 150, "height")
    end)

    T.test("camera and conversions (known answers)", function()
      gg.camera(1, 2, 10)
      local x, y, z = gg.camera()
      T.eq(x, 1, "x"); T.eq(y, 2, "y"); T.eq(z, 10, "zoom")
      local px, py = gg.to_screen(1, 2)
      T.eq(px, 100, "centre x"); T.eq(py, 75, "centre y")
      px, py = gg.to_screen(2, 3) -- 1 m right and up: 10 px right, 10 px up
      T.eq(px, 110, "x"); T.eq(py, 65, "y")
      local wx, wy = gg.to_world(110, 65)
      T.near(wx, 2, 1e-12, "back x"); T.near(wy, 3, 1e-12, "back y")
    end)

    T.test("fit frames a rectangle", function()
      gg.fit(-5, 0, 5, 2, 10) -- zoom = min(180/10, 130/2) = 18
      local x, y, z = gg.camera()
      T.near(z, 18, 1e-12, "zoom"); T.eq(x, 0, "x"); T.eq(y, 1, "y")
      T.checkerror_plain("the rectangle is empty", gg.fit, 1, 0, 0, 1)
      gg.camera(1, 2, 10)
    end)

    T.test("every primitive draws", function()
      T.noerror(gg.color, 1, 0.5, 0, 0.5)
      local r, gr, bl, al = gg.color()
      T.near(r, 1, 0, "r"); T.near(gr, 128 / 255, 1e-12, "g"); T.near(bl, 0, 0, "b"); T.near(al, 128 / 255, 1e-12, "a")
      T.noerror(gg.circle, 0, 0, 1)
      T.noerror(gg.circle, 0, 0, 1, "line")
      T.noerror(gg.line, 0, 0, 1, 1, 2, 0)
      T.noerror(gg.polygon, { 0, 0, 1, 0, 1, 1, 0.5, 0.2 })
      T.noerror(gg.polygon, { 0, 0, 1, 0, 1, 1 }, "line")
      T.noerror(gg.line_width, 3)
      T.noerror(gg.layer, "screen")
      T.noerror(gg.text, 4, 4, "HUD text 123", 2)
      T.noerror(gg.layer, "world")
      T.noerror(w.draw, w)
      T.noerror(w.draw, w, { particles = true, springs = false, color = { 1, 1, 1 }, pinned = { 1, 0, 0, 0.5 }, min_radius = 3 })
      T.noerror(gg.hud, w)
      T.noerror(gg.hud, w, "one more line")
      T.noerror(gg.clear, 0, 0, 0)
    end)

    T.test("images: make, write, read, draw", function()
      local img = gg.new_image(3, 2)
      T.eq(getmetatable(img).__name, "tether.image", "class")
      local W, H = img:size()
      T.eq(W, 3, "width"); T.eq(H, 2, "height")
      T.eq(select(4, img:pixel(2, 1)), 0, "starts transparent")
      img:fill(0, 0, 1)
      img:set_pixel(2, 1, 1, 0, 0, 0.5)
      local r, g2, b, a = img:pixel(2, 1)
      T.eq(r, 1, "r"); T.eq(g2, 0, "g"); T.eq(b, 0, "b"); T.near(a, 128 / 255, 1e-12, "a")
      T.eq(select(3, img:pixel(0, 0)), 1, "filled blue")
      T.ok(tostring(img):find("tether.image (3x2)", 1, true), "tostring")
      T.noerror(gg.image, img, 0, 0, 3, 2)
      T.noerror(gg.image, gg.new_image(1, 1), 0, 0, 1, 1) -- a temporary: kept alive until the frame is drawn
      collectgarbage()
      T.checkerror_plain("bad argument #2 to 'set_pixel'", img.set_pixel, img, 3, 0, 1, 1, 1)
      T.checkerror_plain("bad argument #4 to 'set_pixel'", img.set_pixel, img, 0, 0, 2, 1, 1)
      T.checkerror_plain("bad argument #1 to 'tether.gfx.new_image'", gg.new_image, 0, 1)
      T.checkerror("tether.image expected", gg.image, {}, 0, 0, 1, 1)
      local closed = gg.new_image(1, 1)
      getmetatable(closed).__close(closed)
      T.checkerror_plain("attempt to use a closed image", closed.size, closed)
    end)

    T.test("an image closed after it was drawn lives until the frame is rendered", function()
      local drawn
      do
        local img <close> = gg.new_image(8, 8)
        img:fill(1, 0, 0)
        gg.color(1, 1, 1) -- no tint
        gg.layer("screen")
        gg.image(img, 182, 132, 196, 146) -- the bottom-right corner: checked in frame 2
        gg.layer("world")
        drawn = img
      end -- closed here, before the frame is rendered
      collectgarbage()
      T.checkerror_plain("attempt to use a closed image", drawn.size, drawn)
      T.checkerror_plain("attempt to use a closed image", gg.image, drawn, 0, 0, 1, 1)
      T.ok(tostring(drawn):find("(closed)", 1, true), "tostring: " .. tostring(drawn))
      getmetatable(drawn).__close(drawn) -- closing again is harmless
    end)

    T.test("bad arguments name the function and the argument", function()
      T.checkerror_plain("bad argument #1 to 'tether.gfx.circle'", gg.circle, 0 / 0, 0, 1)
      T.checkerror_plain("bad argument #3 to 'tether.gfx.circle'", gg.circle, 0, 0, -1)
      T.checkerror_plain("invalid mode 'dotted', expected one of: 'fill', 'line'", gg.circle, 0, 0, 1, "dotted")
      T.checkerror_plain("bad argument #1 to 'tether.gfx.color'", gg.color, 2, 0, 0)
      T.checkerror_plain("tether.gfx.line: need an even number (at least 4) of coordinates, got 3", gg.line, 1, 2, 3)
      T.checkerror_plain("bad argument #1 to 'tether.gfx.polygon'", gg.polygon, { 0, 0, 1, 0 })
      T.checkerror_plain("at index 3", gg.polygon, { 0, 0, math.huge, 0, 1, 1 })
      T.checkerror_plain("bad argument #4 to 'tether.gfx.text'", gg.text, 0, 0, "x", 0)
      T.checkerror_plain("invalid layer 'hud', expected one of: 'world', 'screen'", gg.layer, "hud")
      T.checkerror_plain("bad argument #3 to 'tether.gfx.camera'", gg.camera, 0, 0, 0)
      T.checkerror_plain("bad option 'color'", w.draw, w, { color = { 1, 2, 3 } })
      T.checkerror_plain("bad argument #1 to 'tether.gfx.line_width'", gg.line_width, 0)
      T.checkerror("tether.world expected", gg.hud, {})
      T.checkerror_plain("bad argument #1 to 'tether.gfx.polygon' (table of coordinates {x1, y1, x2, y2, ...} expected, got number)",
        gg.polygon, 42)
      T.checkerror_plain("bad argument #1 to 'tether.gfx.polygon' (table of coordinates {x1, y1, x2, y2, ...} expected, got no value)",
        gg.polygon)
      T.checkerror_plain("bad argument #3 to 'tether.gfx.text' (string expected, got table)", gg.text, 0, 0, {})
      T.checkerror_plain("bad argument #3 to 'tether.gfx.text' (string expected, got no value)", gg.text, 0, 0)
      T.noerror(gg.text, 0, 0, 42) -- a number is text
      T.checkerror_plain("bad argument #2 to 'tether.gfx.hud' (string or nil expected, got table)", gg.hud, w, {})
    end)

    T.test("Lua code that destroys the world in the middle of draw or hud", function()
      -- world:draw: an option table whose __index destroys the world
      local w2 = tether.world()
      w2:particle(0, 0)
      local calls = 0
      local opts = setmetatable({}, { __index = function() calls = calls + 1; w2:destroy() end })
      T.noerror(w2.draw, w2, opts)
      T.ok(calls > 0, "the __index ran")
      T.checkerror_plain("attempt to use a destroyed world", w2.count, w2)
      -- g.hud: turning the number 7 into text allocates, which lets the
      -- collector run a finalizer that destroys the world
      local w3 = tether.world()
      local fired = false
      collectgarbage("incremental", 1, 1000) -- pause 1 %: every allocation check collects
      collectgarbage("collect")
      setmetatable({}, { __gc = function() fired = true; w3:destroy() end })
      local ok, err = pcall(gg.hud, w3, 7)
      collectgarbage("incremental", 200, 100)
      T.ok(ok, tostring(err))
      T.ok(fired, "the finalizer ran inside hud")
      T.checkerror_plain("attempt to use a destroyed world", w3.count, w3)
    end)
  end

  function tether.update(dt) w:step(dt) end

  function tether.unload()
    T.test("draw was called once per frame", function() T.eq(frames, tether.runner.frames, "frames") end)
    local p, f = T.counts()
    print(("%d passed, %d failed"):format(p, f))
    if f > 0 then error("test_render: failures") end
  end
end

if tether.runner and tether.runner.mode == "frames" then
  inside_frame()
else
  outside_frame()
  T.done()
end
