-- tests/lua/harness.lua — a tiny test harness for the Lua binding tests.
--
--   package.path = "tests/lua/?.lua;" .. package.path
--   local T = require "harness"
--   T.test("name", function() T.near(x, 1, 1e-9) end)
--   T.checkerror("bad argument #2 to 'position'", w.position, w, "x")
--   T.done()   -- prints "N passed, M failed"; exits non-zero when M > 0
--
-- Failures are reported on stderr as they happen; T.done prints exactly one
-- line on stdout. checkerror accepts its pattern as plain text or as a Lua
-- pattern, so messages with parentheses need no escaping: error messages
-- are part of the contract.
local T = {}

-- The tests run under Lua 5.4 and under LuaJIT (Lua 5.1, numbers are all
-- doubles): test sources use no 5.3 operator (<<, &, //, ~) and no
-- <close>; these helpers stand in, and give integers in 5.4.
T.LUAJIT = type(jit) == "table"
local pack = table.pack or function(...) return { n = select("#", ...), ... } end
local unpack = table.unpack or unpack
T.pack, T.unpack = pack, unpack
--- x (an integer-valued number) as an integer subtype where Lua has one.
function T.int(x) return math.tointeger and math.tointeger(x) or x end
--- Is v an integer: the integer subtype in 5.4, an integral double in LuaJIT.
function T.isint(v)
  if math.type then return math.type(v) == "integer" end
  return type(v) == "number" and v == math.floor(v) and v == v and v - v == 0
end
--- a * 2^n and floor(a / 2^n): shifts of non-negative integers below 2^53.
function T.shl(a, n) return T.int(a * 2 ^ n) end
function T.shr(a, n) return T.int(math.floor(a / 2 ^ n)) end
--- floor(a / b) for integers.
function T.idiv(a, b) return T.int(math.floor(a / b)) end
--- a xor b for integers in [0, 2^31): the 5.3 operator where Lua has it
--- (loaded as text, so LuaJIT never parses it), LuaJIT's bit library there.
T.bxor = bit and bit.bxor or load("return function(a, b) return a ~ b end")()
--- The largest integer both Luas hold exactly: math.maxinteger in 5.4, 2^53 - 1 in LuaJIT.
T.maxint = math.maxinteger or 2 ^ 53 - 1
--- The 8 bytes of a double, little-endian (string.pack in 5.4, the FFI in LuaJIT).
function T.double_bytes(x)
  if string.pack then return string.pack("<d", x) end
  local ffi = require "ffi"
  local u = ffi.new("union { double d; uint8_t b[8]; }")
  u.d = x
  local b, le = {}, ffi.abi("le")
  for i = 0, 7 do b[#b + 1] = string.char(u.b[le and i or 7 - i]) end
  return table.concat(b)
end
--- FNV-1a 64 over strings, in four 16-bit limbs so that every product is
--- exact in a double: the same digest under both Luas as 5.4's integer
--- arithmetic. fnv.new() starts, fnv.add(h, s) feeds, fnv.hex(h) gives %016x.
T.fnv = {}
function T.fnv.new() return { 0x2325, 0x8422, 0x9ce4, 0xcbf2 } end -- 0xcbf29ce484222325
function T.fnv.add(h, s)
  for k = 1, #s do
    local lo = h[1] % 256
    h[1] = h[1] - lo + T.bxor(lo, s:byte(k))
    -- h * 0x100000001b3 = h * 0x1b3 + h * 2^40 (mod 2^64), limb by limb
    local r, carry = {}, 0
    for i = 1, 4 do
      local v = h[i] * 0x1b3 + carry
      if i == 3 then v = v + h[1] * 256 end
      if i == 4 then v = v + h[2] * 256 end
      r[i] = v % 65536
      carry = math.floor(v / 65536)
    end
    h[1], h[2], h[3], h[4] = r[1], r[2], r[3], r[4]
  end
  return h
end
function T.fnv.hex(h) return ("%04x%04x%04x%04x"):format(h[4], h[3], h[2], h[1]) end
--- An integer as the binding writes it in a message (exact in both).
function T.istr(v) return math.type and tostring(v) or string.format("%d", v) end
--- A deterministic generator that is exact in doubles (MINSTD): rand() in
--- [0, 1), the same sequence under both Luas.
function T.minstd(seed)
  local s = seed % 2147483646 + 1
  return function()
    s = s * 48271 % 2147483647
    return (s - 1) / 2147483646
  end
end
--- The collector made to run a whole cycle at (nearly) every allocation
--- check, and back to the host's defaults. LuaJIT finishes a cycle, its
--- finalizers included, inside one step only with a huge step multiplier.
function T.gc_eager()
  if T.LUAJIT then collectgarbage("setpause", 1); collectgarbage("setstepmul", 1000000)
  else collectgarbage("incremental", 1, 1000) end
end
function T.gc_default()
  if T.LUAJIT then collectgarbage("setpause", 200); collectgarbage("setstepmul", 200)
  else collectgarbage("incremental", 200, 100) end
end
--- An object whose finalizer calls fn: a table in 5.4; LuaJIT runs __gc on
--- userdata only, so a proxy there.
function T.finalized(fn)
  if newproxy then
    local u = newproxy(true)
    getmetatable(u).__gc = fn
    return u
  end
  return setmetatable({}, { __gc = fn })
end

local passed, failed = 0, 0
local current = nil   -- name of the running test
local checks = 0      -- checks failed inside the current test

local function where(level)
  local info = debug.getinfo(level + 1, "Sl")
  if info then return info.short_src .. ":" .. (info.currentline or 0) end
  return "?"
end

local function fail(msg, level)
  checks = checks + 1
  io.stderr:write(("FAIL %s: %s (%s)\n"):format(current or "(top level)", msg, where((level or 1) + 1)))
end

--- Runs fn as one test: it passes when it raises nothing and no check failed.
function T.test(name, fn)
  current, checks = name, 0
  local ok, err = xpcall(fn, debug.traceback)
  if not ok then
    io.stderr:write(("FAIL %s: error: %s\n"):format(name, tostring(err)))
    checks = checks + 1
  end
  if checks == 0 then passed = passed + 1 else failed = failed + 1 end
  current = nil
end

--- Checks that a condition holds.
function T.ok(cond, msg)
  if not cond then fail(msg or "condition is false", 2) end
  return cond
end

--- Checks a == b (raw equality).
function T.eq(a, b, msg)
  if a ~= b then fail(("%s: expected %s, got %s"):format(msg or "eq", tostring(b), tostring(a)), 2) end
  return a == b
end

--- Checks |a - b| <= tol (both numbers, neither NaN).
function T.near(a, b, tol, msg)
  local good = type(a) == "number" and type(b) == "number" and math.abs(a - b) <= tol
  if not good then
    fail(("%s: expected %s within %g, got %s (diff %s)"):format(msg or "near", tostring(b), tol, tostring(a),
      (type(a) == "number" and type(b) == "number") and tostring(a - b) or "?"), 2)
  end
  return good
end

-- Does err contain `what`? Plain text always counts; unless plain_only, a
-- Lua pattern match counts too (an invalid pattern is just no match).
local function contains(err, what, plain_only)
  if string.find(err, what, 1, true) then return true end
  if plain_only then return false end
  local ok, found = pcall(string.find, err, what)
  return ok and found ~= nil
end

local function check_error(plain, what, fn, ...)
  local ok, err = pcall(fn, ...)
  if ok then
    fail(("expected an error matching %q, got none"):format(what), 3)
    return false
  end
  err = tostring(err)
  if not contains(err, what, plain) then
    fail(("expected an error matching %q, got %q"):format(what, err), 3)
    return false
  end
  return true, err
end

--- pcall(fn, ...) must fail with a message that contains `pattern`, either
--- as plain text or as a Lua pattern match (string.find). Returns ok, message.
function T.checkerror(pattern, fn, ...)
  return check_error(false, pattern, fn, ...)
end

--- As checkerror, but `text` must appear literally.
function T.checkerror_plain(text, fn, ...)
  return check_error(true, text, fn, ...)
end

--- pcall(fn, ...) must succeed; returns its results.
function T.noerror(fn, ...)
  local r = pack(pcall(fn, ...))
  if not r[1] then fail("unexpected error: " .. tostring(r[2]), 2) end
  return unpack(r, 2, r.n)
end

--- True if x is a NaN or an infinity.
function T.nonfinite(x)
  return x ~= x or x == math.huge or x == -math.huge
end

--- Counts of the tests so far.
function T.counts() return passed, failed end

--- Prints "N passed, M failed" and exits (non-zero when M > 0).
function T.done()
  io.stdout:write(("%d passed, %d failed\n"):format(passed, failed))
  io.stdout:flush()
  os.exit(failed == 0 and 0 or 1, true)
end

return T
