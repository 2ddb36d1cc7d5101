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

#include <lauxlib.h>
#include "lua/lua_compat.h" /* one source for Lua 5.4 and LuaJIT */
#include <lua.h>

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

/* Every key of the table at t must be one of names (NULL-terminated). */
void tl_b2_only_keys(lua_State *L, int t, const char *fn, const char *const *names)
{
    lua_pushnil(L);
    while (lua_next(L, t)) {
        lua_pop(L, 1);
        bool known = false;
        if (lua_type(L, -1) == LUA_TSTRING)
            for (int i = 0; names[i] && !known; i++) known = !strcmp(lua_tostring(L, -1), names[i]);
        if (!known) luaL_error(L, "%s: unknown option '%s'", fn, lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : luaL_typename(L, -1));
    }
}

static double opt_num(lua_State *L, int t, const char *fn, const char *key, double def)
{
    lua_getfield(L, t, key);
    double v = def;
    if (!lua_isnil(L, -1)) {
        if (!lua_isnumber(L, -1)) luaL_error(L, "%s: option '%s' must be a number, got %s", fn, key, luaL_typename(L, -1));
        v = lua_tonumber(L, -1);
        if (!isfinite(v)) luaL_error(L, "%s: option '%s' must be finite", fn, key);
    }
    lua_pop(L, 1);
    return v;
}

static bool opt_bool(lua_State *L, int t, const char *fn, const char *key, bool def)
{
    lua_getfield(L, t, key);
    bool v = def;
    if (!lua_isnil(L, -1)) {
        if (!lua_isboolean(L, -1)) luaL_error(L, "%s: option '%s' must be a boolean, got %s", fn, key, luaL_typename(L, -1));
        v = lua_toboolean(L, -1);
    }
    lua_pop(L, 1);
    return v;
}

/* Up to n numbers from the list t[key] into out; how many there were. */
static int opt_list(lua_State *L, int t, const char *fn, const char *key, double *out, int n)
{
    lua_getfield(L, t, key);
    int got = 0;
    if (!lua_isnil(L, -1)) {
        if (!lua_istable(L, -1)) luaL_error(L, "%s: option '%s' must be a list of numbers", fn, key);
        got = (int)lua_rawlen(L, -1);
        if (got > n) luaL_error(L, "%s: option '%s' has %d numbers, at most %d", fn, key, got, n);
        for (int i = 0; i < got; i++) {
            lua_rawgeti(L, -1, i + 1);
            if (!lua_isnumber(L, -1)) luaL_error(L, "%s: option '%s'[%d] must be a number", fn, key, i + 1);
            out[i] = lua_tonumber(L, -1);
            lua_pop(L, 1);
        }
    }
    lua_pop(L, 1);
    return got;
}

int tl_b2_pick(lua_State *L, int t, const char *fn, const char *key, const char *const *names)
{
    lua_getfield(L, t, key);
    const char *v = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : "";
    for (int i = 0; names[i]; i++)
        if (!strcmp(v, names[i])) {
            lua_pop(L, 1);
            return i;
        }
    luaL_Buffer b;
    luaL_buffinit(L, &b);
    for (int i = 0; names[i]; i++) {
        luaL_addstring(&b, i ? ", '" : "'");
        luaL_addstring(&b, names[i]);
        luaL_addstring(&b, "'");
    }
    luaL_pushresult(&b);
    return luaL_error(L, "%s: option '%s' must be one of %s", fn, key, lua_tostring(L, -1));
}

static const char *const world_keys[] = {"gravity", "velocity_iterations", "position_iterations", "sleep", "continuous", NULL};

tb_world_def tl_b2_world_def(lua_State *L, int t, const char *fn)
{
    tb_world_def d = tb_world_def_default();
    if (lua_isnoneornil(L, t)) return d;
    luaL_checktype(L, t, LUA_TTABLE);
    tl_b2_only_keys(L, t, fn, world_keys);
    if (opt_list(L, t, fn, "gravity", d.gravity, 2) == 1) luaL_error(L, "%s: option 'gravity' must be {x, y}", fn);
    const double vi = opt_num(L, t, fn, "velocity_iterations", 8), pi = opt_num(L, t, fn, "position_iterations", 3);
    if (!(vi >= 1 && vi <= 1000 && pi >= 1 && pi <= 1000) || vi != floor(vi) || pi != floor(pi))
        luaL_error(L, "%s: options 'velocity_iterations' and 'position_iterations' must be integers in [1, 1000]", fn);
    d.velocity_iterations = (int)vi;
    d.position_iterations = (int)pi;
    d.sleep = opt_bool(L, t, fn, "sleep", d.sleep);
    d.continuous = opt_bool(L, t, fn, "continuous", d.continuous);
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
    const tb_world_def d = tl_b2_world_def(L, 1, "tether_box2d.world");
    tl_b2_push_world(L, &d, "tether_box2d.world");
    return 1;
}

static const char *const shapes[] = {"circle", "box", "polygon", "edge", NULL};
static const char *const body_keys[] = {"shape", "dynamic", "x", "y", "angle", "vx", "vy", "spin", "radius", "hx", "hy",
                                        "points", "a", "b", "density", "friction", "restitution", NULL};

/* A body definition from the table at t (the keys of tether_box2d.scene's bodies). */
tb_body_def tl_b2_body_def(lua_State *L, int t, const char *fn)
{
    luaL_checktype(L, t, LUA_TTABLE);
    tl_b2_only_keys(L, t, fn, body_keys);
    tb_body_def d = tb_body_def_default();
    d.shape = (tb_shape)tl_b2_pick(L, t, fn, "shape", shapes);
    d.dynamic = opt_bool(L, t, fn, "dynamic", false);
    d.position[0] = opt_num(L, t, fn, "x", 0);
    d.position[1] = opt_num(L, t, fn, "y", 0);
    d.angle = opt_num(L, t, fn, "angle", 0);
    d.velocity[0] = opt_num(L, t, fn, "vx", 0);
    d.velocity[1] = opt_num(L, t, fn, "vy", 0);
    d.spin = opt_num(L, t, fn, "spin", 0);
    d.radius = opt_num(L, t, fn, "radius", 0.5);
    d.half[0] = opt_num(L, t, fn, "hx", 0.5);
    d.half[1] = opt_num(L, t, fn, "hy", 0.5);
    const int np = opt_list(L, t, fn, "points", d.points, 2 * TB_MAX_POLYGON);
    if (np % 2) luaL_error(L, "%s: option 'points' must be x1, y1, x2, y2, ...", fn);
    d.count = np / 2;
    opt_list(L, t, fn, "a", d.a, 2);
    opt_list(L, t, fn, "b", d.b, 2);
    d.density = opt_num(L, t, fn, "density", d.density);
    d.friction = opt_num(L, t, fn, "friction", d.friction);
    d.restitution = opt_num(L, t, fn, "restitution", d.restitution);
    return d;
}

static int l_body(lua_State *L)
{
    tb_world *w = check_world(L, 1);
    const tb_body_def d = tl_b2_body_def(L, 2, "tether_box2d.world:body");
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
    luaL_newlib(L, methods);
    lua_setfield(L, -2, "__index");
    lua_pop(L, 1);
}
