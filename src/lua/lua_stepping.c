/* tether — Lua world methods that step the world and read or change how it
 * steps: w:step, gravity, wind, damping, integrator, substeps, travel, iterations,
 * tolerance, solver and point attractors (each a getter and a set_ setter). */
#include "lua_common.h"

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
    lua_pushstring(L, (unsigned)i < TT_INTEGRATOR_COUNT ? tl_integrator_names[i] : tt_integrator_name(i));
    return 1;
}

static int w_set_integrator(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    int i = tl_checkoption(L, 2, "integrator", NULL, tl_integrator_names);
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

/* w:travel() → max_travel, max_substeps */
static int w_travel(lua_State *L)
{
    uint32_t most = 0;
    lua_pushnumber(L, tt_world_get_travel(tl_check_world(L, 1), &most));
    lua_pushinteger(L, most);
    return 2;
}

/* w:set_travel(max_travel [, max_substeps = the world's]) */
static int w_set_travel(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    uint32_t most = 0;
    tt_world_get_travel(w, &most);
    const double travel = tl_checknumber(L, 2, &TL_R_NONNEG);
    most = (uint32_t)tl_optinteger(L, 3, 1, TT_MAX_SUBSTEPS, most);
    tl_check_result(L, w, tt_world_set_travel(w, travel, most));
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
    lua_pushstring(L, tl_solver_names[o == TT_JACOBI ? 1 : 0]);
    return 1;
}

static int w_set_solver(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    int o = tl_checkoption(L, 2, "solver", NULL, tl_solver_names);
    tl_check_result(L, w, tt_world_set_solver_order(w, (tt_solver_order)o));
    return 0;
}

/* w:set_attractor(slot, x, y, strength [, softening]): slot 1 … 8; strength 0 clears it */
static int w_set_attractor(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_Integer slot = tl_checkinteger(L, 2, 1, TT_MAX_ATTRACTORS);
    tt_attractor a;
    a.center.x = tl_checknumber(L, 3, &TL_R_COORD);
    a.center.y = tl_checknumber(L, 4, &TL_R_COORD);
    a.strength = tl_checknumber(L, 5, &TL_R_COORD);
    a.softening = tl_optnumber(L, 6, &TL_R_NONNEG, 0.0);
    tl_check_result(L, w, tt_world_set_attractor(w, (uint32_t)(slot - 1), a));
    return 0;
}

/* w:attractor(slot) → x, y, strength, softening (strength 0: unused) */
static int w_attractor(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_Integer slot = tl_checkinteger(L, 2, 1, TT_MAX_ATTRACTORS);
    tt_attractor a;
    tl_check_result(L, w, tt_world_get_attractor(w, (uint32_t)(slot - 1), &a));
    lua_pushnumber(L, a.center.x);
    lua_pushnumber(L, a.center.y);
    lua_pushnumber(L, a.strength);
    lua_pushnumber(L, a.softening);
    return 4;
}

/* w:sleep() → on, speed, time */
static int w_sleep(lua_State *L)
{
    double speed, time;
    lua_pushboolean(L, tt_world_get_sleep(tl_check_world(L, 1), &speed, &time));
    lua_pushnumber(L, speed);
    lua_pushnumber(L, time);
    return 3;
}

/* w:set_sleep(on [, speed = 0.01, time = 1]) */
static int w_set_sleep(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    bool on = tl_checkboolean(L, 2);
    tt_world_def d = tt_world_def_default();
    double speed = tl_optnumber(L, 3, &TL_R_NONNEG, d.sleep_speed), time = tl_optnumber(L, 4, &TL_R_NONNEG, d.sleep_time);
    tl_check_result(L, w, tt_world_set_sleep(w, on, speed, time));
    return 0;
}

/* --- registration ----------------------------------------------------------- */

static const luaL_Reg stepping_methods[] = {
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
    { "travel", w_travel },
    { "set_travel", w_set_travel },
    { "iterations", w_iterations },
    { "set_iterations", w_set_iterations },
    { "tolerance", w_tolerance },
    { "set_tolerance", w_set_tolerance },
    { "solver", w_solver },
    { "set_solver", w_set_solver },
    { "attractor", w_attractor },
    { "set_attractor", w_set_attractor },
    { "sleep", w_sleep },
    { "set_sleep", w_set_sleep },
    { NULL, NULL }
};

void tl_stepping_register(lua_State *L)
{
    tl_world_add_methods(L, stepping_methods);
}
