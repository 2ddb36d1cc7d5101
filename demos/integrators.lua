-- demos/integrators.lua — the same spring oscillator under every integrator.
--
--   build/tether demos/integrators.lua                        (a window)
--   build/tether --headless --frames 60 --every 10 --out build/demo demos/integrators.lua
--   build/tether --headless --steps 600 demos/integrators.lua
--   LUA_CPATH='build/?.so' lua5.4 demos/integrators.lua   (stock Lua: 10 s of simulated time)
--
-- Five worlds side by side, one per integrator, each holding a bob on a
-- spring tied to a pinned anchor (no gravity, no damping: the energy should
-- stay constant). Every second of simulated time it prints the relative
-- energy drift (E - E0) / E0 of each: Euler gains energy, the symplectic
-- ones oscillate around zero, RK4 loses a little. The picture shows each
-- world side by side: the spring on top, and below it the bob's orbit in
-- phase space (position, velocity/omega), which is a closed circle for the
-- exact motion: Euler spirals out, the symplectic ones stay on it.
local tether = require "tether"

local K, MASS, REST, STRETCH = 100, 1, 1, 0.5  -- N/m, kg, m, m: period 2π/sqrt(K/MASS) ≈ 0.63 s

local worlds, e0, bobs, trails = {}, {}, {}, {}
local OMEGA = math.sqrt(K / MASS)
local TRAIL = 240 -- points of orbit kept per world
local time, next_report = 0, 1

local function energy(w) return w:energy().total end

function tether.load()
  local head = { ("%7s"):format("t") }
  for i, name in ipairs(tether.integrators) do
    local w = tether.world { integrator = name, gravity = { 0, 0 } }
    local anchor = w:particle(0, 0, { pinned = true })
    local bob = w:particle(REST + STRETCH, 0, { mass = MASS })
    w:spring(anchor, bob, { stiffness = K, rest = REST })
    worlds[i], e0[i], bobs[i], trails[i] = w, energy(w), bob, {}
    head[#head + 1] = ("%17s"):format(name)
  end
  print(("integrators: bob of %g kg on a %g N/m spring, E0 = %g J; relative energy drift (E - E0)/E0")
    :format(MASS, K, e0[1]))
  print(table.concat(head))
end

function tether.update(dt)
  for i, w in ipairs(worlds) do
    w:step(dt)
    local x = w:position(bobs[i])
    local vx = w:velocity(bobs[i])
    local t = trails[i]
    t[#t + 1] = { (x - REST) / STRETCH, vx / (OMEGA * STRETCH) } -- the unit circle when exact
    if #t > TRAIL then table.remove(t, 1) end
  end
  time = time + dt
  if time >= next_report - 1e-9 then
    local row = { ("%5.1f s"):format(time) }
    for i, w in ipairs(worlds) do row[#row + 1] = ("%+17.3e"):format((energy(w) - e0[i]) / e0[i]) end
    print(table.concat(row))
    next_report = next_report + 1
  end
end

-- One panel per integrator: the spring (world:draw) on top, the phase orbit below.
function tether.draw(g)
  local W, H = g.size()
  local n = #worlds
  local pw = W / n
  local scale = pw >= 200 and 2 or 1
  local r = math.min(pw * 0.4, H * 0.26)
  local oy = H * 0.56
  for i, w in ipairs(worlds) do
    local cx = pw * (i - 0.5) -- panel centre, px
    local left, right = cx - pw / 2, cx + pw / 2
    -- the spring: world x from 0 (anchor) to REST + STRETCH, centred in the panel, at 20 % height
    local zoom = pw / 2.4 / (REST + STRETCH)
    g.camera((REST + STRETCH) / 2 - (cx - W / 2) / zoom, (H * 0.2 - H / 2) / zoom, zoom)
    local x = w:position(bobs[i])
    if math.abs(x) < 1.9 * (REST + STRETCH) then
      w:draw { min_radius = 5 }
    else
      g.layer("screen")
      g.color(0.9, 0.4, 0.3)
      g.text(left + 8, H * 0.2, "off the panel", 1)
      g.layer("world")
    end
    -- phase orbit: the unit circle is the exact motion; the bob's recent trail on top
    g.layer("screen")
    g.color(0.3, 0.3, 0.35)
    g.circle(cx, oy, r, "line")
    local pts = {}
    for _, p in ipairs(trails[i]) do
      local px, py = cx + p[1] * r, oy - p[2] * r
      if px > left and px < right and py > H * 0.26 and py < H * 0.86 then
        pts[#pts + 1] = px
        pts[#pts + 1] = py
      elseif #pts >= 4 then -- the orbit left the panel: draw what came before
        g.color(0.95, 0.75, 0.3)
        g.line(table.unpack(pts))
        pts = {}
      else
        pts = {}
      end
    end
    g.color(0.95, 0.75, 0.3)
    if #pts >= 4 then g.line(table.unpack(pts)) end
    if #pts >= 2 then g.circle(pts[#pts - 1], pts[#pts], 4) end
    g.color(0.9, 0.9, 0.9)
    local label = tether.integrators[i]
    if #label * 6 * scale > pw - 12 then label = label:gsub("symplectic_", "sympl_") end
    g.text(left + 8, H * 0.04, label, scale)
    g.text(left + 8, H * 0.88, ("dE/E\n%+.2e"):format((energy(w) - e0[i]) / e0[i]), scale)
    if i > 1 then
      g.color(0.25, 0.25, 0.3)
      g.line(left, 0, left, H)
    end
    g.layer("world")
  end
  g.layer("screen")
  g.color(0.6, 0.6, 0.6)
  local caption = W >= 640 and "   bob %g kg on a %g N/m spring; below: phase orbit (x, v/omega), exact = circle"
    or "   phase orbits; exact = circle"
  g.text(8, H - 12, ("t = %.2f s" .. caption):format(time, MASS, K), 1)
  g.layer("world")
end

function tether.unload()
  local row = { "force evaluations per step:" }
  for i, w in ipairs(worlds) do
    row[#row + 1] = ("%s %d"):format(tether.integrators[i], w:stats().force_evaluations)
  end
  print(table.concat(row, "  "))
end

if not tether.quit then -- stock Lua: no runner, so run 10 s here
  tether.load()
  for _ = 1, 600 do tether.update(1 / 60) end
  tether.unload()
end
