-- tests/lua/test_terrain.lua — terrains from Lua: made from a mask (copied:
-- the mask may change at once), carved and filled, seen by particles,
-- raycasts, contact events and snapshots, and bad input raising errors that
-- name the function and the argument, with the world left as it was.
package.path = "tests/lua/?.lua;" .. package.path
local T = require "harness"
local tether = require "tether"
local M = tether.mask

-- A 200 x 100 mask, solid from row 50 to 59: a floor from y = -2.5 to -3.0 m at 0.05 m a pixel.
local function floor_mask()
  local m = M.new(200, 100)
  m:fill_rect(0, 50, 200, 10, true)
  return m
end

T.test("a ball rests on the floor and falls through a carved hole", function()
  local w = tether.world {}
  local m = floor_mask()
  local t = w:terrain(m, { pixel = 0.05 })
  m:clear() -- the terrain has its own copy
  T.ok(w:terrain_is_valid(t), "valid"); T.eq(w:terrain_count(), 1, "count")
  T.ok(w:terrain_solid(t, 5, -2.75), "solid in the floor")
  local p = w:particle(5, -1, { radius = 0.2 })
  w:step(1 / 60, 180)
  local _, y = w:position(p)
  T.near(y, -2.5 + 0.2, 0.05, "rests within a pixel")
  w:carve(t, 5, -2.75, 0.6)
  T.ok(not w:terrain_solid(t, 5, -2.75), "carved")
  w:step(1 / 60, 60)
  _, y = w:position(p)
  T.ok(y < -3.2, "fell through")
  w:fill(t, 5, -2.75, 0.6)
  T.ok(w:terrain_solid(t, 5, -2.75), "filled again")
  T.ok(w:terrain_solid(t, 5, -2.3), "the whole circle: above the floor too")
  w:carve_mask(t, M.new(200, 100, true), 0, 0)
  w:fill_mask(t, floor_mask(), 0, 0)
  local copy = w:terrain_mask(t)
  T.eq(copy:count(), floor_mask():count(), "the pixels back")
  T.eq(copy:overlap_area(floor_mask(), 0, 0), floor_mask():count(), "the same pixels")
  local ox, oy, px = w:terrain_place(t)
  T.ok(ox == 0 and oy == 0 and px == 0.05, "place")
end)

T.test("raycast, events and distance see the terrain", function()
  local w = tether.world {}
  local t = w:terrain(floor_mask(), { origin = { 1, 0 } })
  local hit = w:raycast(4, 0, 4, -5)
  T.ok(hit and hit.terrain == t, "the ray hits the terrain")
  T.near(hit.y, -2.5, 0.02, "at its surface")
  local d, nx, ny = w:terrain_distance(t, 4, -2.3)
  T.near(d, 0.2, 0.01, "distance"); T.near(ny, 1, 1e-6, "normal up"); T.near(nx, 0, 1e-6, "normal x")
  w:set_collision { events = { "begin" } }
  w:particle(4, -2, { radius = 0.2 })
  local seen = false
  for _ = 1, 60 do
    w:step(1 / 60)
    for _, e in ipairs(w:contacts()) do if e.terrain == t then seen = true end end
  end
  T.ok(seen, "a begin event names the terrain")
end)

T.test("events restored from a snapshot keep their terrain", function()
  local w = tether.world {}
  local t = w:terrain(floor_mask())
  w:set_collision { events = { "begin", "persist", "end" } }
  local p = w:particle(5, -2.25, { radius = 0.2 })
  w:step(1 / 60, 30)
  local snap = w:snapshot()
  w:set_position(p, 5, 0)
  w:step(1 / 60, 5) -- off the floor: no contact now
  T.eq(#w:contacts(), 0, "no contact before the restore")
  T.ok(w:restore(snap), "the snapshot loads")
  local ev = w:contacts()
  T.eq(#ev, 1, "one contact")
  T.ok(ev[1].terrain == t and ev[1].kind == "persist", "the restored event names the terrain")
  w:set_position(p, 5, 0)
  w:step(1 / 60)
  ev = w:contacts()
  T.ok(#ev == 1 and ev[1].kind == "end" and ev[1].terrain == t, "its end too")
end)

T.test("point and box queries list the terrain", function()
  local w = tether.world {}
  local t = w:terrain(floor_mask()) -- solid from y = -2.5 to -3 m, x from 0 to 10 m
  local ps, ss, ts = w:query_point(5, -2.75)
  T.ok(#ps == 0 and #ss == 0 and #ts == 1 and ts[1] == t, "a point in the floor")
  _, _, ts = w:query_point(5, -2.4)
  T.eq(#ts, 0, "a point above it")
  _, _, ts = w:query_aabb(1, -2.55, 2, -2)
  T.ok(#ts == 1 and ts[1] == t, "a box reaching into it")
  _, _, ts = w:query_aabb(1, -2.45, 2, -2)
  T.eq(#ts, 0, "a box above it")
  _, _, ts = w:query_point(5, -2.75, 2)
  T.eq(#ts, 0, "another layer")
  w:carve(t, 5, -2.75, 0.3)
  _, _, ts = w:query_point(5, -2.75)
  T.eq(#ts, 0, "carved")
end)

T.test("snapshot, carve, restore gives the terrain back", function()
  local w = tether.world {}
  local t = w:terrain(floor_mask())
  w:particle(5, -1, { radius = 0.2 })
  w:step(1 / 60, 10)
  local snap, h0 = w:snapshot(), w:hash()
  w:carve(t, 5, -2.75, 1)
  T.ok(w:hash() ~= h0, "carving changes the hash")
  w:restore(snap)
  T.eq(w:hash(), h0, "restored")
  T.ok(w:terrain_solid(t, 5, -2.75), "the pixels back")
end)

T.test("bad input raises, naming the function and argument, and changes nothing", function()
  local w = tether.world {}
  local h0 = w:hash()
  T.checkerror("bad argument #2 to 'terrain'", w.terrain, w, "x")
  T.checkerror("terrain: bad option 'pixel' (finite number expected, got nan)", w.terrain, w, floor_mask(), { pixel = 0 / 0 })
  T.checkerror("terrain: bad option 'band' (integer in [5, 32] expected, got 2)", w.terrain, w, floor_mask(), { band = 2 })
  T.checkerror("unknown option", w.terrain, w, floor_mask(), { pixle = 1 })
  T.eq(w:hash(), h0, "nothing made")
  local t = w:terrain(floor_mask())
  local p = w:particle(0, 0)
  local h1 = w:hash()
  T.checkerror("bad argument #3 to 'carve' %(finite number expected", w.carve, w, t, 0 / 0, 0, 1)
  T.checkerror("bad argument #5 to 'carve'", w.carve, w, t, 0, 0, -1)
  T.checkerror("bad argument #2 to 'carve' %(terrain expected, got particle%)", w.carve, w, p, 0, 0, 1)
  T.checkerror("bad argument #3 to 'carve_mask'", w.carve_mask, w, t, {}, 0, 0)
  T.checkerror("bad argument #3 to 'terrain_mask'", w.terrain_mask, w, t, M.new(3, 3))
  T.eq(w:hash(), h1, "nothing changed")
  -- an option table whose metamethod removes the terrain's mask from reach: the terrain copies it at once
  local m = floor_mask()
  local opts = setmetatable({}, { __index = function() m = nil; collectgarbage(); return nil end })
  local t2 = w:terrain(m, opts)
  T.ok(w:terrain_is_valid(t2), "made")
  w:remove_terrain(t)
  T.checkerror("bad argument #2 to 'carve' %(stale terrain handle%)", w.carve, w, t, 0, 0, 1)
  T.ok(not w:terrain_is_valid(t), "stale")
  T.eq(w:terrain_count(), 1, "one left")
end)

T.done()
