-- tests/lua/test_mask.lua — pixel masks from Lua: making them (sizes,
-- strings, shapes, images, PNG files), pixels, the overlap family against a
-- per-pixel reference, outlines and chains in a world (image rows go down,
-- world y up), and bad input raising errors that name the function and the
-- argument, with nothing made.
package.path = "tests/lua/?.lua;" .. package.path
local T = require "harness"
local tether = require "tether"
local M = tether.mask

T.test("masks from strings round trip, pixels read and written", function()
  local m = M.from_string("#..\n.##\n...\n")
  T.eq(select(1, m:size()), 3, "width"); T.eq(select(2, m:size()), 3, "height")
  T.eq(m:count(), 3, "count")
  T.eq(m:get(0, 0), true, "top-left set"); T.eq(m:get(0, 1), false, "below it clear")
  T.eq(m:to_string(), "#..\n.##\n...", "round trip")
  m:set(2, 2); m:set(0, 0, false)
  T.eq(m:to_string(), "...\n.##\n..#", "set and clear")
  local x, y, w, h = m:bounding_rect()
  T.ok(x == 1 and y == 1 and w == 2 and h == 2, "bounding rect")
  local cx, cy = m:centroid()
  T.near(cx, 5 / 3, 1e-12, "centroid x"); T.near(cy, 4 / 3, 1e-12, "centroid y")
  local c = m:copy(); m:invert()
  T.eq(m:count(), 6, "inverted"); T.eq(c:count(), 3, "the copy kept")
  m:fill(); T.eq(m:count(), 9, "filled"); m:clear(); T.eq(m:count(), 0, "cleared")
  T.ok(tostring(c):match("^tether%.mask %(3x3%)"), "tostring")
end)

T.test("shapes, transforms, components", function()
  local d = M.circle(20)
  T.near(d:count(), math.pi * 400, math.pi * 400 * 0.01, "disc area")
  local r = M.rect(10, 4)
  T.eq(r:count(), 40, "rect")
  local t = M.polygon({ 0, 0, 10, 0, 0, 10 })
  T.near(t:count(), 50, 6, "triangle")
  local rr = r:rotated(math.pi / 2)
  T.eq(select(1, rr:size()), 4, "rotated width"); T.eq(rr:count(), 40, "rotated keeps pixels")
  T.eq(r:scaled(20, 8):count(), 160, "scaled")
  local m = M.new(20, 10)
  m:fill_rect(1, 1, 3, 3); m:fill_circle(15, 5, 2.5); m:fill_polygon({ 8, 8, 10, 8, 10, 10, 8, 10 })
  T.eq(m:components(), 3, "three components")
  T.eq(m:component(2, 2):count(), 9, "the one at a pixel")
  T.eq(m:component():count(), m:component(15, 5):count(), "the largest")
  local rects = m:component_rects()
  T.eq(#rects, 3, "rects"); T.eq(rects[1][1], 1, "first rect x"); T.eq(rects[1][3], 3, "first rect w")
  local o = m:outline()
  T.eq(#o, 16, "eight border pixels of the 3x3 block"); T.eq(o[1], 1, "starts at its top-left")
  local lines = m:polylines(0)
  T.eq(#lines, 3, "one loop per component")
end)

-- a per-pixel reference of the overlap family
local function ref(a, b, dx, dy)
  local aw, ah = a:size(); local bw, bh = b:size()
  local area, fx, fy = 0, nil, nil
  for y = 0, ah - 1 do
    for x = 0, aw - 1 do
      local bx, by = x - dx, y - dy
      if a:get(x, y) and bx >= 0 and by >= 0 and bx < bw and by < bh and b:get(bx, by) then
        area = area + 1
        if not fy then fx, fy = x, y end
      end
    end
  end
  return area, fx, fy
end

T.test("overlap family agrees with a per-pixel reference", function()
  local seed = 12345
  local function rnd(n) seed = (seed * 1103515245 + 12345) % 2147483648; return seed % n end
  for _ = 1, 60 do
    local a, b = M.new(1 + rnd(70), 1 + rnd(20)), M.new(1 + rnd(70), 1 + rnd(20))
    for _, m in ipairs({ a, b }) do
      local w, h = m:size()
      for _ = 1, T.idiv(w * h, 3) do m:set(rnd(w), rnd(h)) end
    end
    local dx, dy = rnd(150) - 75, rnd(40) - 20
    local area, fx, fy = ref(a, b, dx, dy)
    T.eq(a:overlap_area(b, dx, dy), area, "area")
    T.eq(a:overlap_mask(b, dx, dy):count(), area, "overlap mask count")
    local x, y = a:overlap(b, dx, dy)
    T.eq(x, fx, "first x"); T.eq(y, fy, "first y")
  end
  T.eq(M.rect(5, 5):overlap(M.rect(5, 5), 5, 0), nil, "touching edges do not overlap")
  local nx, ny = M.new(40, 40):overlap_normal(M.rect(4, 4), 0, 0)
  T.ok(nx == 0 and ny == 0, "no overlap, no normal")
  local floor = M.new(40, 40); floor:fill_rect(0, 20, 40, 20)
  nx, ny = floor:overlap_normal(M.rect(8, 8), 10, 15)
  T.near(nx, 0, 1e-12, "normal x"); T.near(ny, -1, 1e-12, "normal points up the image")
  local a = M.new(10, 10); a:draw(M.rect(3, 3), 8, 8)
  T.eq(a:count(), 4, "draw clips"); a:erase(M.rect(1, 1), 9, 9); T.eq(a:count(), 3, "erase")
  T.eq(select(1, M.rect(3, 3):convolve(M.rect(2, 2)):size()), 4, "convolve size")
end)

T.test("PNG files and images", function()
  local m = M.circle(9)
  local base = os.tmpname()
  local path = base .. ".png"
  os.remove(base)
  m:save(path)
  local back = M.load(path)
  os.remove(path)
  T.eq(back:to_string(), m:to_string(), "PNG round trip")
  local img = m:to_image(1, 0, 0)
  local w, h = img:size()
  T.ok(w == 18 and h == 18, "image of the mask's size")
  local r, g, b, a = img:pixel(9, 9); T.ok(r == 1 and g == 0 and a == 1, "set pixel coloured")
  r, g, b, a = img:pixel(0, 0); T.eq(a, 0, "clear pixel transparent")
  T.eq(M.from_image(img):count(), m:count(), "back from the image by alpha")
  T.eq(M.from_color(img, 1, 0, 0):count(), m:count(), "by colour")
  T.eq(M.from_color(img, 1, 0, 0, 0, true):count(), 18 * 18 - m:count(), "by colour key")
  m:paint(img, 0, 1, 0)
  r, g = img:pixel(9, 9); T.ok(r == 0 and g == 1, "repainted")
  local bad = io.open(path, "wb"); bad:write("\137PNG\r\n\26\n\0\0\0\13IHDR\0\0"); bad:close()
  T.checkerror("tether.mask.load: '" .. path .. "': Read Error", M.load, path)
  os.remove(path)
  T.checkerror("tether.mask.load: .*nonexistent", M.load, "/nonexistent/x.png")
  T.checkerror("bad argument #2 to 'tether.mask.load' (integer in [0, 254] expected, got 255)", M.load, "x.png", 255)
end)

T.test("outlines become chains in the world, y flipped", function()
  local w = tether.world()
  local slab = M.new(40, 30); slab:fill_rect(0, 10, 40, 20)
  local shapes = w:mask_chains(slab, { origin = { 0, 3 }, pixel = 0.1, tolerance = 0.5, friction = 0.2 })
  T.eq(#shapes, 1, "one loop"); T.eq(w:shape_type(shapes[1]), "chain", "a chain")
  local p = w:particle(2, 3, { radius = 0.1 })
  w:step(1 / 60, 180)
  local _, y = w:position(p)
  T.near(y, 2.1, 0.02, "resting on the slab's top (row 10 at y = 3 - 1)")
  T.checkerror("bad option 'pixel'", w.mask_chains, w, slab, { pixel = 0 })
  T.checkerror("unknown option 'pixels'", w.mask_chains, w, slab, { pixels = 1 })
  T.checkerror("bad argument #2 to 'mask_chains' (tether.mask expected, got table)", w.mask_chains, w, {})
  T.eq(w:shape_count(), 1, "failed calls made nothing")
end)

T.test("bad input raises errors naming the function and argument", function()
  T.checkerror("bad argument #1 to 'tether.mask.new' (integer in [1, 16384] expected, got 0)", M.new, 0, 5)
  T.checkerror("bad argument #2 to 'tether.mask.new' (integer in [1, 16384] expected, got -1)", M.new, 5, -1)
  T.checkerror("bad argument #1 to 'tether.mask.new' (integer in [1, 16384] expected, got 16385)", M.new, 16385, 1)
  T.checkerror("bad argument #1 to 'tether.mask.new' (integer in [1, 16384] expected, got nan)", M.new, 0 / 0, 1)
  T.checkerror("bad argument #1 to 'tether.mask.from_string' (row 2 has 1 pixels, row 1 has 2)", M.from_string, "##\n#")
  T.checkerror("bad argument #1 to 'tether.mask.from_string' (unexpected character 'a'", M.from_string, "#a")
  T.checkerror("bad argument #1 to 'tether.mask.from_string' (a mask of 0 x 1", M.from_string, "")
  local m = M.new(4, 4)
  T.checkerror("bad argument #2 to 'get' (integer in [0, 3] expected, got 4)", m.get, m, 4, 0)
  T.checkerror("bad argument #1 to 'get' (tether.mask expected, got number)", m.get, 5, 0, 0)
  T.checkerror("bad argument #3 to 'overlap' (integer in [-1000000000, 1000000000] expected, got 1.5)", m.overlap, m, m, 1.5, 0)
  T.checkerror("bad argument #2 to 'overlap_area' (tether.mask expected, got nil)", m.overlap_area, m, nil, 0, 0)
  T.checkerror("bad argument #4 to 'fill_circle' (finite number expected, got inf)", m.fill_circle, m, 1, 1, math.huge)
  T.checkerror("bad argument #2 to 'rotated' (finite number expected, got nan)", m.rotated, m, 0 / 0)
  T.checkerror("bad argument #2 to 'polylines' (number in [0, 1e+06] expected, got -1)", m.polylines, m, -1)
  T.checkerror("bad argument #2 to 'fill_polygon' (between 3 and 1000000 points expected, got 2)", m.fill_polygon, m, { 0, 0, 1, 1 })
  T.checkerror("bad argument #2 to 'paint' (image of 4x4 expected", m.paint, m, M.new(2, 2):to_image())
  T.checkerror("bad argument #2 to 'component' (integer in [0, 3] expected, got 9)", m.component, m, 9, 0)
  T.eq(m:count(), 0, "failed calls changed nothing")
end)

T.done()
