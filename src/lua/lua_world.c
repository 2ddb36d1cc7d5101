/* tether — the Lua world class (metatable "tether.world"): the userdata and
 * its life cycle, the pinning of every call on a world, the scratch buffers,
 * and the checkers and pushers every world method shares. The methods are
 * added by the files of their concept (lua_particles.c, lua_springs.c,
 * lua_stepping.c, lua_stats.c, lua_bulk.c, and the features' files), each
 * through its own tl_<concept>_register, called from luaopen_tether.
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

#include <stdlib.h>
#include <string.h>

/* Same order as tt_integrator. */
const char *const tl_integrator_names[] = { "euler", "symplectic_euler", "leapfrog", "verlet", "rk4", NULL };
_Static_assert(TT_INTEGRATOR_COUNT == 5, "tl_integrator_names lists every tt_integrator");

/* --- checkers --------------------------------------------------------------- */

/* The one checker of the class: a live world at arg. */
/* Raises "tether.world expected"; a method (its name has no module prefix)
 * called as w.step(dt) gets dt as its world, so it adds the likely cause. */
static int not_a_world(lua_State *L, int arg)
{
    if (arg != 1 || strchr(tl_fname(L), '.')) return tl_typeerror(L, arg, TL_WORLD_CLASS);
    const char *got = tl_pushtypename(L, arg);
    return tl_argerror(L, arg, "%s expected, got %s; did you call it with '.' instead of ':'?", TL_WORLD_CLASS, got);
}

tt_world *tl_check_world(lua_State *L, int arg)
{
    tl_world_ud *u = luaL_testudata(L, arg, TL_WORLD_CLASS);
    if (u == NULL)
        not_a_world(L, arg);
    if (u->dead)
        tl_argerror(L, arg, "attempt to use a destroyed world");
    return u->w;
}

tt_world *tl_toworld(lua_State *L, int idx)
{
    tl_world_ud *u = luaL_testudata(L, idx, TL_WORLD_CLASS);
    return u && !u->dead ? u->w : NULL;
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

void *tl_scratch(lua_State *L, size_t bytes)
{
    tl_world_ud *u = lua_touserdata(L, 1);
    unsigned d = u->pins > 0 ? u->pins - 1 : 0;
    if (d >= u->nscratch) {
        tl_buffer *v = realloc(u->scratch, (d + 1) * sizeof *v);
        if (v == NULL)
            tl_error(L, "not enough memory");
        memset(v + u->nscratch, 0, (d + 1 - u->nscratch) * sizeof *v);
        u->scratch = v;
        u->nscratch = d + 1;
    }
    tl_buffer *b = &u->scratch[d];
    if (bytes > b->cap) {
        size_t cap = bytes < 4096 ? 4096 : bytes;
        void *p = realloc(b->p, cap);
        if (p == NULL)
            tl_error(L, "not enough memory (" TL_I " bytes)", TL_IARG(bytes));
        b->p = p;
        b->cap = cap;
    }
    return b->p;
}

/* --- construction and life cycle -------------------------------------------- */

/* Same order as tt_solver_order. */
const char *const tl_solver_names[] = { "gauss_seidel", "jacobi", NULL };

static const tl_opt world_opts[] = {
    TL_OPT_XY(tt_world_def, "gravity", gravity, &TL_R_COORD),
    TL_OPT_CHOICE(tt_world_def, "integrator", integrator, "integrator", tl_integrator_names),
    TL_OPT_NUM(tt_world_def, "damping", damping, &TL_R_NONNEG),
    TL_OPT_XY(tt_world_def, "wind", wind, &TL_R_COORD),
    TL_OPT_NUM(tt_world_def, "dt_hint", dt_hint, &TL_R_DT),
    TL_OPT_UINT(tt_world_def, "capacity", capacity, 0, TL_MAX_CAPACITY),
    TL_OPT_UINT(tt_world_def, "substeps", substeps, 1, TT_MAX_SUBSTEPS),
    TL_OPT_NUM(tt_world_def, "max_travel", max_travel, &TL_R_NONNEG),
    TL_OPT_UINT(tt_world_def, "max_substeps", max_substeps, 1, TT_MAX_SUBSTEPS),
    TL_OPT_UINT(tt_world_def, "iterations", iterations, 1, TT_MAX_ITERATIONS),
    TL_OPT_NUM(tt_world_def, "tolerance", tolerance, &TL_R_NONNEG),
    TL_OPT_CHOICE(tt_world_def, "solver", order, "solver", tl_solver_names),
    TL_OPT_BYHAND("snapshot"),
    TL_OPT_BYHAND("file"),
    TL_OPT_FLAG(tt_world_def, "sleep", sleep),
    TL_OPT_FLAG(tt_world_def, "spin", spin),
    TL_OPT_NUM(tt_world_def, "sleep_speed", sleep_speed, &TL_R_NONNEG),
    TL_OPT_NUM(tt_world_def, "sleep_time", sleep_time, &TL_R_NONNEG),
    TL_OPT_BYHAND("fixed_point"), /* a boolean or the quantum: opt_fixed_point */
    TL_OPT_END,
};

/* fixed_point = true (the quantum TT_FIXED_POINT_QUANTUM), false (off) or
 * the quantum itself, checked by tt_world_create. */
static double opt_fixed_point(lua_State *L, double def)
{
    if (!tl_getopt(L, 1, "fixed_point")) return def;
    double q = def;
    if (lua_type(L, -1) == LUA_TBOOLEAN) q = lua_toboolean(L, -1) ? TT_FIXED_POINT_QUANTUM : 0.0;
    else if (lua_type(L, -1) == LUA_TNUMBER) q = lua_tonumber(L, -1);
    else tl_error(L, "bad option 'fixed_point' (boolean or number expected, got %s)", luaL_typename(L, -1));
    lua_pop(L, 1);
    return q;
}

int tl_world_new(lua_State *L)
{
    tt_world_def def = tt_world_def_default();
    tl_world_ud *u;

    lua_settop(L, 1);
    tl_readopts(L, 1, world_opts, &def);
    def.fixed_point = opt_fixed_point(L, def.fixed_point);

    /* Harmless first: a userdata with no world, its metatable and its user
     * table; only then the world. An error in between leaves nothing. */
    u = lua_newuserdatauv(L, sizeof *u, 1);
    memset(u, 0, sizeof *u);
    luaL_setmetatable(L, TL_WORLD_CLASS);
    lua_newtable(L);
    lua_setiuservalue(L, -2, 1);

    const bool file = tl_getopt(L, 1, "file");
    if (file || tl_getopt(L, 1, "snapshot")) { /* a saved world: it brings its own settings */
        const char *opt = file ? "file" : "snapshot";
        int keys = 0;
        for (lua_pushnil(L); lua_next(L, 1); lua_pop(L, 1)) keys++;
        if (keys > 1) tl_error(L, "option '%s' takes no other option: the %s holds the settings", opt, opt);
        /* through the registry: the snapshot binding (lua_snapshot.c) uses this file, not the reverse */
        lua_getfield(L, LUA_REGISTRYINDEX, TL_SNAPSHOT_LOADER);
        lua_pushvalue(L, 2);
        lua_pushvalue(L, 3);
        lua_pushboolean(L, file);
        lua_call(L, 3, 0);
        lua_settop(L, 2);
        return 1;
    }
    u->w = tt_world_create(&def);
    if (u->w == NULL)
        tl_error(L, "%s", tt_last_error(NULL));
    return 1;
}

/* Frees what the userdata at idx holds, now; safe to repeat. */
static void release(lua_State *L, int idx)
{
    tl_world_ud *u = lua_touserdata(L, idx);
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
    tl_world_ud *u = luaL_testudata(L, 1, TL_WORLD_CLASS);
    if (u == NULL)
        not_a_world(L, 1);
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
    tl_world_ud *u = luaL_testudata(L, 1, TL_WORLD_CLASS);
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
    tl_world_ud *u = luaL_testudata(L, 1, TL_WORLD_CLASS);
    if (u == NULL)
        return tl_typeerror(L, 1, TL_WORLD_CLASS);
    if (u->dead)
        lua_pushfstring(L, TL_WORLD_CLASS ": %p (destroyed)", (void *)u);
    else
        lua_pushfstring(L, TL_WORLD_CLASS ": %p (" TL_I " particles)", (void *)u,
                        TL_IARG(tt_world_particle_count(u->w)));
    return 1;
}

/* --- registration ----------------------------------------------------------- */

/* Only destroy is the class's own: every other method is added by the file
 * of its concept, so that this file depends on none of them. */
static const luaL_Reg world_methods[] = {
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
    for (int i = 0; tl_integrator_names[i] != NULL; i++) {
        lua_pushstring(L, tl_integrator_names[i]);
        lua_rawseti(L, -2, i + 1);
    }
}
