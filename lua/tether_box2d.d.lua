---@meta tether_box2d
-- LuaLS (lua-language-server) annotations for the tether_box2d module: Box2D
-- 2.4.1 worlds beside a tether world, the shared scenes as tables, and the
-- cross-check (README "Box2D cross-check"). Definitions only: never run.
--
-- Bodies are numbered from 1 in creation order; in a joint, body 0 is the
-- ground. Misuse raises an error naming the function and the argument
-- ("tether_box2d.world:state: bad argument #2 (no such body)"). Option tables
-- are read as tether's own are: an unknown key is refused with the list of
-- keys ("tether_box2d.world: unknown option 'slep' (expected one of: …)"),
-- a bad value names the key ("bad option 'sleep' (boolean expected, got
-- number)"); numbers must be finite, Box2D refuses what it cannot build.

---@alias tether_box2d.shape_name
---| "circle"  # radius
---| "box"     # half extents hx, hy
---| "polygon" # points = {x1, y1, x2, y2, …}: 3 to 8 corners, convex, counter-clockwise
---| "edge"    # a = {x, y}, b = {x, y}; static only

---@alias tether_box2d.joint_name
---| "revolute" # a hinge at the anchor
---| "distance" # a rigid rod between the two anchors
---| "weld"     # the two bodies glued at the anchor

---Options of a Box2D world (also the options of `tether_box2d.build`).
---@class tether_box2d.world_options
---@field gravity? number[] {x, y} in m/s² (default {0, -10}; `build` takes the scene's)
---@field velocity_iterations? integer 1…1000 (default 8)
---@field position_iterations? integer 1…1000 (default 3)
---@field sleep? boolean Box2D's sleeping (default true: Box2D's own default)
---@field continuous? boolean continuous collision (default true: Box2D's own default)

---A body: the keys of `w:body` and of a scene's `bodies` entries.
---@class tether_box2d.body
---@field shape tether_box2d.shape_name
---@field dynamic? boolean false: static (default)
---@field x? number position (m)
---@field y? number
---@field angle? number radians
---@field vx? number velocity (m/s)
---@field vy? number
---@field spin? number angular velocity (rad/s)
---@field radius? number circle (m, default 0.5)
---@field hx? number box half width (m, default 0.5)
---@field hy? number box half height (m, default 0.5)
---@field points? number[] polygon corners, local to the body: x1, y1, x2, y2, …
---@field a? number[] edge end {x, y}
---@field b? number[] edge end {x, y}
---@field density? number kg/m² (dynamic bodies; default 1)
---@field friction? number default 0.3; Box2D combines two as √(fa·fb)
---@field restitution? number 0…1, default 0; Box2D takes the larger of two
---@field fixed_rotation? boolean never turns, as tether's particles (default false)

---A joint of a scene table.
---@class tether_box2d.joint
---@field kind tether_box2d.joint_name
---@field a integer body number, 0: the ground
---@field b integer body number (a dynamic body)
---@field anchor_a number[] {x, y} in world coordinates
---@field anchor_b? number[] {x, y} (distance joints; default anchor_a)

---A scene both engines build from (`tether_box2d.scene`).
---@class tether_box2d.scene
---@field name string
---@field gravity number[] {x, y}
---@field dt number the fixed step (s)
---@field steps integer how many steps the cross-check runs
---@field bodies tether_box2d.body[]
---@field joints tether_box2d.joint[]

---One measured row of the cross-check; a missing number is nil.
---@class tether_box2d.row
---@field scene string
---@field measure string
---@field setting string tether's setting, e.g. "1x8" (substeps × sweeps)
---@field unit string
---@field expected? number the analytic answer, where there is one
---@field box2d? number
---@field tether? number

---The timed cost of one scene at one setting (median ms per step).
---@class tether_box2d.cost
---@field scene string
---@field setting string
---@field box2d_ms number
---@field tether_ms? number

---@class tether_box2d.world
local world = {}

---Adds a body; returns its number (from 1).
---@param def tether_box2d.body
---@return integer body
function world:body(def) end

---Adds a joint between body a (0: the ground) and body b at the anchor
---(ax, ay); a distance joint's second anchor is (bx, by), default the first.
---@param kind tether_box2d.joint_name
---@param a integer
---@param b integer
---@param ax number
---@param ay number
---@param bx? number
---@param by? number
---@return integer joint
function world:joint(kind, a, b, ax, ay, bx, by) end

---Steps the world by dt seconds, 0 < dt ≤ 10.
---@param dt number
function world:step(dt) end

---A body's position, angle, velocity and angular velocity.
---@param body integer
---@return number x, number y, number angle, number vx, number vy, number spin
function world:state(body) end

---How many bodies the world holds.
---@return integer
function world:count() end

---Kinetic energy (J) and the dynamic bodies' total mass (kg).
---@return number energy, number mass
function world:energy() end

---Frees the Box2D world now (the collector does it otherwise); any later
---call on it raises "attempt to use a destroyed tether_box2d world".
function world:destroy() end

---@class tether_box2d
---@field version string the Box2D it links, "Box2D 2.4.1".
local tether_box2d = {}

---A new, empty Box2D world.
---@param options? tether_box2d.world_options
---@return tether_box2d.world
function tether_box2d.world(options) end

---A named scene as a plain table: fall, pendulum, bounce, slope, spin,
---pyramid, discs, pour, pour100k; `quick` gives the small size the tests use.
---@param name string
---@param quick? boolean
---@return tether_box2d.scene
function tether_box2d.scene(name, quick) end

---A Box2D world built from a scene table (any table of that shape).
---@param scene tether_box2d.scene
---@param options? tether_box2d.world_options
---@return tether_box2d.world
function tether_box2d.build(scene, options) end

---Runs the cross-check on one scene (all when nil): the measured rows and
---the timed costs; `print` also prints the table `make crosscheck` prints.
---@param scene? string
---@param options? { quick?: boolean, print?: boolean, runs?: integer }
---@return tether_box2d.row[] rows, tether_box2d.cost[] costs
function tether_box2d.crosscheck(scene, options) end

---The command line of `tether crosscheck` (its arguments as strings);
---returns the exit status.
---@param ... string
---@return integer status
function tether_box2d.main(...) end

return tether_box2d
