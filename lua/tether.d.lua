---@meta tether
-- LuaLS (lua-language-server) annotations for the tether module.
-- Definitions only: this file is never run. Reference: docs/lua-api.md.
--
-- Argument numbers in error messages count the world as #1
-- (`w:position(p)`: p is argument #2). Numbers must be numbers (no numeric
-- strings), finite, and inside the documented ranges, or the call raises.

---A particle handle: a Lua integer below 2^53 that carries its kind (bits
---52…50), world tag, reuse counter and slot index (tether/base.h). It goes
---stale when its particle is removed; a handle of another kind is refused.
---@alias tether.particle integer

---A spring handle: a Lua integer, like a particle handle.
---@alias tether.spring integer

---@alias tether.integrator_name
---| "euler"            # explicit Euler: order 1, gains energy
---| "symplectic_euler" # semi-implicit Euler: order 1, bounded energy
---| "leapfrog"         # velocity Verlet (kick-drift-kick), two force evaluations: order 2
---| "verlet"           # position Verlet (the default): order 2
---| "rk4"              # classic Runge-Kutta 4, four force evaluations: order 4

---@alias tether.solver_name
---| "gauss_seidel" # in place, one constraint after another: fewer sweeps
---| "jacobi"       # corrections averaged per particle, then applied

---@alias tether.move_mode
---| "keep"  # velocity is kept (the default)
---| "reset" # velocity becomes 0

---@class tether
---@field version string The library version, e.g. "0.1.0".
---@field integrators tether.integrator_name[] {"euler", "symplectic_euler", "leapfrog", "verlet", "rk4"}
---Runner callback (set it in your script): called once before the first update with the script's arguments.
---@field load? fun(args: string[])
---Runner callback (set it in your script): called every fixed step with dt in seconds.
---@field update? fun(dt: number)
---Runner callback (set it in your script): called once after the last update.
---@field unload? fun()
local tether = {}

---Options of `tether.world`.
---@class tether.world_options
---@field gravity? number[] {gx, gy}, m/s², each in [-1e12, 1e12]; default {0, -9.81}
---@field integrator? tether.integrator_name default "verlet"
---@field damping? number velocity damping, 1/s, in [0, 1e12]: v *= 1 - damping*dt each step; default 0
---@field wind? number[] {fx, fy}, N on every particle, each in [-1e12, 1e12]; default {0, 0}
---@field dt_hint? number the step you expect to use, s, in [1e-9, 10]; default 1/60
---@field capacity? integer particles to reserve up front, 0..16777216; default 0
---@field substeps? integer substeps per step, 1..1000; default 1
---@field max_travel? number substeps by speed: a step runs more substeps (up to max_substeps) where a particle would move more than max_travel radii in one relative to what it can meet (other particles, pinned or sleeping ones, shapes and terrain within reach), in [0, 1e12]; default 0 = off
---@field max_substeps? integer the most substeps max_travel may ask for, 1..1000; default 8
---@field iterations? integer most relaxation sweeps per substep, 1..10000; default 10
---@field tolerance? number sweeps stop once the largest error is <= this, m; default 1e-6
---@field solver? tether.solver_name default "gauss_seidel"
---@field sleep? boolean particles at rest fall asleep by islands and cost nothing until woken; default true
---@field sleep_speed? number a particle rests while its position, smoothed over 1/15 s, stays within sleep_speed·sleep_time of where it was (or leaves slower than this), m/s, in [0, 1e12]; default 0.01
---@field sleep_time? number an island sleeps once all of it rested this long, s, in [0, 1e12]; default 1
---@field spin? boolean particles turn: each a solid disc with an angle and an angular velocity, contact friction acting at the contact point (README "Particles that turn"); default false
---@field fixed_point? boolean|number positions on a fixed-point lattice, so `w:reverse()` runs back bit for bit: true for the quantum 2^-32 m (range ±2^19 m), or the quantum itself, a power of two 2^-k, k = 1..60 (range ±2^51 quanta); positions given are rounded onto it, one outside the range raises; needs integrator "verlet"; default false
---@field snapshot? tether.snapshot|string a saved world (w:snapshot() or its bytes): the new world is that world, settings included; no other option may be given
---@field file? string a snapshot file (w:save(path), tt_world_save_file): the new world is the saved one; a file that cannot be read or is damaged raises; no other option may be given

---A world's whole state at one moment (w:snapshot()): the engine's versioned,
---checksummed stream, and a copy of the particles' user values. `#s` is its size in bytes.
---@class tether.snapshot
local snapshot = {}

---The snapshot as a string, for a file: with the user values (plain data only:
---booleans, numbers, strings, tables of them; anything else raises) unless users
---is false, when it is the engine stream alone and a world restored or loaded
---from it has no user values.
---@param users? boolean default true
---@return string
function snapshot:bytes(users) end

---Makes a new world. Unknown option keys raise ("tether.world: unknown option 'gravty' ...").
---@param opts? tether.world_options
---@---A fixed-step clock: real frame time in, steps of dt out (tether/clock.h).
---@class tether.clock
local clock = {}
---Feeds `real` seconds (>= 0) of the frame; returns the steps to take now.
---@param real number
---@return integer
function clock:advance(real) end
---How far from the last step to the next, [0, 1): blend the drawn states by it.
---@return number
function clock:alpha() end
---@return number
function clock:dt() end
---@return number
function clock:scale() end
---@param s number virtual seconds per real one, [0, 1000]
function clock:set_scale(s) end
---@return boolean
function clock:paused() end
---@param paused boolean
function clock:set_paused(paused) end
---One step at the next advance, even while paused.
function clock:step_once() end
---@return {dt: number, max_steps: integer, scale: number, paused: boolean, time: number, steps: integer, acc: number, dropped: number, capped: boolean}
function clock:info() end

---@class tether.clock_options
---@field dt? number s, default 1/60
---@field max_steps? integer most steps per frame, default 8
---@field scale? number virtual seconds per real one, [0, 1000], default 1

---A new clock.
---@param opts? tether.clock_options
---@return tether.clock
function tether.clock(opts) end

---A rewind ring: the last seconds of a world's history as keyframes every `every`
---steps, delta-coded (tether/rewind.h). A step between keyframes is rebuilt by
---stepping again from the keyframe before it, with the same inputs: give seek a
---driver that does what the script did (a function of w:stats().steps does).
---User values are not in the ring.
---@class tether.rewind
local rewind = {}
---Call after each step (and once before the first). A world at or before the
---newest keyframe starts a new timeline: the keyframes after it go.
---@param w tether.world
function rewind:record(w) end
---Makes w the keyframe at or before `step`; with drive, calls drive(w) (it must step
---w once) until w is at `step`. Returns the step w is at. Raises for a step outside
---the ring ("seek: step 100 is not in the ring (140 … 200)"), the world unchanged.
---@param w tether.world
---@param step integer
---@param drive? fun(w: tether.world)
---@return integer
function rewind:seek(w, step, drive) end
---The oldest keyframe's step and the newest step recorded; nil when empty.
---@return integer|nil first
---@return integer? last
function rewind:range() end
---Bytes held now.
---@return integer
function rewind:memory() end
---Keyframes held now.
---@return integer
function rewind:count() end
---Frees the ring now (the collector does it otherwise); safe to repeat.
function rewind:destroy() end

---@class tether.rewind_options
---@field every? integer steps between keyframes, 1 … 1 000 000, default 10
---@field seconds? number history kept, default 10
---@field dt? number s per step (turns seconds into steps), default 1/60
---@field max_bytes? number memory bound, >= 1024, default 256 MB: the oldest keyframes go first

---Time reversal (position Verlet with forces only): swaps every particle's position
---and previous position, so the next steps of the same dt run the motion backwards.
---Raises naming what prevents it: another integrator, damping, constraints,
---collisions, spring damping, a velocity set since the last step. In a world made
---with `fixed_point` the round trip is exact, bit for bit.
function world:reverse() end

---The fixed-point quantum of the world (option `fixed_point`), m, or nil when positions are plain doubles.
---@return number|nil
function world:fixed_point() end

---A new, empty rewind ring.
---@param opts? tether.rewind_options
---@return tether.rewind
function tether.rewind(opts) end

---A replay journal (tether/journal.h): a snapshot of the world when recording
---began, then per step the dt, the changes calls made since the step before
---(found by comparing the world's stream with the one kept at the end of the
---step before, so no call can be missed) and the hash after the step. Replay it
---into the same or a new world, in this process or another (j:save, tether.load_journal),
---one step per call or to the end, with desync detection. User values are not in it.
---@class tether.journal
local journal = {}
---Stops recording (nothing when it was not); what it holds stays.
function journal:stop() end
---@return boolean
function journal:recording() end
---Steps recorded.
---@return integer
function journal:steps() end
---Bytes held now (snapshot, per-step record, work space).
---@return integer
function journal:size() end
---@class tether.journal_info
---@field steps integer steps recorded
---@field changed integer of them, steps that calls changed the world before
---@field bytes integer memory held
---@field record_bytes integer of it, the per-step record (bytes per step = record_bytes / steps)
---@field snapshot_bytes integer of it, the first snapshot
---@field recording boolean
---@field full boolean recording stopped at max_bytes (or for want of memory)
---@field replayed integer steps the replay has played
---@field desync integer the first replayed step whose hash was not the recorded one; 0: none
---@return tether.journal_info
function journal:info() end
---The first desync: its step (1 = the journal's first), the recorded hash and the
---hash the replay got (hex, as w:hash()); nil when none.
---@return integer|nil step
---@return string? expected
---@return string? got
function journal:desync() end
---Writes the journal to a file (the snapshot files' header and checksum).
---@param path string
---@return true|nil ok
---@return string? err
function journal:save(path) end
---Begins a replay: w becomes the recorded start (its user values stay as they are).
---Raises while the journal records.
---@param w tether.world
function journal:replay(w) end
---Plays the next step into the replay's world: "sync" (the recorded hash),
---"desync" (another: j:desync() says where) or "end" (nothing left). Raises when
---a recorded change no longer applies (after a desync, or the world was changed).
---@return "sync"|"desync"|"end"
function journal:step() end
---Plays to the end or the first desync (call again to play on).
---@return "end"|"desync" where
---@return integer played steps played by this call
function journal:run() end
---Stops recording and frees the journal now; safe to repeat.
function journal:destroy() end

---@class tether.journal_options
---@field max_bytes? number memory bound, >= 1024, default 256 MB: recording stops there (the world steps on)

---Starts journaling the world: every step from now on, with the changes calls make
---between steps. One journal per world.
---@param opts? tether.journal_options
---@return tether.journal
function world:journal(opts) end

---A replay journal saved by j:save, or nil and the reason (a missing, truncated,
---corrupted, foreign or other-version file).
---@param path string
---@return tether.journal|nil
---@return string? err
function tether.load_journal(path) end

return tether.world
function tether.world(opts) end

---Runner only (the `tether` executable): ends the update loop after the current call.
function tether.quit() end

---Options of `w:particle`.
---@class tether.particle_options
---@field vx? number initial velocity x, m/s, in [-1e12, 1e12]; default 0
---@field vy? number initial velocity y, m/s, in [-1e12, 1e12]; default 0
---@field mass? number kg, in [1e-9, 1e9]; default 1
---@field radius? number m, in [0, 1e12]; default 0 (a point)
---@field pinned? boolean infinite mass: never moved by forces or impulses; default false
---@field category? integer collision layer bits, 0..0xFFFF; default 1
---@field mask? integer layers it collides with, 0..0xFFFF; default 0xFFFF
---@field user? any any Lua value, read back with w:user(p)

---Options of `w:spring` and fields of `w:set_spring`.
---@class tether.spring_options
---@field stiffness? number k, N/m, in [0, 1e12]; default 100
---@field damping? number c, N·s/m, in [0, 1e12]; default 0
---@field rest? number rest length, m, in [0, 1e12]; default: the distance between the ends when made

---What `w:spring_info` returns.
---@class tether.spring_info
---@field a tether.particle
---@field b tether.particle
---@field stiffness number N/m
---@field damping number N·s/m
---@field rest number m

---Wall time per pipeline stage of the last step, ms.
---@class tether.stage_times
---@field forces number
---@field integrate number
---@field collide number
---@field solve number
---@field events number

---What `w:stats` returns.
---@class tether.stats
---@field steps integer steps taken since creation
---@field time number simulated time, s
---@field particles integer live particles
---@field springs integer live springs
---@field step_ms number wall time of the last step, ms
---@field force_evaluations integer force evaluations in the last step
---@field diverged integer particles stopped in the last step because |x| or |v| ran away
---@field iterations integer relaxation sweeps in the last step
---@field substeps integer substeps the last step ran (more than the setting where max_travel asked); 0 before the first step
---@field max_error number largest constraint error left after the last step, m
---@field sleeping integer particles asleep now (0 while sleeping is off)
---@field stages tether.stage_times

---What `w:energy` returns, J.
---@class tether.energy
---@field kinetic number Σ ½ m |v|²
---@field gravity number Σ −m g·x
---@field spring number Σ ½ k (length − rest)²
---@field constraint number Σ ½ C²/α over compliant (XPBD) constraints
---@field attractor number Σ −m·strength/√(r² + softening²) over point attractors
---@field total number the sum of the five

---What `w:memory` returns.
---@class tether.memory
---@field total integer bytes the world allocated
---@field particles integer bytes of the particle arrays
---@field capacity integer particle slots allocated
---@field bytes_per_particle number particle array bytes per slot

---A simulation world (userdata, metatable "tether.world"). Freed by the
---garbage collector, by `w:destroy()`, or at the end of a `<close>` scope.
---@class tether.world
local world = {}

---Adds a particle at (x, y), m, each in [-1e12, 1e12].
---@param x number
---@param y number
---@param opts? tether.particle_options
---@return tether.particle
function world:particle(x, y, opts) end

---Removes a particle, the springs attached to it and its user value. Stale handle: raises.
---@param p tether.particle
function world:remove(p) end

---True if p names a live particle of this world; false for stale or never-made handles.
---@param p tether.particle
---@return boolean
function world:is_valid(p) end

---Position, m.
---@param p tether.particle
---@return number x
---@return number y
function world:position(p) end

---Teleports a particle (no force, no sweep).
---@param p tether.particle
---@param x number m, in [-1e12, 1e12]
---@param y number m, in [-1e12, 1e12]
---@param mode? tether.move_mode default "keep"
function world:set_position(p, x, y, mode) end

---Velocity, m/s (Verlet: the backward difference (x − x_old)/dt).
---@param p tether.particle
---@return number vx
---@return number vy
function world:velocity(p) end

---Sets the velocity exactly, m/s, each in [-1e12, 1e12]. A pinned particle raises.
---@param p tether.particle
---@param vx number
---@param vy number
function world:set_velocity(p, vx, vy) end

---Mass, kg (kept while pinned).
---@param p tether.particle
---@return number
function world:mass(p) end

---@param p tether.particle
---@param m number kg, in [1e-9, 1e9]
function world:set_mass(p, m) end

---@param p tether.particle
---@return boolean
function world:pinned(p) end

---Whether the particle sleeps (its island at rest). Any call that changes it wakes its island.
---@param p tether.particle
---@return boolean
function world:asleep(p) end

---The particle's angle, rad in [-pi, pi], counter-clockwise (a world made with spin = true; else raises).
---@param p tether.particle
---@return number
function world:rotation(p) end

---The particle's angular velocity, rad/s, counter-clockwise (spin = true; else raises).
---@param p tether.particle
---@return number
function world:spin(p) end

---Sets the angular velocity, rad/s in [-1e12, 1e12] (spin = true; else raises). A pinned particle and a
---point (radius 0) do not turn: raises for them; pinning or setting the radius to 0 stops a spin.
---@param p tether.particle
---@param omega number
function world:set_spin(p, omega) end

---Pinning stops the particle where it is.
---@param p tether.particle
---@param pinned boolean
function world:set_pinned(p, pinned) end

---@param p tether.particle
---@return number radius m
function world:radius(p) end

---@param p tether.particle
---@param r number m, in [0, 1e12]
function world:set_radius(p, r) end

---Collision filter bits.
---@param p tether.particle
---@return integer category
---@return integer mask
function world:filter(p) end

---@param p tether.particle
---@param category integer 0..0xFFFF
---@param mask integer 0..0xFFFF
function world:set_filter(p, category, mask) end

---The Lua value stored with the particle (nil if none).
---@param p tether.particle
---@return any
function world:user(p) end

---Stores any Lua value with the particle (nil forgets it). Cleared when the particle is removed.
---@param p tether.particle
---@param value any
function world:set_user(p, value) end

---Adds a force, N, for the next step only (forces add up).
---@param p tether.particle
---@param fx number in [-1e12, 1e12]
---@param fy number in [-1e12, 1e12]
function world:apply_force(p, fx, fy) end

---Instant velocity change Δv = j / m, N·s. Pinned particles: no effect.
---@param p tether.particle
---@param jx number in [-1e12, 1e12]
---@param jy number in [-1e12, 1e12]
function world:apply_impulse(p, jx, jy) end

---Radial explosion: every movable particle within `radius` of (x, y) gets
---an impulse of impulse·(1 − d/radius) N·s away from the centre.
---@param x number m, in [-1e12, 1e12]
---@param y number m, in [-1e12, 1e12]
---@param radius number m, in [0, 1e12]
---@param impulse number N·s, in [-1e12, 1e12]
function world:explode(x, y, radius, impulse) end

---Adds a spring between two distinct live particles.
---@param a tether.particle
---@param b tether.particle
---@param opts? tether.spring_options
---@return tether.spring
function world:spring(a, b, opts) end

---Removes a spring. Stale handle: raises.
---@param s tether.spring
function world:remove_spring(s) end

---True if s names a live spring of this world.
---@param s tether.spring
---@return boolean
function world:spring_is_valid(s) end

---Current length |xa − xb|, m.
---@param s tether.spring
---@return number
function world:spring_length(s) end

---@param s tether.spring
---@return tether.spring_info
function world:spring_info(s) end

---Changes only the given fields; all are checked before any changes.
---@param s tether.spring
---@param fields tether.spring_options
function world:set_spring(s, fields) end

---Advances the world n times by dt seconds.
---@param dt number s, in [1e-9, 10]
---@param n? integer 1..10000000, default 1
function world:step(dt, n) end

---@return number gx m/s²
---@return number gy m/s²
function world:gravity() end

---@param gx number m/s², in [-1e12, 1e12]
---@param gy number m/s², in [-1e12, 1e12]
function world:set_gravity(gx, gy) end

---A point attractor (planet, magnet): every movable particle accelerates
---towards (x, y) by strength·r/(r² + softening²)^(3/2) m/s², whatever its
---mass; a negative strength repels; strength 0 clears the slot.
---@param slot integer 1 … 8
---@param x number m
---@param y number m
---@param strength number G·M, m³/s², in [-1e12, 1e12]
---@param softening? number m, in [0, 1e12], default 0 (exact 1/r²)
function world:set_attractor(slot, x, y, strength, softening) end

---@param slot integer 1 … 8
---@return number x
---@return number y
---@return number strength 0 when the slot is unused
---@return number softening
function world:attractor(slot) end

---@return number fx N
---@return number fy N
function world:wind() end

---@param fx number N on every particle, in [-1e12, 1e12]
---@param fy number N on every particle, in [-1e12, 1e12]
function world:set_wind(fx, fy) end

---@return number damping 1/s
function world:damping() end

---@param d number 1/s, in [0, 1e12]
function world:set_damping(d) end

---@return tether.integrator_name
function world:integrator() end

---Switches integrator between steps; every particle keeps its velocity.
---@param name tether.integrator_name
function world:set_integrator(name) end

---@return integer substeps per step
function world:substeps() end

---@param n integer substeps per step, 1..1000
function world:set_substeps(n) end

---Substeps by speed: max_travel in radii per substep (0: off) and the most substeps it may ask for.
---@return number max_travel
---@return integer max_substeps
function world:travel() end

---@param max_travel number radii a particle may move in one substep, in [0, 1e12]; 0 switches it off
---@param max_substeps? integer the most substeps it may ask for, 1..1000; default: the world's (8 when never set)
function world:set_travel(max_travel, max_substeps) end

---@return integer most relaxation sweeps per substep
function world:iterations() end

---@param n integer most relaxation sweeps per substep, 1..10000
function world:set_iterations(n) end

---@return number tolerance, m
function world:tolerance() end

---@param m number sweeps stop once the largest error is <= m, in [0, 1e12]
function world:set_tolerance(m) end

---@return tether.solver_name
function world:solver() end

---@return boolean on whether sleeping is on
---@return number speed m/s below which a particle rests (0 when off)
---@return number time s at rest before an island sleeps (0 when off)
function world:sleep() end

---Sleeping on or off; off wakes every sleeper.
---@param on boolean
---@param speed? number m/s, in [0, 1e12]; default 0.01
---@param time? number s, in [0, 1e12]; default 1
function world:set_sleep(on, speed, time) end

---@param name tether.solver_name
function world:set_solver(name) end

---@return integer live particles
function world:count() end

---@return integer live springs
function world:spring_count() end

---@return tether.stats
function world:stats() end

---@return tether.energy
function world:energy() end

---@return tether.memory
function world:memory() end

---The state hash as 16 hex digits: the hash of the stream w:snapshot() holds (the
---world's tag left out), so it covers exactly what a snapshot saves.
---@return string
function world:hash() end

---The whole state of the world now (see tether.snapshot), to restore later or to
---save (s:bytes()) and load as a new world (tether.world{snapshot = s}).
---@return tether.snapshot
function world:snapshot() end

---Makes this world bit-exactly the one saved in s (a snapshot, or its bytes): the
---same steps then give the same states; each particle's user value is what it was
---when s was taken (none from s:bytes(false)). A truncated, corrupted or foreign stream
---returns nil and the reason, and the world is unchanged.
---@param s tether.snapshot|string
---@return true|nil ok
---@return string? reason
function world:restore(s) end

---Saves the world to a snapshot file: s:bytes(users) behind a header (signature,
---file format version, engine version, length) and a checksum; written to path..".tmp"
---and renamed over path, so a failed save leaves the old file whole. Returns nil and
---the reason when the file cannot be written; raises on user values that are not
---plain data (save(path, false) leaves them out).
---@param path string
---@param users? boolean default true
---@return true|nil ok
---@return string? reason
function world:save(path, users) end

---Makes this world the one saved in the file (as w:restore). A missing, truncated,
---padded, corrupted, foreign or other-version file returns nil and the reason
---("restore_file: 'path': checksum mismatch (corrupted); ..."), the world unchanged.
---@param path string
---@return true|nil ok
---@return string? reason
function world:restore_file(path) end

---Live particle handles in slot order. Reuses t if given (entries past n are cleared).
---@param t? tether.particle[]
---@return tether.particle[] handles
---@return integer n
function world:particles(t) end

---Positions {x1, y1, x2, y2, …} in the order of w:particles(). Reuses t if given.
---@param t? number[]
---@return number[] xy
---@return integer n particles (the table holds 2n numbers)
function world:positions(t) end

---Teleports n particles: xy holds exactly 2n numbers. Everything is checked before anything moves.
---@param handles tether.particle[]
---@param xy number[]
---@param mode? tether.move_mode default "keep"
function world:set_positions(handles, xy, mode) end

---Iterates over the live particles: `for p, x, y in w:each() do … end`.
---Particles removed during the loop are skipped; new ones are not visited.
---@return fun(): tether.particle?, number?, number?
function world:each() end

---Frees the world now. Idempotent; afterwards every other method raises
---"attempt to use a destroyed world". Called from Lua code that runs in the
---middle of a method on this world (an option table's __index, a finalizer,
---a __close), the world is freed when that method returns.
function world:destroy() end

-- Constraints and composites (lua_constraints.c, lua_composites.c) ---------

---@alias tether.constraint integer
---@alias tether.composite integer

---@class tether.distance_options
---@field length? number m, ≥ 0; default the distance now
---@field mode? "rigid"|"max"|"min" default "rigid"
---@field stiffness? number [0, 1]; default 1
---@field compliance? number m/N, 0 or in [1e-12, 1e12]; default 0
---@field break_strain? number ≥ 0; default 0 = never
---@field max_rate? number m/s, ≥ 0: a winch, length changes proceed at most this fast; default 0 = no limit
---@field collide? boolean default false

---@class tether.composite_options
---@field mass? number kg per particle; default 1
---@field radius? number m; default 0
---@field stiffness? number [0, 1]; default 1
---@field compliance? number m/N; default 0
---@field collide? boolean default false: two particles joined by one of its links do not collide with each other (everything else collides as the world's settings say)

---Distance constraint between two distinct particles.
---@param a tether.particle
---@param b tether.particle
---@param opts? tether.distance_options
---@return tether.constraint
function world:distance(a, b, opts) end
---Pins p to an anchor (default where it is). opts: anchor {x, y}, stiffness, compliance, max_rate (m/s of anchor travel, 0 = no limit).
---@param p tether.particle
---@param opts? table
---@return tether.constraint
function world:pin(p, opts) end
---Keeps particles inside (or, outside = true, out of) a box. opts: particles, outside, friction.
---@return tether.constraint
function world:bounds(xmin, ymin, xmax, ymax, opts) end
---Angle at b within [min, max] rad. opts: min, max, stiffness, compliance.
---@return tether.constraint
function world:angle(a, b, c, opts) end
---Polygon area kept at pressure × rest area. opts: area, pressure, stiffness, compliance.
---@param handles tether.particle[]
---@return tether.constraint
function world:area(handles, opts) end
---b kept on the line through a and c. opts: stiffness, compliance.
---@return tether.constraint
function world:collinear(a, b, c, opts) end
---@param c tether.constraint
function world:remove_constraint(c) end
---@return boolean
function world:constraint_is_valid(c) end
---@return "distance"|"pin"|"bounds"|"angle"|"area"|"collinear"
function world:constraint_kind(c) end
---Error now: m, rad (angle) or m² (area).
---@return number
function world:constraint_error(c) end
---@return tether.particle[]
function world:constraint_particles(c) end
---fields: stiffness, compliance, length, anchor {x, y}, box {xmin, ymin, xmax, ymax}, max_rate (m/s, distance and pin).
---A new length or anchor is reached across the substeps of the next step (at most max_rate m/s when set).
function world:set_constraint(c, fields) end
---@return number x, number y
function world:pin_anchor(c) end
---@return number m
function world:rest_length(c) end
---@return integer
function world:constraint_count() end
---Segments {x1, y1, x2, y2, …} of distance constraints, then pins.
---@param t? number[]
---@return number[] xy, integer n
function world:constraint_lines(t) end
---Constraints broken in the last step.
---@return {constraint: tether.constraint, a: tether.particle, b: tether.particle, length: number, strain: number}[]
function world:break_events() end
---opts: start, finish, segments, pin_start, pin_finish, slack, break_strain + composite options.
---@return tether.composite
function world:rope(opts) end
---opts: origin, width, height, columns, rows, shear_stiffness, bend_stiffness, pin_top_corners, pin_top_row, break_strain, long_range (attachments to the pins, and between two pinned corners an angle limit that keeps the top band from sagging: no stretch under its own weight; not with break_strain) + composite options.
---@return tether.composite
function world:cloth(opts) end
---opts: position, height, limits + composite options.
---@return tether.composite
function world:ragdoll(opts) end
---opts: center, ring_radius (m; radius is each particle's), segments, pressure, area_stiffness, area_compliance + composite options.
---@return tether.composite
function world:soft_body(opts) end
---opts: center, width, height, angle, columns, rows or points {x1, y1, …} (no point repeated, no three consecutive on a line) + composite options.
---@return tether.composite
function world:lattice(opts) end
---@param h tether.composite
function world:remove_composite(h) end
---@return boolean
function world:composite_is_valid(h) end
---@return tether.particle[]
function world:composite_particles(h) end
---@return tether.constraint[]
function world:composite_constraints(h) end
---@return number x, number y
function world:composite_center(h) end
---@return number rad
function world:composite_angle(h) end
---@return integer
function world:composite_count() end
-- Collisions (src/lua/lua_collide.c; docs/collisions.md) --------------------------

---@alias tether.shape integer

---@class tether.shape_options
---@field restitution? number bounce 0..1, default 0
---@field friction? number sets friction_static and friction_kinetic
---@field friction_static? number default 0.6
---@field friction_kinetic? number default 0.5
---@field category? integer layer bits, default 1
---@field mask? integer default 0xFFFF
---@field sensor? boolean reports overlaps, never pushes; default false
---@field angle? number rad (box, polygon)
---@field loop? boolean chain: close it

---@class tether.collision_settings
---@field particles? boolean particle-particle contacts, default true
---@field broadphase? "grid"|"brute"
---@field cell_size? number m, 0 = auto
---@field restitution? number particles' default bounce
---@field friction? number particles' default friction (both)
---@field friction_static? number
---@field friction_kinetic? number
---@field restitution_threshold? number m/s
---@field stacking? number mass scaling by height for piles, ≥ 0 (0 = off; 2 for deep piles)
---@field anchored_friction? boolean particle pairs' static friction held across substeps: piles and stacks of circles stand (default false)
---@field warm_start? number with anchored friction, 0…1: the share of a resting pair's last normal correction pushed before the sweeps, so a pile rests under 1 % at few sweeps (default 0 = off; 0.75 for piles)
---@field events? ("begin"|"persist"|"end")[]

---@class tether.ray_hit
---@field particle? tether.particle
---@field shape? tether.shape
---@field terrain? tether.terrain
---@field x number
---@field y number
---@field nx number
---@field ny number
---@field fraction number

---@class tether.contact
---@field kind "begin"|"persist"|"end"
---@field a tether.particle
---@field b? tether.particle
---@field shape? tether.shape
---@field terrain? tether.terrain
---@field x number
---@field y number
---@field nx number
---@field ny number
---@field impulse number N·s
---@field sensor boolean

---A two-sided segment.
---@return tether.shape
function world:segment(x1, y1, x2, y2, opts) end
---A polyline through {x1, y1, x2, y2, ...}.
---@param points number[]
---@param opts? tether.shape_options
---@return tether.shape
function world:chain(points, opts) end
---Axis-aligned box from min to max corner.
---@return tether.shape
function world:aabb(x1, y1, x2, y2, opts) end
---Oriented box: centre, half extents, opts.angle.
---@return tether.shape
function world:box(cx, cy, half_w, half_h, opts) end
---A static circle.
---@return tether.shape
function world:circle(x, y, r, opts) end
---A segment with a radius.
---@return tether.shape
function world:capsule(x1, y1, x2, y2, r, opts) end
---A convex polygon {x1, y1, ...}, 3..64 points.
---@param points number[]
---@param opts? tether.shape_options
---@return tether.shape
function world:polygon(points, opts) end
---@param s tether.shape
function world:remove_shape(s) end
---@param s tether.shape
---@return boolean
function world:shape_is_valid(s) end
---@return integer
function world:shape_count() end
---@param s tether.shape
---@return string
function world:shape_type(s) end
---@param s tether.shape
---@return number x, number y, number angle
function world:shape_transform(s) end
---Kinematic move of a shape.
---@param s tether.shape
function world:set_shape_transform(s, x, y, angle) end
---@param s tether.shape
function world:set_shape_material(s, restitution, friction_static, friction_kinetic) end
---@param s tether.shape
function world:set_shape_filter(s, category, mask) end
---@param s tether.shape
---@param sensor boolean
function world:set_shape_sensor(s, sensor) end
---@param s tether.shape
---@return number x1, number y1, number x2, number y2
function world:shape_aabb(s) end
---Switches collisions on.
---@param opts? tether.collision_settings
function world:set_collision(opts) end
---@return tether.collision_settings
function world:collision() end
---@return table
function world:collision_stats() end
---@param p tether.particle
function world:set_material(p, restitution, friction_static, friction_kinetic) end
---@param p tether.particle
---@return number restitution, number friction_static, number friction_kinetic
function world:material(p) end
---Continuous detection against shapes for this particle.
---@param p tether.particle
---@param bullet boolean
function world:set_bullet(p, bullet) end
---@param p tether.particle
---@return boolean
function world:bullet(p) end
---@param a tether.particle
---@param b tether.particle
---@param enabled boolean
function world:set_pair_collision(a, b, enabled) end
---First hit along the segment, or nil.
---@return tether.ray_hit?
function world:raycast(x1, y1, x2, y2, mask) end
---Particles and shapes containing the point, and terrains with a solid pixel there.
---@return tether.particle[] particles, tether.shape[] shapes, tether.terrain[] terrains
function world:query_point(x, y, mask) end
---Particles and shapes overlapping the box, and terrains with a solid pixel in it.
---@return tether.particle[] particles, tether.shape[] shapes, tether.terrain[] terrains
function world:query_aabb(x1, y1, x2, y2, mask) end
---Contact events of the last step.
---@return tether.contact[]
function world:contacts() end

-- ---------------------------------------------------------------------------
-- Terrains: carvable pixel-mask ground (include/tether/terrain.h). A terrain
-- copies the mask it is made from: the mask may change or be collected at once.

---@alias tether.terrain integer

---@class tether.terrain_options
---@field origin? number[] {x, y}: pixel (0, 0)'s top-left corner, m; default {0, 0}
---@field pixel? number m per pixel, > 0; default 0.05
---@field band? integer distance band, 5…32 pixels; default 10 (radii up to band − 4 pixels are seen: give band ≥ radius / pixel + 4)
---@field restitution? number 0…1; default 0
---@field friction? number sets both frictions
---@field friction_static? number default 0.6
---@field friction_kinetic? number default 0.5
---@field category? integer default 1
---@field mask? integer default 0xFFFF

---A terrain from mask m (copied): set pixels are solid; rows go down, the world's y up.
---@param m tether.mask
---@param opts? tether.terrain_options
---@return tether.terrain
function world:terrain(m, opts) end
---@param t tether.terrain
function world:remove_terrain(t) end
---@param t tether.terrain
---@return boolean
function world:terrain_is_valid(t) end
---@return integer
function world:terrain_count() end
---Erases the pixels whose centres lie in the circle (world m); wakes what rests nearby.
---@param t tether.terrain
function world:carve(t, x, y, r) end
---Fills the pixels whose centres lie in the circle.
---@param t tether.terrain
function world:fill(t, x, y, r) end
---Erases the pixels set in m, m's pixel (0, 0) on the terrain's pixel (dx, dy).
---@param t tether.terrain
---@param m tether.mask
function world:carve_mask(t, m, dx, dy) end
---Fills the pixels set in m, m's pixel (0, 0) on the terrain's pixel (dx, dy).
---@param t tether.terrain
---@param m tether.mask
function world:fill_mask(t, m, dx, dy) end
---A copy of the terrain's pixels (into: a mask of the same size, overwritten and returned).
---@param t tether.terrain
---@param into? tether.mask
---@return tether.mask
function world:terrain_mask(t, into) end
---@param t tether.terrain
---@return number x, number y, number pixel origin (m) and pixel size (m)
function world:terrain_place(t) end
---Signed distance to the surface (m, negative inside, clamped to the band) and the outward normal.
---@param t tether.terrain
---@return number d, number nx, number ny
function world:terrain_distance(t, x, y) end
---Whether the point lies in a solid pixel.
---@param t tether.terrain
---@return boolean
function world:terrain_solid(t, x, y) end
---@param t tether.terrain
---@param friction_kinetic? number default friction_static
function world:set_terrain_material(t, restitution, friction_static, friction_kinetic) end
-- ---------------------------------------------------------------------------
-- Drawing (runner only): tether.draw(g), tether.gfx, world:draw(), tether.runner.
-- Reference: the section "Drawing, the window and PNG frames" of docs/lua-api.md.

---@alias tether.draw_mode
---| "fill" # filled (the default)
---| "line" # outline, of the current line width

---@alias tether.layer
---| "world"  # world units through the camera, y up (the default each frame)
---| "screen" # pixels from the top-left corner, y down: for a HUD

---Called once per frame by the runner (window, or --headless --out DIR), after
---the frame's tether.update calls; g is tether.gfx.
---@type fun(g: tether.gfx)?
tether.draw = nil

---How the runner shows this script; nil under stock lua5.4.
---@class tether.runner_info
---@field mode "window"|"frames"|"headless"
---@field width integer frame or window width, px
---@field height integer frame or window height, px
---@field dt number the fixed step, s
---@field every integer tether.update calls per frame (frames mode)
---@field frames? integer frames to draw, when given
---@field out? string folder of the PNG frames (frames mode)

---@type tether.runner_info?
tether.runner = nil

---Drawing functions; valid only inside tether.draw(g) under the runner.
---@class tether.gfx
tether.gfx = {}

---Sets the colour of what follows (numbers in [0, 1], a default 1); without arguments returns it.
---@param r? number
---@param g? number
---@param b? number
---@param a? number
---@return number? r, number? g, number? b, number? a
function tether.gfx.color(r, g, b, a) end

---Starts the frame over on this background colour.
---@param r number
---@param g number
---@param b number
function tether.gfx.clear(r, g, b) end

---A circle; r >= 0 in layer units.
---@param x number
---@param y number
---@param r number
---@param mode? tether.draw_mode default "fill"
function tether.gfx.circle(x, y, r, mode) end

---A polyline through 2 or more points: g.line(x1, y1, x2, y2, ...).
---@param ... number
function tether.gfx.line(...) end

---A polygon of 3 or more points {x1, y1, x2, y2, ...}, either winding, concave allowed.
---@param points number[]
---@param mode? tether.draw_mode default "fill"
function tether.gfx.polygon(points, mode) end

---Text in the built-in 5x7 font, top-left corner at (x, y).
---@param x number
---@param y number
---@param text string
---@param scale? integer 1..64 px per font pixel; default 1
function tether.gfx.text(x, y, text, scale) end

---Width of lines and outlines, px in [0.1, 1000]; default 1.5.
---@param px number
function tether.gfx.line_width(px) end

---Layer of what follows.
---@param name tether.layer
function tether.gfx.layer(name) end

---Sets the camera (world point at the centre, zoom in px per world unit); without arguments returns it.
---@param x? number
---@param y? number
---@param zoom? number in [1e-9, 1e9] px per world unit
---@return number? x, number? y, number? zoom
function tether.gfx.camera(x, y, zoom) end

---Camera so the world rectangle fills the frame.
---@param x1 number
---@param y1 number
---@param x2 number > x1
---@param y2 number > y1
---@param margin? number px; default 10
function tether.gfx.fit(x1, y1, x2, y2, margin) end

---The frame size in pixels.
---@return integer width, integer height
function tether.gfx.size() end

---World point to pixel (through the current camera).
---@return number px, number py
function tether.gfx.to_screen(x, y) end

---Pixel to world point (through the current camera).
---@return number x, number y
function tether.gfx.to_world(px, py) end

---A HUD panel at the top-left: time, step time, particles, springs, iterations, error (+ text).
---@param w tether.world
---@param text? string
function tether.gfx.hud(w, text) end

---An RGBA image, drawn as a texture with g.image. Freed by the collector or
---at the end of a `<close>` scope; one drawn in the frame being made is freed
---once that frame has been rendered.
---@class tether.image
local image = {}
---@return integer width, integer height
function image:size() end
---Colour of pixel (x, y), x in [0, width-1], y in [0, height-1] from the top; numbers in [0, 1].
---@return number r, number g, number b, number a
function image:pixel(x, y) end
---@param a? number default 1
function image:set_pixel(x, y, r, g, b, a) end
---@param a? number default 1
function image:fill(r, g, b, a) end

---A new image, 1..8192 pixels a side, transparent black.
---@param width integer
---@param height integer
---@return tether.image
function tether.gfx.new_image(width, height) end

---Reads a PNG file (runner only: absent under stock lua5.4).
---@param path string
---@return tether.image? image
---@return string? message
function tether.gfx.load_image(path) end

---Draws an image stretched over the rectangle (its first row at the top), tinted by the current colour.
---@param img tether.image
---@param x1 number
---@param y1 number
---@param x2 number
---@param y2 number
function tether.gfx.image(img, x1, y1, x2, y2) end

---@class tether.draw_options
---@field particles? boolean default true
---@field springs? boolean default true; coloured by strain
---@field constraints? boolean default true
---@field shapes? boolean default true
---@field color? number[] {r, g, b [, a]} of particles
---@field pinned? number[] {r, g, b [, a]} of pinned particles
---@field min_radius? number px, in [0, 1000]; default 1.5
---@field alpha? number in [0, 1]: particles and springs drawn at previous + alpha*(current - previous), between the last two steps; default the frame's (the runner's clock alpha in a window, 1 headless: the current positions). Below 1 it turns w:set_interpolation(true) on

---Debug draw of the whole world (shapes, springs, constraints, particles) on the world layer;
---the world becomes draggable with the mouse in the window.
---@param opts? tether.draw_options
function world:draw(opts) end

---Keeps (true) or drops (false) where every particle was as each step began, for
---drawing between steps (w:draw{alpha=}): 16 bytes a particle, any integrator. Not
---world state: the hash and snapshots do not see it. Default false.
---@param on boolean
function world:set_interpolation(on) end

---Whether the world keeps its previous positions (w:set_interpolation).
---@return boolean
function world:interpolation() end

---A width × height bit mask (1..16384 a side) for pixel-perfect collision.
---Pixel (0, 0) is the image's top-left; y goes down (the world's goes up).
---Offsets dx, dy are integers within ±1e9: other's pixel (bx, by) lies on (bx + dx, by + dy).
---@class tether.mask
local mask = {}
---@return integer width, integer height
function mask:size() end
---@return boolean
function mask:get(x, y) end
---@param value? boolean default true
function mask:set(x, y, value) end
---@return integer
function mask:count() end
function mask:clear() end
function mask:fill() end
function mask:invert() end
---@return integer x, integer y, integer width, integer height
function mask:bounding_rect() end
---@return number x, number y
function mask:centroid() end
---@return tether.mask
function mask:copy() end
---Turned counter-clockwise on screen, radians.
---@return tether.mask
function mask:rotated(angle) end
---@return tether.mask
function mask:scaled(width, height) end
---Rows of '#' and '.' joined by "\n".
---@return string
function mask:to_string() end
---@param path string
function mask:save(path) end
---@param value? boolean default true
function mask:fill_circle(cx, cy, r, value) end
---@param value? boolean default true
function mask:fill_rect(x, y, w, h, value) end
---@param points number[] {x1, y1, ...}
---@param value? boolean default true
function mask:fill_polygon(points, value) end
---@param other tether.mask
function mask:draw(other, dx, dy) end
---@param other tether.mask
function mask:erase(other, dx, dy) end
---The first overlapping pixel (topmost row, leftmost), in this mask's frame; nil when none.
---@param other tether.mask
---@return integer? x, integer? y
function mask:overlap(other, dx, dy) end
---@param other tether.mask
---@return integer
function mask:overlap_area(other, dx, dy) end
---@param other tether.mask
---@return tether.mask
function mask:overlap_mask(other, dx, dy) end
---Unit direction (image frame, y down) to push other out; 0, 0 when none.
---@param other tether.mask
---@return number nx, number ny
function mask:overlap_normal(other, dx, dy) end
---@param other tether.mask
---@return tether.mask
function mask:convolve(other) end
---@return integer
function mask:components() end
---The component at pixel (x, y), or the largest without arguments.
---@return tether.mask
function mask:component(x, y) end
---@return integer[][] rects {{x, y, w, h}, ...}
function mask:component_rects() end
---@return integer[] xy {x1, y1, x2, y2, ...}
function mask:outline() end
---@param tolerance? number pixels, default 0.5
---@return number[][] lines {{x1, y1, ...}, ...}
function mask:polylines(tolerance) end
---@return tether.image
function mask:to_image(r, g, b, a) end
---@param img tether.image
function mask:paint(img, r, g, b, a) end

---@class tether.mask_module
tether.mask = {}
---@return tether.mask
function tether.mask.new(width, height, filled) end
---@param rows string
---@return tether.mask
function tether.mask.from_string(rows) end
---@param path string
---@param threshold? integer 0..254, default 127
---@return tether.mask
function tether.mask.load(path, threshold) end
---@param img tether.image
---@return tether.mask
function tether.mask.from_image(img, threshold) end
---@param img tether.image
---@return tether.mask
function tether.mask.from_color(img, r, g, b, tolerance, invert) end
---@return tether.mask
function tether.mask.circle(radius) end
---@return tether.mask
function tether.mask.rect(width, height) end
---@param points number[] {x1, y1, ...}
---@return tether.mask
function tether.mask.polygon(points) end

---@class tether.mask_chain_options
---@field origin? number[] {x, y}: world position of pixel (0, 0)'s top-left corner; default {0, 0}
---@field pixel? number metres per pixel; default 1
---@field tolerance? number pixels; default 0.5
---@field restitution? number
---@field friction? number sets both frictions
---@field friction_static? number
---@field friction_kinetic? number
---@field category? integer
---@field mask? integer
---@field sensor? boolean

---The mask's outline as static looped chains (image rows go down, world y up).
---@param m tether.mask
---@param opts? tether.mask_chain_options
---@return integer[] shapes
function world:mask_chains(m, opts) end

---Draws a mask stretched over the world rectangle, set pixels in the current colour, its top row at the top.
---@param m tether.mask
function tether.gfx.mask(m, x1, y1, x2, y2) end

return tether
