-- tests/lua/test_snapshot.lua — w:snapshot(), w:restore(s), tether.world{snapshot = s}:
-- a restored world repeats the same steps bit for bit, per-particle user
-- values follow the restore, a bad stream is refused with the world unchanged.
package.path = "tests/lua/?.lua;" .. package.path
local T = require "harness"
local tether = require "tether"

-- Every feature: springs, each constraint kind, a torn cloth, composites,
-- shapes of each kind (one moved by the script), contacts with friction and
-- events, a bullet, materials, removals.
local function scene()
  local w = tether.world { substeps = 2, iterations = 6 }
  w:set_collision { friction = 0.4, restitution = 0.1, events = { "begin", "persist", "end" } }
  w:segment(-10, -2, 10, -2)
  w:chain { -10, 0, -5, -1, 0, -1.5, 5, -1, 10, 0 }
  w:aabb(-11, -3, -10, 10)
  local kin = w:box(6, 1, 1, 0.2, { angle = 0.2 })
  w:circle(-3, 1, 0.5)
  w:capsule(2, 0, 4, 0.5, 0.2)
  w:polygon { -6, 2, -5, 2, -5.5, 3 }
  local cloth = w:cloth { origin = { -2, 6 }, width = 2, height = 2, columns = 8, rows = 8, break_strain = 0.2,
                          shear_stiffness = 0.1, radius = 0.05 }
  w:rope { start = { 3, 6 }, finish = { 6, 6 }, segments = 6, radius = 0.1 }
  w:ragdoll { position = { -6, 5 }, radius = 0.1 }
  w:soft_body { center = { 1, 9 }, radius = 0.8, segments = 10 }
  local ps = {}
  for i = 1, 40 do
    ps[i] = w:particle(-8 + i * 0.4, 3 + (i % 3), { radius = 0.15, user = { id = i } })
  end
  w:set_material(ps[1], 0.8, 0.1)
  w:set_bullet(ps[2], true)
  w:set_pair_collision(ps[3], ps[4], false)
  w:spring(ps[5], ps[6], { stiffness = 80, damping = 0.2 })
  local d = w:distance(ps[7], ps[8], { mode = "max" })
  local pin = w:pin(ps[9])
  local hem = w:composite_particles(cloth)
  local grab = w:pin(hem[#hem]) -- a hand on the hem's corner that tears the cloth (drive)
  w:angle(ps[10], ps[11], ps[12])
  w:area { ps[13], ps[14], ps[15] }
  w:collinear(ps[16], ps[17], ps[18])
  w:bounds(-10, -3, 10, 30)
  for i = 20, 24 do w:remove(ps[i]) end
  local step = 0
  local function drive()
    step = w:stats().steps
    w:set_shape_transform(kin, 6 + math.sin(step / 30), 1, 0.2)
    if step % 50 == 0 then w:set_constraint(d, { length = 0.2 + (step % 100) / 200 }) end
    if step % 70 == 0 then w:set_constraint(pin, { anchor = { -4.4 + math.sin(step) * 0.3, 4 } }) end
    if step % 90 == 0 then w:explode(0, 0, 3, 1) end
    if step == 200 then w:set_constraint(grab, { anchor = { -6, 14 } }) end
    w:step(1 / 60)
  end
  return w, ps, drive, cloth
end

T.test("snapshot, 1000 steps, restore, 1000 steps: the same hash twice", function()
  local w, ps, drive = scene()
  for _ = 1, 30 do drive() end
  local s = w:snapshot()
  local h0 = w:hash()
  local torn, contacts = 0, 0
  for _ = 1, 1000 do
    drive()
    torn = torn + #w:break_events()
    contacts = contacts + #w:contacts()
  end
  local h1 = w:hash()
  T.ok(h1 ~= h0, "the steps changed the world")
  T.ok(torn > 0, "the cloth tore")
  T.ok(contacts > 0, "contacts were reported")
  T.eq(w:restore(s), true)
  T.eq(w:hash(), h0, "restored")
  for _ = 1, 1000 do drive() end
  T.eq(w:hash(), h1, "the same 1000 steps")
end)

T.test("a new world from a snapshot or its bytes continues as the original", function()
  local w, _, drive = scene()
  for _ = 1, 45 do drive() end
  local s = w:snapshot()
  local copy = tether.world { snapshot = s }
  local from_bytes = tether.world { snapshot = s:bytes() }
  T.eq(copy:hash(), w:hash())
  T.eq(from_bytes:hash(), w:hash())
  for _ = 1, 300 do copy:step(1 / 60); from_bytes:step(1 / 60); w:step(1 / 60) end
  T.eq(copy:hash(), w:hash())
  T.eq(from_bytes:hash(), w:hash())
  T.eq(#s, #s:bytes(false))
  T.ok(tostring(s):match("^tether.snapshot %(%d+ bytes%)"), tostring(s))
end)

T.test("user values follow a restore", function()
  local w, ps = scene()
  local s = w:snapshot()
  w:set_user(ps[1], "changed")
  w:remove(ps[2])
  local extra = w:particle(0, 20, { user = "made after" })
  w:step(1 / 60)
  T.eq(w:restore(s), true)
  T.eq(w:user(ps[1]).id, 1)
  T.eq(w:user(ps[2]).id, 2)
  T.ok(w:is_valid(ps[2]), "the removed particle is back")
  T.ok(not w:is_valid(extra), "the particle made after is gone")
  T.eq(w:user(ps[30]).id, 30)
  -- the snapshot keeps its own copy: changes after a restore do not reach it
  w:set_user(ps[1], "again")
  T.eq(w:restore(s), true)
  T.eq(w:user(ps[1]).id, 1)
  local copy = tether.world { snapshot = s }
  T.eq(copy:user(ps[3]).id, 3)
  -- bytes carry them (plain data), unless asked not to
  local saved = tether.world { snapshot = s:bytes() }
  T.eq(saved:user(ps[3]).id, 3)
  T.ok(saved:is_valid(ps[3]), "the saved handle is valid in the loaded world")
  local bare = tether.world { snapshot = s:bytes(false) }
  T.eq(bare:user(ps[3]), nil)
  T.eq(bare:hash(), saved:hash())
end)

T.test("user values written as bytes: plain data round-trips, the rest is refused", function()
  local w = tether.world {}
  local nested = { name = "crate", hp = 3.5, tags = { "wood", "small", [10] = true }, flag = false, big = T.maxint }
  local a = w:particle(0, 0, { user = nested })
  local b = w:particle(1, 0, { user = "plain string\0with a zero" })
  local c = w:particle(2, 0, { user = -0.25 })
  local bytes = w:snapshot():bytes()
  T.eq(bytes:sub(1, 4), "TTLU")
  local l = tether.world { snapshot = bytes }
  local got = l:user(a)
  T.eq(got.name, "crate"); T.eq(got.hp, 3.5); T.eq(got.tags[2], "small"); T.eq(got.tags[10], true)
  T.eq(got.flag, false); T.eq(got.big, T.maxint); T.ok(T.isint(got.big), "an integer stays an integer")
  T.eq(l:user(b), "plain string\0with a zero"); T.eq(l:user(c), -0.25)
  w:set_user(a, "changed")
  T.eq(w:restore(bytes), true)
  T.eq(w:user(a).tags[1], "wood")
  -- not plain data: refused when written, with the way out named
  w:set_user(c, function() end)
  T.checkerror("bytes: a user value holds a value that is not plain data", w:snapshot().bytes, w:snapshot())
  local cyc = {}; cyc.self = cyc
  w:set_user(c, cyc)
  T.checkerror("nested too deep (or a cycle)", w:snapshot().bytes, w:snapshot())
  w:set_user(c, setmetatable({}, {}))
  T.checkerror("a table with a metatable", w:snapshot().bytes, w:snapshot())
  T.ok(#w:snapshot():bytes(false) > 0)
  -- a corrupted envelope is refused, the world unchanged
  local h = w:hash()
  for _, cut in ipairs { 3, 10, 17, #bytes - 1 } do
    local ok, msg = w:restore(bytes:sub(1, cut))
    T.eq(ok, nil, "cut at " .. cut); T.ok(msg:match("unchanged"), msg)
  end
  local ok, msg = w:restore(bytes .. "\1")
  T.eq(ok, nil); T.ok(msg:match("user values are corrupted"), msg)
  T.eq(w:hash(), h)
  T.checkerror("tether.world: its user values are corrupted", tether.world, { snapshot = bytes .. "\1" })
  -- every byte of the envelope changed in turn: refused with the world unchanged, or a world (no checksum
  -- guards the user values: a changed string or number is still plain data)
  local small = tether.world {}
  small:particle(0, 0, { user = { 1, "two", { three = 3.0 } } })
  local env = small:snapshot():bytes()
  local before = small:snapshot():bytes()
  for i = 1, #env do
    local bad = env:sub(1, i - 1) .. string.char(T.bxor(env:byte(i), 0x21)) .. env:sub(i + 1)
    if small:restore(bad) then
      small:step(1 / 60)
      small:restore(env)
    else
      T.ok(small:snapshot():bytes() == before, "byte " .. i .. ": refused but changed")
    end
  end
end)

T.test("a truncated, corrupted or foreign stream is refused, the world unchanged", function()
  local w = tether.world {}
  local p = w:particle(0, 0, { radius = 0.2 })
  w:spring(p, w:particle(1, 0))
  w:segment(-1, -1, 1, -1)
  w:step(1 / 60)
  local bytes = w:snapshot():bytes()
  w:step(1 / 60)
  local before = w:snapshot():bytes()
  local function refused(s, what)
    local ok, msg = w:restore(s)
    T.eq(ok, nil, what)
    T.ok(type(msg) == "string" and msg:match("unchanged"), what .. ": " .. tostring(msg))
    T.ok(w:snapshot():bytes() == before, what .. ": world unchanged")
  end
  for _, n in ipairs { 0, 1, 31, 32, 33, T.idiv(#bytes, 2), #bytes - 1 } do refused(bytes:sub(1, n), "truncated to " .. n) end
  for i = 1, #bytes do
    local b = bytes:byte(i)
    local bad = bytes:sub(1, i - 1) .. string.char(T.bxor(b, 0x10)) .. bytes:sub(i + 1)
    local ok = w:restore(bad)
    if ok then T.ok(false, "byte " .. i .. " changed: accepted") break end
  end
  refused("PK\3\4 a zip file, not a snapshot, and long enough to have a header", "foreign")
  refused(bytes .. "x", "one byte too many")
  T.checkerror("bad argument #2 to 'restore' (tether.snapshot or string expected, got number)", w.restore, w, 42)
  T.checkerror("tether.world: tt_world_load: ", tether.world, { snapshot = "nope" })
  T.checkerror("option 'snapshot' takes no other option", tether.world, { snapshot = bytes, gravity = { 0, 0 } })
  T.eq(w:restore(bytes), true)
end)

T.done()
