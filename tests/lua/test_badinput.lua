-- tests/lua/test_badinput.lua — every public function and method, fed wrong
-- types, NaN, ±Inf, huge and out-of-range numbers, stale and never-made
-- handles, and a destroyed world. Each call must raise an error whose
-- message names the function and the argument, must leave the world exactly
-- as it was (same hash), and no NaN may ever reach the world.
package.path = "tests/lua/?.lua;" .. package.path
local T = require "harness"
local tether = require "tether"

local NAN, INF = 0 / 0, math.huge
local function fn() end
local NIL = setmetatable({}, { __tostring = function() return "NIL" end }) -- stands for an explicit nil

local function show(v)
  if v == NIL then return "nil" end
  if type(v) == "string" then return string.format("%q", v) end
  return tostring(v)
end

-- Wrong types every typed argument must refuse, with the type name in the
-- message: a userdata by its class's __name (Lua 5.4 names files "FILE*",
-- LuaJIT does not name them).
local FILE = (getmetatable(io.stdout) or {}).__name or "userdata"
local WRONG_TYPES = {
  { NIL, "nil" }, { "x", "string" }, { "1", "string" }, { {}, "table" }, { true, "boolean" },
  { false, "boolean" }, { fn, "function" }, { io.stdout, FILE }, { coroutine.create(fn), "thread" },
}

-- Bad values of a number kind: wrong types, non-finite, out of range.
local function number_bad(range, out_of_range)
  local bad = {}
  for _, t in ipairs(WRONG_TYPES) do bad[#bad + 1] = { t[1], "number expected, got " .. t[2] } end
  bad[#bad + 1] = { NAN, "finite number expected, got nan" }
  bad[#bad + 1] = { -NAN, "finite number expected, got nan" }
  bad[#bad + 1] = { INF, "finite number expected, got inf" }
  bad[#bad + 1] = { -INF, "finite number expected, got -inf" }
  for _, v in ipairs(out_of_range) do
    bad[#bad + 1] = { v, "number in " .. range .. " expected, got " }
  end
  return bad
end

local function integer_bad(range, out_of_range)
  local bad = {}
  for _, t in ipairs(WRONG_TYPES) do bad[#bad + 1] = { t[1], "integer expected, got " .. t[2] } end
  for _, v in ipairs { NAN, INF, -INF, 0.5 } do bad[#bad + 1] = { v, "integer in " .. range .. " expected, got " } end
  for _, v in ipairs(out_of_range) do bad[#bad + 1] = { v, "integer in " .. range .. " expected, got " } end
  return bad
end

-- Every handle carries its kind (tether/base.h): bits 52…50. Integers that
-- are no handle: 0 (null), no kind, a kind past the last, past 2^53, negative.
-- (2^53 + 1 and the 64-bit extremes exist only where integers are not doubles.)
local NOT_HANDLES = { 0, 987654321, T.shl(7, 50), T.int(2 ^ 53), -1 }
if not T.LUAJIT then
  local more = { T.int(2 ^ 53) + 1, math.maxinteger, math.mininteger }
  for _, v in ipairs(more) do NOT_HANDLES[#NOT_HANDLES + 1] = v end
end
local HANDLES = {} -- one live handle of each kind, by kind name (filled below)

-- The bad values of a handle argument of `kind`. stale: handles of that kind
-- the world must refuse as stale (nil for is_valid-like calls, which answer
-- false instead, as they do for integers that are no handle).
local function handle_bad(kind, stale)
  local bad = {}
  for _, t in ipairs(WRONG_TYPES) do bad[#bad + 1] = { t[1], kind .. " handle expected, got " .. t[2] } end
  for _, v in ipairs { 1.5, NAN, INF, -INF, 1e300 } do bad[#bad + 1] = { v, kind .. " handle expected, got " } end
  for other, h in pairs(HANDLES) do
    if other ~= kind then bad[#bad + 1] = { h, kind .. " expected, got " .. other } end
  end
  if stale then
    for _, v in ipairs(NOT_HANDLES) do bad[#bad + 1] = { v, kind .. " handle expected, got " .. T.istr(v) } end
    for _, v in ipairs(stale) do bad[#bad + 1] = { v, "stale " .. kind .. " handle" } end
  end
  return bad
end

local COORD = "[-1e+12, 1e+12]"
local NONNEG = "[0, 1e+12]"

-- The world every case runs against, with its fixtures.
local W = tether.world { integrator = "leapfrog" }
local P1 = W:particle(0, 10, { vx = 1, user = "p1" })
local P2 = W:particle(1, 10)
local P3 = W:particle(2, 10, { pinned = true })
local S1 = W:spring(P1, P2, { stiffness = 50 })
local gone = W:particle(5, 5)
local gone_s = W:spring(P2, gone)
W:remove(gone)                   -- also removes gone_s
local SH1 = W:segment(-50, -5, 50, -5)                 -- collisions (lua_collide.c)
local gone_sh = W:circle(20, 20, 1)
W:remove_shape(gone_sh)
local STALE_SH = { gone_sh, SH1 + T.shl(1, 40), SH1 + T.shl(1, 24) } -- removed, another world's tag, another generation
local STALE_P = { gone, P1 + T.shl(1, 40), P1 + T.shl(1, 24), P1 + 1000 }
local STALE_S = { gone_s, S1 + T.shl(1, 40), S1 + T.shl(1, 24) }
local C1 = W:distance(P1, P2)      -- constraints and composites (lua_constraints.c, lua_composites.c)
local PIN1 = W:pin(P3)
local H1 = W:lattice { center = { 20, 20 } }
local gone_c = W:distance(P1, P3)
W:remove_constraint(gone_c)
local gone_h = W:rope { start = { 30, 30 }, finish = { 31, 30 }, segments = 1 }
W:remove_composite(gone_h)
local STALE_C = { gone_c, C1 + T.shl(1, 40), C1 + T.shl(1, 24) }
local STALE_H = { gone_h, H1 + T.shl(1, 40), H1 + T.shl(1, 24) }
local TER1 = W:terrain(tether.mask.rect(8, 8), { origin = { 40, 40 } }) -- terrains (lua_terrain.c)
local gone_t = W:terrain(tether.mask.rect(4, 4), { origin = { 60, 60 } })
W:remove_terrain(gone_t)
local STALE_T = { gone_t, TER1 + T.shl(1, 40), TER1 + T.shl(1, 24) }
HANDLES.particle, HANDLES.spring, HANDLES.constraint, HANDLES.shape, HANDLES.composite = P1, S1, C1, SH1, H1
HANDLES.terrain = TER1
local N_FIXTURES = W:count()
W:step(1 / 60, 5)

-- Argument kinds: a good value (a function so handles can be fresh), whether
-- nil is accepted, and the bad values with a fragment of the expected message.
local K = {}
K.coord = { good = function() return 0.5 end, bad = number_bad(COORD, { 1e300, -1e300, 1.0000001e12, -2e12 }) }
K.nonneg = { good = function() return 0.5 end, bad = number_bad(NONNEG, { -1, -1e-300, 1e300, 2e12 }) }
K.mass = { good = function() return 2 end, bad = number_bad("[1e-09, 1e+09]", { 0, -1, 1e-10, 2e9, 1e300 }) }
K.dt = { good = function() return 1 / 60 end, bad = number_bad("[1e-09, 10]", { 0, -0.0, -1, 1e-320, 0.5e-9, 10.5, 1e300 }) }
K.u16 = { good = function() return 3 end, bad = integer_bad("[0, 65535]", { -1, 65536, 1e300, math.maxinteger }) }
K.nsteps = { good = function() return 2 end, optional = true,
             bad = integer_bad("[1, 10000000]", { 0, -5, 10000001, 1e300 }) }
K.slot = { good = function() return 2 end, bad = integer_bad("[1, 8]", { 0, -1, 9, 1e300 }) }
K.optnonneg = { good = function() return 0.5 end, optional = true, bad = K.nonneg.bad }
K.substeps = { good = function() return 2 end, bad = integer_bad("[1, 1000]", { 0, -1, 1001, 1e300 }) }
K.optsubsteps = { good = function() return 2 end, optional = true, bad = K.substeps.bad }
K.iterations = { good = function() return 5 end, bad = integer_bad("[1, 10000]", { 0, -1, 10001, 1e300 }) }
K.solver = { good = function() return "jacobi" end, bad = {
  { NIL, "string expected, got nil" }, { "x", "invalid solver 'x', expected one of: 'gauss_seidel', 'jacobi'" },
  { 1, "string expected, got number" }, { {}, "string expected, got table" } } }
K.bool = { good = function() return true end, bad = {} }
for _, v in ipairs { NIL, 0, 1, "true", {}, fn } do
  K.bool.bad[#K.bool.bad + 1] = { v, "boolean expected, got " }
end
K.P = { good = function() return P1 end, bad = handle_bad("particle", STALE_P) }
K.P2 = { good = function() return P2 end, bad = handle_bad("particle", STALE_P) }
K.Pq = { good = function() return P1 end, bad = handle_bad("particle") }   -- is_valid: stale is not an error
K.S = { good = function() return S1 end, bad = handle_bad("spring", STALE_S) }
K.Sq = { good = function() return S1 end, bad = handle_bad("spring") }
K.C = { good = function() return C1 end, bad = handle_bad("constraint", STALE_C) }
K.Cpin = { good = function() return PIN1 end, bad = handle_bad("constraint", STALE_C) }
K.Cq = { good = function() return C1 end, bad = handle_bad("constraint") }
K.H = { good = function() return H1 end, bad = handle_bad("composite", STALE_H) }
K.Hq = { good = function() return H1 end, bad = handle_bad("composite") }
K.P3 = { good = function() return P3 end, bad = handle_bad("particle", STALE_P) }
K.lo = { good = function() return -1 end, bad = K.coord.bad }
K.hi = { good = function() return 1 end, bad = K.coord.bad }
K.mode = { good = function() return "keep" end, optional = true, bad = {
  { "x", "invalid mode 'x', expected one of: 'keep', 'reset'" }, { "", "invalid mode ''" },
  { "KEEP", "invalid mode 'KEEP'" }, { 1, "string expected, got number" }, { {}, "string expected, got table" },
  { true, "string expected, got boolean" }, { fn, "string expected, got function" } } }
K.integrator = { good = function() return "rk4" end, bad = {
  { NIL, "string expected, got nil" }, { "x", "invalid integrator 'x', expected one of: 'euler', " ..
    "'symplectic_euler', 'leapfrog', 'verlet', 'rk4'" }, { "Verlet", "invalid integrator 'Verlet'" },
  { 1, "string expected, got number" }, { {}, "string expected, got table" }, { true, "string expected, got boolean" } } }
K.any = { good = function() return "v" end, optional = true, bad = {} }
local function table_kind(optional, what)
  local k = { good = function() return {} end, optional = optional, bad = {} }
  for _, t in ipairs(WRONG_TYPES) do
    if t[1] ~= NIL and t[2] ~= "table" then k.bad[#k.bad + 1] = { t[1], what .. " expected, got " .. t[2] } end
  end
  if not optional then table.insert(k.bad, 1, { NIL, what .. " expected, got nil" }) end
  return k
end
K.opttable = table_kind(true, "table or nil")
K.popts = table_kind(true, "table or nil")
K.sopts = table_kind(true, "table or nil")
K.setspring = table_kind(false, "table")
K.handles = table_kind(false, "table of particle handles")
K.handles.good = function() return { P1, P2 } end
K.handles3 = table_kind(false, "table of particle handles")
K.handles3.good = function() return { P1, P2, P3 } end
K.xy = table_kind(false, "table of numbers")
K.xy.good = function() return { 1, 2, 3, 4 } end
-- collisions (lua_collide.c)
K.SH = { good = function() return SH1 end, bad = handle_bad("shape", STALE_SH) }
K.SHq = { good = function() return SH1 end, bad = handle_bad("shape") }
K.pos = { good = function() return 0.5 end, bad = number_bad("(0, 1e+12]", { 0, -1, 1e300, 2e12 }) }
K.unit = { good = function() return 0.5 end, bad = number_bad("[0, 1]", { -0.1, 1.5, 1e300 }) }
K.optcoord = { good = function() return 0.5 end, optional = true, bad = number_bad(COORD, { 1e300, -2e12 }) }
K.optnonneg = { good = function() return 0.5 end, optional = true, bad = number_bad(NONNEG, { -1, 1e300 }) }
K.optu16 = { good = function() return 3 end, optional = true, bad = integer_bad("[0, 65535]", { -1, 65536, 1e300 }) }
K.shopts = table_kind(true, "table or nil")
K.copts = table_kind(true, "table or nil")
K.points = table_kind(false, "table of coordinates {x1, y1, x2, y2, ...}")
K.points.good = function() return { 0, 0, 1, 0, 0, 1 } end
-- masks (lua_mask_ops.c)
K.mask = { good = function() return tether.mask.rect(4, 4) end, bad = {} }
for _, t in ipairs(WRONG_TYPES) do K.mask.bad[#K.mask.bad + 1] = { t[1], "tether.mask expected, got " .. t[2] } end
K.mopts = table_kind(true, "table or nil")
-- w:restore: a snapshot or its bytes; a refused stream returns nil, msg (tests/lua/test_snapshot.lua)
K.TER = { good = function() return TER1 end, bad = handle_bad("terrain", STALE_T) }
K.TERq = { good = function() return TER1 end, bad = handle_bad("terrain") }
K.topts = table_kind(true, "table or nil")
K.offset = { good = function() return 1 end, bad = integer_bad("[-1000000000, 1000000000]", { -1000000001, 1e300 }) }
K.optmask = { good = function() return nil end, optional = true, bad = {
  { 42, "tether.mask expected, got number" }, { {}, "tether.mask expected, got table" } } }
K.snap = { good = function() return tether.world():snapshot() end, bad = {
  { 42, "tether.snapshot or string expected, got number" }, { NIL, "tether.snapshot or string expected, got nil" },
  { {}, "tether.snapshot or string expected, got table" } } }
-- Every method and the kinds of its arguments after self.
local METHODS = {
  { "particle", "coord", "coord", "popts" },
  { "remove", "P" },
  { "is_valid", "Pq" },
  { "position", "P" },
  { "set_position", "P", "coord", "coord", "mode" },
  { "velocity", "P" },
  { "set_velocity", "P", "coord", "coord" },
  { "mass", "P" },
  { "set_mass", "P", "mass" },
  { "pinned", "P" },
  { "set_pinned", "P", "bool" },
  { "asleep", "P" },
  { "radius", "P" },
  { "set_radius", "P", "nonneg" },
  { "filter", "P" },
  { "set_filter", "P", "u16", "u16" },
  { "user", "P" },
  { "set_user", "P", "any" },
  { "apply_force", "P", "coord", "coord" },
  { "apply_impulse", "P", "coord", "coord" },
  { "explode", "coord", "coord", "nonneg", "coord" },
  { "spring", "P", "P2", "sopts" },
  { "remove_spring", "S" },
  { "spring_is_valid", "Sq" },
  { "spring_length", "S" },
  { "spring_info", "S" },
  { "set_spring", "S", "setspring" },
  { "step", "dt", "nsteps" },
  { "gravity" },
  { "set_gravity", "coord", "coord" },
  { "wind" },
  { "set_wind", "coord", "coord" },
  { "damping" },
  { "set_damping", "nonneg" },
  { "attractor", "slot" },
  { "set_attractor", "slot", "coord", "coord", "coord", "optnonneg" },
  { "integrator" },
  { "set_integrator", "integrator" },
  { "substeps" },
  { "set_substeps", "substeps" },
  { "travel" },
  { "set_travel", "nonneg", "optsubsteps" },
  { "iterations" },
  { "set_iterations", "iterations" },
  { "tolerance" },
  { "set_tolerance", "nonneg" },
  { "sleep" },
  { "set_sleep", "bool", "optnonneg", "optnonneg" },
  { "solver" },
  { "set_solver", "solver" },
  { "count" },
  { "spring_count" },
  { "stats" },
  { "energy" },
  { "memory" },
  { "hash" },
  { "snapshot" },
  { "restore", "snap" },
  { "reverse" },
  { "fixed_point" },
  { "set_interpolation", "bool" },
  { "interpolation" },
  { "journal", "opttable" },
  { "particles", "opttable" },
  { "positions", "opttable" },
  { "set_positions", "handles", "xy", "mode" },
  { "each" },
  { "destroy" },
  { "distance", "P", "P2", "opttable" },
  { "pin", "P", "opttable" },
  { "bounds", "lo", "lo", "hi", "hi", "opttable" },
  { "angle", "P", "P2", "P3", "opttable" },
  { "area", "handles3", "opttable" },
  { "collinear", "P", "P2", "P3", "opttable" },
  { "remove_constraint", "C" },
  { "constraint_is_valid", "Cq" },
  { "constraint_kind", "C" },
  { "constraint_error", "C" },
  { "constraint_particles", "C" },
  { "set_constraint", "C", "setspring" },
  { "pin_anchor", "Cpin" },
  { "rest_length", "C" },
  { "constraint_count" },
  { "constraint_lines", "opttable" },
  { "break_events" },
  { "rope", "opttable" },
  { "cloth", "opttable" },
  { "ragdoll", "opttable" },
  { "soft_body", "opttable" },
  { "lattice", "opttable" },
  { "remove_composite", "H" },
  { "composite_is_valid", "Hq" },
  { "composite_particles", "H" },
  { "composite_constraints", "H" },
  { "composite_center", "H" },
  { "composite_angle", "H" },
  { "composite_count" },
  -- collisions (lua_collide.c)
  { "segment", "coord", "coord", "coord", "coord", "shopts" },
  { "capsule", "coord", "coord", "coord", "coord", "nonneg", "shopts" },
  { "aabb", "coord", "coord", "coord", "coord", "shopts" },
  { "box", "coord", "coord", "pos", "pos", "shopts" },
  { "circle", "coord", "coord", "pos", "shopts" },
  { "chain", "points", "shopts" },
  { "polygon", "points", "shopts" },
  { "remove_shape", "SH" },
  { "shape_is_valid", "SHq" },
  { "shape_count" },
  { "shape_type", "SH" },
  { "shape_transform", "SH" },
  { "set_shape_transform", "SH", "coord", "coord", "optcoord" },
  { "set_shape_material", "SH", "unit", "nonneg", "optnonneg" },
  { "set_shape_filter", "SH", "u16", "u16" },
  { "set_shape_sensor", "SH", "bool" },
  { "shape_aabb", "SH" },
  { "set_collision", "copts" },
  { "collision" },
  { "collision_stats" },
  { "set_material", "P", "unit", "nonneg", "optnonneg" },
  { "material", "P" },
  { "set_bullet", "P", "bool" },
  { "bullet", "P" },
  { "set_pair_collision", "P", "P2", "bool" },
  { "raycast", "coord", "coord", "coord", "coord", "optu16" },
  { "query_point", "coord", "coord", "optu16" },
  { "query_aabb", "coord", "coord", "coord", "coord", "optu16" },
  { "contacts" },
  -- masks (lua_mask_ops.c)
  { "mask_chains", "mask", "mopts" },
  -- terrains (lua_terrain.c)
  { "terrain", "mask", "topts" },
  { "remove_terrain", "TER" },
  { "terrain_is_valid", "TERq" },
  { "terrain_count" },
  { "carve", "TER", "coord", "coord", "nonneg" },
  { "fill", "TER", "coord", "coord", "nonneg" },
  { "carve_mask", "TER", "mask", "offset", "offset" },
  { "fill_mask", "TER", "mask", "offset", "offset" },
  { "terrain_mask", "TER", "optmask" },
  { "terrain_place", "TER" },
  { "terrain_distance", "TER", "coord", "coord" },
  { "terrain_solid", "TER", "coord", "coord" },
  { "set_terrain_material", "TER", "unit", "nonneg", "optnonneg" },
}

-- Option tables: fields and their kinds.
local OPTIONS = {
  particle = { arg = 4, fields = { vx = "coord", vy = "coord", mass = "mass", radius = "nonneg", pinned = "bool",
                                   category = "u16", mask = "u16" } },
  spring = { arg = 4, fields = { stiffness = "nonneg", damping = "nonneg", rest = "nonneg" } },
  set_spring = { arg = 3, fields = { stiffness = "nonneg", damping = "nonneg", rest = "nonneg" } },
  circle = { arg = 5, fields = { restitution = "unit", friction = "nonneg", friction_static = "nonneg",
                                 friction_kinetic = "nonneg", category = "u16", mask = "u16", sensor = "bool" } },
  terrain = { arg = 3, fields = { restitution = "unit", friction = "nonneg", friction_static = "nonneg",
                                  friction_kinetic = "nonneg", category = "u16", mask = "u16" } },
  mask_chains = { arg = 3, fields = { restitution = "unit", friction = "nonneg",
                                      category = "u16", mask = "u16", sensor = "bool" } },
  set_collision = { arg = 2, fields = { particles = "bool", cell_size = "nonneg", restitution = "unit",
                                        friction = "nonneg", friction_static = "nonneg", friction_kinetic = "nonneg",
                                        restitution_threshold = "nonneg", stacking = "nonneg",
                                        anchored_friction = "bool", warm_start = "unit" } },
}

local function good_args(spec)
  local args = {}
  for i = 2, #spec do args[i - 1] = K[spec[i]].good() end
  return args, #spec - 1
end

local function unpack_args(args, n)
  local out = {}
  for i = 1, n do
    if args[i] == NIL then out[i] = nil else out[i] = args[i] end
  end
  return T.unpack(out, 1, n)
end

-- Every particle position and velocity of W, the energy and the stats are finite.
local function world_is_finite(w, what)
  local hs = w:particles()
  for _, p in ipairs(hs) do
    local x, y = w:position(p)
    local vx, vy = w:velocity(p)
    if T.nonfinite(x) or T.nonfinite(y) or T.nonfinite(vx) or T.nonfinite(vy) then
      T.ok(false, what .. ": non-finite state in particle " .. p)
      return false
    end
  end
  local xy = w:positions()
  for i = 1, #xy do
    if T.nonfinite(xy[i]) then T.ok(false, what .. ": non-finite bulk position"); return false end
  end
  local e = w:energy()
  for _, k in ipairs { "kinetic", "gravity", "spring", "total" } do
    if T.nonfinite(e[k]) then T.ok(false, what .. ": non-finite energy." .. k); return false end
  end
  return true
end

-- One call that must fail: message contains both fragments; world unchanged.
local function expect_fail(what, fragments, f, ...)
  local before = W:hash()
  local n0 = W:count()
  local ok, err = pcall(f, ...)
  if ok then
    T.ok(false, what .. ": expected an error, got none")
    return
  end
  err = tostring(err)
  for _, frag in ipairs(fragments) do
    if not err:find(frag, 1, true) then
      T.ok(false, ("%s: message %q lacks %q"):format(what, err, frag))
      return
    end
  end
  T.eq(W:hash(), before, what .. ": a failed call changed the world")
  T.eq(W:count(), n0, what .. ": a failed call changed the count")
end

T.test("good arguments work (the baseline of every case)", function()
  for _, spec in ipairs(METHODS) do
    local name = spec[1]
    -- reverse: the fixtures (a distance, a shape) make this world irreversible (tests/lua/test_rewind.lua)
    if name ~= "destroy" and name ~= "remove" and name ~= "remove_spring" and name ~= "remove_constraint"
        and name ~= "remove_composite" and name ~= "reverse" then
      local args, n = good_args(spec)
      local w = tether.world()
      local a = w:particle(0, 0); local b = w:particle(1, 0)
      local s = w:spring(a, b)
      local c3 = w:particle(2, 0)
      local sh = w:segment(-1, -3, 1, -3)
      local fix = { [P1] = a, [P2] = b, [P3] = c3, [S1] = s, [C1] = w:distance(a, b), [PIN1] = w:pin(c3),
                    [H1] = w:lattice(), [SH1] = sh, [TER1] = w:terrain(tether.mask.rect(8, 8)) }
      -- map the fixtures of W onto w
      for i = 1, n do
        if fix[args[i]] then args[i] = fix[args[i]] end
        if type(args[i]) == "table" and args[i][1] == P1 then
          for j = 1, #args[i] do args[i][j] = fix[args[i][j]] or args[i][j] end
        end
      end
      local ok, err = pcall(w[name], w, unpack_args(args, n))
      T.ok(ok, name .. " with good arguments: " .. tostring(err))
    end
  end
end)

-- Methods that work only inside the runner's tether.draw(g) (no frame here),
-- with their bad-input cases in the file named.
local FRAME_ONLY = { draw = "tests/lua/test_render.lua" }
-- Methods whose argument is a path: the probes here, numbers and strings
-- taken as paths, would write and read files named after them in the
-- working directory; their bad input is tested in the file named.
local PATHS = { save = "tests/lua/test_snapfile.lua", restore_file = "tests/lua/test_snapfile.lua" }
-- Methods that need a world made with spin = true (the fixtures' world is
-- not): their bad input is tested in the file named.
local SPIN_ONLY = { rotation = "tests/lua/test_spin.lua", spin = "tests/lua/test_spin.lua", set_spin = "tests/lua/test_spin.lua" }

T.test("the table above lists every method of the world class", function()
  local listed = {}
  for _, m in ipairs(METHODS) do listed[m[1]] = true end
  for name in pairs(FRAME_ONLY) do listed[name] = true end
  for name in pairs(PATHS) do listed[name] = true end
  for name in pairs(SPIN_ONLY) do listed[name] = true end
  local index = getmetatable(tether.world()).__index
  for name in pairs(index) do
    T.ok(listed[name], "method '" .. name .. "' has no bad-input row in METHODS")
  end
end)

T.test("every argument of every method refuses bad values", function()
  local cases = 0
  for _, spec in ipairs(METHODS) do
    local name = spec[1]
    for i = 2, #spec do
      local kind = K[spec[i]]
      for _, b in ipairs(kind.bad) do
        if not (kind.optional and b[1] == NIL) then
          local args, n = good_args(spec)
          args[i - 1] = b[1]
          local what = ("%s arg #%d = %s"):format(name, i, show(b[1]))
          expect_fail(what, { ("bad argument #%d to '%s' ("):format(i, name), b[2] }, W[name], W, unpack_args(args, n))
          cases = cases + 1
        end
      end
    end
  end
  T.ok(cases > 500, "enough cases: " .. cases)
  world_is_finite(W, "after bad arguments")
end)

T.test("option tables refuse unknown keys and bad values", function()
  for name, o in pairs(OPTIONS) do
    local spec
    for _, s in ipairs(METHODS) do if s[1] == name then spec = s end end
    -- unknown keys, including non-string ones
    for _, key in ipairs { "bogus", "Mass", "x", 1, true } do
      local args, n = good_args(spec)
      args[o.arg - 1] = { [key] = 1 }
      expect_fail(name .. " unknown option " .. tostring(key),
        { name .. ": unknown option '" .. tostring(key) .. "' (expected one of: " }, W[name], W, unpack_args(args, n))
    end
    for field, kname in pairs(o.fields) do
      for _, b in ipairs(K[kname].bad) do
        if b[1] ~= NIL then
          local args, n = good_args(spec)
          args[o.arg - 1] = { [field] = b[1] }
          expect_fail(("%s option %s = %s"):format(name, field, show(b[1])),
            { name .. ": bad option '" .. field .. "' (", b[2] }, W[name], W, unpack_args(args, n))
        end
      end
    end
  end
  -- user accepts any value, including a function
  local p = W:particle(0, 0, { user = fn })
  T.eq(W:user(p), fn, "user = function")
  W:remove(p)
  T.eq(W:count(), N_FIXTURES, "fixtures only")
  world_is_finite(W, "after bad options")
end)

T.test("set_spring checks everything before changing anything", function()
  local before = W:spring_info(S1)
  expect_fail("set_spring partly bad", { "set_spring: bad option 'damping'" },
    W.set_spring, W, S1, { stiffness = 7, damping = -1 })
  expect_fail("set_spring partly bad", { "set_spring: bad option 'rest'" },
    W.set_spring, W, S1, { stiffness = 7, rest = NAN })
  local after = W:spring_info(S1)
  T.eq(after.stiffness, before.stiffness, "stiffness unchanged")
end)

T.test("spring ends", function()
  expect_fail("spring(a, a)", { "bad argument #3 to 'spring' (a spring needs two distinct particles)" },
    W.spring, W, P1, P1)
end)

T.test("bulk: set_positions validates every element first", function()
  expect_fail("length mismatch", { "bad argument #3 to 'set_positions' (4 numbers expected (2 per handle), got 3)" },
    W.set_positions, W, { P1, P2 }, { 1, 2, 3 })
  expect_fail("length mismatch", { "bad argument #3 to 'set_positions' (", "got 5" },
    W.set_positions, W, { P1, P2 }, { 1, 2, 3, 4, 5 })
  for _, b in ipairs(K.P.bad) do
    if b[1] ~= NIL then
      expect_fail("handle list item " .. show(b[1]), { "bad argument #2 to 'set_positions' (index 2: ", b[2] },
        W.set_positions, W, { P1, b[1] }, { 1, 2, 3, 4 })
    end
  end
  for _, b in ipairs(K.coord.bad) do
    if b[1] ~= NIL then
      expect_fail("xy item " .. show(b[1]), { "bad argument #3 to 'set_positions' (index 4: ", b[2] },
        W.set_positions, W, { P1, P2 }, { 1, 2, 3, b[1] })
    end
  end
  -- a hole in the xy list is nil at that index
  expect_fail("xy hole", { "bad argument #3 to 'set_positions' (index 2: number expected, got nil)" },
    W.set_positions, W, { P1, P2 }, { 1, nil, 3, 4 })
  world_is_finite(W, "after bad bulk calls")
end)

T.test("wrong self for every method", function()
  local other = setmetatable({}, { __name = "not.a.world" })
  for _, spec in ipairs(METHODS) do
    local name = spec[1]
    for _, s in ipairs { { NIL, "nil" }, { 1, "number" }, { "w", "string" }, { {}, "table" }, { io.stdout, FILE },
                         { other, "not.a.world" }, { fn, "function" } } do
      local args, n = good_args(spec)
      expect_fail(name .. " self = " .. show(s[1]),
        { ("bad argument #1 to '%s' (tether.world expected, got %s; did you call it with '.' instead of ':'?)"):format(name, s[2]) },
        W[name], s[1] ~= NIL and s[1] or nil, unpack_args(args, n))
    end
  end
end)

T.test("a method called with '.' says so", function()
  local w = tether.world()
  T.checkerror_plain("bad argument #1 to 'step' (tether.world expected, got number; did you call it with '.' instead of ':'?)",
    w.step, 1 / 60)
  T.checkerror_plain("bad argument #1 to 'particle' (tether.world expected, got number; did you call it with '.' instead of ':'?)",
    w.particle, 0, 0)
end)

T.test("a destroyed world refuses every method but destroy", function()
  local D = tether.world()
  local a, b = D:particle(0, 0), D:particle(1, 1)
  local s = D:spring(a, b)
  local iter = D:each()
  D:destroy()
  for _, spec in ipairs(METHODS) do
    local name = spec[1]
    local args, n = good_args(spec)
    for i = 1, n do
      if args[i] == P1 then args[i] = a elseif args[i] == P2 then args[i] = b elseif args[i] == S1 then args[i] = s end
    end
    if name == "destroy" then
      T.noerror(D.destroy, D)
    else
      local ok, err = pcall(D[name], D, unpack_args(args, n))
      T.ok(not ok and tostring(err):find(("bad argument #1 to '%s' (attempt to use a destroyed world)"):format(name),
        1, true), name .. " on a destroyed world: " .. tostring(err))
    end
  end
  T.checkerror("each: attempt to use a destroyed world", iter)
  T.ok(tostring(D):find("destroyed", 1, true), "tostring of a destroyed world")
end)

T.test("lists and option keys are read raw: no metamethod makes an error that names nothing", function()
  local len25 = { __len = function() return 2.5 end } -- a length that is not an integer
  T.checkerror_plain("bad argument #2 to 'polygon' (between 3 and 64 points expected, got 0)",
    W.polygon, W, setmetatable({}, len25))
  T.checkerror_plain("bad argument #2 to 'chain' (between 2 and 1000000 points expected, got 0)",
    W.chain, W, setmetatable({}, len25))
  -- what is in the table counts, not what __len says
  local sh = T.noerror(W.polygon, W, setmetatable({ 0, 0, 1, 0, 0, 1 }, len25))
  if sh then W:remove_shape(sh) end
  local C = tether.world()
  T.noerror(C.set_collision, C, { events = setmetatable({ "begin" }, len25) })
  T.eq(table.concat(C:collision().events, ","), "begin", "events")
  -- an unknown key is named without calling its __tostring (which may fail or return a number)
  local key = setmetatable({}, { __tostring = function() return 42 end })
  T.checkerror_plain("tether.world: unknown option 'table: ", tether.world, { [key] = 1 })
  T.checkerror_plain("particle: unknown option 'table: ", W.particle, W, 0, 0, { [key] = 1 })
  local named = setmetatable({}, { __name = "my.key", __tostring = function() error("called") end })
  T.checkerror_plain("tether.world: unknown option 'my.key: ", tether.world, { [named] = 1 })
  T.eq(W:count(), N_FIXTURES, "fixtures only")
end)

T.test("tether.world refuses bad options", function()
  for _, t in ipairs(WRONG_TYPES) do
    if t[1] ~= NIL and t[2] ~= "table" then
      T.checkerror("bad argument #1 to 'tether.world' (table or nil expected, got " .. t[2] .. ")", tether.world, t[1])
    end
  end
  T.checkerror("tether.world: unknown option 'gravty' (expected one of: 'gravity', ", tether.world, { gravty = 1 })
  T.checkerror("tether.world: unknown option '1'", tether.world, { 1 })
  local fields = { damping = "nonneg", dt_hint = "dt" }
  for field, kname in pairs(fields) do
    for _, b in ipairs(K[kname].bad) do
      if b[1] ~= NIL then
        T.checkerror("tether.world: bad option '" .. field .. "' (" .. b[2], tether.world, { [field] = b[1] })
      end
    end
  end
  for _, b in ipairs(integer_bad("[0, 16777216]", { -1, 16777217, 1e300 })) do
    if b[1] ~= NIL then
      T.checkerror("tether.world: bad option 'capacity' (" .. b[2], tether.world, { capacity = b[1] })
    end
  end
  for _, field in ipairs { "gravity", "wind" } do
    for _, v in ipairs { 1, "x", true, fn } do
      T.checkerror("tether.world: bad option '" .. field .. "' (table {x, y} expected, got ", tether.world, { [field] = v })
    end
    for _, b in ipairs(K.coord.bad) do
      if b[1] ~= NIL then
        T.checkerror("tether.world: bad option '" .. field .. "' (index 1: " .. b[2], tether.world, { [field] = { b[1], 0 } })
        T.checkerror("tether.world: bad option '" .. field .. "' (index 2: " .. b[2], tether.world, { [field] = { 0, b[1] } })
      end
    end
    T.checkerror("tether.world: bad option '" .. field .. "' (index 2: number expected, got nil)", tether.world,
      { [field] = { 1 } })
    T.checkerror("tether.world: bad option '" .. field .. "' (table {x, y} of exactly two numbers expected)",
      tether.world, { [field] = { 1, 2, 3 } })
  end
  for _, b in ipairs(K.integrator.bad) do
    if b[1] ~= NIL then
      local frag = b[2]:gsub("^string expected", "bad option 'integrator' (string expected")
      T.checkerror("tether.world: " .. frag, tether.world, { integrator = b[1] })
    end
  end
end)

T.test("C-level refusals are raised, not ignored", function()
  expect_fail("set_velocity on a pinned particle", { "set_velocity: " }, W.set_velocity, W, P3, 1, 1)
end)

T.test("denormal steps and compliances are refused, the world unchanged", function()
  local w = tether.world { integrator = "leapfrog" }
  local a = w:particle(0, 0, { pinned = true })
  local b = w:particle(1.5, 0)
  w:distance(a, b, { length = 1 })
  local h = w:hash()
  T.checkerror_plain("bad argument #2 to 'step' (number in [1e-09, 10] expected, got 9.99", w.step, w, 1e-320)
  T.checkerror_plain("compliance must be 0 (rigid) or in [1e-12, 1e+12] m/N, got 9.99", w.distance, w, a, b, { compliance = 1e-320 })
  T.eq(w:hash(), h, "world unchanged")
  w:step(1e-9)
  w:step(1 / 60)
  world_is_finite(w, "after the smallest step")
end)

T.test("extreme but legal input never produces NaN or Inf", function()
  for _, integrator in ipairs(tether.integrators) do
    local w = tether.world { integrator = integrator, gravity = { 1e12, -1e12 }, wind = { -1e12, 1e12 }, damping = 1e12 }
    local a = w:particle(1e12, -1e12, { vx = 1e12, vy = -1e12, mass = 1e-9 })
    local b = w:particle(-1e12, 1e12, { mass = 1e9 })
    local c = w:particle(1e12, -1e12, { mass = 1e-9 })   -- on top of a
    w:spring(a, b, { stiffness = 1e12, damping = 1e12, rest = 0 })
    w:spring(a, c, { stiffness = 1e12, rest = 1e12 })      -- zero length, non-zero rest
    w:apply_force(a, 1e12, 1e12)
    w:apply_impulse(b, -1e12, 1e12)
    w:explode(0, 0, 1e12, 1e12)
    w:explode(1e12, -1e12, 1e12, -1e12)
    for _ = 1, 20 do
      pcall(w.step, w, 10, 5)
      w:explode(0, 0, 1e12, 1e12)
    end
    w:set_damping(0)
    pcall(w.step, w, 1e-300 + 1e-9, 10)
    world_is_finite(w, "extreme " .. integrator)
    local s = w:stats()
    T.ok(not T.nonfinite(s.time), "time finite")
  end
end)

T.test("random calls never crash or poison the world", function()
  local rnd = T.minstd(12345)
  local function rand(n) return math.floor(rnd() * n) + 1 end -- deterministic: same cases every run
  local w = tether.world()
  local handles = {}
  for i = 1, 8 do handles[i] = w:particle(i, i) end
  handles[#handles + 1] = w:spring(handles[1], handles[2])
  local values = { NIL, 0, 1, -1, 2, 0.5, 1.5, 1e12, -1e12, 1e300, NAN, INF, -INF, 65535, 65536, 1e-9, 10, 11,
                   "x", "keep", "reset", "verlet", "euler", true, false, {}, { 1, 2 }, { mass = 0 }, { vx = 1 }, fn,
                   math.maxinteger, math.mininteger, 0 }
  local names = {}
  for _, spec in ipairs(METHODS) do if spec[1] ~= "destroy" then names[#names + 1] = spec[1] end end
  local errors = 0
  for _ = 1, 20000 do
    local name = names[rand(#names)]
    local n = rand(5) - 1
    local args = {}
    for i = 1, n do
      if rand(3) == 1 then args[i] = handles[rand(#handles)] else args[i] = values[rand(#values)] end
    end
    -- Random composites can pile thousands of particles on one spot (an O(n²) cell for any
    -- broadphase): a valid step count there is minutes of work, so keep steps to one.
    if name == "step" and n >= 2 and type(args[2]) == "number" and args[2] == args[2] and args[2] > 1 then args[2] = 1 end
    local ok, r = pcall(w[name], w, unpack_args(args, n))
    if not ok then
      errors = errors + 1
      if type(r) ~= "string" or not (r:find("'" .. name .. "'", 1, true) or r:find(name .. ":", 1, true)) then
        T.ok(false, ("random %s: message does not name the method: %s"):format(name, tostring(r)))
      end
    elseif name == "particle" or name == "spring" then
      handles[#handles + 1] = r
    end
  end
  T.ok(errors > 1000, "most random calls fail: " .. errors)
  world_is_finite(w, "after random calls")
end)

T.done()
