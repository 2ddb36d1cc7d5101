/* tether — Lua world methods on every particle at once: w:particles,
 * w:positions, w:set_positions and the w:each() iterator. A table given to
 * fill is reused, so reading positions every frame allocates nothing. */
#include "lua_common.h"

#include <string.h>

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
    mode = tl_checkoption(L, 4, "mode", "keep", tl_move_modes);
    n = lua_rawlen(L, 2);
    nxy = lua_rawlen(L, 3);
    if (n > UINT32_MAX)
        tl_argerror(L, 2, "too many handles (" TL_I ")", TL_IARG(n));
    if (nxy != 2 * n)
        tl_argerror(L, 3, TL_I " numbers expected (2 per handle), got " TL_I, TL_IARG(2 * n), TL_IARG(nxy));

    xy = tl_scratch(L, n * (2 * sizeof *xy + sizeof *ids) + 1);
    ids = (tt_particle *)(xy + 2 * n);
    for (size_t i = 0; i < n; i++) {
        uint64_t h = 0;
        lua_rawgeti(L, 2, (lua_Integer)i + 1);
        if (!tl_tohandle(L, -1, w, TT_KIND_PARTICLE, &h))
            tl_argerror(L, 2, "index " TL_I ": %s", TL_IARG(i + 1), lua_tostring(L, -1));
        ids[i] = tt_particle_from_u64(h);
        lua_pop(L, 1);
    }
    for (size_t i = 0; i < 2 * n; i++) {
        lua_rawgeti(L, 3, (lua_Integer)i + 1);
        if (!tl_tonumber_in(L, -1, &TL_R_COORD, &xy[i]))
            tl_argerror(L, 3, "index " TL_I ": %s", TL_IARG(i + 1), lua_tostring(L, -1));
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
    tl_world_ud *u = lua_touserdata(L, lua_upvalueindex(2));
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

static const luaL_Reg bulk_methods[] = {
    { "particles", w_particles },
    { "positions", w_positions },
    { "set_positions", w_set_positions },
    { "each", w_each },
    { NULL, NULL }
};

void tl_bulk_register(lua_State *L)
{
    tl_world_add_methods(L, bulk_methods);
}
