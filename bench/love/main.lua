-- bench/love/main.lua — love.physics (Box2D, as LÖVE 11.4 bundles it) and
-- tether side by side in one LÖVE process: N circles poured into the same
-- box by each, ms/step of each, and beside it what the step bought: the
-- deepest overlap between two circles (or a circle and a wall) and the
-- kinetic energy left once the pile should have settled.
--
--   make bench-love            (LUA_CPATH="$PWD/build/luajit/?.so" love bench/love --out build/bench-out)
--   arguments: --sizes 2000,10000 --runs 3 --steps 360 --out DIR
--
-- Runs alternate which engine goes first, so a change in the machine's load
-- falls on both; per run the median ms/step over all steps; then per engine
-- and size the median and min–max over runs. Same scene in both: circles of
-- radius R and mass 1 in a 20 m wide box, dropped from a loose grid, g = 9.81,
-- 1/60 s steps, friction 0.5, no bounce. Box2D: LÖVE's defaults (8 velocity,
-- 3 position iterations, sleeping on); tether: SUBSTEPS × ITERATIONS below.
-- Kinetic energy is the translational ½mv² of every circle (tether's
-- particles do not spin; Box2D's rolling energy is left out).
local tether = require "tether"

local R, WIDTH, DT = 0.1, 20, 1 / 60
local SUBSTEPS, ITERATIONS = 4, 2

local function grid_position(i) -- loose grid, 2.2 R apart, rows from 0.5 m up
  local per_row = math.floor((WIDTH - 4 * R) / (2.2 * R))
  local row, col = math.floor((i - 1) / per_row), (i - 1) % per_row
  return 2 * R + (col + 0.5) * 2.2 * R + (row % 2) * 0.3 * R, 0.5 + row * 2.2 * R
end

local function make_tether(n)
  local w = tether.world { substeps = SUBSTEPS, iterations = ITERATIONS, capacity = n }
  w:set_collision { friction_static = 0.5, friction_kinetic = 0.5 }
  w:segment(0, 0, WIDTH, 0); w:segment(0, 0, 0, 1000); w:segment(WIDTH, 0, WIDTH, 1000)
  local ps = {}
  for i = 1, n do local x, y = grid_position(i); ps[i] = w:particle(x, y, { radius = R, mass = 1 }) end
  local xy = {}
  return {
    step = function() w:step(DT) end,
    positions = function() return (w:positions(xy)) end,
    kinetic = function()
      local e = 0
      for i = 1, n do local vx, vy = w:velocity(ps[i]); e = e + 0.5 * (vx * vx + vy * vy) end
      return e
    end,
    close = function() w:destroy() end,
  }
end

local function make_box2d(n)
  love.physics.setMeter(1) -- metres in, metres out
  local w = love.physics.newWorld(0, -9.81, true)
  local ground = love.physics.newBody(w, 0, 0, "static")
  for _, e in ipairs { { 0, 0, WIDTH, 0 }, { 0, 0, 0, 1000 }, { WIDTH, 0, WIDTH, 1000 } } do
    love.physics.newFixture(ground, love.physics.newEdgeShape(e[1], e[2], e[3], e[4])):setFriction(0.5)
  end
  local shape, bodies = love.physics.newCircleShape(R), {}
  for i = 1, n do
    local x, y = grid_position(i)
    local b = love.physics.newBody(w, x, y, "dynamic")
    local f = love.physics.newFixture(b, shape, 1 / (math.pi * R * R)) -- mass 1
    f:setFriction(0.5); f:setRestitution(0)
    bodies[i] = b
  end
  local xy = {}
  return {
    step = function() w:update(DT) end,
    positions = function()
      for i = 1, n do xy[2 * i - 1], xy[2 * i] = bodies[i]:getPosition() end
      return xy
    end,
    kinetic = function()
      local e = 0
      for i = 1, n do local vx, vy = bodies[i]:getLinearVelocity(); e = e + 0.5 * (vx * vx + vy * vy) end
      return e
    end,
    close = function() w:destroy() end,
  }
end

-- Deepest overlap, m: between two circles (a cell hash, cells 2R wide) or
-- through the floor or a wall.
local function max_overlap(xy, n)
  local cells, worst = {}, 0
  local function key(cx, cy) return cx * 100003 + cy end
  for i = 1, n do
    local x, y = xy[2 * i - 1], xy[2 * i]
    worst = math.max(worst, R - y, R - x, x + R - WIDTH)
    local k = key(math.floor(x / (2 * R)), math.floor(y / (2 * R)))
    local c = cells[k]
    if not c then c = {}; cells[k] = c end
    c[#c + 1] = i
  end
  for i = 1, n do
    local x, y = xy[2 * i - 1], xy[2 * i]
    local cx, cy = math.floor(x / (2 * R)), math.floor(y / (2 * R))
    for dx = -1, 1 do for dy = -1, 1 do
      local c = cells[key(cx + dx, cy + dy)]
      if c then
        for _, j in ipairs(c) do
          if j > i then
            local ex, ey = xy[2 * j - 1] - x, xy[2 * j] - y
            worst = math.max(worst, 2 * R - math.sqrt(ex * ex + ey * ey))
          end
        end
      end
    end end
  end
  return worst
end

local function median(t)
  local s = {}
  for i, v in ipairs(t) do s[i] = v end
  table.sort(s)
  local m = #s
  return m % 2 == 1 and s[(m + 1) / 2] or 0.5 * (s[m / 2] + s[m / 2 + 1])
end

local function run(make, n, steps)
  collectgarbage("collect")
  local e = make(n)
  local times = {}
  for s = 1, steps do
    local t0 = love.timer.getTime()
    e.step()
    times[s] = (love.timer.getTime() - t0) * 1000
  end
  local r = { ms = median(times), overlap = max_overlap(e.positions(), n), kinetic = e.kinetic() }
  e.close()
  io.stderr:write(("pour: %d circles, %s: %.3f ms/step\n"):format(n, make == make_tether and "tether" or "love.physics", r.ms))
  return r
end

local function loadavg()
  local f = io.open("/proc/loadavg")
  local s = f and f:read("*l") or "?"
  if f then f:close() end
  return s:match("^(%S+ %S+ %S+)") or s
end

function love.load(args)
  local sizes, runs, steps, out = { 2000, 10000 }, 3, 360, nil
  for i = 1, #args - 1 do
    local a, v = args[i], args[i + 1]
    if a == "--sizes" then sizes = {}; for s in v:gmatch("%d+") do sizes[#sizes + 1] = tonumber(s) end end
    if a == "--runs" then runs = tonumber(v) end
    if a == "--steps" then steps = tonumber(v) end
    if a == "--out" then out = v end
  end
  local engines = { tether = make_tether, ["love.physics"] = make_box2d }
  local order = { "tether", "love.physics" }
  print(("pour: %s; %d runs of %d steps (%.1f s) per engine and size; load average before: %s"):format(
    jit and jit.version or _VERSION, runs, steps, steps * DT, loadavg()))
  local rows = {}
  for _, n in ipairs(sizes) do
    local got = { tether = {}, ["love.physics"] = {} }
    for r = 1, runs do
      for k = 1, 2 do
        local name = order[(r + k) % 2 + 1] -- alternate who goes first
        got[name][#got[name] + 1] = run(engines[name], n, steps)
      end
    end
    for _, name in ipairs(order) do
      local ms, ov, ke = {}, {}, {}
      for i, g in ipairs(got[name]) do ms[i], ov[i], ke[i] = g.ms, g.overlap, g.kinetic end
      table.sort(ms)
      rows[#rows + 1] = { n = n, engine = name, ms = median(ms), lo = ms[1], hi = ms[#ms],
                          overlap = math.max(unpack(ov)), kinetic = median(ke) }
    end
  end
  print(("%-7s %-13s %10s %16s %14s %14s"):format("circles", "engine", "ms/step", "(min-max)", "max overlap", "kinetic J"))
  for _, r in ipairs(rows) do
    print(("%-7d %-13s %10.3f %16s %11.4f m %14.3f"):format(r.n, r.engine, r.ms,
      ("(%.3f-%.3f)"):format(r.lo, r.hi), r.overlap, r.kinetic))
  end
  print(("tether: %d substeps x %d iterations; love.physics: 8 velocity, 3 position iterations; load average after: %s")
    :format(SUBSTEPS, ITERATIONS, loadavg()))
  if out then
    local f = io.open(out .. "/love_pour.csv", "w")
    if f then
      f:write("circles,engine,ms_median,ms_min,ms_max,max_overlap_m,kinetic_J\n")
      for _, r in ipairs(rows) do
        f:write(("%d,%s,%.4f,%.4f,%.4f,%.5f,%.4f\n"):format(r.n, r.engine, r.ms, r.lo, r.hi, r.overlap, r.kinetic))
      end
      f:close()
      print("pour: " .. out .. "/love_pour.csv")
    end
  end
  love.event.quit(0)
end
