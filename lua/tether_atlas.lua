-- tether_atlas — the speed/accuracy atlas: runs a scene over a grid of
-- settings (integrator × dt × substeps × iterations × solver order × substeps
-- by speed), measures
-- each point's error against the scene's known answer and its cost, and
-- writes CSV and log-log plots of error against cost with the Pareto front.
--
--   tether atlas [--quick] [--out DIR] [--repeats N] [SCRIPT]   (the runner)
--   require "tether_atlas".sweep(scene, opts)                    (any Lua)
--
-- A scene is a table (the built-in ones are in tether_atlas_scenes.lua; a
-- SCRIPT returns one, or a list of them):
--   name        file name of its CSV and plot
--   title       what it is, for the plot
--   error_name  what its error measures, with its unit, for the axis
--   duration    simulated seconds of one run
--   build(cfg)  → world, ctx: the scene from its start; cfg holds the point's
--               settings (integrator, dt, substeps, iterations, solver, travel) and
--               the atlas sets them on the world after build returns
--   sample(w, ctx, t)  optional, every `sample_every` s of simulated time
--                      (outside the timing): record what error needs
--   error(w, ctx) → the error of the run (≥ 0; nan or inf: it blew up)
--   particles   optional: the particles the cost is divided by (default w:count())
--   sweep       optional: lists per axis, e.g. {dt = {1/120, 1/60}, substeps = {1, 4}}
--   line        optional: the axis that makes one line of the plot ("integrator")
--
-- Cost is CPU time (os.clock) of the w:step calls alone, per particle, as
-- ns per particle-step and as µs per particle per simulated second (what a
-- game pays for one second of its scene: the fair axis across dt). Each
-- point runs `repeats` times, the points alternating (every repeat goes
-- through all points, in reverse order every other time), and its cost is
-- the median; the error is the first run's (runs are bit-identical).
--
-- `--instructions` (under callgrind: bench/atlas_cg.sh, `make atlas-cg`)
-- runs each point once and has callgrind count the instructions of its
-- w:step calls alone and dump them apart, labelled "atlas SCENE I" (I: the
-- point's row in the scene's CSV): a cost that does not move with the
-- machine's load, read back by the script.
local tether = require "tether"

local atlas = {}

atlas.DTS = { 1 / 1000, 1 / 480, 1 / 240, 1 / 120, 1 / 60, 1 / 30, 1 / 10 }
atlas.AXES = { "integrator", "dt", "substeps", "iterations", "solver", "travel" }
local DEFAULT = { integrator = { "verlet" }, dt = { 1 / 60 }, substeps = { 1 }, iterations = { 10 },
  solver = { "gauss_seidel" }, travel = { 0 } } -- travel: w:set_travel's max_travel, 0 = off

local function median(v)
  local s = {}
  for i = 1, #v do s[i] = v[i] end
  table.sort(s)
  local n = #s
  if n == 0 then return 0 / 0 end
  local h = math.floor(n / 2) -- (no // : the atlas runs under LuaJIT too)
  return n % 2 == 1 and s[h + 1] or 0.5 * (s[h] + s[h + 1])
end
atlas.median = median

-- Every combination of the scene's axes, in a fixed order.
local function grid(scene)
  local axes = scene.sweep or {}
  local points = { {} }
  for _, axis in ipairs(atlas.AXES) do
    local values = axes[axis] or DEFAULT[axis]
    local next_points = {}
    for _, p in ipairs(points) do
      for _, v in ipairs(values) do
        local q = {}
        for k, x in pairs(p) do q[k] = x end
        q[axis] = v
        next_points[#next_points + 1] = q
      end
    end
    points = next_points
  end
  return points
end
atlas.grid = grid

local function run_point(scene, cfg, measure, probe)
  local w, ctx = scene.build(cfg)
  w:set_integrator(cfg.integrator)
  w:set_substeps(cfg.substeps)
  w:set_iterations(cfg.iterations)
  w:set_solver(cfg.solver)
  w:set_travel(cfg.travel)
  local steps = math.max(1, math.floor(scene.duration / cfg.dt + 0.5))
  local chunk = steps
  if scene.sample then chunk = math.max(1, math.floor((scene.sample_every or 0.1) / cfg.dt + 0.5)) end
  local cpu, done, ok = 0.0, 0, true
  while done < steps and ok do
    local k = math.min(chunk, steps - done)
    local t0 = os.clock()
    if probe then probe.count(true) end
    ok = pcall(w.step, w, cfg.dt, k)
    if probe then probe.count(false) end
    cpu = cpu + (os.clock() - t0)
    done = done + k
    if ok and measure and scene.sample then scene.sample(w, ctx, done * cfg.dt) end
  end
  local err = math.huge
  if ok and measure then err = scene.error(w, ctx) end
  if err ~= err then err = math.huge end -- nan: it blew up
  local n = scene.particles or w:count()
  w:destroy()
  return err, cpu, steps, n
end

-- Marks the points no other point beats at once on cost and error.
local function pareto(rows)
  local order = {}
  for i, r in ipairs(rows) do
    r.pareto = false
    if r.error < math.huge then order[#order + 1] = i end
  end
  table.sort(order, function(a, b)
    local ra, rb = rows[a], rows[b]
    if ra.us_per_s ~= rb.us_per_s then return ra.us_per_s < rb.us_per_s end
    return ra.error < rb.error
  end)
  local best = math.huge
  for _, i in ipairs(order) do
    if rows[i].error < best then
      rows[i].pareto = true
      best = rows[i].error
    end
  end
end
atlas.pareto = pareto

local function label(scene, cfg)
  local axis = scene.line or "integrator"
  if type(axis) == "function" then return axis(cfg) end
  local v = cfg[axis]
  if axis == "dt" then return ("dt 1/%d"):format(math.floor(1 / v + 0.5)) end
  if type(v) == "number" then return ("%s %d"):format(axis, v) end
  return tostring(v)
end

atlas.CSV_HEADER = "scene,line,integrator,dt,substeps,iterations,solver,particles,steps,error,"
  .. "ns_per_particle_step,us_per_particle_second,cost_min,cost_max,pareto,travel"

local function csv_row(scene, r)
  return ("%s,%s,%s,%.9g,%d,%d,%s,%d,%d,%.6e,%.4f,%.4f,%.4f,%.4f,%d,%.9g"):format(scene.name, r.line, r.cfg.integrator,
    r.cfg.dt, r.cfg.substeps, r.cfg.iterations, r.cfg.solver, r.particles, r.steps, r.error, r.ns_step, r.us_per_s,
    r.us_min, r.us_max, r.pareto and 1 or 0, r.cfg.travel)
end
atlas.csv_row = csv_row

-- Sweeps one scene; returns its rows. opts: repeats (default 3), log (a
-- function given progress lines, default print), probe (the runner's
-- tether_probe: each point's steps counted and dumped apart, on the first
-- repeat).
function atlas.sweep(scene, opts)
  opts = opts or {}
  local repeats = opts.repeats or 3
  local log = opts.log or print
  local points = grid(scene)
  local rows = {}
  for i, cfg in ipairs(points) do rows[i] = { cfg = cfg, costs = {}, line = label(scene, cfg) } end
  for rep = 1, repeats do
    local first, last, step = 1, #points, 1
    if rep % 2 == 0 then first, last, step = #points, 1, -1 end
    for i = first, last, step do
      local r = rows[i]
      local probe = rep == 1 and opts.probe or nil
      local err, cpu, steps, n = run_point(scene, r.cfg, rep == 1 or not scene.sample_first_run_only, probe)
      if probe then probe.dump(("atlas %s %d"):format(scene.name, i)) end
      if rep == 1 then r.error, r.steps, r.particles = err, steps, n end
      r.costs[#r.costs + 1] = cpu
    end
  end
  for _, r in ipairs(rows) do
    local per = 1e9 / (r.particles * r.steps) -- ns per particle-step per CPU second
    local lo, hi = math.huge, 0
    for _, c in ipairs(r.costs) do lo, hi = math.min(lo, c), math.max(hi, c) end
    r.ns_step = median(r.costs) * per
    local sps = 1 / r.cfg.dt -- steps per simulated second
    r.us_per_s = r.ns_step * sps / 1000
    r.us_min, r.us_max = lo * per * sps / 1000, hi * per * sps / 1000
  end
  pareto(rows)
  log(("atlas: %-16s %4d points × %d repeats"):format(scene.name, #points, repeats))
  return rows
end

-- gnuplot script for one scene: a line per label, the front on top.
local function plot_script(scene, dir, labels)
  local q = function(s) return "'" .. s:gsub("'", "''") .. "'" end
  local data = dir .. "/" .. scene.name .. ".dat"
  local out = {
    "set terminal pngcairo size 900,620 font ',11'",
    "set output " .. q(dir .. "/" .. scene.name .. ".png"),
    "set logscale xy", "set format y '10^{%L}'", "set grid", "set key outside right top noenhanced",
    "set xlabel 'cost: CPU µs per particle per simulated second (median of repeats)'",
    "set ylabel " .. q(scene.error_name or "error"),
    'set title "' .. (scene.title or scene.name):gsub('[\\"]', "'") .. '\\n(grey: the Pareto front)" noenhanced font ",10"',
  }
  -- the front first, wide and translucent, so the settings' lines stay visible on it
  local parts = { ("%s using 1:2 with linespoints lw 7 lc rgb '#A0000000' pt 6 ps 2 title 'Pareto front'"):format(
    q(dir .. "/" .. scene.name .. ".front")) }
  for i, l in ipairs(labels) do
    -- gnuplot cycles 8 colours: past them, another point shape and dashes tell lines apart
    local shape = ({ 7, 5, 9, 11, 13 })[math.floor((i - 1) / 8) % 5 + 1]
    parts[#parts + 1] = ("%s index %d using 1:2 with linespoints lw 1.5 dt %d pt %d ps 0.7 title %s"):format(q(data), i - 1,
      math.floor((i - 1) / 8) % 5 + 1, shape, q(l))
  end
  out[#out + 1] = "plot " .. table.concat(parts, ", \\\n  ")
  return table.concat(out, "\n") .. "\n"
end

-- An error of exactly 0 (Verlet's projectile) is drawn at this floor.
local FLOOR = 1e-16

local function write(path, text)
  local f = assert(io.open(path, "w"))
  f:write(text)
  f:close()
end

-- Writes DIR/NAME.csv, the plot's data and script, and the PNG when gnuplot
-- is there; returns the PNG's path or nil.
function atlas.write(scene, rows, dir)
  local lines = { atlas.CSV_HEADER }
  for _, r in ipairs(rows) do lines[#lines + 1] = csv_row(scene, r) end
  write(dir .. "/" .. scene.name .. ".csv", table.concat(lines, "\n") .. "\n")
  local labels, by = {}, {}
  for _, r in ipairs(rows) do
    if not by[r.line] then
      by[r.line] = {}
      labels[#labels + 1] = r.line
    end
    if r.error < math.huge then table.insert(by[r.line], r) end
  end
  local blocks = {}
  for _, l in ipairs(labels) do
    local pts = by[l]
    table.sort(pts, function(a, b) return a.us_per_s < b.us_per_s end)
    local b = { "# " .. l }
    for _, r in ipairs(pts) do b[#b + 1] = ("%.6g %.6g"):format(r.us_per_s, math.max(r.error, FLOOR)) end
    if #pts == 0 then b[#b + 1] = "nan nan" end
    blocks[#blocks + 1] = table.concat(b, "\n")
  end
  write(dir .. "/" .. scene.name .. ".dat", table.concat(blocks, "\n\n\n") .. "\n")
  local front = {}
  for _, r in ipairs(rows) do if r.pareto then front[#front + 1] = r end end
  table.sort(front, function(a, b) return a.us_per_s < b.us_per_s end)
  local f = {}
  for _, r in ipairs(front) do f[#f + 1] = ("%.6g %.6g"):format(r.us_per_s, math.max(r.error, FLOOR)) end
  if #f == 0 then f[1] = "nan nan" end
  write(dir .. "/" .. scene.name .. ".front", table.concat(f, "\n") .. "\n")
  local gp = dir .. "/" .. scene.name .. ".gp"
  write(gp, plot_script(scene, dir, labels))
  if os.execute("command -v gnuplot >/dev/null 2>&1") then
    if os.execute("gnuplot " .. ("%q"):format(gp)) then return dir .. "/" .. scene.name .. ".png" end
  end
  return nil
end

local function describe(r)
  return ("%s dt 1/%d, %d × %d %s%s"):format(r.cfg.integrator, math.floor(1 / r.cfg.dt + 0.5), r.cfg.substeps,
    r.cfg.iterations, r.cfg.solver == "jacobi" and "jacobi" or "gs",
    r.cfg.travel > 0 and (", max_travel %g"):format(r.cfg.travel) or "")
end
atlas.describe = describe

-- The front as text: cheapest first, the error it buys.
function atlas.summary(scene, rows)
  local front = {}
  for _, r in ipairs(rows) do if r.pareto then front[#front + 1] = r end end
  table.sort(front, function(a, b) return a.us_per_s < b.us_per_s end)
  local out = { ("%s — %s; front (cheapest first):"):format(scene.name, scene.error_name or "error") }
  for _, r in ipairs(front) do
    out[#out + 1] = ("  %10.3g µs/particle/s  error %-10.3g %s"):format(r.us_per_s, r.error, describe(r))
  end
  return table.concat(out, "\n")
end

local function usage()
  return "usage: tether atlas [--quick] [--out DIR] [--repeats N] [--only NAME] [--instructions] [SCRIPT [args…]]\n"
    .. "  SCRIPT returns a scene table (or a list of them): see lua/tether_atlas.lua; without one, the built-in scenes"
end

local function parse(args)
  local o = { out = "build/atlas", scripts = {} }
  local i = 1
  while i <= #args do
    local a = args[i]
    if a == "--quick" then o.quick = true
    elseif a == "--out" then i = i + 1; o.out = args[i]
    elseif a == "--repeats" then i = i + 1; o.repeats = tonumber(args[i])
    elseif a == "--only" then i = i + 1; o.only = args[i]
    elseif a == "--instructions" then o.instructions = true
    elseif a == "--help" or a == "-h" then return nil, usage()
    elseif a:sub(1, 2) == "--" then return nil, "tether atlas: unknown option " .. a .. "\n" .. usage()
    else
      o.script = a
      o.script_args = { table.unpack(args, i + 1) }
      break
    end
    i = i + 1
  end
  if not o.out or (o.repeats and not (o.repeats >= 1)) then return nil, usage() end
  return o
end

local function load_scenes(o)
  if not o.script then return require("tether_atlas_scenes").scenes(o.quick) end
  local chunk, err = loadfile(o.script)
  if not chunk then error(err, 0) end
  local s = chunk(o.quick, table.unpack(o.script_args))
  if type(s) ~= "table" then error(o.script .. ": must return a scene table or a list of them", 0) end
  if s.build then s = { s } end
  for _, sc in ipairs(s) do
    for _, k in ipairs { "name", "build", "error", "duration" } do
      if sc[k] == nil then error(("%s: scene %s has no '%s'"):format(o.script, tostring(sc.name), k), 0) end
    end
  end
  return s
end

-- The command line; returns an exit status.
function atlas.main(...)
  local o, msg = parse({ ... })
  if not o then
    io.stderr:write(msg, "\n")
    return msg == usage() and 0 or 2
  end
  local ok, scenes = pcall(load_scenes, o)
  if not ok then
    io.stderr:write("tether atlas: ", tostring(scenes), "\n")
    return 1
  end
  local probe
  if o.instructions then
    local found
    found, probe = pcall(require, "tether_probe")
    if not found or not probe.running() then
      io.stderr:write("tether atlas: --instructions counts under callgrind: sh bench/atlas_cg.sh (make atlas-cg)\n")
      return 2
    end
  end
  os.execute("mkdir -p " .. ("%q"):format(o.out))
  local all = { atlas.CSV_HEADER }
  local t0 = os.time()
  for _, scene in ipairs(scenes) do
    if not o.only or o.only == scene.name then
      local rows = atlas.sweep(scene, { repeats = probe and 1 or o.repeats or (o.quick and 1 or 3), probe = probe })
      local png = atlas.write(scene, rows, o.out)
      for _, r in ipairs(rows) do all[#all + 1] = csv_row(scene, r) end
      print(atlas.summary(scene, rows))
      print("  " .. (png or ("no gnuplot: no plot (" .. o.out .. "/" .. scene.name .. ".gp)")))
      io.stdout:flush()
    end
  end
  write(o.out .. "/atlas.csv", table.concat(all, "\n") .. "\n")
  print(("atlas: %d points in %d s; CSV %s/atlas.csv"):format(#all - 1, os.time() - t0, o.out))
  return 0
end

atlas.tether = tether
return atlas
