-- tests/fuzz/fuzz_lib.lua — what the Lua API fuzzer and the replay scripts it
-- writes share: the pools of things made so far, the hostile values, and
-- F.call, which makes one call under pcall and checks what tether promises:
--   * a call that raises names its function (never '?') and leaves every
--     world exactly as it was (same hash), unless the script's own callbacks
--     ran during it (they may change the world legitimately);
--   * nothing a call returns is NaN or Inf;
--   * after a step no particle's position or velocity is NaN, Inf or past
--     1e15, and energy and stats are finite.
-- A broken promise raises an error starting "FUZZ FAILURE".
local F = {}
-- The harness's helpers that let one source run under Lua 5.4 and LuaJIT.
package.path = "tests/lua/?.lua;" .. package.path
local T = require "harness"
F.T = T

F.W, F.H, F.IMG = {}, {}, {}   -- worlds, integer handles, images: in the order made
F.MASK = {}                    -- masks, in the order made
F.CLK = {}                     -- clocks, in the order made
F.callbacks = 0                -- bumped by every hostile callback that runs
F.counts = {}                  -- calls per function, "world.particle" = 12
F.fns = {}                     -- "world.particle" → the function

local NAN, INF = 0 / 0, math.huge

function F.fail(fmt, ...)
  error("FUZZ FAILURE: " .. string.format(fmt, ...), 0)
end

-- m:save and w:save write a file wherever their path says, and the
-- fuzzer's paths are strings such as "x" or "1": each goes under FUZZ_OUT
-- (default /tmp) as fuzz-<path>, never into the working tree (w:save, new
-- with snapshot files, once left "nan", "rk4", "42" … in the repository root).
local SAVE_DIR = os.getenv("FUZZ_OUT") or "/tmp"
local function confined_save(save)
  return function(m, path, ...)
    if type(path) == "string" or type(path) == "number" then
      path = SAVE_DIR .. "/fuzz-" .. (tostring(path):gsub("/", "_"))
    end
    return save(m, path, ...)
  end
end

-- Registers every function of a table under prefix.
function F.register(prefix, t)
  for k, v in pairs(t) do
    if type(v) == "function" then
      local writes = k == "save" and (prefix == "masks" or prefix == "world")
      F.fns[prefix .. "." .. k] = writes and confined_save(v) or v
    end
  end
end

function F.fn(name)
  return F.fns[name] or F.fail("unknown function %s", name)
end

local function is_world(v)
  return type(v) == "userdata" and tostring(v):find("^tether.world") ~= nil
end

local function is_image(v)
  return type(v) == "userdata" and tostring(v):find("^tether.image") ~= nil
end

local function is_mask(v)
  return type(v) == "userdata" and tostring(v):find("^tether.mask") ~= nil
end

local function is_clock(v)
  return type(v) == "userdata" and tostring(v):find("^tether.clock") ~= nil
end

local function alive(w)
  return is_world(w) and not tostring(w):find("destroyed", 1, true)
end
F.alive = alive

-- Results go to the pools: integers are handles (of any kind), worlds and
-- images by type. The replay does the same, so the indices agree.
local function keep(r)
  for i = 2, r.n do
    local v = r[i]
    if T.isint(v) then F.H[#F.H + 1] = v
    elseif is_world(v) then F.W[#F.W + 1] = v
    elseif is_image(v) then F.IMG[#F.IMG + 1] = v
    elseif is_mask(v) then F.MASK[#F.MASK + 1] = v
    elseif is_clock(v) then F.CLK[#F.CLK + 1] = v
    end
  end
end

local function finite_values(v, where, depth)
  if type(v) == "number" then
    if v ~= v or v == INF or v == -INF then F.fail("%s returned %s", where, tostring(v)) end
  elseif type(v) == "table" and depth > 0 and getmetatable(v) == nil then
    for _, x in pairs(v) do finite_values(x, where, depth - 1) end
  end
end

local function finite(x, what)
  if not (x == x and x > -1e15 and x < 1e15) then F.fail("%s is %s", what, tostring(x)) end
end

-- Every particle, energy and stat of a live world is finite and bounded.
-- The getters run under pcall: a finalizer may destroy the world midway.
function F.check_world(w)
  if not alive(w) then return end
  local ok, xy, n = pcall(w.positions, w)
  if not ok then return end
  for i = 1, 2 * n do finite(xy[i], "a position") end
  local ok2, ps = pcall(w.particles, w)
  for _, p in ipairs(ok2 and ps or {}) do
    local ok3, vx, vy = pcall(w.velocity, w, p)
    if ok3 then finite(vx, "a velocity"); finite(vy, "a velocity") end
  end
  local ok4, e = pcall(w.energy, w)
  if ok4 then finite_values(e, "energy", 1) end
  local ok5, st = pcall(w.stats, w)
  if ok5 then finite_values(st, "stats", 2) end
end

local function hashes()
  local h = {}
  -- pcall: a finalizer may destroy the world between the check and the hash
  for i, w in ipairs(F.W) do if alive(w) then local ok, x = pcall(w.hash, w); h[i] = ok and x or nil end end
  return h
end

-- One call: fn(...) under pcall, then the checks above.
function F.call(name, ...)
  local fn = F.fn(name)
  F.counts[name] = (F.counts[name] or 0) + 1
  local cb = F.callbacks -- a finalizer may run inside hashes() too: read the count first
  local before = hashes()
  local r = T.pack(pcall(fn, ...))
  if not r[1] then
    local msg = r[2]
    if type(msg) == "string" and msg:find("^FUZZ FAILURE") then error(msg, 0) end
    if type(msg) ~= "string" then F.fail("%s raised a %s, not a message", name, type(msg)) end
    if msg:find("to '?'", 1, true) or msg == "" then F.fail("%s: the error names no function: %s", name, msg) end
    local changed
    for i, h in pairs(before) do
      local ok, now = pcall(F.W[i].hash, F.W[i])
      if ok and now ~= h then changed = changed or i end
    end
    if changed and F.callbacks == cb then F.fail("%s failed (%s) yet world %d changed", name, msg, changed) end
    return msg
  end
  -- a table the caller passed in comes back refilled ("a given table is
  -- reused"): what the call did not write there is the caller's own
  local given = {}
  for i = 1, select("#", ...) do local v = select(i, ...); if type(v) == "table" then given[v] = true end end
  for i = 2, r.n do if not given[r[i]] then finite_values(r[i], name, 2) end end
  keep(r)
  if name == "world.step" then for _, w in ipairs(F.W) do F.check_world(w) end end
end

-- Hostile values. Each callback bumps F.callbacks before it acts.
local function act(w, what)
  F.callbacks = F.callbacks + 1
  if not alive(w) then return end
  if what == "destroy" then w:destroy()
  elseif what == "step" then pcall(w.step, w, 1 / 60)
  elseif what == "remove" then local ps = w:particles(); if ps[1] then pcall(w.remove, w, ps[#ps]) end
  elseif what == "add" then pcall(w.particle, w, 0, 0)
  elseif what == "gc" then collectgarbage()
  end
end

-- An option table whose every read runs `what` on w and then answers v.
function F.hostile_index(w, what, v)
  return setmetatable({}, { __index = function() act(w, what); return v end })
end

-- A sequence whose length is `len` (2.5, -1, 1e300 …) and whose reads act.
function F.hostile_len(w, what, len)
  return setmetatable({ 1, 2, 3, 4 }, { __len = function() act(w, what); return len end,
                                        __index = function() act(w, what); return 1 end })
end

-- Garbage whose finalizer runs `what` on w: finalizers run at any allocation,
-- in the middle of a binding call.
function F.finalizer(w, what)
  T.finalized(function() act(w, what) end)
  return nil
end

function F.callback(w, what)
  return function() act(w, what); return 1 end
end

F.NAN, F.INF = NAN, INF
return F
