-- tests/lua/test_snapfile.lua — snapshot files from Lua: w:save(path),
-- w:restore_file(path), tether.world{file = path}: round trips with user
-- values, and damaged, foreign or missing files refused with the world unchanged.
package.path = "tests/lua/?.lua;" .. package.path
local T = require "harness"
local tether = require "tether"

local function scene()
  local w = tether.world { substeps = 2 }
  w:set_collision { friction = 0.3 }
  w:segment(-10, 0, 10, 0)
  local ps = {}
  for i = 1, 60 do ps[i] = w:particle(-6 + (i % 12), 1 + math.floor(i / 12), { radius = 0.3, user = { id = i } }) end
  w:spring(ps[1], ps[2], { stiffness = 50 })
  return w, ps
end

local function run(w, n) for _ = 1, n do w:step(1 / 60) end end

local function slurp(path)
  local f = assert(io.open(path, "rb")); local s = f:read("a") or f:read("*a"); f:close(); return s
end
local function spit(path, s)
  local f = assert(io.open(path, "wb")); f:write(s); f:close()
end

local path, bad = os.tmpname(), os.tmpname()

T.test("save, step, restore_file: the same state and the same future, user values back", function()
  local w, ps = scene()
  run(w, 30)
  T.eq(w:save(path), true)
  local h30 = w:hash()
  w:set_user(ps[1], { id = "changed" })
  run(w, 30)
  local h60 = w:hash()
  T.eq(w:restore_file(path), true)
  T.eq(w:hash(), h30)
  T.eq(w:user(ps[1]).id, 1, "the user value saved")
  run(w, 30)
  T.eq(w:hash(), h60)
  -- into a new world
  local w2 = tether.world { file = path }
  T.eq(w2:hash(), h30)
  T.eq(w2:user(ps[5]).id, 5)
  run(w2, 30)
  T.eq(w2:hash(), h60)
  -- without user values, and a file the C API wrote
  T.eq(w:save(path, false), true)
  T.eq(tether.world { file = path }:user(ps[5]), nil)
end)

T.test("damaged, foreign and missing files: nil and a reason, the world unchanged", function()
  local w = scene()
  run(w, 10)
  T.eq(w:save(path), true)
  run(w, 10)
  local h = w:hash()
  local good = slurp(path)
  local cases = {
    { good:sub(1, #good - 1), "truncated or padded" },
    { good .. "x", "truncated or padded" },
    { good:sub(1, 30), "truncated" },
    { "just some text, not a tether file at all .................................", "not a tether snapshot file" },
    { good:sub(1, 200) .. string.char((good:byte(201) + 1) % 256) .. good:sub(202), "checksum mismatch" },
  }
  for i, c in ipairs(cases) do
    spit(bad, c[1])
    local ok, msg = w:restore_file(bad)
    T.eq(ok, nil, "case " .. i)
    T.ok(msg:find("restore_file: '" .. bad .. "'", 1, true) and msg:find(c[2], 1, true), msg)
    T.eq(w:hash(), h, "unchanged, case " .. i)
    T.checkerror("tether.world: '" .. bad .. "': .*" .. c[2], tether.world, { file = bad })
  end
  local ok, msg = w:restore_file("/nonexistent-dir/none.tts")
  T.ok(ok == nil and msg:find("cannot open"), msg)
  ok, msg = w:save("/nonexistent-dir/none.tts")
  T.ok(ok == nil and msg:find("save: cannot open"), msg)
  T.eq(w:hash(), h)
end)

T.test("bad arguments raise, naming the function and argument", function()
  local w = scene()
  T.checkerror("bad argument #2 to 'save' (string expected, got table)", w.save, w, {})
  T.checkerror("bad argument #3 to 'save'", w.save, w, path, "yes")
  T.checkerror("bad argument #2 to 'restore_file'", w.restore_file, w, nil)
  T.checkerror("bad option 'file' (string expected, got table)", tether.world, { file = {} })
  T.checkerror("option 'file' takes no other option", tether.world, { file = path, gravity = { 0, 0 } })
  w:set_user(w:particle(0, 0), { f = print })
  T.checkerror("save: a user value holds a value that is not plain data (nil, boolean, number, string, table): " ..
    "only plain data can be written as bytes (w:save(path, false) leaves the user values out)", w.save, w, path)
  T.eq(w:save(path, false), true)
end)

os.remove(path)
os.remove(bad)
T.done()
