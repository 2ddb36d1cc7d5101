-- docs/atlas_example.lua — the speed/accuracy trade of *your* scene:
--
--   build/tether atlas docs/atlas_example.lua          (or --quick)
--
-- writes build/atlas/grapple.csv and grapple.png: error against cost for
-- every setting swept, the Pareto front drawn thick. A script returns a
-- scene table (or a list of them); the atlas passes it `quick` (true with
-- --quick) and any arguments after the script. Fields: see lua/tether_atlas.lua.
local tether = require "tether"
local quick = ...

local LINKS = 20
return {
  name = "grapple",
  title = "grappling hook: a 5 kg hook swinging on a 20-link rope, 4 s",
  error_name = "largest link stretch over the run, of its length",
  duration = 4,
  sample_every = 0.05,           -- sample() runs every 0.05 s of game time, outside the timing
  sweep = quick and { dt = { 1 / 60 }, substeps = { 1, 4 }, iterations = { 2, 8 } }
    or { dt = { 1 / 120, 1 / 60, 1 / 30 }, substeps = { 1, 2, 4, 8 }, iterations = { 1, 2, 4, 8, 16 } },
  line = "substeps",             -- one plotted line per substep count
  build = function(cfg)          -- the scene from its start; the atlas then sets cfg's settings
    local w = tether.world { gravity = { 0, -9.81 }, dt_hint = cfg.dt, tolerance = 0 }
    local rope = w:rope { start = { 0, 10 }, finish = { 10, 10 }, segments = LINKS }
    local ps = w:composite_particles(rope)
    w:set_mass(ps[#ps], 5)       -- the hook
    return w, { links = w:composite_constraints(rope), worst = 0 }
  end,
  sample = function(w, ctx)
    for _, c in ipairs(ctx.links) do
      local s = math.abs(w:constraint_error(c)) / w:rest_length(c)
      if s > ctx.worst then ctx.worst = s end
    end
  end,
  error = function(_, ctx) return ctx.worst end,
}
