-- tether_atlas_scenes — the atlas's reference scenes, each with a known
-- answer: exact (projectile, oscillator, Kepler orbit, the discrete
-- catenary, the bounce's e²·h, the winch's rate), the pendulum's ODE solved
-- by RK4 at 1e-5 s here (not by the engine), the cloth against itself at
-- converged settings, the reference pour and a fast landing against zero
-- overlap. Many copies of each small system run side by side, so a step
-- costs enough to time.
-- See tether_atlas.lua for what a scene table holds.
local tether = require "tether"
local atlas = require "tether_atlas"

local S = {}
local G = 9.81
local ALL = { "euler", "symplectic_euler", "leapfrog", "verlet", "rk4" }

local function world(cfg, opts)
  opts = opts or {}
  opts.tolerance = 0 -- every sweep runs: the cost of a setting is fixed work
  opts.sleep = false -- the solver is measured: a scene at rest would fall asleep and keep the error it had then
  return tether.world(opts)
end

local function max_err(ctx, e) if e > ctx.err or e ~= e then ctx.err = e end end

-- Thrown under gravity: exact for a constant force.
function S.projectile(q)
  local n = q and 200 or 1000
  return {
    name = "projectile", title = ("projectile, %d particles, 2 s"):format(n),
    error_name = "largest position error over 2 s, m", duration = 2, sample_every = 0.1,
    sweep = { integrator = ALL, dt = atlas.DTS },
    build = function(cfg)
      local w = world(cfg, { gravity = { 0, -G }, dt_hint = cfg.dt })
      local ps = {}
      for i = 1, n do ps[i] = w:particle(i * 10, 0, { vx = 10, vy = 10 }) end
      return w, { p = ps[1], x0 = 10, err = 0 }
    end,
    sample = function(w, ctx, t)
      local x, y = w:position(ctx.p)
      max_err(ctx, math.sqrt((x - ctx.x0 - 10 * t) ^ 2 + (y - 10 * t + 0.5 * G * t * t) ^ 2))
    end,
    error = function(_, ctx) return ctx.err end,
  }
end

-- Unit mass on a spring k = 1 to a pin: x = cos t.
function S.oscillator(q)
  local n = q and 200 or 1000
  return {
    name = "oscillator", title = ("harmonic oscillator (k = 1, m = 1), %d copies, 10 s"):format(n),
    error_name = "largest position error over 10 s, m (amplitude 1)", duration = 10, sample_every = 0.1,
    sweep = { integrator = ALL, dt = atlas.DTS }, particles = n,
    build = function(cfg)
      local w = world(cfg, { gravity = { 0, 0 }, dt_hint = cfg.dt })
      local first
      for i = 1, n do
        local a = w:particle(i * 10, 0, { pinned = true })
        local p = w:particle(i * 10 + 1, 0)
        w:spring(p, a, { stiffness = 1, rest = 0 })
        first = first or p
      end
      return w, { p = first, x0 = 10, err = 0 }
    end,
    sample = function(w, ctx, t)
      local x, y = w:position(ctx.p)
      max_err(ctx, math.sqrt((x - ctx.x0 - math.cos(t)) ^ 2 + y * y))
    end,
    error = function(_, ctx) return ctx.err end,
  }
end

-- θ'' = −(g/L) sin θ by RK4 at 1e-5 s, sampled every 0.1 s: the reference.
local pendulum_ref = {}
local function pendulum_reference(theta0, duration)
  local key = theta0 .. ":" .. duration
  if pendulum_ref[key] then return pendulum_ref[key] end
  local h, k = 1e-5, G / 1.0
  local th, om = theta0, 0.0
  local out, per = { [0] = th }, math.floor(0.1 / h + 0.5)
  local f = function(a) return -k * math.sin(a) end
  for s = 1, math.floor(duration / 0.1 + 0.5) do
    for _ = 1, per do
      local k1t, k1o = om, f(th)
      local k2t, k2o = om + 0.5 * h * k1o, f(th + 0.5 * h * k1t)
      local k3t, k3o = om + 0.5 * h * k2o, f(th + 0.5 * h * k2t)
      local k4t, k4o = om + h * k3o, f(th + h * k3t)
      th = th + h / 6 * (k1t + 2 * k2t + 2 * k3t + k4t)
      om = om + h / 6 * (k1o + 2 * k2o + 2 * k3o + k4o)
    end
    out[s] = th
  end
  pendulum_ref[key] = out
  return out
end

-- A bob on a rigid link (pin + distance constraint), L = 1 m.
local function pendulum(q, deg)
  local n, duration = q and 20 or 100, 10
  local theta0 = math.rad(deg)
  return {
    name = deg < 45 and "pendulum_small" or "pendulum_large",
    title = ("pendulum %d°, L = 1 m, pin + distance link, %d copies, %d s (reference: RK4 at 1e-5 s)"):format(deg, n, duration),
    error_name = "largest angle error over 10 s, rad", duration = duration, sample_every = 0.1, particles = n,
    -- one link per bob: one sweep solves it exactly, more would only cost
    sweep = q and { integrator = { "verlet", "leapfrog", "rk4" }, dt = { 1 / 240, 1 / 60, 1 / 10 }, substeps = { 1, 8 }, iterations = { 1 } }
      or { integrator = ALL, dt = atlas.DTS, substeps = { 1, 4, 16 }, iterations = { 1 } },
    line = function(cfg) return ("%s ×%d"):format(cfg.integrator, cfg.substeps) end,
    build = function(cfg)
      local w = world(cfg, { gravity = { 0, -G }, dt_hint = cfg.dt })
      local first
      for i = 1, n do
        local a = w:particle(i * 5, 0, { pinned = true })
        local p = w:particle(i * 5 + math.sin(theta0), -math.cos(theta0))
        w:distance(a, p, { length = 1 })
        first = first or p
      end
      return w, { p = first, x0 = 5, err = 0, ref = pendulum_reference(theta0, duration) }
    end,
    sample = function(w, ctx, t)
      local x, y = w:position(ctx.p)
      local th = math.atan(x - ctx.x0, -y)
      max_err(ctx, math.abs(th - ctx.ref[math.floor(t / 0.1 + 0.5)]))
    end,
    error = function(_, ctx) return ctx.err end,
  }
end
S.pendulum_small = function(q) return pendulum(q, 10) end
S.pendulum_large = function(q) return pendulum(q, 120) end

-- Kepler: GM = 1, a = 1, e = 0.5 from perihelion; the exact position from
-- Kepler's equation. Copies start at turned perihelia around one attractor.
function S.kepler(q)
  local n, e = q and 20 or 100, 0.5
  return {
    name = "kepler", title = ("Kepler orbit e = 0.5 (point attractor), %d copies, 20 s (3.2 orbits)"):format(n),
    error_name = "largest position error over 20 s, of the semi-major axis", duration = 20, sample_every = 0.1,
    sweep = { integrator = ALL, dt = q and { 1 / 480, 1 / 60, 1 / 10 } or atlas.DTS },
    build = function(cfg)
      local w = world(cfg, { gravity = { 0, 0 }, dt_hint = cfg.dt })
      w:set_attractor(1, 0, 0, 1, 0)
      local v = math.sqrt((1 + e) / (1 - e))
      local first
      for i = 0, n - 1 do
        local a = 2 * math.pi * i / n
        local c, s = math.cos(a), math.sin(a)
        local p = w:particle(0.5 * c, 0.5 * s, { vx = -v * s, vy = v * c })
        first = first or p
      end
      return w, { p = first, err = 0 }
    end,
    sample = function(w, ctx, t)
      local E = t
      for _ = 1, 50 do E = E - (E - e * math.sin(E) - t) / (1 - e * math.cos(E)) end
      local x, y = w:position(ctx.p)
      max_err(ctx, math.sqrt((x - (math.cos(E) - e)) ^ 2 + (y - math.sqrt(1 - e * e) * math.sin(E)) ^ 2))
    end,
    error = function(_, ctx) return ctx.err end,
  }
end

-- The discrete catenary: N equal links of l, N − 1 equal masses, ends pinned
-- at the same height `span` apart. Horizontal tension H is the same in
-- every link, the vertical drops by m·g at each mass and is symmetric.
local function catenary(N, l, span)
  local function pts(H)
    local p, x, y = { { 0, 0 } }, 0, 0
    for k = 0, N - 1 do
      local s = (N - 1) / 2 - k
      local d = math.sqrt(H * H + s * s)
      x, y = x + l * H / d, y - l * s / d
      p[#p + 1] = { x, y }
    end
    return p
  end
  local lo, hi = 0, 1e6
  for _ = 1, 200 do
    local mid = 0.5 * (lo + hi)
    if pts(mid)[N + 1][1] < span then lo = mid else hi = mid end
  end
  return pts(0.5 * (lo + hi))
end

function S.chain(q)
  local N, L, span, copies = 20, 10, 8, q and 5 or 20
  local exact = catenary(N, L / N, span)
  return {
    name = "chain", title = ("hanging chain, %d links, %d copies: the discrete catenary at rest (10 s, damping 2/s)"):format(N, copies),
    error_name = "largest distance from the catenary at 10 s, m (chain 10 m)", duration = 10,
    particles = copies * (N - 1),
    sweep = q and { dt = { 1 / 60 }, substeps = { 1, 4 }, iterations = { 1, 4, 16 } }
      or { dt = { 1 / 120, 1 / 60 }, substeps = { 1, 2, 4, 8, 16 }, iterations = { 1, 2, 4, 8, 16, 32 },
        solver = { "gauss_seidel", "jacobi" } },
    line = function(cfg) return ("%s ×%d substeps"):format(cfg.solver == "jacobi" and "jacobi" or "gs", cfg.substeps) end,
    build = function(cfg)
      local w = world(cfg, { gravity = { 0, -G }, damping = 2, dt_hint = cfg.dt })
      local ctx = { ropes = {} }
      for c = 1, copies do
        local x0 = (c - 1) * 20
        local h = w:rope { start = { x0, 0 }, finish = { x0 + L, 0 }, segments = N }
        local ps = w:composite_particles(h)
        w:set_pinned(ps[#ps], true)
        w:set_position(ps[#ps], x0 + span, 0, "reset")
        ctx.ropes[c] = { x0 = x0, ps = ps }
      end
      return w, ctx
    end,
    error = function(w, ctx)
      local err = 0
      for _, r in ipairs(ctx.ropes) do
        for i, p in ipairs(r.ps) do
          local x, y = w:position(p)
          local d = math.sqrt((x - r.x0 - exact[i][1]) ^ 2 + (y - exact[i][2]) ^ 2)
          if d > err or d ~= d then err = d end
        end
      end
      return err
    end,
  }
end

-- A 16 × 16 cloth (1 m, top corners pinned, shear 0.1), damped to rest:
-- its sag against the same cloth at 32 substeps × 64 sweeps.
local cloth_ref
function S.cloth(q)
  local function build(cfg)
    local w = world(cfg, { gravity = { 0, -G }, damping = 2, dt_hint = cfg.dt })
    local h = w:cloth { origin = { 0, 0 }, width = 1, height = 1, columns = 16, rows = 16, shear_stiffness = 0.1 }
    return w, { ps = w:composite_particles(h) }
  end
  local function positions(w, ctx)
    local out = {}
    for i, p in ipairs(ctx.ps) do out[2 * i - 1], out[2 * i] = w:position(p) end
    return out
  end
  local scene
  scene = {
    name = "cloth", title = "cloth 16 × 16 (1 m, shear 0.1) at rest after 5 s, against 32 substeps × 64 sweeps",
    error_name = "RMS distance from the converged sag, m", duration = 5, particles = 254,
    sweep = q and { dt = { 1 / 60 }, substeps = { 1, 8 }, iterations = { 1, 8 } }
      or { dt = { 1 / 120, 1 / 60, 1 / 30 }, substeps = { 1, 2, 4, 8, 16 }, iterations = { 1, 2, 4, 8, 16, 32 },
        solver = { "gauss_seidel", "jacobi" } },
    line = function(cfg) return ("%s ×%d substeps"):format(cfg.solver == "jacobi" and "jacobi" or "gs", cfg.substeps) end,
    build = build,
    error = function(w, ctx)
      if not cloth_ref then
        local rw, rctx = build { dt = 1 / 60 }
        rw:set_substeps(32)
        rw:set_iterations(64)
        rw:step(1 / 60, 300)
        cloth_ref = positions(rw, rctx)
        rw:destroy()
      end
      local xy, sum = positions(w, ctx), 0
      for i = 1, #xy do sum = sum + (xy[i] - cloth_ref[i]) ^ 2 end
      return math.sqrt(sum / (#xy / 2))
    end,
  }
  return scene
end

-- A ball dropped from 2 m (bottom) onto a floor, e = 0.5: it rebounds to e²·h.
function S.bounce(q)
  local n, r, h, e = q and 100 or 1000, 0.1, 2, 0.5
  return {
    name = "bounce", title = ("ball bounce, e = 0.5 from 2 m, %d balls: the rebound against e²·h = 0.5 m"):format(n),
    error_name = "|first rebound − e²·h| / e²·h", duration = 1.5, sample_every = 1e-9, particles = n,
    sweep = q and { integrator = { "verlet", "symplectic_euler" }, dt = { 1 / 240, 1 / 60 }, substeps = { 1, 4 }, iterations = { 1 } }
      or { integrator = ALL, dt = atlas.DTS, substeps = { 1, 4 }, iterations = { 1 } },
    line = function(cfg) return ("%s ×%d"):format(cfg.integrator, cfg.substeps) end,
    build = function(cfg)
      local w = world(cfg, { gravity = { 0, -G }, dt_hint = cfg.dt })
      w:set_collision { particles = false, restitution = e, friction = 0 }
      local s = w:segment(-1, 0, n + 1, 0)
      w:set_shape_material(s, e, 0)
      local first
      for i = 1, n do
        local p = w:particle(i, h + r, { radius = r })
        first = first or p
      end
      return w, { p = first, phase = "fall", top = -math.huge, last = h + r }
    end,
    sample = function(w, ctx)
      local _, y = w:position(ctx.p)
      if ctx.phase == "fall" and y > ctx.last then ctx.phase = "rise" end
      if ctx.phase == "rise" then
        if y > ctx.top then ctx.top = y end
        if y < ctx.top then ctx.phase = "done" end
      end
      ctx.last = y
    end,
    error = function(_, ctx)
      if ctx.phase == "fall" then return math.huge end
      return math.abs((ctx.top - r) - e * e * h) / (e * e * h)
    end,
  }
end

-- The reference pour (README "Box2D cross-check"): circles r = 0.5 from a
-- staggered grid 1.1 apart, 89 a row, into a box 100 wide; g = 10, friction
-- 0.3, no bounce. Error: the deepest overlap at any sampled time.
local function overlap(w, r)
  local xy, n = w:positions()
  local cells, deepest = {}, 0
  for i = 1, n do
    local k = math.floor(xy[2 * i - 1] / (2 * r)) * 1000003 + math.floor(xy[2 * i] / (2 * r))
    local c = cells[k]
    if not c then c = {}; cells[k] = c end
    c[#c + 1] = i
  end
  for i = 1, n do
    local x, y = xy[2 * i - 1], xy[2 * i]
    local cx, cy = math.floor(x / (2 * r)), math.floor(y / (2 * r))
    for dx = -1, 1 do
      for dy = -1, 1 do
        local c = cells[(cx + dx) * 1000003 + cy + dy]
        if c then
          for _, j in ipairs(c) do
            if j > i then
              local d = math.sqrt((xy[2 * j - 1] - x) ^ 2 + (xy[2 * j] - y) ^ 2)
              if d < 2 * r and 2 * r - d > deepest then deepest = 2 * r - d end
            end
          end
        end
      end
    end
  end
  return deepest / r
end

function S.pour(q)
  local n, duration = q and 1000 or 10000, q and 3 or 5
  return {
    name = "pour", title = ("the reference pour, %d circles, %g s"):format(n, duration),
    error_name = "deepest overlap in the run (sampled every 0.25 s), of a radius", duration = duration, sample_every = 0.25,
    particles = n, sample_first_run_only = true,
    sweep = q and { dt = { 1 / 60 }, substeps = { 1, 4 }, iterations = { 1, 8 } }
      or { dt = { 1 / 60, 1 / 30 }, substeps = { 1, 2, 4, 8 }, iterations = { 1, 2, 4, 8, 16 } },
    line = function(cfg) return ("dt 1/%d ×%d substeps"):format(math.floor(1 / cfg.dt + 0.5), cfg.substeps) end,
    build = function(cfg)
      local w = world(cfg, { gravity = { 0, -10 }, dt_hint = cfg.dt, capacity = n })
      w:set_collision { restitution = 0, friction = 0.3 }
      for _, s in ipairs { w:aabb(-51, -1, 51, 0), w:aabb(-51, 0, -50, 400), w:aabb(50, 0, 51, 400) } do
        w:set_shape_material(s, 0, 0.3)
      end
      for i = 0, n - 1 do
        local row, col = math.floor(i / 89), i % 89
        local x = -48.4 + 1.1 * col + (row % 2 == 1 and 0.05 or 0)
        w:particle(x, 0.55 + 1.1 * row, { radius = 0.5 })
      end
      return w, { err = 0 }
    end,
    sample = function(w, ctx) max_err(ctx, overlap(w, 0.5)) end,
    error = function(_, ctx) return ctx.err end,
  }
end

-- A load thrown down at 60 m/s (two radii a step at 60 Hz) into a well 12 m
-- wide: circles r = 0.5 in rows 1.02 apart. A fixed substep lets the layers
-- above run into the stopped ones; substeps by speed (w:set_travel) split
-- only the fast steps. Error: the deepest overlap at any sampled time.
function S.landing(q)
  local cols, rows = 11, q and 10 or 30
  return {
    name = "landing", title = ("a load of %d circles thrown down at 60 m/s into a well, 2 s"):format(cols * rows),
    error_name = "deepest overlap in the run (sampled every 1/20 s), of a radius", duration = 2, sample_every = 0.05,
    particles = cols * rows,
    sweep = q and { dt = { 1 / 60 }, substeps = { 1, 4 }, iterations = { 8 }, travel = { 0, 0.5 } }
      or { dt = { 1 / 60 }, substeps = { 1, 2, 4, 8 }, iterations = { 8 }, travel = { 0, 0.25, 0.5, 1 } },
    line = function(cfg) return cfg.travel > 0 and ("max_travel %g"):format(cfg.travel) or "fixed substeps" end,
    build = function(cfg)
      local w = world(cfg, { dt_hint = cfg.dt })
      w:set_collision {}
      w:aabb(-7, -1, 7, 0)
      w:aabb(-7, 0, -6, 80)
      w:aabb(6, 0, 7, 80)
      for r = 0, rows - 1 do
        for c = 0, cols - 1 do
          w:particle((c - 0.5 * (cols - 1)) * 1.02 + (r % 2) * 0.02, 12 + r * 1.02, { radius = 0.5, vy = -60 })
        end
      end
      return w, { err = 0 }
    end,
    sample = function(w, ctx) max_err(ctx, overlap(w, 0.5)) end,
    error = function(_, ctx) return ctx.err end,
  }
end

-- A winch reels a load (with a 5-link rope hanging from it) up at 1 m/s:
-- the load should rise at exactly that speed.
function S.winch(q)
  local copies = q and 10 or 50
  return {
    name = "winch", title = ("rope winch at 1 m/s, %d copies, 3 s"):format(copies),
    error_name = "largest |load speed − 1 m/s| from 0.5 s to 3 s, m/s", duration = 3, sample_every = 0.05,
    particles = copies * 6,
    sweep = q and { integrator = { "verlet" }, dt = { 1 / 60 }, substeps = { 1, 4 }, iterations = { 1, 8 } }
      or { integrator = ALL, dt = atlas.DTS, substeps = { 1, 4 }, iterations = { 1, 4, 16 } },
    line = function(cfg) return ("%s ×%d"):format(cfg.integrator, cfg.substeps) end,
    build = function(cfg)
      local w = world(cfg, { gravity = { 0, -G }, dt_hint = cfg.dt })
      local ctx = { err = 0 }
      for c = 1, copies do
        local x0 = c * 5
        local a = w:particle(x0, 0, { pinned = true })
        local load = w:particle(x0, -5)
        local cable = w:distance(a, load, { length = 5, max_rate = 1 })
        local h = w:rope { start = { x0, -5 }, finish = { x0, -6 }, segments = 5, pin_start = false }
        w:distance(load, w:composite_particles(h)[1], { length = 0 })
        w:set_constraint(cable, { length = 1 })
        ctx.load = ctx.load or load
      end
      return w, ctx
    end,
    sample = function(w, ctx, t)
      if t < 0.5 - 1e-9 then return end
      local _, vy = w:velocity(ctx.load)
      max_err(ctx, math.abs(vy - 1))
    end,
    error = function(_, ctx) return ctx.err end,
  }
end

local ORDER = { "projectile", "oscillator", "pendulum_small", "pendulum_large", "kepler", "chain", "cloth", "bounce", "pour",
  "landing", "winch" }

local M = { make = S, order = ORDER }
function M.scenes(quick)
  local out = {}
  for _, name in ipairs(ORDER) do out[#out + 1] = S[name](quick) end
  return out
end
return M
