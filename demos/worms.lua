-- demos/worms.lua — destructible pixel terrain: shells carve craters, debris
-- bounces on the new ground, a rope bridge spans a chasm, a ragdoll tumbles.
--
--   build/tether --headless --steps 600 demos/worms.lua
--   LUA_CPATH='build/?.so' lua5.4 demos/worms.lua   (stock Lua: 10 s simulated)
--
-- The ground is a 640 x 320 pixel mask the demo draws, writes to a PNG file
-- and loads back (as a game loads its level), placed as a terrain of 5 cm
-- pixels: particles collide with its pixels inside the solver. Two worms
-- (sprites, masks) take turns firing shells; a shell that meets the ground
-- carves a crater (w:carve: the cost is the crater's, not the level's),
-- throws debris particles and pushes what is near. A shell that passes over
-- the other worm is tested against its mask pixel by pixel (m:overlap):
-- a hit explodes there. Every second it prints the craters, the debris and
-- the hits; at the end the state hash.
local tether = require "tether"
local M = tether.mask

local PIXEL, W, H = 0.05, 640, 320
local X0, Y0 = -16, 8 -- the terrain's top-left corner: pixel (px, py) is world (X0 + px·PIXEL, Y0 − py·PIXEL)
local w, ground, view, worms, shells = nil, nil, nil, {}, {}
local time, turn, next_shot, craters, hits, debris = 0, 0, 0.4, 0, 0, 0
local seed = 12345
local function rand() seed = (seed * 48271) % 2147483647; return seed / 2147483647 end

-- Height of the ground's surface (pixel row) at pixel column x: hills, a chasm in the middle.
local function surface(x)
  return 170 - 40 * math.sin(x / W * math.pi * 2 + 0.6) - 12 * math.sin(x / 23)
end

local function level()
  local m = M.new(W, H)
  local top = {}
  for x = 0, W, 8 do top[#top + 1] = x; top[#top + 1] = surface(x) end
  top[#top + 1] = W; top[#top + 1] = H; top[#top + 1] = 0; top[#top + 1] = H
  m:fill_polygon(top)
  m:fill_rect(280, 0, 80, 290, false) -- the chasm
  m:fill_circle(150, 230, 22, false)   -- a cave
  return m
end

local function via_png(m)
  local base = os.tmpname()
  local path = base .. ".png"
  m:save(path)
  local back = M.load(path)
  os.remove(path)
  os.remove(base)
  return back
end

local function world_of(px, py) return X0 + px * PIXEL, Y0 - py * PIXEL end

-- A worm: an upright capsule of pixels standing on the ground at column px.
local function worm(px)
  local m = M.new(16, 24)
  m:fill_circle(8, 8, 7); m:fill_rect(1, 8, 14, 10); m:fill_circle(8, 17, 7)
  return { mask = m, px = px - 8, py = math.floor(surface(px)) - 24 }
end

-- A worm stands on the ground: down until its bottom row's middle is solid.
local function settle(wm)
  while wm.py < H - 24 do
    local x, y = world_of(wm.px + 8, wm.py + 24.5)
    if w:terrain_solid(ground, x, y) then break end
    wm.py = wm.py + 1
  end
end

local function fire()
  local from, to = worms[turn % 2 + 1], worms[(turn + 1) % 2 + 1]
  turn = turn + 1
  local x, y = world_of(from.px + 8, from.py - 2)
  local tx = world_of(to.px + 8, 0)
  local dist = tx - x
  local vy = 7 + rand() * 3
  local vx = dist / (2 * vy / 9.81) * (0.75 + 0.35 * rand()) -- short, long or on target
  local p = w:particle(x, y, { radius = 0.08, vx = vx, vy = vy, mass = 0.5 })
  w:set_bullet(p, true)
  shells[#shells + 1] = { p = p, target = to }
end

local function explode(x, y)
  w:carve(ground, x, y, 1.1)
  w:explode(x, y, 3.0, 4.0)
  for k = 1, 16 do
    local a = k / 16 * 2 * math.pi
    w:particle(x + 0.3 * math.cos(a), y + 0.3 * math.sin(a) + 0.3,
      { radius = 0.06 + 0.04 * rand(), vx = 5 * math.cos(a), vy = 5 * math.abs(math.sin(a)) + 2, mass = 0.2 })
  end
  craters, debris = craters + 1, debris + 16
  w:terrain_mask(ground, view) -- the picture follows the pixels
  for _, wm in ipairs(worms) do settle(wm) end
end

-- Shells: a pixel-perfect test against the target worm, then the ground.
local function fly()
  local shell_mask = M.circle(2)
  for i = #shells, 1, -1 do
    local s = shells[i]
    local x, y = w:position(s.p)
    local px, py = math.floor((x - X0) / PIXEL), math.floor((Y0 - y) / PIXEL)
    local hit = s.target.mask:overlap(shell_mask, px - 2 - s.target.px, py - 2 - s.target.py)
    if hit then
      hits = hits + 1
      s.target.flash = 0.5
    end
    local d = w:terrain_distance(ground, x, y)
    if hit or d < 0.12 or y < Y0 - H * PIXEL then
      if y > Y0 - H * PIXEL then explode(x, y) end
      w:remove(s.p)
      table.remove(shells, i)
    end
  end
end

function tether.load()
  w = tether.world { substeps = 4, iterations = 6 }
  w:set_collision { restitution = 0.3, friction = 0.5 }
  local m = via_png(level())
  ground = w:terrain(m, { origin = { X0, Y0 }, pixel = PIXEL, friction = 0.7, restitution = 0.2 })
  view = w:terrain_mask(ground)
  worms = { worm(120), worm(540) }
  -- the rope bridge over the chasm, pinned at both edges, a little slack
  local lx, ly = world_of(278, surface(278))
  local rx, ry = world_of(362, surface(362))
  w:rope { start = { lx, ly }, finish = { rx, ry }, segments = 24, pin_start = true, pin_finish = true,
           slack = true, radius = 0.08, mass = 0.3 }
  -- a ragdoll dropped on the left hill, and a few rocks
  local gx, gy = world_of(200, surface(200))
  w:ragdoll { position = { gx, gy + 2.5 }, height = 1.2, mass = 2, radius = 0.06 }
  for k = 1, 12 do
    local x = world_of(380 + 12 * k, 0)
    w:particle(x, 7, { radius = 0.12 + 0.08 * rand(), mass = 1 })
  end
  print(("worms: a %dx%d pixel terrain (%.0f x %.0f m) from a PNG, %d particles"):format(W, H, W * PIXEL,
    H * PIXEL, w:count()))
end

local next_report = 1
function tether.update(dt)
  time = time + dt
  if time >= next_shot then fire(); next_shot = next_shot + 0.7 end
  w:step(dt)
  fly()
  for _, wm in ipairs(worms) do if wm.flash then wm.flash = wm.flash > dt and wm.flash - dt or nil end end
  for _, p in ipairs(w:particles()) do -- what fell off the level goes
    local _, y = w:position(p)
    if y < Y0 - H * PIXEL - 2 then w:remove(p) end
  end
  if time >= next_report - 1e-9 then
    print(("%4.1fs  craters %d  debris %d  shell hits %d  particles %d"):format(time, craters, debris, hits, w:count()))
    next_report = next_report + 1
  end
end

local function draw_mask(g, m, px, py)
  local mw, mh = m:size()
  g.mask(m, X0 + px * PIXEL, Y0 - (py + mh) * PIXEL, X0 + (px + mw) * PIXEL, Y0 - py * PIXEL)
end

function tether.draw(g)
  g.fit(X0 - 0.5, Y0 - H * PIXEL - 0.5, X0 + W * PIXEL + 0.5, Y0 + 0.5)
  g.color(0.45, 0.33, 0.2)
  draw_mask(g, view, 0, 0)
  w:draw { color = { 0.85, 0.85, 0.9 } }
  for _, wm in ipairs(worms) do
    if wm.flash then g.color(1, 0.3, 0.2) else g.color(0.95, 0.6, 0.7) end
    draw_mask(g, wm.mask, wm.px, wm.py)
  end
  g.color(1, 1, 1)
  g.hud(w, ("craters %d   debris %d   shell hits %d"):format(craters, debris, hits))
end

function tether.unload()
  print(("worms: %d craters, %d debris, %d shell hits over %.1f s; hash %s"):format(craters, debris, hits, time,
    w:hash()))
end

if not tether.quit then -- stock Lua: no runner, so run 10 s here
  tether.load()
  for _ = 1, 600 do tether.update(1 / 60) end
  tether.unload()
end
