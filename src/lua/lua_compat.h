/* tether — what the binding needs from the Lua 5.3/5.4 API, supplied on the
 * Lua 5.1 API of LuaJIT 2.1 (LÖVE's Lua), so that one set of binding sources
 * builds both modules (`make luajit`). Included by lua_common.h after lua.h
 * and lauxlib.h; under Lua 5.4 it adds only the message format of integers.
 *
 * What differs, and why each item is here:
 *  - LuaJIT numbers are all doubles. lua_tointegerx there truncates 3.5 to 3
 *    and calls it a number; the binding asks "is this exactly an integer",
 *    so that is what the 5.1 version answers (a double that holds an integer
 *    in lua_Integer's range). lua_isinteger answers the same: LuaJIT has no
 *    integer subtype, and an integral double is what its scripts mean by one.
 *  - lua_rawgeti/lua_rawseti take an int key in 5.1; the binding indexes by
 *    lua_Integer, handles (up to 2^53) included, so larger keys go through a
 *    number key and lua_rawget/lua_rawset.
 *  - 5.1's lua_getfield, lua_rawget, lua_rawgeti and luaL_getmetafield return
 *    nothing (or 0/1); the binding tests the type they return.
 *  - A 5.1 userdata has one environment table instead of user values; the
 *    binding uses only user value 1 of a world, and clears it with nil, which
 *    an environment cannot hold (an empty table stands in).
 *  - 5.1's luaL_newmetatable does not set __name, which names the class in
 *    the binding's messages.
 *  - lua_pushfstring has no %I in 5.1: TL_I / TL_IARG format a lua_Integer
 *    through snprintf there (exact, where LuaJIT's own %f writes 14 digits).
 *  - __close (5.4) is only a metatable field: harmless and unused in 5.1.
 *  - luaL_checkversion and lua_absindex do not exist in LuaJIT. */
#ifndef TETHER_LUA_COMPAT_H
#define TETHER_LUA_COMPAT_H

#include <lua.h>
#include <lauxlib.h>

#if LUA_VERSION_NUM >= 503

#define TL_I "%I"
#define TL_IARG(v) ((LUAI_UACINT)(v))

#else /* Lua 5.1 API: LuaJIT */

#include <math.h>
#include <stdio.h>

#define TL_I "%s"
#define TL_IARG(v) tlc_fmtint((char[24]){ 0 }, (long long)(v))
static inline const char *tlc_fmtint(char *buf, long long v)
{
    snprintf(buf, 24, "%lld", v);
    return buf;
}

#define lua_absindex(L, i) ((i) > 0 || (i) <= LUA_REGISTRYINDEX ? (i) : lua_gettop(L) + (i) + 1)
#define luaL_checkversion(L) ((void)(L))
#define lua_rawlen(L, i) lua_objlen(L, (i))

/* The range test comes first: a double outside lua_Integer's range cast to it is undefined. */
static inline lua_Integer tlc_tointegerx(lua_State *L, int idx, int *isint)
{
    lua_Number d = lua_type(L, idx) == LUA_TNUMBER ? lua_tonumber(L, idx) : 0.5;
    int ok = d >= -9223372036854775808.0 && d < 9223372036854775808.0 && floor(d) == d;
    if (isint != NULL)
        *isint = ok;
    return ok ? (lua_Integer)d : 0;
}
#define lua_tointegerx(L, i, isint) tlc_tointegerx(L, (i), (isint))
static inline int tlc_isinteger(lua_State *L, int idx)
{
    int ok;
    tlc_tointegerx(L, idx, &ok);
    return ok;
}
#define lua_isinteger(L, i) tlc_isinteger(L, (i))

static inline int tlc_getfield(lua_State *L, int idx, const char *k)
{
    (lua_getfield)(L, idx, k);
    return lua_type(L, -1);
}
#define lua_getfield(L, i, k) tlc_getfield(L, (i), (k))

static inline int tlc_int_key(lua_Integer n)
{
    return n >= -2147483647 - 1 && n <= 2147483647;
}
static inline int tlc_rawgeti(lua_State *L, int idx, lua_Integer n)
{
    if (tlc_int_key(n)) {
        (lua_rawgeti)(L, idx, (int)n);
    } else {
        idx = lua_absindex(L, idx);
        lua_pushnumber(L, (lua_Number)n);
        lua_rawget(L, idx);
    }
    return lua_type(L, -1);
}
#define lua_rawgeti(L, i, n) tlc_rawgeti(L, (i), (n))
static inline void tlc_rawseti(lua_State *L, int idx, lua_Integer n)
{
    if (tlc_int_key(n)) {
        (lua_rawseti)(L, idx, (int)n);
    } else {
        idx = lua_absindex(L, idx);
        lua_pushnumber(L, (lua_Number)n);
        lua_insert(L, -2);
        lua_rawset(L, idx);
    }
}
#define lua_rawseti(L, i, n) tlc_rawseti(L, (i), (n))
static inline int tlc_rawget(lua_State *L, int idx)
{
    (lua_rawget)(L, idx);
    return lua_type(L, -1);
}
#define lua_rawget(L, i) tlc_rawget(L, (i))

static inline int tlc_getmetafield(lua_State *L, int obj, const char *e)
{
    return (luaL_getmetafield)(L, obj, e) ? lua_type(L, -1) : LUA_TNIL;
}
#define luaL_getmetafield(L, o, e) tlc_getmetafield(L, (o), (e))

static inline int tlc_newmetatable(lua_State *L, const char *tname)
{
    if (!(luaL_newmetatable)(L, tname))
        return 0;
    lua_pushstring(L, tname);
    lua_setfield(L, -2, "__name");
    return 1;
}
#define luaL_newmetatable(L, t) tlc_newmetatable(L, (t))

#define lua_newuserdatauv(L, size, nuv) ((void)(nuv), lua_newuserdata(L, (size)))
static inline int tlc_getiuservalue(lua_State *L, int idx, int n)
{
    (void)n; /* always 1: the environment table */
    lua_getfenv(L, idx);
    return lua_type(L, -1);
}
#define lua_getiuservalue(L, i, n) tlc_getiuservalue(L, (i), (n))
static inline int tlc_setiuservalue(lua_State *L, int idx, int n)
{
    (void)n;
    idx = lua_absindex(L, idx);
    if (lua_isnil(L, -1)) {
        lua_pop(L, 1);
        lua_newtable(L);
    }
    return lua_setfenv(L, idx);
}
#define lua_setiuservalue(L, i, n) tlc_setiuservalue(L, (i), (n))

#endif
#endif
