/* tether — snapshots from Lua: w:snapshot(), w:restore(s), and
 * tether.world{snapshot = s} for a new world (a saved game).
 *
 * A snapshot is a userdata of class tether.snapshot holding the engine's
 * stream (tt_world_save) and, as its user value, a copy of the world's
 * particle user values (handle → Lua value) when it was taken: a restore
 * puts both back, so each particle's user value is what it was then.
 * s:bytes() is the stream as a Lua string, for a file; a string is
 * accepted wherever a snapshot is, and carries the engine state only (Lua
 * values cannot be written as bytes): restoring or loading one leaves no
 * user values. */
#include "lua_common.h"

#include <string.h>

#define TL_SNAPSHOT_CLASS "tether.snapshot"

typedef struct tl_snapshot {
    size_t size;
    unsigned char bytes[];
} tl_snapshot;

/* A shallow copy of the table at idx, pushed. */
static void push_copy(lua_State *L, int idx)
{
    idx = lua_absindex(L, idx);
    lua_newtable(L);
    lua_pushnil(L);
    while (lua_next(L, idx) != 0) {
        lua_pushvalue(L, -2);
        lua_insert(L, -2);
        lua_rawset(L, -4);
    }
}

/* w:snapshot() → snapshot */
static int w_snapshot(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    size_t n = 0;
    tt_result r = tt_world_save(w, NULL, 0, &n);
    if (r != TT_ENOMEM) tl_check_result(L, w, r);
    tl_snapshot *s = lua_newuserdatauv(L, sizeof *s + n, 1);
    s->size = 0;
    luaL_setmetatable(L, TL_SNAPSHOT_CLASS);
    /* the Lua allocation above may run a finalizer that changed the world: save again, into the room there is */
    tl_check_result(L, w, tt_world_save(w, s->bytes, n, &s->size));
    lua_getiuservalue(L, 1, 1);
    if (lua_istable(L, -1)) {
        push_copy(L, -1);
        lua_setiuservalue(L, -3, 1);
    }
    lua_pop(L, 1);
    return 1;
}

/* The stream at arg (a snapshot or a string); *users: whether the snapshot carries user values. */
static const void *check_stream(lua_State *L, int arg, size_t *size, bool *users)
{
    tl_snapshot *s = luaL_testudata(L, arg, TL_SNAPSHOT_CLASS);
    *users = s != NULL;
    if (s) {
        *size = s->size;
        return s->bytes;
    }
    if (lua_type(L, arg) != LUA_TSTRING) tl_typeerror(L, arg, "tether.snapshot or string");
    return lua_tolstring(L, arg, size);
}

/* Makes the user values of the world at idx those of the snapshot at arg (none for a string). */
static void set_users(lua_State *L, int idx, int arg, bool users)
{
    if (users && lua_getiuservalue(L, arg, 1) == LUA_TTABLE) push_copy(L, -1);
    else lua_newtable(L);
    lua_setiuservalue(L, idx, 1);
    if (users) lua_pop(L, 1);
}

/* w:restore(s) → true, or nil and the reason (the world unchanged) */
static int w_restore(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    size_t size;
    bool users;
    const void *data = check_stream(L, 2, &size, &users);
    /* the new user table first: once the world is restored nothing may fail */
    if (users && lua_getiuservalue(L, 2, 1) == LUA_TTABLE) push_copy(L, -1);
    else lua_newtable(L);
    if (tt_world_restore(w, data, size) != TT_OK) {
        lua_pushnil(L);
        lua_pushstring(L, tt_last_error(w));
        return 2;
    }
    lua_setiuservalue(L, 1, 1);
    lua_pushboolean(L, 1);
    return 1;
}

/* registry[TL_SNAPSHOT_LOADER](ud, s): the world of tether.world{snapshot = s} */
static int load_into(lua_State *L)
{
    tl_world_ud *u = luaL_checkudata(L, 1, TL_WORLD_CLASS);
    if (!luaL_testudata(L, 2, TL_SNAPSHOT_CLASS) && lua_type(L, 2) != LUA_TSTRING)
        tl_error(L, "bad option 'snapshot' (tether.snapshot or string expected, got %s)", tl_pushtypename(L, 2));
    size_t size;
    bool users;
    const void *data = check_stream(L, 2, &size, &users);
    tt_world *w = tt_world_load(data, size);
    if (!w) tl_error(L, "%s", tt_last_error(NULL));
    u->w = w;
    set_users(L, 1, 2, users);
    return 0;
}

/* s:bytes() → the stream as a string (to write to a file) */
static int s_bytes(lua_State *L)
{
    tl_snapshot *s = luaL_checkudata(L, 1, TL_SNAPSHOT_CLASS);
    lua_pushlstring(L, (const char *)s->bytes, s->size);
    return 1;
}

static int s_len(lua_State *L)
{
    tl_snapshot *s = luaL_checkudata(L, 1, TL_SNAPSHOT_CLASS);
    lua_pushinteger(L, (lua_Integer)s->size);
    return 1;
}

static int s_tostring(lua_State *L)
{
    tl_snapshot *s = luaL_checkudata(L, 1, TL_SNAPSHOT_CLASS);
    lua_pushfstring(L, "tether.snapshot (%I bytes): %p", (lua_Integer)s->size, (void *)s);
    return 1;
}

static const luaL_Reg snapshot_world_methods[] = { { "snapshot", w_snapshot }, { "restore", w_restore }, { NULL, NULL } };
static const luaL_Reg snapshot_methods[] = { { "bytes", s_bytes }, { NULL, NULL } };
static const luaL_Reg snapshot_meta[] = { { "__len", s_len }, { "__tostring", s_tostring }, { NULL, NULL } };

void tl_snapshot_register(lua_State *L)
{
    if (luaL_newmetatable(L, TL_SNAPSHOT_CLASS)) {
        tl_setfuncs(L, snapshot_meta, "");
        lua_createtable(L, 0, 1);
        tl_setfuncs(L, snapshot_methods, "");
        lua_setfield(L, -2, "__index");
    }
    lua_pop(L, 1);
    tl_world_add_methods(L, snapshot_world_methods);
    lua_pushstring(L, "tether.world"); /* its errors name the function the script called */
    lua_pushcclosure(L, load_into, 1);
    lua_setfield(L, LUA_REGISTRYINDEX, TL_SNAPSHOT_LOADER);
}
