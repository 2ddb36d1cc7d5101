/* tether — Lua world methods that report on the whole world: w:count,
 * w:spring_count, w:stats, w:energy, w:memory, w:hash. */
#include "lua_common.h"

#include <inttypes.h>
#include <stdio.h>
#include <string.h>

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
 *              diverged, iterations, substeps, max_error, sleeping, stages = {...}} */
static int w_stats(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    static const char *const stage_names[TT_STAGE_COUNT] = { "forces", "integrate", "collide", "solve", "events" };
    tt_stats s;
    memset(&s, 0, sizeof s);
    tl_check_result(L, w, tt_world_get_stats(w, &s));
    lua_createtable(L, 0, 12);
    setint(L, "steps", (lua_Integer)s.steps);
    setnum(L, "time", s.time);
    setint(L, "particles", (lua_Integer)s.particles);
    setint(L, "springs", (lua_Integer)s.springs);
    setnum(L, "step_ms", s.step_ms);
    setint(L, "force_evaluations", (lua_Integer)s.force_evaluations);
    setint(L, "diverged", (lua_Integer)s.diverged);
    setint(L, "iterations", (lua_Integer)s.iterations);
    setint(L, "substeps", (lua_Integer)s.substeps);
    setnum(L, "max_error", s.max_error);
    setint(L, "sleeping", (lua_Integer)s.sleeping);
    lua_createtable(L, 0, TT_STAGE_COUNT);
    for (int i = 0; i < TT_STAGE_COUNT; i++)
        setnum(L, stage_names[i], s.stage_ms[i]);
    lua_setfield(L, -2, "stages");
    return 1;
}

/* w:energy() → {kinetic, gravity, spring, constraint, attractor, total} */
static int w_energy(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_energy e;
    memset(&e, 0, sizeof e);
    tl_check_result(L, w, tt_world_get_energy(w, &e));
    lua_createtable(L, 0, 6);
    setnum(L, "kinetic", e.kinetic);
    setnum(L, "gravity", e.gravity);
    setnum(L, "spring", e.spring);
    setnum(L, "constraint", e.constraint);
    setnum(L, "attractor", e.attractor);
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

/* --- registration ----------------------------------------------------------- */

static const luaL_Reg stats_methods[] = {
    { "count", w_count },
    { "spring_count", w_spring_count },
    { "stats", w_stats },
    { "energy", w_energy },
    { "memory", w_memory },
    { "hash", w_hash },
    { NULL, NULL }
};

void tl_stats_register(lua_State *L)
{
    tl_world_add_methods(L, stats_methods);
}
