/* tether — Lua clocks (class "tether.clock"): tether.clock{dt, max_steps,
 * scale} and its methods, a thin layer over tt_clock (tether/clock.h):
 *
 *   local clock = tether.clock { dt = 1 / 60 }
 *   function love.update(real)            -- or tether.update, or any loop
 *     for _ = 1, clock:advance(real) do w:step(clock:dt()) end
 *   end
 *   -- draw the last state blended with the one before by clock:alpha() */
#include "lua_common.h"

#define TL_CLOCK_CLASS "tether.clock"

static const tl_range R_SCALE = {0.0, 1000.0, false};
static const tl_range R_REAL = {0.0, TT_MAX_VALUE, false};

static tt_clock *check_clock(lua_State *L, int arg)
{
    tt_clock *c = luaL_testudata(L, arg, TL_CLOCK_CLASS);
    if (c == NULL) tl_typeerror(L, arg, TL_CLOCK_CLASS);
    return c;
}

typedef struct clock_def { double dt; uint32_t max_steps; double scale; } clock_def;
static const tl_opt clock_opts[] = {
    TL_OPT_NUM(clock_def, "dt", dt, &TL_R_DT),
    TL_OPT_UINT(clock_def, "max_steps", max_steps, 1, 1000000),
    TL_OPT_NUM(clock_def, "scale", scale, &R_SCALE),
    TL_OPT_END,
};

/* tether.clock([opts]) → clock: dt (s, default 1/60), max_steps (default 8), scale (default 1) */
static int clock_new(lua_State *L)
{
    clock_def d = {1.0 / 60.0, 8, 1.0};
    tl_readopts(L, 1, clock_opts, &d);
    tt_clock *c = lua_newuserdatauv(L, sizeof *c, 0);
    tt_clock_init(c, d.dt, d.max_steps);
    tt_clock_set_scale(c, d.scale);
    luaL_setmetatable(L, TL_CLOCK_CLASS);
    return 1;
}

/* c:advance(real) → steps to take now */
static int c_advance(lua_State *L)
{
    tt_clock *c = check_clock(L, 1);
    uint32_t n = 0;
    tt_clock_advance(c, tl_checknumber(L, 2, &R_REAL), &n);
    lua_pushinteger(L, (lua_Integer)n);
    return 1;
}

static int c_alpha(lua_State *L)
{
    lua_pushnumber(L, tt_clock_alpha(check_clock(L, 1)));
    return 1;
}

static int c_dt(lua_State *L)
{
    lua_pushnumber(L, check_clock(L, 1)->dt);
    return 1;
}

static int c_scale(lua_State *L)
{
    lua_pushnumber(L, check_clock(L, 1)->scale);
    return 1;
}

static int c_set_scale(lua_State *L)
{
    tt_clock *c = check_clock(L, 1);
    tt_clock_set_scale(c, tl_checknumber(L, 2, &R_SCALE));
    return 0;
}

static int c_paused(lua_State *L)
{
    lua_pushboolean(L, check_clock(L, 1)->paused);
    return 1;
}

static int c_set_paused(lua_State *L)
{
    tt_clock *c = check_clock(L, 1);
    tt_clock_set_paused(c, tl_checkboolean(L, 2));
    return 0;
}

static int c_step_once(lua_State *L)
{
    tt_clock_request_step(check_clock(L, 1));
    return 0;
}

/* c:info() → {dt, max_steps, scale, paused, time, steps, acc, dropped, capped} */
static int c_info(lua_State *L)
{
    const tt_clock *c = check_clock(L, 1);
    lua_createtable(L, 0, 9);
    lua_pushnumber(L, c->dt), lua_setfield(L, -2, "dt");
    lua_pushinteger(L, c->max_steps), lua_setfield(L, -2, "max_steps");
    lua_pushnumber(L, c->scale), lua_setfield(L, -2, "scale");
    lua_pushboolean(L, c->paused), lua_setfield(L, -2, "paused");
    lua_pushnumber(L, c->time), lua_setfield(L, -2, "time");
    lua_pushinteger(L, (lua_Integer)c->steps), lua_setfield(L, -2, "steps");
    lua_pushnumber(L, c->acc), lua_setfield(L, -2, "acc");
    lua_pushnumber(L, c->dropped), lua_setfield(L, -2, "dropped");
    lua_pushboolean(L, c->capped), lua_setfield(L, -2, "capped");
    return 1;
}

static int c_tostring(lua_State *L)
{
    const tt_clock *c = check_clock(L, 1);
    lua_pushfstring(L, "tether.clock (dt %f s, x%f%s, " TL_I " steps)", c->dt, c->scale, c->paused ? ", paused" : "",
                    TL_IARG(c->steps));
    return 1;
}

static const luaL_Reg clock_methods[] = {
    {"advance", c_advance}, {"alpha", c_alpha}, {"dt", c_dt}, {"scale", c_scale}, {"set_scale", c_set_scale},
    {"paused", c_paused}, {"set_paused", c_set_paused}, {"step_once", c_step_once}, {"info", c_info},
    {NULL, NULL}};

static const luaL_Reg clock_meta[] = {{"__tostring", c_tostring}, {NULL, NULL}};
static const luaL_Reg clock_funcs[] = {{"clock", clock_new}, {NULL, NULL}};

/* Adds tether.clock to the module table on top of the stack. */
void tl_clock_register(lua_State *L)
{
    if (luaL_newmetatable(L, TL_CLOCK_CLASS)) { /* sets __name */
        tl_setfuncs(L, clock_meta, ""); /* named: its errors say '__tostring', as every function's do */
        lua_createtable(L, 0, 9);
        tl_setfuncs(L, clock_methods, "");
        lua_setfield(L, -2, "__index");
    }
    lua_pop(L, 1);
    tl_setfuncs(L, clock_funcs, "tether.");
}
