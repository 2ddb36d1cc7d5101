/* tether — the Lua module tether_box2d: Box2D 2.4.1 worlds a script can
 * run beside its own tether world, the project's named scenes as Lua
 * tables (the same tables build either engine), and the cross-check.
 *
 *   local b2 = require "tether_box2d"
 *   local w = b2.world{ gravity = {0, -10}, sleep = false }
 *   local i = w:body{ shape = "box", dynamic = true, x = 0, y = 5, hx = 0.5, hy = 0.5 }
 *   w:step(1/60); print(w:state(i))            -- x, y, angle, vx, vy, spin
 *   local pour = b2.scene("pour", true)         -- a plain table
 *   local w2 = b2.build(pour, { sleep = false })
 *   local rows = b2.crosscheck("fall", { quick = true, print = false })
 *
 * Bodies are numbered from 1 in creation order; a joint's body 0 is the
 * ground. Misuse raises an error naming the function and the argument. */
#include "lua_box2d.h"

#include "lua/lua_common.h" /* option tables and checkers as every binding has them; Lua 5.4 and LuaJIT */

#include <float.h>
#include <math.h>
#include <string.h>

#define WORLD "tether_box2d.world"

typedef struct lb_world { tb_world *w; } lb_world;

static tb_world *check_world(lua_State *L, int i)
{
    lb_world *u = luaL_checkudata(L, i, WORLD);
    if (!u->w) luaL_error(L, "attempt to use a destroyed tether_box2d world");  /* the message of a closed file, in kind */
    return u->w;
}

/* Methods are reached through __index, where Lua cannot name them: every
 * argument error says the function's full name itself. */
static int arg_error(lua_State *L, const char *fn, int arg, const char *what)
{
    return luaL_error(L, "%s: bad argument #%d (%s)", fn, arg, what);
}

static double check_num(lua_State *L, int i, const char *fn, const char *name)
{
    if (!lua_isnumber(L, i)) luaL_error(L, "%s: bad argument #%d (%s must be a number, got %s)", fn, i, name, luaL_typename(L, i));
    const double v = lua_tonumber(L, i);
    if (!isfinite(v)) luaL_error(L, "%s: bad argument #%d (%s must be finite)", fn, i, name);
    return v;
}

static lua_Integer check_int(lua_State *L, int i, const char *fn, const char *name)
{
    if (!lua_isinteger(L, i)) luaL_error(L, "%s: bad argument #%d (%s must be an integer, got %s)", fn, i, name, luaL_typename(L, i));
    return lua_tointeger(L, i);
}

/* Option tables are read as every tether binding reads them
 * (src/lua/lua_options.c): one tl_opt description per table, so the keys,
 * their ranges and the unknown-key list are written once, and the errors
 * read "fn: bad option 'key' (why)". The bridge checks what Box2D itself
 * refuses (a radius of 0, a concave polygon): here any finite number. */
static const tl_range FINITE = {-DBL_MAX, DBL_MAX, false};

/* {x, y} of finite numbers, or def when the option is absent. */
static void opt_pair(lua_State *L, int t, const char *key, double out[2])
{
    const tt_vec2 v = tl_optfield_vec2(L, t, key, &FINITE, (tt_vec2){out[0], out[1]});
    out[0] = v.x;
    out[1] = v.y;
}

static const tl_opt world_opts[] = {
    TL_OPT_BYHAND("gravity"), /* two doubles, read as {x, y} */
    TL_OPT_INT(tb_world_def, "velocity_iterations", velocity_iterations, 1, 1000),
    TL_OPT_INT(tb_world_def, "position_iterations", position_iterations, 1, 1000),
    TL_OPT_FLAG(tb_world_def, "sleep", sleep),
    TL_OPT_FLAG(tb_world_def, "continuous", continuous),
    TL_OPT_END,
};

tb_world_def tl_b2_world_def(lua_State *L, int t)
{
    tb_world_def d = tb_world_def_default();
    tl_readopts(L, t, world_opts, &d);
    opt_pair(L, t, "gravity", d.gravity);
    return d;
}

tb_world *tl_b2_push_world(lua_State *L, const tb_world_def *d, const char *fn)
{
    lb_world *u = lua_newuserdatauv(L, sizeof *u, 0); /* harmless until the world exists */
    u->w = NULL;
    luaL_setmetatable(L, WORLD);
    if (!(u->w = tb_world_create(d))) luaL_error(L, "%s: %s", fn, tb_last_error());
    return u->w;
}

int tl_b2_world(lua_State *L)
{
    const tb_world_def d = tl_b2_world_def(L, 1);
    tl_b2_push_world(L, &d, "tether_box2d.world");
    return 1;
}

static const char *const shapes[] = {"circle", "box", "polygon", "edge", NULL};
static const tl_opt body_opts[] = {
    TL_OPT_BYHAND("shape"), /* required */
    TL_OPT_FLAG(tb_body_def, "dynamic", dynamic),
    TL_OPT_NUM(tb_body_def, "x", position[0], &FINITE),
    TL_OPT_NUM(tb_body_def, "y", position[1], &FINITE),
    TL_OPT_NUM(tb_body_def, "angle", angle, &FINITE),
    TL_OPT_NUM(tb_body_def, "vx", velocity[0], &FINITE),
    TL_OPT_NUM(tb_body_def, "vy", velocity[1], &FINITE),
    TL_OPT_NUM(tb_body_def, "spin", spin, &FINITE),
    TL_OPT_NUM(tb_body_def, "radius", radius, &FINITE),
    TL_OPT_NUM(tb_body_def, "hx", half[0], &FINITE),
    TL_OPT_NUM(tb_body_def, "hy", half[1], &FINITE),
    TL_OPT_BYHAND("points"), /* x1, y1, x2, y2, … */
    TL_OPT_BYHAND("a"),
    TL_OPT_BYHAND("b"),
    TL_OPT_NUM(tb_body_def, "density", density, &FINITE),
    TL_OPT_NUM(tb_body_def, "friction", friction, &FINITE),
    TL_OPT_NUM(tb_body_def, "restitution", restitution, &FINITE),
    TL_OPT_FLAG(tb_body_def, "fixed_rotation", fixed_rotation),
    TL_OPT_END,
};

/* The polygon's x1, y1, x2, y2, … into d. */
static void opt_points(lua_State *L, int t, tb_body_def *d)
{
    if (!tl_getopt(L, t, "points")) return;
    const int p = lua_gettop(L);
    if (lua_type(L, p) != LUA_TTABLE) {
        tl_push_expected(L, p, "list of numbers x1, y1, x2, y2, ...", false);
        tl_error(L, "bad option 'points' (%s)", lua_tostring(L, -1));
    }
    const size_t n = lua_rawlen(L, p);
    if (n % 2 || n > 2 * TB_MAX_POLYGON)
        tl_error(L, "bad option 'points' (x1, y1, x2, y2, ... of at most %d points expected, got %d numbers)", TB_MAX_POLYGON, (int)n);
    for (size_t i = 0; i < n; i++) {
        lua_rawgeti(L, p, (lua_Integer)i + 1);
        if (!tl_tonumber_in(L, -1, &FINITE, &d->points[i])) tl_error(L, "bad option 'points' (index %d: %s)", (int)i + 1, lua_tostring(L, -1));
        lua_pop(L, 1);
    }
    lua_pop(L, 1);
    d->count = (int)n / 2;
}

/* A body definition from the table at t (the keys of tether_box2d.scene's bodies). */
tb_body_def tl_b2_body_def(lua_State *L, int t)
{
    tb_body_def d = tb_body_def_default();
    if (!tl_readopts(L, t, body_opts, &d)) tl_typeerror(L, t, "table");
    const int shape = tl_optfield_option(L, t, "shape", "shape", shapes, -1);
    if (shape < 0) {
        tl_push_choices(L, shapes);
        tl_error(L, "bad option 'shape' (one of %s expected, got no value)", lua_tostring(L, -1));
    }
    d.shape = (tb_shape)shape;
    opt_points(L, t, &d);
    opt_pair(L, t, "a", d.a);
    opt_pair(L, t, "b", d.b);
    return d;
}

static int l_body(lua_State *L)
{
    tb_world *w = check_world(L, 1);
    const tb_body_def d = tl_b2_body_def(L, 2);
    const int i = tb_body_create(w, &d);
    if (i < 0) return luaL_error(L, "tether_box2d.world:body: %s", tb_last_error());
    lua_pushinteger(L, i + 1);
    return 1;
}

static const char *const joints[] = {"revolute", "distance", "weld", NULL};

/* w:joint(kind, a, b, ax, ay [, bx, by]): a = 0 is the ground. */
static int l_joint(lua_State *L)
{
    const char *fn = "tether_box2d.world:joint";
    tb_world *w = check_world(L, 1);
    const char *k = lua_tostring(L, 2);
    int kind = 0;
    while (joints[kind] && (!k || strcmp(k, joints[kind]))) kind++;
    if (!joints[kind]) return arg_error(L, fn, 2, "kind must be 'revolute', 'distance' or 'weld'");
    const lua_Integer a = check_int(L, 3, fn, "a"), b = check_int(L, 4, fn, "b"), n = tb_world_body_count(w);
    if (a < 0 || a > n) return arg_error(L, fn, 3, "body a must be 0 (the ground) or an existing body");
    if (b < 1 || b > n || b == a) return arg_error(L, fn, 4, "body b must be another existing body");
    const double pa[2] = {check_num(L, 5, fn, "ax"), check_num(L, 6, fn, "ay")};
    const double pb[2] = {lua_isnoneornil(L, 7) ? pa[0] : check_num(L, 7, fn, "bx"), lua_isnoneornil(L, 8) ? pa[1] : check_num(L, 8, fn, "by")};
    const int j = tb_joint_create(w, (tb_joint)kind, (int)a - 1, (int)b - 1, pa, pb);
    if (j < 0) return luaL_error(L, "%s: %s", fn, tb_last_error());
    lua_pushinteger(L, j + 1);
    return 1;
}

static int l_step(lua_State *L)
{
    tb_world *w = check_world(L, 1);
    const double dt = check_num(L, 2, "tether_box2d.world:step", "dt");
    if (!(dt > 0 && dt <= 10)) return arg_error(L, "tether_box2d.world:step", 2, "dt must be in (0, 10] s");
    if (!tb_world_step(w, dt)) return luaL_error(L, "tether_box2d.world:step: %s", tb_last_error());
    return 0;
}

static int l_state(lua_State *L)
{
    tb_world *w = check_world(L, 1);
    const lua_Integer i = check_int(L, 2, "tether_box2d.world:state", "body");
    tb_body_state st;
    if (i < 1 || i > tb_world_body_count(w)) return arg_error(L, "tether_box2d.world:state", 2, "no such body");
    tb_body_state_get(w, (int)i - 1, &st);
    const double v[6] = {st.position[0], st.position[1], st.angle, st.velocity[0], st.velocity[1], st.spin};
    for (int k = 0; k < 6; k++) lua_pushnumber(L, v[k]);
    return 6;
}

static int l_count(lua_State *L)
{
    lua_pushinteger(L, tb_world_body_count(check_world(L, 1)));
    return 1;
}

/* Kinetic energy (J) and the dynamic bodies' mass (kg). */
static int l_energy(lua_State *L)
{
    tb_world *w = check_world(L, 1);
    lua_pushnumber(L, tb_world_kinetic_energy(w));
    lua_pushnumber(L, tb_world_mass(w));
    return 2;
}

static int l_destroy(lua_State *L)
{
    lb_world *u = luaL_checkudata(L, 1, WORLD);
    tb_world_destroy(u->w);
    u->w = NULL;
    return 0;
}

static int l_tostring(lua_State *L)
{
    lb_world *u = luaL_checkudata(L, 1, WORLD);
    if (u->w) lua_pushfstring(L, "tether_box2d.world{%d bodies}: %p", tb_world_body_count(u->w), (void *)u);
    else lua_pushliteral(L, "tether_box2d.world{destroyed}");
    return 1;
}

void tl_b2_register(lua_State *L)
{
    static const luaL_Reg methods[] = {{"body", l_body},     {"joint", l_joint},   {"step", l_step},       {"state", l_state},
                                       {"count", l_count},   {"energy", l_energy}, {"destroy", l_destroy}, {NULL, NULL}};
    static const luaL_Reg meta[] = {{"__gc", l_destroy}, {"__close", l_destroy}, {"__tostring", l_tostring}, {NULL, NULL}};
    luaL_newmetatable(L, WORLD);
    luaL_setfuncs(L, meta, 0);
    lua_newtable(L);
    tl_setfuncs(L, methods, "tether_box2d.world:"); /* named for the option tables' errors */
    lua_setfield(L, -2, "__index");
    lua_pop(L, 1);
}
