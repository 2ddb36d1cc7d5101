/* tether — the Lua world class (metatable "tether.world") and its methods.
 *
 * A thin layer: every method checks all its arguments (lua_common.c) before
 * it calls the C core, so nothing the core would refuse ever reaches it; if
 * the core refuses anyway, its message is raised as "method: message".
 * Handles are Lua integers (tt_particle_to_u64 / tt_spring_to_u64). The
 * world userdata's user value 1 is a table handle → Lua value (w:user).
 *
 * Lua code can run in the middle of a method: an __index of an option
 * table, a __close, a finalizer that one of the method's own allocations
 * lets the collector run. Whatever it does, it must not free what the
 * method is using, so every method runs with its world pinned (pinned_call):
 * a pinned world that is destroyed is marked destroyed at once (every later
 * use raises) and freed when the outermost call on it returns. What a
 * method reads from the world it copies into C memory (scratch) before it
 * makes any Lua value, since that Lua code may also step or grow the world. */
#include "lua_common.h"

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A reusable buffer of the bulk accessors, so that reading positions every
 * frame allocates nothing. */
typedef struct lw_buffer {
    void *p;
    size_t cap;
} lw_buffer;

/* The userdata. Made with w = NULL (harmless) before the world exists;
 * w = NULL again once freed. scratch[d] belongs to the call at depth d + 1
 * (a call nested in another on the same world must not clobber the outer
 * one's buffer while it is still reading it). */
typedef struct lw_world {
    tt_world *w;
    bool dead;         /* destroyed: no new call may use it; freed when pins is 0 */
    unsigned pins;     /* calls running on this world, nested ones included */
    lw_buffer *scratch;
    unsigned nscratch;
} lw_world;

/* Same order as tt_integrator. */
static const char *const integrator_names[] = { "euler", "symplectic_euler", "leapfrog", "verlet", "rk4", NULL };
_Static_assert(TT_INTEGRATOR_COUNT == 5, "integrator_names lists every tt_integrator");

static const char *const move_modes[] = { "keep", "reset", NULL };

/* --- checkers --------------------------------------------------------------- */

/* The one checker of the class: a live world at arg. */
tt_world *tl_check_world(lua_State *L, int arg)
{
    lw_world *u = luaL_testudata(L, arg, TL_WORLD_CLASS);
    if (u == NULL)
        tl_typeerror(L, arg, TL_WORLD_CLASS);
    if (u->dead)
        tl_argerror(L, arg, "attempt to use a destroyed world");
    return u->w;
}

tt_world *tl_toworld(lua_State *L, int idx)
{
    lw_world *u = luaL_testudata(L, idx, TL_WORLD_CLASS);
    return u && !u->dead ? u->w : NULL;
}

/* The handle checker: a live particle (or spring) of w at arg. */
tt_particle tl_check_particle(lua_State *L, tt_world *w, int arg)
{
    tt_particle p = tt_particle_from_u64(tl_checkhandle(L, arg, "particle"));
    if (!tt_particle_is_valid(w, p))
        tl_argerror(L, arg, "stale particle handle");
    return p;
}

static tt_spring check_spring(lua_State *L, tt_world *w, int arg)
{
    tt_spring s = tt_spring_from_u64(tl_checkhandle(L, arg, "spring"));
    if (!tt_spring_is_valid(w, s))
        tl_argerror(L, arg, "stale spring handle");
    return s;
}

/* A failed C call: raises "method: <tt_last_error>". */
void tl_check_result(lua_State *L, const tt_world *w, tt_result r)
{
    if (r != TT_OK) {
        const char *msg = tt_last_error(w);
        if (msg == NULL || msg[0] == '\0')
            msg = tt_result_string(r);
        /* The core names its C function ("tt_particle_set_velocity: …"); the
         * Lua error already names the Lua one, so say it once. */
        const char *colon = strncmp(msg, "tt_", 3) == 0 ? strstr(msg, ": ") : NULL;
        tl_error(L, "%s", colon ? colon + 2 : msg);
    }
}

void tl_push_particle(lua_State *L, tt_particle p)
{
    lua_pushinteger(L, (lua_Integer)tt_particle_to_u64(p));
}

static void push_spring(lua_State *L, tt_spring s)
{
    lua_pushinteger(L, (lua_Integer)tt_spring_to_u64(s));
}

void *tl_scratch(lua_State *L, size_t bytes)
{
    lw_world *u = lua_touserdata(L, 1);
    unsigned d = u->pins > 0 ? u->pins - 1 : 0;
    if (d >= u->nscratch) {
        lw_buffer *v = realloc(u->scratch, (d + 1) * sizeof *v);
        if (v == NULL)
            tl_error(L, "not enough memory");
        memset(v + u->nscratch, 0, (d + 1 - u->nscratch) * sizeof *v);
        u->scratch = v;
        u->nscratch = d + 1;
    }
    lw_buffer *b = &u->scratch[d];
    if (bytes > b->cap) {
        size_t cap = bytes < 4096 ? 4096 : bytes;
        void *p = realloc(b->p, cap);
        if (p == NULL)
            tl_error(L, "not enough memory (%I bytes)", (LUAI_UACINT)bytes);
        b->p = p;
        b->cap = cap;
    }
    return b->p;
}

/* Pushes the world's handle → user value table. */
static void push_users(lua_State *L)
{
    lua_getiuservalue(L, 1, 1);
}

/* Forgets the user value of handle h. */
static void clear_user(lua_State *L, uint64_t h)
{
    push_users(L);
    if (lua_istable(L, -1)) {
        lua_pushnil(L);
        lua_rawseti(L, -2, (lua_Integer)h);
    }
    lua_pop(L, 1);
}

/* --- construction and life cycle -------------------------------------------- */

static const char *const world_opts[] = { "gravity", "integrator", "damping", "wind", "dt_hint", "capacity",
                                          "substeps", "iterations", "tolerance", "solver", NULL };
/* Same order as tt_solver_order. */
static const char *const solver_names[] = { "gauss_seidel", "jacobi", NULL };

int tl_world_new(lua_State *L)
{
    tt_world_def def = tt_world_def_default();
    lw_world *u;

    lua_settop(L, 1);
    tl_checkopts(L, 1, world_opts);
    def.gravity = tl_optfield_vec2(L, 1, "gravity", &TL_R_COORD, def.gravity);
    def.integrator = (tt_integrator)tl_optfield_option(L, 1, "integrator", "integrator", integrator_names, (int)def.integrator);
    def.damping = tl_optfield_number(L, 1, "damping", &TL_R_NONNEG, def.damping);
    def.wind = tl_optfield_vec2(L, 1, "wind", &TL_R_COORD, def.wind);
    def.dt_hint = tl_optfield_number(L, 1, "dt_hint", &TL_R_DT, def.dt_hint);
    def.capacity = (uint32_t)tl_optfield_integer(L, 1, "capacity", 0, TL_MAX_CAPACITY, def.capacity);
    def.substeps = (uint32_t)tl_optfield_integer(L, 1, "substeps", 1, TT_MAX_SUBSTEPS, def.substeps);
    def.iterations = (uint32_t)tl_optfield_integer(L, 1, "iterations", 1, TT_MAX_ITERATIONS, def.iterations);
    def.tolerance = tl_optfield_number(L, 1, "tolerance", &TL_R_NONNEG, def.tolerance);
    def.order = (tt_solver_order)tl_optfield_option(L, 1, "solver", "solver", solver_names, (int)def.order);

    /* Harmless first: a userdata with no world, its metatable and its user
     * table; only then the world. An error in between leaves nothing. */
    u = lua_newuserdatauv(L, sizeof *u, 1);
    memset(u, 0, sizeof *u);
    luaL_setmetatable(L, TL_WORLD_CLASS);
    lua_newtable(L);
    lua_setiuservalue(L, -2, 1);

    u->w = tt_world_create(&def);
    if (u->w == NULL)
        tl_error(L, "%s", tt_last_error(NULL));
    return 1;
}

/* Frees what the userdata at idx holds, now; safe to repeat. */
static void release(lua_State *L, int idx)
{
    lw_world *u = lua_touserdata(L, idx);
    u->dead = true;
    tt_world_destroy(u->w);
    u->w = NULL;
    for (unsigned i = 0; i < u->nscratch; i++)
        free(u->scratch[i].p);
    free(u->scratch);
    u->scratch = NULL;
    u->nscratch = 0;
    lua_pushnil(L);
    lua_setiuservalue(L, idx, 1);
}

/* w:destroy() and __close — idempotent. Inside a call on this world (from an
 * __index, a finalizer, …) the world is freed when that call returns: the
 * call finishes on it, and every use after this one raises. */
static int w_destroy(lua_State *L)
{
    lw_world *u = luaL_testudata(L, 1, TL_WORLD_CLASS);
    if (u == NULL)
        tl_typeerror(L, 1, TL_WORLD_CLASS);
    u->dead = true;
    if (u->pins == 0)
        release(L, 1);
    return 0;
}

/* The collector frees it whatever the pins say: an unreachable world is in
 * no running call, and lua_close (os.exit(…, true) from inside a call)
 * never returns to the calls still pinning it. */
static int w_gc(lua_State *L)
{
    if (luaL_testudata(L, 1, TL_WORLD_CLASS) != NULL)
        release(L, 1);
    return 0;
}

/* Every function whose argument 1 is a world runs through here, with that
 * world pinned for the whole call. The call is protected so that the pin
 * is dropped however it ends; an error is raised again unchanged.
 * Upvalues: 1 the name, 2 the function (a closure with the same name). */
static int pinned_call(lua_State *L)
{
    lw_world *u = luaL_testudata(L, 1, TL_WORLD_CLASS);
    int status;
    if (u == NULL || u->w == NULL) /* nothing to pin: the function raises its own error */
        return lua_tocfunction(L, lua_upvalueindex(2))(L);
    u->pins++;
    lua_pushvalue(L, 1); /* the world stays on this frame, below the call */
    lua_insert(L, 1);
    lua_pushvalue(L, lua_upvalueindex(2));
    lua_insert(L, 2);
    status = lua_pcall(L, lua_gettop(L) - 2, LUA_MULTRET, 0);
    if (--u->pins == 0 && u->dead)
        release(L, 1);
    if (status != LUA_OK)
        return lua_error(L);
    return lua_gettop(L) - 1;
}

void tl_setfuncs_pinned(lua_State *L, const luaL_Reg *l, const char *prefix)
{
    for (; l->name != NULL; l++) {
        lua_pushfstring(L, "%s%s", prefix, l->name);
        lua_pushvalue(L, -1);
        lua_pushcclosure(L, l->func, 1);
        lua_pushcclosure(L, pinned_call, 2);
        lua_setfield(L, -2, l->name);
    }
}

static int w_tostring(lua_State *L)
{
    lw_world *u = luaL_testudata(L, 1, TL_WORLD_CLASS);
    if (u == NULL)
        return tl_typeerror(L, 1, TL_WORLD_CLASS);
    if (u->dead)
        lua_pushfstring(L, TL_WORLD_CLASS ": %p (destroyed)", (void *)u);
    else
        lua_pushfstring(L, TL_WORLD_CLASS ": %p (%I particles)", (void *)u,
                        (LUAI_UACINT)tt_world_particle_count(u->w));
    return 1;
}

/* --- particles -------------------------------------------------------------- */

static const char *const particle_opts[] = { "vx", "vy", "mass", "radius", "pinned", "category", "mask", "user", NULL };

/* w:particle(x, y [, opts]) → handle */
static int w_particle(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle_def def = tt_particle_def_default();
    tt_particle p;

    lua_settop(L, 4);
    def.position.x = tl_checknumber(L, 2, &TL_R_COORD);
    def.position.y = tl_checknumber(L, 3, &TL_R_COORD);
    tl_checkopts(L, 4, particle_opts);
    def.velocity.x = tl_optfield_number(L, 4, "vx", &TL_R_COORD, def.velocity.x);
    def.velocity.y = tl_optfield_number(L, 4, "vy", &TL_R_COORD, def.velocity.y);
    def.mass = tl_optfield_number(L, 4, "mass", &TL_R_MASS, def.mass);
    def.radius = tl_optfield_number(L, 4, "radius", &TL_R_NONNEG, def.radius);
    def.pinned = tl_optfield_boolean(L, 4, "pinned", def.pinned);
    def.category = (uint16_t)tl_optfield_integer(L, 4, "category", 0, 0xFFFF, def.category);
    def.mask = (uint16_t)tl_optfield_integer(L, 4, "mask", 0, 0xFFFF, def.mask);

    p = tt_particle_create(w, &def);
    if (p.gen == 0)
        tl_check_result(L, w, TT_ENOMEM);
    if (tl_getopt(L, 4, "user")) {
        push_users(L);
        lua_insert(L, -2);
        lua_rawseti(L, -2, (lua_Integer)tt_particle_to_u64(p));
        lua_pop(L, 1);
    }
    tl_push_particle(L, p);
    return 1;
}

/* w:remove(p) */
static int w_remove(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    tl_check_result(L, w, tt_particle_destroy(w, p));
    clear_user(L, tt_particle_to_u64(p));
    return 0;
}

/* w:is_valid(p) → boolean */
static int w_is_valid(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tt_particle_from_u64(tl_checkhandle(L, 2, "particle"));
    lua_pushboolean(L, tt_particle_is_valid(w, p));
    return 1;
}

static int w_position(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    tt_vec2 v;
    tl_check_result(L, w, tt_particle_get_position(w, p, &v));
    lua_pushnumber(L, v.x);
    lua_pushnumber(L, v.y);
    return 2;
}

/* w:set_position(p, x, y [, mode]) */
static int w_set_position(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    tt_vec2 v;
    int mode;
    v.x = tl_checknumber(L, 3, &TL_R_COORD);
    v.y = tl_checknumber(L, 4, &TL_R_COORD);
    mode = tl_checkoption(L, 5, "mode", "keep", move_modes);
    tl_check_result(L, w, tt_particle_set_position(w, p, v, mode == 0 ? TT_MOVE_KEEP_VELOCITY : TT_MOVE_RESET_VELOCITY));
    return 0;
}

static int w_velocity(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    tt_vec2 v;
    tl_check_result(L, w, tt_particle_get_velocity(w, p, &v));
    lua_pushnumber(L, v.x);
    lua_pushnumber(L, v.y);
    return 2;
}

static int w_set_velocity(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    tt_vec2 v;
    v.x = tl_checknumber(L, 3, &TL_R_COORD);
    v.y = tl_checknumber(L, 4, &TL_R_COORD);
    tl_check_result(L, w, tt_particle_set_velocity(w, p, v));
    return 0;
}

static int w_mass(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    double m;
    tl_check_result(L, w, tt_particle_get_mass(w, p, &m));
    lua_pushnumber(L, m);
    return 1;
}

static int w_set_mass(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    double m = tl_checknumber(L, 3, &TL_R_MASS);
    tl_check_result(L, w, tt_particle_set_mass(w, p, m));
    return 0;
}

static int w_pinned(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    bool b;
    tl_check_result(L, w, tt_particle_get_pinned(w, p, &b));
    lua_pushboolean(L, b);
    return 1;
}

static int w_set_pinned(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    bool b = tl_checkboolean(L, 3);
    tl_check_result(L, w, tt_particle_set_pinned(w, p, b));
    return 0;
}

static int w_radius(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    double r;
    tl_check_result(L, w, tt_particle_get_radius(w, p, &r));
    lua_pushnumber(L, r);
    return 1;
}

static int w_set_radius(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    double r = tl_checknumber(L, 3, &TL_R_NONNEG);
    tl_check_result(L, w, tt_particle_set_radius(w, p, r));
    return 0;
}

static int w_filter(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    uint16_t category, mask;
    tl_check_result(L, w, tt_particle_get_filter(w, p, &category, &mask));
    lua_pushinteger(L, category);
    lua_pushinteger(L, mask);
    return 2;
}

static int w_set_filter(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    uint16_t category = (uint16_t)tl_checkinteger(L, 3, 0, 0xFFFF);
    uint16_t mask = (uint16_t)tl_checkinteger(L, 4, 0, 0xFFFF);
    tl_check_result(L, w, tt_particle_set_filter(w, p, category, mask));
    return 0;
}

/* w:user(p) → the Lua value stored with p (nil if none) */
static int w_user(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    push_users(L);
    lua_rawgeti(L, -1, (lua_Integer)tt_particle_to_u64(p));
    return 1;
}

/* w:set_user(p, value) — any Lua value; nil forgets it */
static int w_set_user(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    lua_settop(L, 3);
    push_users(L);
    lua_pushvalue(L, 3);
    lua_rawseti(L, -2, (lua_Integer)tt_particle_to_u64(p));
    return 0;
}

static int w_apply_force(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    tt_vec2 f;
    f.x = tl_checknumber(L, 3, &TL_R_COORD);
    f.y = tl_checknumber(L, 4, &TL_R_COORD);
    tl_check_result(L, w, tt_particle_apply_force(w, p, f));
    return 0;
}

static int w_apply_impulse(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    tt_vec2 j;
    j.x = tl_checknumber(L, 3, &TL_R_COORD);
    j.y = tl_checknumber(L, 4, &TL_R_COORD);
    tl_check_result(L, w, tt_particle_apply_impulse(w, p, j));
    return 0;
}

/* w:explode(x, y, radius, impulse) */
static int w_explode(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_vec2 c;
    double radius, impulse;
    c.x = tl_checknumber(L, 2, &TL_R_COORD);
    c.y = tl_checknumber(L, 3, &TL_R_COORD);
    radius = tl_checknumber(L, 4, &TL_R_NONNEG);
    impulse = tl_checknumber(L, 5, &TL_R_COORD);
    tl_check_result(L, w, tt_world_explode(w, c, radius, impulse));
    return 0;
}

/* --- springs ---------------------------------------------------------------- */

static const char *const spring_opts[] = { "stiffness", "damping", "rest", NULL };

/* w:spring(a, b [, opts]) → spring handle */
static int w_spring(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_spring_def def = tt_spring_def_default();
    tt_spring s;

    lua_settop(L, 4);
    def.a = tl_check_particle(L, w, 2);
    def.b = tl_check_particle(L, w, 3);
    if (def.a.index == def.b.index && def.a.gen == def.b.gen)
        tl_argerror(L, 3, "a spring needs two distinct particles");
    tl_checkopts(L, 4, spring_opts);
    def.stiffness = tl_optfield_number(L, 4, "stiffness", &TL_R_NONNEG, def.stiffness);
    def.damping = tl_optfield_number(L, 4, "damping", &TL_R_NONNEG, def.damping);
    def.rest_length = tl_optfield_number(L, 4, "rest", &TL_R_NONNEG, def.rest_length);

    s = tt_spring_create(w, &def);
    if (s.gen == 0)
        tl_check_result(L, w, TT_EINVAL);
    push_spring(L, s);
    return 1;
}

static int w_remove_spring(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_spring s = check_spring(L, w, 2);
    tl_check_result(L, w, tt_spring_destroy(w, s));
    return 0;
}

static int w_spring_is_valid(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_spring s = tt_spring_from_u64(tl_checkhandle(L, 2, "spring"));
    lua_pushboolean(L, tt_spring_is_valid(w, s));
    return 1;
}

static int w_spring_length(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_spring s = check_spring(L, w, 2);
    double len;
    tl_check_result(L, w, tt_spring_get_length(w, s, &len));
    lua_pushnumber(L, len);
    return 1;
}

/* w:spring_info(s) → {a=, b=, stiffness=, damping=, rest=} */
static int w_spring_info(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_spring s = check_spring(L, w, 2);
    tt_spring_def d;
    tl_check_result(L, w, tt_spring_get_def(w, s, &d));
    lua_createtable(L, 0, 5);
    tl_push_particle(L, d.a);
    lua_setfield(L, -2, "a");
    tl_push_particle(L, d.b);
    lua_setfield(L, -2, "b");
    lua_pushnumber(L, d.stiffness);
    lua_setfield(L, -2, "stiffness");
    lua_pushnumber(L, d.damping);
    lua_setfield(L, -2, "damping");
    lua_pushnumber(L, d.rest_length);
    lua_setfield(L, -2, "rest");
    return 1;
}

/* w:set_spring(s, {stiffness=, damping=, rest=}) — only the given fields
 * change; all are checked before any changes. */
static int w_set_spring(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_spring s = check_spring(L, w, 2);
    double k, c, rest;

    lua_settop(L, 3);
    if (lua_type(L, 3) != LUA_TTABLE)
        tl_typeerror(L, 3, "table");
    tl_checkopts(L, 3, spring_opts);
    /* −1 marks a field that is absent: every valid value is ≥ 0 */
    k = tl_optfield_number(L, 3, "stiffness", &TL_R_NONNEG, -1.0);
    c = tl_optfield_number(L, 3, "damping", &TL_R_NONNEG, -1.0);
    rest = tl_optfield_number(L, 3, "rest", &TL_R_NONNEG, -1.0);
    if (k >= 0.0) tl_check_result(L, w, tt_spring_set_stiffness(w, s, k));
    if (c >= 0.0) tl_check_result(L, w, tt_spring_set_damping(w, s, c));
    if (rest >= 0.0) tl_check_result(L, w, tt_spring_set_rest_length(w, s, rest));
    return 0;
}

/* --- stepping and settings -------------------------------------------------- */

/* w:step(dt [, n]) */
static int w_step(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    double dt = tl_checknumber(L, 2, &TL_R_DT);
    lua_Integer n = tl_optinteger(L, 3, 1, TL_MAX_STEPS, 1);
    for (lua_Integer i = 0; i < n; i++)
        tl_check_result(L, w, tt_world_step(w, dt));
    return 0;
}

static int w_gravity(lua_State *L)
{
    tt_vec2 g = tt_world_get_gravity(tl_check_world(L, 1));
    lua_pushnumber(L, g.x);
    lua_pushnumber(L, g.y);
    return 2;
}

static int w_set_gravity(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_vec2 g;
    g.x = tl_checknumber(L, 2, &TL_R_COORD);
    g.y = tl_checknumber(L, 3, &TL_R_COORD);
    tl_check_result(L, w, tt_world_set_gravity(w, g));
    return 0;
}

static int w_wind(lua_State *L)
{
    tt_vec2 f = tt_world_get_wind(tl_check_world(L, 1));
    lua_pushnumber(L, f.x);
    lua_pushnumber(L, f.y);
    return 2;
}

static int w_set_wind(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_vec2 f;
    f.x = tl_checknumber(L, 2, &TL_R_COORD);
    f.y = tl_checknumber(L, 3, &TL_R_COORD);
    tl_check_result(L, w, tt_world_set_wind(w, f));
    return 0;
}

static int w_damping(lua_State *L)
{
    lua_pushnumber(L, tt_world_get_damping(tl_check_world(L, 1)));
    return 1;
}

static int w_set_damping(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    double d = tl_checknumber(L, 2, &TL_R_NONNEG);
    tl_check_result(L, w, tt_world_set_damping(w, d));
    return 0;
}

static int w_integrator(lua_State *L)
{
    tt_integrator i = tt_world_get_integrator(tl_check_world(L, 1));
    lua_pushstring(L, (unsigned)i < TT_INTEGRATOR_COUNT ? integrator_names[i] : tt_integrator_name(i));
    return 1;
}

static int w_set_integrator(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    int i = tl_checkoption(L, 2, "integrator", NULL, integrator_names);
    tl_check_result(L, w, tt_world_set_integrator(w, (tt_integrator)i));
    return 0;
}

static int w_substeps(lua_State *L)
{
    lua_pushinteger(L, tt_world_get_substeps(tl_check_world(L, 1)));
    return 1;
}

static int w_set_substeps(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tl_check_result(L, w, tt_world_set_substeps(w, (uint32_t)tl_checkinteger(L, 2, 1, TT_MAX_SUBSTEPS)));
    return 0;
}

static int w_iterations(lua_State *L)
{
    lua_pushinteger(L, tt_world_get_iterations(tl_check_world(L, 1)));
    return 1;
}

static int w_set_iterations(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tl_check_result(L, w, tt_world_set_iterations(w, (uint32_t)tl_checkinteger(L, 2, 1, TT_MAX_ITERATIONS)));
    return 0;
}

static int w_tolerance(lua_State *L)
{
    lua_pushnumber(L, tt_world_get_tolerance(tl_check_world(L, 1)));
    return 1;
}

static int w_set_tolerance(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tl_check_result(L, w, tt_world_set_tolerance(w, tl_checknumber(L, 2, &TL_R_NONNEG)));
    return 0;
}

static int w_solver(lua_State *L)
{
    tt_solver_order o = tt_world_get_solver_order(tl_check_world(L, 1));
    lua_pushstring(L, solver_names[o == TT_JACOBI ? 1 : 0]);
    return 1;
}

static int w_set_solver(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    int o = tl_checkoption(L, 2, "solver", NULL, solver_names);
    tl_check_result(L, w, tt_world_set_solver_order(w, (tt_solver_order)o));
    return 0;
}

/* --- queries ---------------------------------------------------------------- */

static int w_count(lua_State *L)
{
    lua_pushinteger(L, (lua_Integer)tt_world_particle_count(tl_check_world(L, 1)));
    return 1;
}

static int w_spring_count(lua_State *L)
{
    lua_pushinteger(L, (lua_Integer)tt_world_spring_count(tl_check_world(L, 1)));
    return 1;
}

static void setnum(lua_State *L, const char *k, double v)
{
    lua_pushnumber(L, v);
    lua_setfield(L, -2, k);
}

static void setint(lua_State *L, const char *k, lua_Integer v)
{
    lua_pushinteger(L, v);
    lua_setfield(L, -2, k);
}

/* w:stats() → {steps, time, particles, springs, step_ms, force_evaluations,
 *              diverged, iterations, max_error, stages = {...}} */
static int w_stats(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    static const char *const stage_names[TT_STAGE_COUNT] = { "forces", "integrate", "collide", "solve", "events" };
    tt_stats s;
    memset(&s, 0, sizeof s);
    tl_check_result(L, w, tt_world_get_stats(w, &s));
    lua_createtable(L, 0, 10);
    setint(L, "steps", (lua_Integer)s.steps);
    setnum(L, "time", s.time);
    setint(L, "particles", (lua_Integer)s.particles);
    setint(L, "springs", (lua_Integer)s.springs);
    setnum(L, "step_ms", s.step_ms);
    setint(L, "force_evaluations", (lua_Integer)s.force_evaluations);
    setint(L, "diverged", (lua_Integer)s.diverged);
    setint(L, "iterations", (lua_Integer)s.iterations);
    setnum(L, "max_error", s.max_error);
    lua_createtable(L, 0, TT_STAGE_COUNT);
    for (int i = 0; i < TT_STAGE_COUNT; i++)
        setnum(L, stage_names[i], s.stage_ms[i]);
    lua_setfield(L, -2, "stages");
    return 1;
}

/* w:energy() → {kinetic, gravity, spring, constraint, total} */
static int w_energy(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_energy e;
    memset(&e, 0, sizeof e);
    tl_check_result(L, w, tt_world_get_energy(w, &e));
    lua_createtable(L, 0, 5);
    setnum(L, "kinetic", e.kinetic);
    setnum(L, "gravity", e.gravity);
    setnum(L, "spring", e.spring);
    setnum(L, "constraint", e.constraint);
    setnum(L, "total", e.total);
    return 1;
}

/* w:memory() → {total, particles, capacity, bytes_per_particle} */
static int w_memory(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_memory m;
    memset(&m, 0, sizeof m);
    tl_check_result(L, w, tt_world_get_memory(w, &m));
    lua_createtable(L, 0, 4);
    setint(L, "total", (lua_Integer)m.total);
    setint(L, "particles", (lua_Integer)m.particles);
    setint(L, "capacity", (lua_Integer)m.capacity);
    setnum(L, "bytes_per_particle", m.bytes_per_particle);
    return 1;
}

/* w:hash() → "0123456789abcdef" */
static int w_hash(lua_State *L)
{
    char buf[24];
    snprintf(buf, sizeof buf, "%016" PRIx64, tt_world_hash(tl_check_world(L, 1)));
    lua_pushstring(L, buf);
    return 1;
}

/* --- bulk ------------------------------------------------------------------- */

/* The table to fill: the one at arg if given (reused), else a new one.
 * Leaves it on the top of the stack. */
static void result_table(lua_State *L, int arg, size_t n)
{
    if (tl_opttable(L, arg))
        lua_pushvalue(L, arg);
    else
        lua_createtable(L, n > INT32_MAX ? INT32_MAX : (int)n, 0);
}

/* Sets t[from], t[from + 1], … to nil, up to the end of the sequence. */
static void clear_from(lua_State *L, int t, lua_Integer from)
{
    lua_Integer len = (lua_Integer)lua_rawlen(L, t);
    for (lua_Integer i = from; i <= len; i++) {
        lua_pushnil(L);
        lua_rawseti(L, t, i);
    }
    for (lua_Integer i = len < from ? from : len + 1;; i++) {
        bool more = lua_rawgeti(L, t, i) != LUA_TNIL;
        lua_pop(L, 1);
        if (!more)
            break;
        lua_pushnil(L);
        lua_rawseti(L, t, i);
    }
}

/* w:particles([t]) → {p1, p2, …}, n — live handles in slot order */
static int w_particles(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    uint32_t n = tt_world_particle_count(w), m;
    tt_particle *ids;
    int t;
    lua_settop(L, 2);
    ids = tl_scratch(L, (size_t)n * sizeof *ids + 1);
    m = tt_world_list_particles(w, ids, n);
    if (m > n) m = n;
    result_table(L, 2, m);
    t = lua_gettop(L);
    for (uint32_t i = 0; i < m; i++) {
        tl_push_particle(L, ids[i]);
        lua_rawseti(L, t, (lua_Integer)i + 1);
    }
    clear_from(L, t, (lua_Integer)m + 1);
    lua_pushinteger(L, (lua_Integer)m);
    return 2;
}

/* w:positions([t]) → {x1, y1, x2, y2, …}, n — the order of w:particles() */
static int w_positions(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    uint32_t n = tt_world_particle_count(w), m;
    double *xy;
    int t;
    lua_settop(L, 2);
    xy = tl_scratch(L, (size_t)n * 2 * sizeof *xy + 1);
    m = tt_world_read_positions(w, xy, n);
    if (m > n) m = n;
    result_table(L, 2, (size_t)m * 2);
    t = lua_gettop(L);
    for (size_t i = 0; i < (size_t)m * 2; i++) {
        lua_pushnumber(L, xy[i]);
        lua_rawseti(L, t, (lua_Integer)i + 1);
    }
    clear_from(L, t, (lua_Integer)m * 2 + 1);
    lua_pushinteger(L, (lua_Integer)m);
    return 2;
}

/* w:set_positions(handles, xy [, mode]) — everything is checked before
 * anything moves. */
static int w_set_positions(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    size_t n, nxy;
    tt_particle *ids;
    double *xy;
    int mode;

    lua_settop(L, 4);
    if (lua_type(L, 2) != LUA_TTABLE)
        tl_typeerror(L, 2, "table of particle handles");
    if (lua_type(L, 3) != LUA_TTABLE)
        tl_typeerror(L, 3, "table of numbers");
    mode = tl_checkoption(L, 4, "mode", "keep", move_modes);
    n = lua_rawlen(L, 2);
    nxy = lua_rawlen(L, 3);
    if (n > UINT32_MAX)
        tl_argerror(L, 2, "too many handles (%I)", (LUAI_UACINT)n);
    if (nxy != 2 * n)
        tl_argerror(L, 3, "%I numbers expected (2 per handle), got %I", (LUAI_UACINT)(2 * n), (LUAI_UACINT)nxy);

    xy = tl_scratch(L, n * (2 * sizeof *xy + sizeof *ids) + 1);
    ids = (tt_particle *)(xy + 2 * n);
    for (size_t i = 0; i < n; i++) {
        uint64_t h = 0;
        lua_rawgeti(L, 2, (lua_Integer)i + 1);
        if (!tl_tohandle(L, -1, "particle", &h))
            tl_argerror(L, 2, "index %I: %s", (LUAI_UACINT)(i + 1), lua_tostring(L, -1));
        ids[i] = tt_particle_from_u64(h);
        if (!tt_particle_is_valid(w, ids[i]))
            tl_argerror(L, 2, "index %I: stale particle handle", (LUAI_UACINT)(i + 1));
        lua_pop(L, 1);
    }
    for (size_t i = 0; i < 2 * n; i++) {
        lua_rawgeti(L, 3, (lua_Integer)i + 1);
        if (!tl_tonumber_in(L, -1, &TL_R_COORD, &xy[i]))
            tl_argerror(L, 3, "index %I: %s", (LUAI_UACINT)(i + 1), lua_tostring(L, -1));
        lua_pop(L, 1);
    }
    tl_check_result(L, w, tt_particles_set_positions(w, ids, (uint32_t)n, xy,
                                                  mode == 0 ? TT_MOVE_KEEP_VELOCITY : TT_MOVE_RESET_VELOCITY));
    return 0;
}

/* The iterator of w:each(). Upvalues: 1 name, 2 world userdata, 3 snapshot
 * of the handles (userdata array), 4 count, 5 next index. Handles removed
 * since the snapshot are skipped; particles added since are not visited. */
static int each_next(lua_State *L)
{
    lw_world *u = lua_touserdata(L, lua_upvalueindex(2));
    const tt_particle *ids = lua_touserdata(L, lua_upvalueindex(3));
    lua_Integer n = lua_tointeger(L, lua_upvalueindex(4));
    lua_Integer i = lua_tointeger(L, lua_upvalueindex(5));
    if (u->dead)
        return tl_error(L, "attempt to use a destroyed world");
    for (; i < n; i++) {
        tt_vec2 v;
        if (tt_particle_get_position(u->w, ids[i], &v) == TT_OK) {
            lua_pushinteger(L, i + 1);
            lua_replace(L, lua_upvalueindex(5));
            tl_push_particle(L, ids[i]);
            lua_pushnumber(L, v.x);
            lua_pushnumber(L, v.y);
            return 3;
        }
    }
    lua_pushinteger(L, n);
    lua_replace(L, lua_upvalueindex(5));
    lua_pushnil(L);
    return 1;
}

/* w:each() → iterator: for p, x, y in w:each() do … end */
static int w_each(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    uint32_t n = tt_world_particle_count(w), m;
    tt_particle *ids, *snapshot;
    lua_settop(L, 1);
    ids = tl_scratch(L, (size_t)n * sizeof *ids + 1);
    m = tt_world_list_particles(w, ids, n);
    if (m > n) m = n;
    lua_pushliteral(L, "each");
    lua_pushvalue(L, 1);
    snapshot = lua_newuserdatauv(L, (size_t)m * sizeof *snapshot + 1, 0);
    memcpy(snapshot, ids, (size_t)m * sizeof *snapshot);
    lua_pushinteger(L, (lua_Integer)m);
    lua_pushinteger(L, 0);
    lua_pushcclosure(L, each_next, 5);
    return 1;
}

/* --- registration ----------------------------------------------------------- */

static const luaL_Reg world_methods[] = {
    { "particle", w_particle },
    { "remove", w_remove },
    { "is_valid", w_is_valid },
    { "position", w_position },
    { "set_position", w_set_position },
    { "velocity", w_velocity },
    { "set_velocity", w_set_velocity },
    { "mass", w_mass },
    { "set_mass", w_set_mass },
    { "pinned", w_pinned },
    { "set_pinned", w_set_pinned },
    { "radius", w_radius },
    { "set_radius", w_set_radius },
    { "filter", w_filter },
    { "set_filter", w_set_filter },
    { "user", w_user },
    { "set_user", w_set_user },
    { "apply_force", w_apply_force },
    { "apply_impulse", w_apply_impulse },
    { "explode", w_explode },
    { "spring", w_spring },
    { "remove_spring", w_remove_spring },
    { "spring_is_valid", w_spring_is_valid },
    { "spring_length", w_spring_length },
    { "spring_info", w_spring_info },
    { "set_spring", w_set_spring },
    { "step", w_step },
    { "gravity", w_gravity },
    { "set_gravity", w_set_gravity },
    { "wind", w_wind },
    { "set_wind", w_set_wind },
    { "damping", w_damping },
    { "set_damping", w_set_damping },
    { "integrator", w_integrator },
    { "set_integrator", w_set_integrator },
    { "substeps", w_substeps },
    { "set_substeps", w_set_substeps },
    { "iterations", w_iterations },
    { "set_iterations", w_set_iterations },
    { "tolerance", w_tolerance },
    { "set_tolerance", w_set_tolerance },
    { "solver", w_solver },
    { "set_solver", w_set_solver },
    { "count", w_count },
    { "spring_count", w_spring_count },
    { "stats", w_stats },
    { "energy", w_energy },
    { "memory", w_memory },
    { "hash", w_hash },
    { "particles", w_particles },
    { "positions", w_positions },
    { "set_positions", w_set_positions },
    { "each", w_each },
    { "destroy", w_destroy },
    { NULL, NULL }
};

static const luaL_Reg world_meta[] = {
    { "__gc", w_gc },
    { "__close", w_destroy },
    { "__tostring", w_tostring },
    { NULL, NULL }
};

void tl_world_register(lua_State *L)
{
    if (luaL_newmetatable(L, TL_WORLD_CLASS)) { /* sets __name */
        tl_setfuncs(L, world_meta, "");
        lua_createtable(L, 0, (int)(sizeof world_methods / sizeof world_methods[0]));
        tl_setfuncs_pinned(L, world_methods, "");
        lua_setfield(L, -2, "__index");
    }
    lua_pop(L, 1);
}

void tl_world_add_methods(lua_State *L, const luaL_Reg *methods)
{
    tl_world_register(L);
    luaL_getmetatable(L, TL_WORLD_CLASS);
    lua_getfield(L, -1, "__index");
    tl_setfuncs_pinned(L, methods, "");
    lua_pop(L, 2);
}

void tl_push_integrators(lua_State *L)
{
    lua_createtable(L, TT_INTEGRATOR_COUNT, 0);
    for (int i = 0; integrator_names[i] != NULL; i++) {
        lua_pushstring(L, integrator_names[i]);
        lua_rawseti(L, -2, i + 1);
    }
}
