-- demos/rewind.lua — time rewinding: a pour plays for 4.3 s, then runs
-- backwards through the rewind ring at twice its speed for 2 s of
-- simulated time, then plays forward again; the HUD draws the time line.
--
--   build/tether --headless --frames 60 --every 10 --out /tmp/rw demos/rewind.lua
--   build/tether demos/rewind.lua                 (a window: the same, scripted)
--
-- The ring keeps a keyframe every 10 steps; a step between two is rebuilt
-- by re-stepping from the keyframe before it with drive(), whose inputs
-- (the emitter, a blast) are a function of the step counter alone, so the
-- rebuilt steps are the steps that were: when the pour passes step 260 a
-- second time it prints whether the hash is the first pass's.
local tether = require "tether"

local REWIND_AT, BACK, SPEED = 260, 120, 2  -- update that starts the rewind, steps back, steps per update
local w, ring, first_hash
local update, step_now, mode = 0, 0, "play"

local function drive(world)
  local n = world:stats().steps
  if n % 2 == 0 and n < 400 then           -- the emitter: two grains every 2 steps, fanned
    for k = 0, 1 do
      local a = math.sin(n * 0.37 + k) * 0.6
      world:particle(-6.5 + a, 8.5 + k * 0.6, { radius = 0.2, vx = 5 + 2 * math.cos(n * 0.21 + k), vy = 1 })
    end
  end
  if n == 150 then world:explode(-1, 0.5, 3, 6) end
  world:step(1 / 60)
end

function tether.load()
  w = tether.world { substeps = 4, iterations = 4 }
  w:set_collision { friction = 0.4, restitution = 0.1 }
  w:chain { -8, 10, -8, 0, 8, 0, 8, 10 }
  w:circle(1, 3, 1.2)
  w:circle(-3, 5, 0.8)
  ring = tether.rewind { every = 10, seconds = 8 }
  ring:record(w)
  print("rewind: a keyframe every 10 steps, 8 s kept; back " .. BACK .. " steps at " .. SPEED .. "x from update " .. REWIND_AT)
end

function tether.update()
  update = update + 1
  if mode == "play" and update == REWIND_AT + 1 then
    mode, first_hash = "rewind", w:hash()
    print(("rewind: at step %d (%d grains), %d keyframes in %.2f MB; playing backwards"):format(
      step_now, w:stats().particles, ring:count(), ring:memory() / 1e6))
  end
  if mode == "rewind" then
    step_now = math.max(REWIND_AT - BACK, step_now - SPEED)
    ring:seek(w, step_now, drive)
    if step_now == REWIND_AT - BACK then
      mode = "play"
      print(("rewind: back at step %d, playing forward"):format(step_now))
    end
    return
  end
  drive(w)
  ring:record(w)
  step_now = w:stats().steps
  if step_now == REWIND_AT and first_hash then
    print(("rewind: step %d again: hash %s, the first pass's: %s"):format(step_now, w:hash(),
      tostring(w:hash() == first_hash)))
  end
end

-- The time line: the ring's range as a bar, the present as a marker.
local function timeline(g)
  local width, height = g.size()
  local x0, x1, y = 20, width - 20, height - 28
  local first, last = ring:range()
  local span = math.max(600, last)
  local function px(s) return x0 + (x1 - x0) * s / span end
  g.layer("screen")
  g.color(0.3, 0.3, 0.35); g.line_width(6); g.line(x0, y, x1, y)
  g.color(0.35, 0.6, 0.9); g.line(px(first), y, px(last), y)
  g.color(mode == "rewind" and 1 or 0.4, mode == "rewind" and 0.3 or 1, 0.3)
  g.line_width(2); g.polygon({ px(step_now) - 7, y - 14, px(step_now) + 7, y - 14, px(step_now), y - 4 })
  g.color(1, 1, 1)
  g.text(x0, y + 8, ("%s  step %d   ring %d .. %d, %d keyframes, %.2f MB"):format(
    mode == "rewind" and "<< REWIND" or "PLAY >", step_now, first, last, ring:count(), ring:memory() / 1e6), 1)
  g.layer("world")
end

function tether.draw(g)
  g.fit(-9, -1, 9, 11)
  w:draw()
  g.hud(w, mode == "rewind" and "rewinding through the ring" or "playing")
  timeline(g)
end

function tether.unload()
  print("rewind: hash " .. w:hash())
end

if not tether.quit then -- stock Lua: no runner
  tether.load()
  for _ = 1, 600 do tether.update(1 / 60) end
  tether.unload()
end
