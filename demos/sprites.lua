-- demos/sprites.lua — pixel-perfect sprite hits, and an image outline that
-- particles bounce on.
--
--   build/tether --headless --steps 300 demos/sprites.lua
--   LUA_CPATH='build/?.so' lua5.4 demos/sprites.lua   (stock Lua: 5 s simulated)
--
-- The demo draws its sprites as masks, writes them to PNG files and loads
-- them back (as a game loads its art): a turning propeller, a ring that
-- slides across it and a star that bobs over it. Each frame the masks are
-- tested pixel by pixel (m:overlap_mask at the integer offset between the
-- sprites): while two touch they are drawn orange and the pixels they share
-- red. Below them a hilly island with a cave, also a PNG, becomes chain
-- shapes (w:mask_chains: marching squares, simplified to half a pixel) that
-- a stream of particles falls and bounces on.
--
-- Mask pixel (0, 0) is an image's top-left and its rows go down; the world's
-- y goes up. Sprites live on a grid of PIXEL metres whose pixel (0, 0) is at
-- the world's (X0, Y0): pixel (px, py) is world (X0 + px·PIXEL, Y0 − py·PIXEL).
local tether = require "tether"
local M = tether.mask

local PIXEL, X0, Y0 = 0.05, -8, 9
local w, island, sprites, time, hits, emitted = nil, nil, {}, 0, 0, 0

-- Writes a mask to a PNG file and reads it back: the sprites come from image files.
local function via_png(m)
  local base = os.tmpname() -- made empty by tmpname: the PNG goes beside it
  local path = base .. ".png"
  m:save(path)
  local back = M.load(path)
  os.remove(path)
  os.remove(base)
  return back
end

local function propeller()
  local m = M.new(90, 90)
  m:fill_circle(45, 45, 9)
  m:fill_polygon({ 40, 45, 50, 45, 50, 2, 40, 8 })
  m:fill_polygon({ 45, 40, 45, 50, 88, 50, 82, 40 })
  m:fill_polygon({ 40, 45, 50, 45, 50, 82, 40, 88 })
  m:fill_polygon({ 45, 40, 45, 50, 2, 50, 8, 40 })
  return m
end

local function ring()
  local m = M.circle(22)
  m:fill_circle(22, 22, 13, false)
  return m
end

local function star()
  local pts = {}
  for i = 0, 9 do
    local a, r = math.pi / 2 + i * math.pi / 5, (i % 2 == 0) and 24 or 10
    pts[#pts + 1] = 25 + r * math.cos(a); pts[#pts + 1] = 25 - r * math.sin(a)
  end
  return M.polygon(pts)
end

-- The island: hills along the top, a cave under the left hill, 320 x 90 pixels.
local function island_mask()
  local m = M.new(320, 90)
  local top = {}
  for x = 0, 320, 8 do
    top[#top + 1] = x; top[#top + 1] = 45 - 18 * math.sin(x / 320 * 2 * math.pi) - 8 * math.sin(x / 40)
  end
  top[#top + 1] = 320; top[#top + 1] = 90; top[#top + 1] = 0; top[#top + 1] = 90
  m:fill_polygon(top)
  m:fill_circle(100, 58, 14, false) -- the cave
  return m
end

-- A sprite: its mask turned as it is now, and the pixel position of its centre.
local function sprite(name, mask)
  sprites[#sprites + 1] = { name = name, base = mask, mask = mask, cx = 0, cy = 0, touching = false }
  return sprites[#sprites]
end

local function move(t)
  local p, r, s = sprites[1], sprites[2], sprites[3]
  p.cx, p.cy, p.mask = 160, 60, p.base:rotated(t * 1.3)
  r.cx, r.cy = 160 + 110 * math.sin(t * 0.9), 60 + 8 * math.sin(t * 2.1)
  s.cx, s.cy = 160 + 30 * math.sin(t * 0.5 + 1), 60 - 60 * math.cos(t * 1.1) + 10
end

-- Top-left pixel of a sprite's current mask.
local function corner(sp)
  local mw, mh = sp.mask:size()
  return math.floor(sp.cx - mw / 2), math.floor(sp.cy - mh / 2)
end

local function test_hits()
  for _, sp in ipairs(sprites) do sp.touching, sp.shared = false, nil end
  for i = 1, #sprites do
    for j = i + 1, #sprites do
      local a, b = sprites[i], sprites[j]
      local ax, ay = corner(a)
      local bx, by = corner(b)
      if a.mask:overlap(b.mask, bx - ax, by - ay) then
        a.touching, b.touching = true, true
        a.shared = a.shared or M.new(a.mask:size())
        a.shared:draw(a.mask:overlap_mask(b.mask, bx - ax, by - ay), 0, 0)
        hits = hits + 1
      end
    end
  end
end

function tether.load()
  w = tether.world { substeps = 4, iterations = 4 }
  w:set_collision { restitution = 0.4, friction = 0.3 }
  sprite("propeller", via_png(propeller()))
  sprite("ring", via_png(ring()))
  sprite("star", via_png(star()))
  island = via_png(island_mask())
  local chains = w:mask_chains(island, { origin = { X0, Y0 - 120 * PIXEL }, pixel = PIXEL, tolerance = 0.5,
                                         restitution = 0.5, friction = 0.2 })
  print(("sprites: %d sprites from PNG files; the island's outline is %d chain shapes"):format(#sprites, #chains))
  move(0)
end

function tether.update(dt)
  time = time + dt
  move(time)
  test_hits()
  if w:count() < 400 and math.floor(time * 30) > emitted then -- a stream of drops over the island
    emitted = emitted + 1
    local x = X0 + 1 + (emitted * 37 % 140) / 10
    w:particle(x, Y0 + 0.5, { radius = 0.06 + 0.04 * (emitted % 3), vx = 0.3 * math.sin(emitted) })
  end
  w:step(dt)
  for _, p in ipairs(w:particles()) do -- drops that fell off the island go
    local _, y = w:position(p)
    if y < -2 then w:remove(p) end
  end
end

-- A mask drawn with its pixel (px, py) top-left on the sprite grid.
local function draw_mask(g, m, px, py)
  local mw, mh = m:size()
  g.mask(m, X0 + px * PIXEL, Y0 - (py + mh) * PIXEL, X0 + (px + mw) * PIXEL, Y0 - py * PIXEL)
end

function tether.draw(g)
  g.fit(X0 - 0.5, -1.5, X0 + 16.5, Y0 + 1)
  g.color(0.35, 0.55, 0.35)
  draw_mask(g, island, 0, 120)
  w:draw { shapes = true, color = { 0.55, 0.75, 1.0 } }
  for _, sp in ipairs(sprites) do
    if sp.touching then g.color(1.0, 0.6, 0.15) else g.color(0.8, 0.85, 0.95) end
    draw_mask(g, sp.mask, corner(sp))
  end
  g.color(1, 0.1, 0.1) -- the shared pixels over every sprite
  for _, sp in ipairs(sprites) do
    if sp.shared then draw_mask(g, sp.shared, corner(sp)) end
  end
  g.color(1, 1, 1)
  g.hud(w, ("pixel hits %d frames   drops %d"):format(hits, w:count()))
end

function tether.unload()
  print(("sprites: %d hit tests touched over %.1f s; %d drops on the island; hash %s"):format(hits, time, w:count(),
    w:hash()))
end

if not tether.quit then -- stock Lua: no runner, so run 5 s here
  tether.load()
  for _ = 1, 300 do tether.update(1 / 60) end
  tether.unload()
end
