-- tests/window_input.lua — the window's keys and mouse, driven by
-- tests/window_input.events under Xvfb (tests/run.sh):
--   build/tether --frames 40 --size 320x240 --events tests/window_input.events tests/window_input.lua
-- One particle at the origin, no gravity, camera 100 px/m centred on it:
-- pixel (160, 120) is the particle, (210, 70) is the world point (0.5, 0.5).
-- Prints "N passed, M failed" at the end.
local w, p
local frame, updates = 0, 0
local updates_at = {}   -- updates done when each frame was drawn
local pos_at = {}       -- particle position and pinned state when each frame was drawn
local size_at = {}      -- g.size() of each frame

function tether.load()
  w = tether.world { gravity = { 0, 0 } }
  p = w:particle(0, 0, { radius = 0.05, mass = 2 })
end

function tether.update(dt)
  updates = updates + 1
  w:step(dt)
end

function tether.draw(g)
  frame = frame + 1
  g.camera(0, 0, 100)
  w:draw()
  local x, y = w:position(p)
  updates_at[frame], pos_at[frame] = updates, { x, y, w:pinned(p) }
  size_at[frame] = { g.size() }
end

function tether.unload()
  local passed, failed = 0, 0
  local function check(ok, what)
    if ok then passed = passed + 1 else failed = failed + 1; io.stderr:write("FAIL " .. what .. "\n") end
  end
  -- events: 3 down at the particle, 5 move to (210, 70), 10 up; 12 key space (pause), 20 key s (one step),
  -- 22 key space (run), 30 down on empty space, 31 up, 33 resize 400 300
  local f = pos_at[8]
  check(f and math.abs(f[1] - 0.5) < 1e-9 and math.abs(f[2] - 0.5) < 1e-9, "dragged to (0.5, 0.5): " ..
    (f and ("%g %g"):format(f[1], f[2]) or "no frame 8"))
  check(f and f[3] == true, "pinned while dragged")
  local r = pos_at[11]
  check(r and r[3] == false, "unpinned after release")
  check(w:mass(p) == 2, "mass back after release")
  check(r and math.abs(r[1] - 0.5) < 1e-9 and math.abs(r[2] - 0.5) < 1e-9, "at rest where released")
  check(updates_at[19] - updates_at[14] == 0, ("paused: no update between frames 14 and 19 (got %d)")
    :format(updates_at[19] - updates_at[14]))
  check(updates_at[21] - updates_at[19] == 1, ("one step on 's' (got %d)"):format(updates_at[21] - updates_at[19]))
  check(updates > updates_at[21], "running again after the second space")
  local x, y = w:position(p)
  check(math.abs(x - 0.5) < 1e-9 and math.abs(y - 0.5) < 1e-9 and not w:pinned(p), "a click on empty space drags nothing")
  check(size_at[30][1] == 320 and size_at[30][2] == 240, "320x240 before the resize")
  -- the window draws at its clock's alpha, in [0, 1): w:draw then keeps the previous positions
  -- (headless frames draw at 1 and keep nothing: tests/lua/test_render.lua)
  check(w:interpolation() == true, "the clock's alpha reached w:draw (the world keeps its previous positions)")
  local s = size_at[40]
  check(s[1] == 400 and s[2] == 300, ("400x300 after the resize (got %dx%d)"):format(s[1], s[2]))
  print(("%d passed, %d failed"):format(passed, failed))
  if failed > 0 then error("window input: failures") end
end
