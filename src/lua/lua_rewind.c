/* tether — Lua rewind rings (class "tether.rewind"), a thin layer over
 * tt_rewind (tether/rewind.h):
 *
 *   local ring = tether.rewind { every = 10, seconds = 10 }
 *   function tether.update(dt)
 *     if rewinding then
 *       step = math.max(first, step - 2)        -- scrub back at any speed
 *       ring:seek(w, step, drive)               -- drive(w) re-steps from the keyframe
 *     else
 *       drive(w); ring:record(w)
 *     end
 *   end
 *
 * drive must give the steps it re-runs the inputs it gave them the first
 * time (a function of w:stats().steps does); user values are not in the
 * ring: a seek leaves them as they are. Also w:reverse() (time reversal). */
#include "lua_common.h"
#include "tether/rewind.h"

#include <math.h>

#define TL_REWIND_CLASS "tether.rewind"

typedef struct tl_rewind {
    tt_rewind *r; /* NULL once destroyed */
} tl_rewind;

static tt_rewind *check_ring(lua_State *L, int arg)
{
    tl_rewind *u = luaL_testudata(L, arg, TL_REWIND_CLASS);
    if (u == NULL) tl_typeerror(L, arg, TL_REWIND_CLASS);
    if (u->r == NULL) tl_argerror(L, arg, "the ring was destroyed");
    return u->r;
}

static const tl_range R_SECONDS = {1e-9, 1e9, false};
static const tl_range R_BYTES = {1024, 1e15, false};
typedef struct rewind_opts_def {
    tt_rewind_def def;
    double seconds, dt, max_bytes; /* the ring counts steps and bytes; a script says seconds */
} rewind_opts_def;
static const tl_opt rewind_opts[] = {
    TL_OPT_UINT(rewind_opts_def, "every", def.every, 1, 1000000),
    TL_OPT_NUM(rewind_opts_def, "seconds", seconds, &R_SECONDS),
    TL_OPT_NUM(rewind_opts_def, "dt", dt, &TL_R_DT),
    TL_OPT_NUM(rewind_opts_def, "max_bytes", max_bytes, &R_BYTES),
    TL_OPT_END,
};

/* tether.rewind([opts]) → ring: every (steps between keyframes, default
 * 10), seconds of history (default 10) at dt (default 1/60), max_bytes
 * (default 256 MB) */
static int rewind_new(lua_State *L)
{
    rewind_opts_def o = {tt_rewind_def_default(), 10.0, 1.0 / 60.0, 0.0};
    o.max_bytes = (double)o.def.max_bytes;
    tl_readopts(L, 1, rewind_opts, &o);
    tt_rewind_def def = o.def;
    def.max_bytes = (size_t)o.max_bytes;
    const double seconds = o.seconds, dt = o.dt;
    const double steps = ceil(seconds / dt);
    if (steps > 9007199254740992.0) tl_error(L, "bad option 'seconds' (%f s at dt %f is too many steps)", seconds, dt);
    def.keep_steps = (uint64_t)steps < def.every ? def.every : (uint64_t)steps;
    tl_rewind *u = lua_newuserdatauv(L, sizeof *u, 0);
    u->r = NULL;
    luaL_setmetatable(L, TL_REWIND_CLASS);
    u->r = tt_rewind_create(&def);
    if (!u->r) tl_error(L, "%s", tt_last_error(NULL));
    return 1;
}

/* ring:record(w): after each step (and once before the first) */
static int r_record(lua_State *L)
{
    tt_rewind *r = check_ring(L, 1);
    tt_world *w = tl_check_world(L, 2);
    tl_check_result(L, w, tt_rewind_record(r, w));
    return 0;
}

/* ring:seek(w, step [, drive]) → the step w is at: the keyframe at or
 * before step, or step itself when drive (called as drive(w), it must step
 * w once) re-steps from there */
static int r_seek(lua_State *L)
{
    tt_rewind *r = check_ring(L, 1);
    tt_world *w = tl_check_world(L, 2);
    const uint64_t step = (uint64_t)tl_checkinteger(L, 3, 0, (lua_Integer)1 << 53);
    const bool drive = !lua_isnoneornil(L, 4);
    if (drive && lua_type(L, 4) != LUA_TFUNCTION) tl_typeerror(L, 4, "function");
    uint64_t at = 0;
    tl_check_result(L, w, tt_rewind_seek(r, w, step, &at));
    while (drive && at < step) {
        lua_pushvalue(L, 4);
        lua_pushvalue(L, 2);
        lua_call(L, 1, 0);
        w = tl_check_world(L, 2); /* drive may have destroyed it */
        tt_stats st;
        tt_world_get_stats(w, &st);
        if (st.steps <= at) tl_error(L, "drive did not step the world (at step " TL_I ")", TL_IARG(at));
        at = st.steps;
    }
    lua_pushinteger(L, (lua_Integer)at);
    return 1;
}

/* ring:range() → first, last (nil when empty) */
static int r_range(lua_State *L)
{
    uint64_t first, last;
    if (tt_rewind_get_range(check_ring(L, 1), &first, &last) != TT_OK) {
        lua_pushnil(L);
        return 1;
    }
    lua_pushinteger(L, (lua_Integer)first);
    lua_pushinteger(L, (lua_Integer)last);
    return 2;
}

static int r_memory(lua_State *L)
{
    lua_pushinteger(L, (lua_Integer)tt_rewind_get_memory(check_ring(L, 1)));
    return 1;
}

static int r_count(lua_State *L)
{
    lua_pushinteger(L, (lua_Integer)tt_rewind_get_count(check_ring(L, 1)));
    return 1;
}

/* ring:destroy(), and the collector: frees it now; safe to repeat */
static int r_destroy(lua_State *L)
{
    tl_rewind *u = luaL_checkudata(L, 1, TL_REWIND_CLASS);
    tt_rewind_destroy(u->r);
    u->r = NULL;
    return 0;
}

static int r_tostring(lua_State *L)
{
    tl_rewind *u = luaL_checkudata(L, 1, TL_REWIND_CLASS);
    if (!u->r) {
        lua_pushstring(L, "tether.rewind (destroyed)");
        return 1;
    }
    lua_pushfstring(L, "tether.rewind (%d keyframes, " TL_I " bytes)", (int)tt_rewind_get_count(u->r),
                    TL_IARG(tt_rewind_get_memory(u->r)));
    return 1;
}

/* w:reverse(): the motion runs backwards from the next step (tt_world_reverse);
 * raises naming what prevents it */
static int w_reverse(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tl_check_result(L, w, tt_world_reverse(w));
    return 0;
}

/* w:fixed_point() → the quantum of a fixed-point world (tether.world{fixed_point = …}), or nil */
static int w_fixed_point(lua_State *L)
{
    double q = tt_world_get_fixed_point(tl_check_world(L, 1));
    if (q == 0.0) lua_pushnil(L);
    else lua_pushnumber(L, q);
    return 1;
}

static const luaL_Reg reverse_world_methods[] = {{"reverse", w_reverse}, {"fixed_point", w_fixed_point}, {NULL, NULL}};

static const luaL_Reg rewind_methods[] = {
    {"record", r_record}, {"seek", r_seek}, {"range", r_range}, {"memory", r_memory}, {"count", r_count},
    {"destroy", r_destroy}, {NULL, NULL}};
static const luaL_Reg rewind_meta[] = {{"__gc", r_destroy}, {"__tostring", r_tostring}, {NULL, NULL}};
static const luaL_Reg rewind_funcs[] = {{"rewind", rewind_new}, {NULL, NULL}};

/* Adds tether.rewind to the module table on top of the stack. */
void tl_rewind_register(lua_State *L)
{
    if (luaL_newmetatable(L, TL_REWIND_CLASS)) {
        tl_setfuncs(L, rewind_meta, "");
        lua_createtable(L, 0, 6);
        tl_setfuncs(L, rewind_methods, "");
        lua_setfield(L, -2, "__index");
    }
    lua_pop(L, 1);
    tl_setfuncs(L, rewind_funcs, "tether.");
    tl_world_add_methods(L, reverse_world_methods);
}
