-- demos/galton.lua — a Galton board: balls fall through rows of pegs into bins.
--
--   build/tether --headless --steps 900 demos/galton.lua
--   LUA_CPATH='build/?.so' lua5.4 demos/galton.lua   (stock Lua: 15 s simulated)
--
-- Pegs are static circles in a triangle of 12 rows; 600 balls are released
-- two every third step from a closed hopper just above the top peg. Bins
-- are walls below the pegs. At the end it prints the histogram of the bins,
-- which should look binomial.
local tether = require "tether"

local ROWS, SPACING, PEG_R, BALL_R = 12, 1.0, 0.12, 0.2
local BALLS, PER_STEP = 600, 2
local BINS = ROWS + 1
local w, made, steps = nil, 0, 0
local BIN_TOP = -ROWS * SPACING * 0.866 - 1.0

function tether.load()
  w = tether.world { substeps = 4, iterations = 4 }
  w:set_collision { restitution = 0.3, friction = 0.1 }
  for row = 0, ROWS - 1 do
    local y = -row * SPACING * 0.866
    for k = 0, row do
      w:circle((k - row / 2) * SPACING, y, PEG_R, { restitution = 0.4, friction = 0.1 })
    end
  end
  -- bin walls, floor, and side walls that keep everything on the board
  for b = 0, BINS do
    local x = (b - BINS / 2) * SPACING
    w:segment(x, BIN_TOP, x, BIN_TOP - 12)
  end
  local half = BINS / 2 * SPACING
  w:aabb(-half - 1, BIN_TOP - 13, half + 1, BIN_TOP - 12)
  w:segment(-half, BIN_TOP, -0.6, 2)
  w:segment(half, BIN_TOP, 0.6, 2)
  w:segment(-0.6, 2, 0.6, 2) -- the hopper's lid: balls thrown up by the crowd stay on the board
  print(("galton: %d rows of pegs, %d bins, %d balls"):format(ROWS, BINS, BALLS))
end

function tether.update(dt)
  steps = steps + 1
  if made < BALLS and steps % 3 == 0 then
    for _ = 1, PER_STEP do
      -- two side by side, thrown down so the next pair has room; a tiny
      -- deterministic offset so the first peg has something to decide
      local jitter = ((made * 7919) % 101 - 50) * 1e-4
      w:particle(jitter + (made % 2 == 0 and -0.25 or 0.25), 1.5, { radius = BALL_R, vy = -4 })
      made = made + 1
    end
  end
  w:step(dt)
end

function tether.draw(g)
  local half = BINS / 2 * SPACING
  g.fit(-half - 1.5, BIN_TOP - 13.5, half + 1.5, 3)
  w:draw()
  g.hud(w, ("balls %d of %d"):format(made, BALLS))
end

function tether.unload()
  local hist, landed = {}, 0
  for b = 1, BINS do hist[b] = 0 end
  local xy, n = w:positions()
  for i = 1, n do
    local x, y = xy[2 * i - 1], xy[2 * i]
    if y < BIN_TOP then
      local b = math.floor(x / SPACING + BINS / 2) + 1
      if b >= 1 and b <= BINS then hist[b] = hist[b] + 1; landed = landed + 1 end
    end
  end
  print(("galton: %d of %d balls made landed in the bins"):format(landed, made))
  local top = 1
  for b = 1, BINS do top = math.max(top, hist[b]) end
  for b = 1, BINS do
    print(("bin %2d %4d %s"):format(b, hist[b], ("#"):rep(math.floor(40 * hist[b] / top + 0.5))))
  end
  print("galton: hash " .. w:hash())
end

if not tether.quit then -- stock Lua: no runner, so run 15 s here
  tether.load()
  for _ = 1, 900 do tether.update(1 / 60) end
  tether.unload()
end
