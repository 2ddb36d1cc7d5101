-- demos/cloth.lua — a hanging cloth in gusty wind that tears when pulled too
-- far: a corner is grabbed by a pin whose anchor the script drags away.
--
--   build/tether --headless --steps 600 demos/cloth.lua [columns]
--   LUA_CPATH='build/?.so' lua5.4 demos/cloth.lua      (stock Lua: runs 600 steps itself)
--
-- Every second it prints the wind, the torn link count and the solver's
-- convergence; at the end the state hash (the same on every run).
local tether = require "tether"

local N = 32
local LOG_EVERY = 60
local world, cloth, grab, steps, torn = nil, nil, nil, 0, 0
local lines = {}

function tether.load(args)
  N = tonumber((args[1] or ""):match("^%d+$")) or N
  world = tether.world { iterations = 15, substeps = 2, damping = 0.1 }
  cloth = world:cloth { origin = { -2, 3 }, width = 4, height = 3, columns = N, rows = N,
                        mass = 0.01, pin_top_row = true, break_strain = 0.6,
                        shear_stiffness = 0.1, bend_stiffness = 0.1 } -- drapes: see docs (w:cloth)
  print(("cloth: %dx%d particles, %d links, tears past 60%% stretch"):format(N, N, world:constraint_count()))
end

function tether.update(dt)
  steps = steps + 1
  local t = steps * dt
  -- gusts: a steady breeze plus a slow swell (N per particle)
  world:set_wind(0.04 + 0.05 * math.sin(t * 1.7) ^ 2, 0.01 * math.sin(t * 3.1))
  if steps == 240 then -- a hand grabs five particles in the middle of the bottom hem …
    local ps = world:composite_particles(cloth)
    grab = {}
    local mid = math.floor(N / 2)
    for c = mid - 2, mid + 2 do grab[#grab + 1] = world:pin(ps[(N - 1) * N + c]) end
  end
  if grab then         -- … and pulls them down and away
    for _, g in ipairs(grab) do
      local x, y = world:pin_anchor(g)
      world:set_constraint(g, { anchor = { x + 0.01, y - 0.02 } })
    end
  end
  world:step(dt)
  torn = torn + #world:break_events()
  if steps % LOG_EVERY == 0 then
    local st = world:stats()
    local _, n = world:constraint_lines(lines)
    local wx = world:wind()
    print(("t=%5.2f s  wind %.3f N  torn %4d  links drawn %5d  sweeps %3d  error %.1e m  %.2f ms")
      :format(st.time, wx, torn, n, st.iterations, st.max_error, st.step_ms))
  end
end

function tether.draw(g)
  g.fit(-3.5, -1.5, 3.5, 3.5)
  world:draw { particles = false }
  g.hud(world, ("torn %d links"):format(torn))
end

function tether.unload()
  print(("cloth: %d steps, torn %d, hash %s"):format(steps, torn, world:hash()))
  world:destroy()
end

if not tether.quit then
  tether.load(arg or {})
  for _ = 1, 600 do tether.update(1 / 60) end
  tether.unload()
end
