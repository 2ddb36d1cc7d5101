-- tests/fuzz/fuzz_api.lua — a seeded fuzzer of the whole Lua API, run by the
-- runner with PNG frames so drawing is fuzzed inside tether.draw:
--   build/tether --headless --frames 1000000 --every 20 --size 96x72 --out DIR tests/fuzz/fuzz_api.lua
-- Environment: FUZZ_SEED (default: the clock), FUZZ_SECONDS (default 10),
-- FUZZ_CALLS (stop after this many calls), FUZZ_SKIP (call numbers drawn
-- but not called, "12,40-97" or "@FILE" holding such a list: the
-- minimiser's knob), FUZZ_REPLAY (where
-- the replay script goes; default DIR/replay.lua).
-- Under a plain host (LUA_CPATH='build/luajit/?.so' luajit tests/fuzz/fuzz_api.lua,
-- or lua5.4) it runs the update phase alone, the same calls for a seed.
-- Every module function, world method and metamethod, gfx function, image
-- method, tether.mask function and mask method is called with hostile arguments: wrong types, NaN, ±Inf, 1e300,
-- denormals, huge integers, stale and foreign handles, option tables whose
-- reads call back into the world, finalizers that destroy it mid-call. The
-- checks are fuzz_lib's. Before each call its line is written (and flushed)
-- to the replay script, so even a crash leaves a script that replays it.
-- At the end: "fuzz: N calls, seed S, every function reached" and
-- "N passed, 0 failed"; a function never reached is a failure.
package.path = "tests/fuzz/?.lua;" .. package.path
local F = require "fuzz_lib"
tether = tether or require "tether" -- the runner's global, or a plain host's module

local seed = tonumber(os.getenv("FUZZ_SEED") or "") or os.time()
local seconds = tonumber(os.getenv("FUZZ_SECONDS") or "") or 10
local max_calls = tonumber(os.getenv("FUZZ_CALLS") or "") or math.huge
-- FUZZ_KEEP_GOING=1: report each kind of failure once and go on (a campaign's survey)
local keep_going = os.getenv("FUZZ_KEEP_GOING") == "1"
local found = {}
local skip = {}
do -- "12,40-97", or "@FILE" holding such a list (minimise.lua skips thousands)
  local list = os.getenv("FUZZ_SKIP") or ""
  if list:sub(1, 1) == "@" then
    local fh = assert(io.open(list:sub(2)))
    list = fh:read("*a")
    fh:close()
  end
  for a, b in list:gmatch("(%d+)%-?(%d*)") do
    for k = tonumber(a), tonumber(b ~= "" and b or a) do skip[k] = true end
  end
end
local out_dir = tether.runner and tether.runner.out or "."
local replay_path = os.getenv("FUZZ_REPLAY") or (out_dir .. "/replay.lua")

local T = F.T
-- exact in doubles: the same calls on every machine, and in both Luas, for a seed
local uniform = T.minstd(seed)
local function rand(n) return math.floor(uniform() * n) + 1 end
local function pick(t) return t[rand(#t)] end

-- Replay script: a prelude, then one line per call in the phase it ran in.
local replay = assert(io.open(replay_path, "w"))
replay:write(string.format([[
-- replay of fuzz_api.lua, seed %d: build/tether --headless --frames 1000000 --every 20 --size 96x72 --out DIR THIS_FILE
package.path = "tests/fuzz/?.lua;" .. package.path
local F = require "fuzz_lib"
local W, H, IMG, MASK, CLK = F.W, F.H, F.IMG, F.MASK, F.CLK
local NAN, INF = F.NAN, F.INF
local UP, DR, u, d = {}, {}, 0, 0
local function at(t, k, f) t[k] = t[k] or {}; table.insert(t[k], f) end
local function U(k, f) at(UP, k, f) end
local function D(k, f) at(DR, k, f) end
F.register("tether", tether)
-- Under a plain host (luajit, lua5.4) there are no frames: gfx only raises
-- "nothing to draw on", so only the runner fuzzes it.
if tether.runner then F.register("gfx", tether.gfx) end
local wm = getmetatable(tether.world())
F.register("world", wm.__index); F.register("world", wm)
F.register("mask", tether.mask)
local mm = getmetatable(tether.mask.new(1, 1))
F.register("masks", mm.__index); F.register("masks", mm)
local cm = getmetatable(tether.clock())
F.register("clocks", cm.__index); F.register("clocks", cm)
function tether.update()
  u = u + 1
  for _, f in ipairs(UP[u] or {}) do f() end
  if u > #UP and d >= #DR then tether.quit() end
end
function tether.draw(g)
  d = d + 1
  if d == 1 then local m = getmetatable(g.new_image(1, 1)); F.register("image", m.__index); F.register("image", m) end
  for _, f in ipairs(DR[d] or {}) do f(g) end
end
-- the calls, in order: U(k, …) in the k-th update, D(k, …) in the k-th frame
]], seed))
local names = {}
local calls = 0
local learn

-- What each argument of each function wants, learnt from the errors it
-- raises ("bad argument #3 to 'particle' (number expected, got table)"), so
-- later calls get past the checks more often and reach deeper: into the
-- option tables (where the hostile reads wait), the steps and the events.
local wants = {}
local KINDS = { { "tether.world", "world" }, { "tether.image", "image" }, { "tether.mask", "mask" }, { "tether.clock", "clock" }, { "table", "table" },
                { "particle", "handle1" }, { "spring", "handle2" }, { "constraint", "handle3" },
                { "shape", "handle4" }, { "composite", "handle5" }, { "handle", "handle" },
                { "integer", "integer" }, { "number", "number" },
                { "string", "string" }, { "boolean", "boolean" } }
learn = function(name, msg)
  if type(msg) ~= "string" then return end
  local i, what = msg:match("bad argument #(%d+) to '[^']*' %(([^)]*) expected")
  if not i then return end
  for _, k in ipairs(KINDS) do
    if what:find(k[1], 1, true) then
      wants[name] = wants[name] or {}
      wants[name][tonumber(i)] = k[2]
      return
    end
  end
end
local phase = "U(0, function() "
-- Writes the call's replay line (flushed: a crash leaves it) and makes it.
local function emit(name, n, args, srcs)
  calls = calls + 1
  if skip[calls] then return end
  replay:write(string.format("%sF.call(%q%s%s) end) -- %d\n", phase, name, n > 0 and ", " or "",
                             table.concat(srcs, ", ", 1, n), calls))
  replay:flush()
  if not keep_going then return learn(name, F.call(name, T.unpack(args, 1, n))) end
  local ok, msg = pcall(F.call, name, T.unpack(args, 1, n))
  if ok then learn(name, msg) else
    local kind = tostring(msg):gsub("[%d%.e+-]+", "#"):sub(1, 160)
    if not found[kind] then
      found[kind] = calls
      io.stderr:write(string.format("fuzz: call %d: %s\n", calls, tostring(msg)))
    end
  end
end

-- Values, each with the Lua source that makes it again in the replay.
local function num_src(v)
  if v ~= v then return "NAN" elseif v == math.huge then return "INF" elseif v == -math.huge then return "-INF" end
  if T.isint(v) and (math.type or math.abs(v) < 2 ^ 53) then
    if v == math.mininteger then return "math.mininteger" end
    return string.format("%d", v)
  end
  return string.format("%.17g", v)
end

local NUMBERS = { 0, -0.0, 1, -1, 2, 0.5, 1.5, 3, 10, 100, 1e-9, 1e-12, 1e12, -1e12, 1e13, 1e300, -1e300,
                  5e-324, 1e-320, 0 / 0, math.huge, -math.huge, math.maxinteger or 2 ^ 63, math.mininteger or -2 ^ 63, 2 ^ 53,
                  65535, 65536, 1 / 60, 0.1, 4, 16, 1000 }
local STRINGS = { "", "x", "rigid", "max", "min", "fill", "line", "world", "screen", "verlet", "euler",
                  "symplectic_euler", "leapfrog", "rk4", "jacobi", "gauss_seidel", "keep", "reset", "grid",
                  "brute", "destroy", "1", "nan" }
local KEYS = { "mass", "radius", "vx", "vy", "pinned", "user", "category", "mask", "restitution", "friction",
               "friction_static", "friction_kinetic", "stiffness", "damping", "rest", "length", "mode",
               "compliance", "break_strain", "collide", "anchor", "particles", "outside", "min", "max", "area",
               "pressure", "start", "finish", "segments", "pin_start", "pin_finish", "slack", "origin", "width",
               "height", "columns", "rows", "shear_stiffness", "bend_stiffness", "pin_top_corners",
               "pin_top_row", "position", "limits", "center", "ring_radius", "area_stiffness", "area_compliance",
               "angle", "points", "box", "sensor", "loop", "integrator", "gravity", "wind", "substeps",
               "max_travel", "max_substeps",
               "iterations", "tolerance", "solver", "dt_hint", "capacity", "max_particles", "cell_size",
               "broadphase", "shapes", "constraints", "springs", "color", "min_radius", "bullet", "events",
               "max_rate", "x", "y", "pair_particles", "spin", "sleep" }
local ACTIONS = { "destroy", "step", "remove", "add", "gc" }

local value -- forward

local function number()
  if rand(3) == 1 then return pick(NUMBERS) end
  local v = (rand(2001) - 1001) / 100
  return v
end

local function world_src()
  if #F.W == 0 then return nil, "nil" end
  local i = rand(#F.W)
  return F.W[i], "W[" .. i .. "]"
end

-- A handle, mostly a recent one; of kind k (tether/base.h: bits 52…50) when
-- k is given and one is found among the last 40 tried.
local function handle(k)
  if #F.H == 0 or rand(10) == 1 then local v = pick(NUMBERS); return v, num_src(v) end
  local i = #F.H - rand(math.min(#F.H, 40)) + 1 -- mostly recent ones
  if k and rand(8) > 1 then
    for _ = 1, 40 do
      local j = #F.H - rand(math.min(#F.H, 200)) + 1
      if T.shr(F.H[j], 50) == k then i = j; break end
    end
  end
  return F.H[i], "H[" .. i .. "]"
end

local function plain_table(depth)
  local t, src = {}, {}
  local kind = rand(4)
  if kind == 1 then                              -- a point or a list of numbers
    for i = 1, rand(8) do local v = number(); t[i] = v; src[i] = num_src(v) end
    if rand(4) == 1 then for i = #t + 1, 70 do t[i] = (i % 7) * 0.3; src[i] = num_src(t[i]) end end
  elseif kind == 2 then                          -- a list of handles
    for i = 1, rand(6) do local v, s = handle(); t[i] = v; src[i] = s end
  else                                           -- an option table
    for _ = 1, rand(5) do
      local k = pick(KEYS)
      local v, s = value(depth + 1)
      t[k] = v
      src[#src + 1] = "[" .. string.format("%q", k) .. "] = " .. s
    end
  end
  return t, "{" .. table.concat(src, ", ") .. "}"
end

function value(depth)
  depth = depth or 0
  local r = rand(depth > 1 and 6 or 22)
  if r <= 2 then local v = number(); return v, num_src(v)
  elseif r <= 4 then return handle()
  elseif r == 5 then return nil, "nil"
  elseif r == 6 then local b = rand(2) == 1; return b, tostring(b)
  elseif r <= 8 then local s = pick(STRINGS); return s, string.format("%q", s)
  elseif r <= 13 then return plain_table(depth)
  elseif r == 14 then return world_src()
  elseif r == 15 then
    if #F.MASK > 0 and rand(2) == 1 then local i = rand(#F.MASK); return F.MASK[i], "MASK[" .. i .. "]" end
    if #F.IMG == 0 then return nil, "nil" end
    local i = rand(#F.IMG); return F.IMG[i], "IMG[" .. i .. "]"
  end
  local w, ws = world_src()
  local what = pick(ACTIONS)
  if r == 16 then
    local v, s = value(depth + 1)
    return F.hostile_index(w, what, v), string.format("F.hostile_index(%s, %q, %s)", ws, what, s)
  elseif r == 17 then
    local len = pick { 2.5, -1, 1e300, 0, 3, 100000, NAN = nil }
    return F.hostile_len(w, what, len), string.format("F.hostile_len(%s, %q, %s)", ws, what, num_src(len))
  elseif r == 18 then
    return F.callback(w, what), string.format("F.callback(%s, %q)", ws, what)
  elseif r == 19 then
    return F.finalizer(w, what), string.format("F.finalizer(%s, %q)", ws, what)
  end
  local v = number()
  return v, num_src(v)
end

-- One random call of a function under prefix; self is usually right.
local function wanted(kind)
  if kind == "number" then local v = number(); return v, num_src(v)
  elseif kind == "integer" then local v = rand(8) - 1; return v, tostring(v)
  elseif kind == "handle" then return handle()
  elseif kind:match("^handle%d$") then return handle(tonumber(kind:sub(-1)))
  elseif kind == "world" then return world_src()
  elseif kind == "image" and #F.IMG > 0 then local i = rand(#F.IMG); return F.IMG[i], "IMG[" .. i .. "]"
  elseif kind == "mask" and #F.MASK > 0 then local i = rand(#F.MASK); return F.MASK[i], "MASK[" .. i .. "]"
  elseif kind == "clock" and #F.CLK > 0 then local i = rand(#F.CLK); return F.CLK[i], "CLK[" .. i .. "]"
  elseif kind == "table" and rand(3) == 1 then -- an option table whose reads act on a world
    local w, ws = world_src()
    local what = pick(ACTIONS)
    local v, vs = value(1)
    return F.hostile_index(w, what, v), string.format("F.hostile_index(%s, %q, %s)", ws, what, vs)
  elseif kind == "table" then return plain_table(1)
  elseif kind == "string" then local v = pick(STRINGS); return v, string.format("%q", v)
  elseif kind == "boolean" then local b = rand(2) == 1; return b, tostring(b)
  end
  return value()
end

local function one_call(prefix, self, self_src)
  local list = names[prefix]
  local name = pick(list)
  local args, srcs = {}, {}
  local n = rand(7) - 1
  if self ~= nil and rand(12) > 1 then args[1], srcs[1] = self, self_src; n = n + 1 end
  local want = wants[name] or {}
  local most = 0
  for i in pairs(want) do if i > most then most = i end end
  if most > n and rand(4) > 1 then n = most + rand(2) - 1 end
  for i = #args + 1, n do
    if want[i] and rand(4) > 1 then args[i], srcs[i] = wanted(want[i]) else args[i], srcs[i] = value() end
  end
  emit(name, n, args, srcs)
end

local function list_of(prefix)
  local l = {}
  -- tether.quit ends the run: it is called once, at the end
  for k in pairs(F.fns) do if k:sub(1, #prefix + 1) == prefix .. "." and k ~= "tether.quit" then l[#l + 1] = k end end
  table.sort(l) -- pairs order is not the same from run to run
  names[prefix] = l
end

F.register("tether", tether)
-- Under a plain host (luajit, lua5.4) there are no frames: gfx only raises
-- "nothing to draw on", so only the runner fuzzes it.
if tether.runner then F.register("gfx", tether.gfx) end
local wm = getmetatable(tether.world())
F.register("world", wm.__index)
F.register("world", wm)
F.register("mask", tether.mask)
local mm = getmetatable(tether.mask.new(1, 1))
F.register("masks", mm.__index)
F.register("masks", mm)
local cm = getmetatable(tether.clock())
F.register("clocks", cm.__index)
F.register("clocks", cm)
list_of("tether"); list_of("world"); list_of("mask"); list_of("masks"); list_of("clocks")
-- The update phase: world methods and module functions, steps weighted up.
local start = os.clock()
local updates, draws = 0, 0
local done = false
local function over()
  return calls >= max_calls or os.clock() - start > seconds
end

function tether.update()
  if done then return end
  updates = updates + 1
  phase = string.format("U(%d, function() ", updates)
  local live = 0
  for _, w in ipairs(F.W) do if F.alive(w) then live = live + 1 end end
  if live == 0 or rand(200) == 1 then emit("tether.world", 0, {}, {}) end
  for _ = 1, 20 do
    if over() then done = true; break end
    local w, ws = world_src()
    -- pcall: a finalizer run by the string alive() makes may destroy the world before count
    local big = F.alive(w) and select(2, pcall(w.count, w))
    if type(big) == "number" and big > 600 then -- big worlds only slow the calls down
      emit("world.destroy", 1, { w }, { ws })
    elseif rand(10) == 1 then
      one_call("tether", nil, nil)
    elseif rand(12) == 1 and #F.CLK > 0 then -- clocks: tether.clock makes them (one_call "tether")
      local i = rand(#F.CLK)
      one_call("clocks", F.CLK[i], "CLK[" .. i .. "]")
    elseif rand(5) == 1 then -- masks: made from small sizes often enough to be used
      if #F.MASK == 0 or rand(6) == 1 then
        local wd, ht, full = rand(140), rand(70), rand(2) == 1
        emit("mask.new", 3, { wd, ht, full }, { tostring(wd), tostring(ht), tostring(full) })
      elseif rand(4) == 1 then
        one_call("mask", nil, nil)
      else
        local i = rand(#F.MASK)
        one_call("masks", F.MASK[i], "MASK[" .. i .. "]")
      end
    else
      one_call("world", w, ws)
    end
  end
end

-- The end of the run: what was found, what was never reached.
local function report()
  replay:close()
  if tether.quit then F.call("tether.quit") end
  local missing = {}
  for k in pairs(F.fns) do if not F.counts[k] then missing[#missing + 1] = k end end
  table.sort(missing)
  local nf, nr = 0, 0
  for _ in pairs(F.fns) do nf = nf + 1 end
  for _ in pairs(F.counts) do nr = nr + 1 end
  print(string.format("fuzz: %d calls in %.1f s, seed %d, %d of %d functions reached", calls, os.clock() - start,
                      seed, nr, nf))
  local kinds = 0
  for _ in pairs(found) do kinds = kinds + 1 end
  if kinds > 0 then
    print(string.format("fuzz: %d kinds of failure (first call of each above)", kinds))
    print("0 passed, 1 failed")
  end
  if #missing > 0 then print("fuzz: never reached: " .. table.concat(missing, " ")) end
  if kinds > 0 then
  elseif #missing > 0 and max_calls == math.huge then
    print("0 passed, 1 failed")
  else
    print("1 passed, 0 failed")
  end
end

function tether.draw(g)
  if done then return report() end
  draws = draws + 1
  if draws == 1 then
    local m = getmetatable(g.new_image(1, 1))
    F.register("image", m.__index); F.register("image", m)
    list_of("gfx"); list_of("image")
  end
  phase = string.format("D(%d, function(g) ", draws)
  for _ = 1, 40 do
    local r = rand(4)
    if r == 1 and (#F.IMG == 0 or rand(8) == 1) then -- random sizes are rarely valid: make some
      local wd, ht = rand(40), rand(40)
      emit("gfx.new_image", 2, { wd, ht }, { tostring(wd), tostring(ht) })
    elseif r == 1 then
      local i = rand(#F.IMG)
      one_call("image", F.IMG[i], "IMG[" .. i .. "]")
    elseif r == 2 then
      local w, ws = world_src()
      local o, os_ = value()
      emit("world.draw", 2, { w, o }, { ws, os_ })
    else
      one_call("gfx", nil, nil)
    end
  end
end

-- A plain host: no runner calls update and draw, so the script does.
if not tether.runner then
  while not done do tether.update(1 / 60) end
  report()
  os.exit(0, true)
end
