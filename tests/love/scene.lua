-- tests/love/scene.lua — the scene of the LÖVE test, plain Lua (5.1 or 5.4):
-- LÖVE steps it in love.update, and tests/love/run.sh steps the same under
-- plain luajit and lua5.4 for the hash LÖVE must reach. A rope from a pin,
-- a cloth hanging by its top corners and 24 balls dropped on a floor.
local S = { FRAMES = 120, DT = 1 / 60 }

function S.build(tether)
  local w = tether.world { substeps = 4, iterations = 8 }
  w:set_collision {}
  w:segment(-10, 0, 10, 0)
  local s = { world = w, balls = {} }
  s.rope = w:rope { start = { -6, 9 }, finish = { -2, 9 }, segments = 12, radius = 0.1, mass = 0.2 }
  s.cloth = w:cloth { origin = { 1, 10 }, width = 4, height = 3, columns = 10, rows = 7, mass = 0.05,
                      shear_stiffness = 0.1 }
  for i = 1, 24 do s.balls[i] = w:particle(-6.5 + 0.55 * i, 3 + (i % 4) * 0.5, { radius = 0.2 }) end
  return s
end

function S.step(s) s.world:step(S.DT) end

-- After S.FRAMES steps: nil, or what is wrong.
function S.check(s)
  local w = s.world
  for i, b in ipairs(s.balls) do
    local _, y = w:position(b)
    if y < 0.15 or y > 0.5 then return ("ball %d at y = %g: not resting on the floor"):format(i, y) end
  end
  local rp = w:composite_particles(s.rope)
  local px, py = w:position(rp[1])
  local ex, ey = w:position(rp[#rp])
  if px ~= -6 or py ~= 9 then return "the rope's pinned end moved" end
  -- 4 m of rope swinging down from its pin: below it, never further than the rope is long
  local d = math.sqrt((ex - px) ^ 2 + (ey - py) ^ 2)
  if ey >= py or d > 4.1 or d < 3 then return ("the rope's free end at (%g, %g): no rope from the pin"):format(ex, ey) end
  local e = w:energy().total
  if e ~= e or math.abs(e) > 1e6 then return "energy " .. tostring(e) end
  return nil
end

return S
