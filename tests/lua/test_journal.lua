-- tests/lua/test_journal.lua — replay journals: a recorded 10 000-call
-- random sequence of world-changing calls between steps replays to the
-- recorded hash at every step, in the same process and from a file into a
-- new world; a corrupted or cut file is refused with the world unchanged;
-- desyncs are reported at their step; bad arguments raise.
package.path = "tests/lua/?.lua;" .. package.path
local T = require "harness"
local tether = require "tether"

local tmp = os.tmpname()
local function tmpfile(name) return tmp .. "." .. name end

-- A seeded random session: CALLS world-changing calls (particles, springs,
-- constraints, composites, shapes, impulses and forces, removals, set_*),
-- a step every 8 calls. Calls may fail (a removed handle, a value out of
-- range): a failed call changes nothing, and that too must replay.
local CALLS = 10000
local function session(w, seed, on_step)
  local rand = T.minstd(seed)
  local function pick(t) return t[1 + math.floor(rand() * #t)] end
  local function num(lo, hi) return lo + (hi - lo) * rand() end
  local ps, springs, cons, shapes, comps = {}, {}, {}, {}, {}
  local function p() return ps[1 + math.floor(rand() * math.max(#ps, 1))] or 0 end
  local function add(list, ok, h) if ok and h then list[#list + 1] = h end end
  local calls = {
    function() add(ps, pcall(w.particle, w, num(-8, 8), num(1, 9), { radius = num(0.1, 0.4), mass = num(0.5, 2) })) end,
    function() add(ps, pcall(w.particle, w, num(-8, 8), num(1, 9), { radius = 0.2, velocity = { num(-3, 3), num(-3, 3) } })) end,
    function() pcall(w.remove, w, p()) end,
    function() pcall(w.set_position, w, p(), num(-8, 8), num(1, 9)) end,
    function() pcall(w.set_velocity, w, p(), num(-5, 5), num(-5, 5)) end,
    function() pcall(w.apply_impulse, w, p(), num(-1, 1), num(-1, 1)) end,
    function() pcall(w.apply_force, w, p(), num(-20, 20), num(-20, 20)) end,
    function() pcall(w.set_mass, w, p(), num(0.2, 3)) end,
    function() pcall(w.set_pinned, w, p(), rand() < 0.3) end,
    function() pcall(w.set_radius, w, p(), num(0.05, 0.5)) end,
    function() pcall(w.set_filter, w, p(), 1 + math.floor(rand() * 3), 0xFFFF) end,
    function() pcall(w.explode, w, num(-5, 5), num(0, 5), num(0.5, 4), num(0, 2)) end,
    function() add(springs, pcall(w.spring, w, p(), p(), { stiffness = num(10, 200), damping = num(0, 2) })) end,
    function() pcall(w.remove_spring, w, pick(springs) or 0) end,
    function() pcall(w.set_spring, w, pick(springs) or 0, { stiffness = num(10, 100) }) end,
    function() add(cons, pcall(w.distance, w, p(), p(), { stiffness = num(0.2, 1) })) end,
    function() add(cons, pcall(w.pin, w, p(), { anchor = { num(-5, 5), num(2, 8) } })) end,
    function() add(cons, pcall(w.angle, w, p(), p(), p(), { min = 0.5, max = 2.5 })) end,
    function() pcall(w.remove_constraint, w, pick(cons) or 0) end,
    function() pcall(w.set_constraint, w, pick(cons) or 0, { stiffness = num(0.1, 1) }) end,
    function() add(comps, pcall(w.rope, w, { start = { num(-6, 0), 8 }, finish = { num(0, 6), 8 }, segments = 5, radius = 0.1 })) end,
    function() pcall(w.remove_composite, w, pick(comps) or 0) end,
    function() add(shapes, pcall(w.circle, w, num(-6, 6), num(0, 4), num(0.3, 1))) end,
    function() add(shapes, pcall(w.box, w, num(-6, 6), num(0, 4), num(0.2, 1), num(0.2, 1))) end,
    function() pcall(w.remove_shape, w, pick(shapes) or 0) end,
    function() pcall(w.set_shape_transform, w, pick(shapes) or 0, num(-6, 6), num(0, 4), num(-1, 1)) end,
    function() pcall(w.set_shape_material, w, pick(shapes) or 0, num(0, 1), num(0, 1), num(0, 0.5)) end,
    function() pcall(w.set_material, w, p(), num(0, 1), num(0, 1), num(0, 0.5)) end,
    function() pcall(w.set_bullet, w, p(), rand() < 0.5) end,
    function() w:set_gravity(num(-2, 2), num(-12, -5)) end,
    function() w:set_wind(num(-1, 1), 0) end,
    function() w:set_damping(num(0, 0.5)) end,
    function() w:set_integrator(pick { "verlet", "symplectic_euler", "leapfrog", "verlet" }) end,
    function() w:set_substeps(1 + math.floor(rand() * 3)) end,
    function() w:set_travel(rand() < 0.5 and 0 or num(0.2, 1), 1 + math.floor(rand() * 4)) end,
    function() w:set_iterations(2 + math.floor(rand() * 8)) end,
    function() w:set_solver(pick { "gauss_seidel", "jacobi" }) end,
    function() w:set_sleep(rand() < 0.5) end,
    function() w:set_attractor(1 + math.floor(rand() * 2), num(-3, 3), num(2, 6), num(-5, 5), 0.5) end,
    function() w:set_collision { friction = num(0, 0.8), restitution = num(0, 0.5) } end,
    function() pcall(w.set_pair_collision, w, p(), p(), rand() < 0.5) end,
  }
  for i = 1, CALLS do
    calls[1 + math.floor(rand() * #calls)]()
    if i % 8 == 0 then
      w:step(pick { 1 / 60, 1 / 60, 1 / 60, 1 / 30 })
      if on_step then on_step(w) end
    end
    -- a small world, so that the test stays quick: the oldest of each kind goes
    if #ps > 40 then pcall(w.remove, w, table.remove(ps, 1)) end
    if #comps > 2 then pcall(w.remove_composite, w, table.remove(comps, 1)) end
    if #shapes > 6 then pcall(w.remove_shape, w, table.remove(shapes, 1)) end
    if #cons > 20 then pcall(w.remove_constraint, w, table.remove(cons, 1)) end
    if #springs > 20 then pcall(w.remove_spring, w, table.remove(springs, 1)) end
  end
end

local function arena()
  local w = tether.world { gravity = { 0, -9.81 } }
  w:set_collision { friction = 0.3 }
  w:bounds(-10, -1, 10, 12)
  w:segment(-10, 0, 10, 0)
  return w
end

T.test("a 10 000-call random session replays to the recorded hash at every step, here and from a file", function()
  local w = arena()
  local j = w:journal()
  local hashes = {}
  session(w, 20261202, function(world) hashes[#hashes + 1] = world:hash() end)
  T.eq(j:steps(), #hashes)
  T.eq(j:steps(), CALLS / 8)
  T.ok(j:recording())
  j:stop()
  T.ok(not j:recording())
  local info = j:info()
  T.ok(info.changed > 0.9 * info.steps, "calls before nearly every step: " .. info.changed .. " of " .. info.steps)
  T.ok(info.bytes >= info.record_bytes + info.snapshot_bytes)
  -- into the same world: step by step, then the rest at once
  j:replay(w)
  for s = 1, 300 do
    T.eq(j:step(), "sync", "step " .. s)
    if w:hash() ~= hashes[s] then T.eq(w:hash(), hashes[s], "step " .. s); break end
  end
  local where, played = j:run()
  T.eq(where, "end")
  T.eq(played, #hashes - 300)
  T.eq(w:hash(), hashes[#hashes])
  T.eq(j:step(), "end")
  -- saved, loaded (as another process would), into a new world
  local path = tmpfile("session.ttj")
  T.eq(j:save(path), true)
  local k = assert(tether.load_journal(path))
  T.eq(k:steps(), #hashes)
  local fresh = tether.world()
  k:replay(fresh)
  for s = 1, #hashes do
    T.eq(k:step(), "sync", "file, step " .. s)
    if fresh:hash() ~= hashes[s] then T.eq(fresh:hash(), hashes[s], "file, step " .. s); break end
  end
  T.eq(k:step(), "end")
  T.eq(k:desync(), nil)
  os.remove(path)
end)

T.test("a corrupted, cut or foreign file is refused, naming it, and the world is unchanged", function()
  local w = arena()
  local j = w:journal()
  for i = 1, 60 do
    if i % 10 == 0 then w:particle(0, 8, { radius = 0.3 }) end
    w:step(1 / 60)
  end
  j:stop()
  local path, bad = tmpfile("good.ttj"), tmpfile("bad.ttj")
  assert(j:save(path))
  local f = assert(io.open(path, "rb"))
  local bytes = f:read("a")
  f:close()
  local function write(s) local g = assert(io.open(bad, "wb")); g:write(s); g:close() end
  local other = arena()
  other:particle(1, 1)
  local h = other:hash()
  for _, s in ipairs {
    bytes:sub(1, #bytes - 1), bytes:sub(1, 47), bytes:sub(1, 100), bytes .. "x",
    bytes:sub(1, 60) .. string.char((bytes:byte(61) + 1) % 256) .. bytes:sub(62),
    bytes:sub(1, #bytes - 5) .. "xxxxx", "not a journal at all",
  } do
    write(s)
    local k, msg = tether.load_journal(bad)
    T.eq(k, nil)
    T.ok(msg:find(bad, 1, true), msg)
  end
  T.eq(other:hash(), h)
  -- a snapshot file is no journal, and a journal file no snapshot
  assert(other:save(bad))
  local k, msg = tether.load_journal(bad)
  T.eq(k, nil)
  T.ok(msg:find("not a replay journal", 1, true), msg)
  local ok, why = other:restore_file(path)
  T.eq(ok, nil)
  T.ok(why:find("replay journal", 1, true), why)
  T.eq(other:hash(), h)
  os.remove(path)
  os.remove(bad)
end)

T.test("a desync is reported at its step; a journal records from its start; misuse raises", function()
  local w = arena()
  for i = 1, 20 do w:particle(-5 + i * 0.5, 3, { radius = 0.2 }) end
  local j = w:journal { max_bytes = 1e6 }
  T.checkerror("journal: the world is journaled already", w.journal, w)
  for _ = 1, 30 do w:step(1 / 60) end
  T.checkerror("step: the journal is recording", j.step, j)
  T.checkerror("replay: the journal is recording", j.replay, j, w)
  j:stop()
  j:stop()
  T.checkerror("step: no replay begun", j.step, j)
  local r = tether.world()
  j:replay(r)
  for _ = 1, 10 do T.eq(j:step(), "sync") end
  r:set_gravity(0, -9)
  local s, n = j:run()
  T.eq(s, "desync")
  T.eq(n, 1)
  local at, expected, got = j:desync()
  T.eq(at, 11)
  T.eq(got, r:hash())
  T.ok(expected ~= got and #expected == 16)
  T.eq(j:info().replayed, 11)
  T.checkerror("unknown option 'max_byte'", w.journal, w, { max_byte = 1 })
  T.checkerror("bad option 'max_bytes'", w.journal, w, { max_bytes = 10 })
  T.checkerror("bad argument #2 to 'replay' %(tether.world expected", j.replay, j, {})
  T.checkerror("bad argument #1 to 'step' %(tether.journal expected", j.step, {})
  T.ok(tostring(j):match("^tether.journal %(30 steps, %d+ bytes%)$"), tostring(j))
  T.ok(tostring(w:journal()):match("recording"))
  r:destroy()
  T.checkerror("its world was destroyed", j.step, j)
  j:destroy()
  j:destroy()
  T.eq(tostring(j), "tether.journal (destroyed)")
  T.checkerror("the journal was destroyed", j.steps, j)
  T.checkerror("bad argument #1 to 'tether.load_journal'", tether.load_journal, {})
end)

T.test("a world destroyed while recording: the journal stops and keeps what it holds", function()
  local w = arena()
  local j = w:journal()
  w:particle(0, 5)
  for _ = 1, 12 do w:step(1 / 60) end
  local h = w:hash()
  w:destroy()
  T.ok(not j:recording())
  T.eq(j:steps(), 12)
  local r = tether.world()
  j:replay(r)
  T.eq(j:run(), "end")
  T.eq(r:hash(), h)
  collectgarbage()
end)

-- The C fuzzer's desync (seed 1796210282), from Lua: a world of a velocity
-- integrator whose only shape went after a step that met it, then a particle
-- made (the end positions of the last substep no longer hold). The recorded
-- world kept new ones at every step and the replay, loaded without the
-- arrays for them, did not: step 1 desynced.
T.test("a velocity integrator's world whose shapes are gone replays in sync", function()
  for _, integrator in ipairs { "euler", "symplectic_euler", "leapfrog", "rk4" } do
    local w = tether.world()
    w:set_integrator(integrator)
    w:particle(0, 0.55, { radius = 0.05 })
    local s = w:circle(0, 0, 0.5)
    w:step(1 / 60)
    w:remove_shape(s)
    w:particle(3, 0)
    local j = w:journal()
    local hashes = {}
    for k = 1, 6 do w:step(1 / 60); hashes[k] = w:hash() end
    j:stop()
    local fresh = tether.world()
    j:replay(fresh)
    for k = 1, 6 do
      T.eq(j:step(), "sync", integrator .. ", step " .. k)
      T.eq(fresh:hash(), hashes[k], integrator .. ", step " .. k)
    end
  end
end)

T.done()
