/* tether — snapshots from Lua: w:snapshot(), w:restore(s), and
 * tether.world{snapshot = s} for a new world (a saved game).
 *
 * A snapshot is a userdata of class tether.snapshot holding the engine's
 * stream (tt_world_save) and, as its user value, a copy of the world's
 * particle user values (handle → Lua value) when it was taken: a restore
 * puts both back, so each particle's user value is what it was then.
 *
 * s:bytes() is the snapshot as a string, for a file. With user values it is
 * an envelope: "TTLU", its version (u32), the engine stream's length (u64),
 * the engine stream, then the user values, which must be plain data (nil,
 * booleans, numbers, strings, and tables of them without metatables or
 * cycles); s:bytes(false) is the engine stream alone. A string is accepted
 * wherever a snapshot is; one without user values leaves none.
 *
 * Files (w:save(path), w:restore_file(path), tether.world{file = path})
 * hold those bytes behind the engine's file header (src/core/snapfile.c):
 * a file saved from Lua, with or without user values, restores from C too. */
#include "lua_common.h"
#include "core/snapfile.h"

#include <stdlib.h>
#include <string.h>

#define TL_SNAPSHOT_CLASS "tether.snapshot"
#define TL_USERS_MAGIC "TTLU"
enum { TL_USERS_VERSION = 1, TL_USERS_HEADER = 16, TL_USERS_DEPTH = 64 };

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

/* ---- user values as bytes ------------------------------------------------------ */

enum { UV_FALSE = 1, UV_TRUE, UV_INT, UV_FLOAT, UV_STRING, UV_TABLE };

typedef struct ubuf {
    char *p;
    size_t n, cap;
    const char *why; /* the first failure */
} ubuf;

static void uput(ubuf *b, const void *d, size_t n)
{
    if (b->why) return;
    if (b->n + n > b->cap) {
        size_t cap = b->cap ? b->cap * 2 : 256;
        while (cap < b->n + n) cap *= 2;
        char *p = realloc(b->p, cap);
        if (!p) { b->why = "out of memory"; return; }
        b->p = p;
        b->cap = cap;
    }
    memcpy(b->p + b->n, d, n);
    b->n += n;
}

static void uput_tag(ubuf *b, unsigned char t) { uput(b, &t, 1); }

/* The value at idx (a key when key is true), or b->why set. */
static void put_value(lua_State *L, ubuf *b, int idx, int depth, bool key)
{
    idx = lua_absindex(L, idx);
    switch (lua_type(L, idx)) {
    case LUA_TBOOLEAN: uput_tag(b, lua_toboolean(L, idx) ? UV_TRUE : UV_FALSE); return;
    case LUA_TNUMBER:
        if (lua_isinteger(L, idx)) {
            lua_Integer i = lua_tointeger(L, idx);
            uput_tag(b, UV_INT);
            uput(b, &i, sizeof i);
        } else {
            lua_Number d = lua_tonumber(L, idx);
            uput_tag(b, UV_FLOAT);
            uput(b, &d, sizeof d);
        }
        return;
    case LUA_TSTRING: {
        size_t n;
        const char *s = lua_tolstring(L, idx, &n);
        uint32_t n32 = (uint32_t)n;
        if (n > UINT32_MAX) { b->why = "a string over 4 GB"; return; }
        uput_tag(b, UV_STRING);
        uput(b, &n32, 4);
        uput(b, s, n);
        return;
    }
    case LUA_TTABLE: break;
    default: b->why = "a value that is not plain data (nil, boolean, number, string, table)"; return;
    }
    if (key) { b->why = "a table used as a key"; return; }
    if (depth >= TL_USERS_DEPTH) { b->why = "tables nested too deep (or a cycle)"; return; }
    if (lua_getmetatable(L, idx)) {
        lua_pop(L, 1);
        b->why = "a table with a metatable";
        return;
    }
    uint32_t count = 0;
    for (lua_pushnil(L); lua_next(L, idx); lua_pop(L, 1)) count++;
    uput_tag(b, UV_TABLE);
    uput(b, &count, 4);
    luaL_checkstack(L, 4, "user values");
    for (lua_pushnil(L); !b->why && lua_next(L, idx); lua_pop(L, 1)) {
        put_value(L, b, -2, depth + 1, true);
        put_value(L, b, -1, depth + 1, false);
    }
    if (b->why) lua_pop(L, 1); /* the key the loop left */
}

typedef struct ucur {
    const unsigned char *p;
    size_t n, at;
} ucur;

static bool uget(ucur *c, void *out, size_t n)
{
    if (n > c->n - c->at) return false;
    memcpy(out, c->p + c->at, n);
    c->at += n;
    return true;
}

/* Pushes the value at the cursor; false (nothing pushed) when the bytes are not one. */
static bool get_value(lua_State *L, ucur *c, int depth, bool key)
{
    unsigned char t;
    if (!uget(c, &t, 1) || !lua_checkstack(L, 3)) return false;
    switch (t) {
    case UV_FALSE: case UV_TRUE: lua_pushboolean(L, t == UV_TRUE); return true;
    case UV_INT: { lua_Integer i; if (!uget(c, &i, sizeof i)) return false; lua_pushinteger(L, i); return true; }
    case UV_FLOAT: {
        lua_Number d;
        if (!uget(c, &d, sizeof d) || (key && d != d)) return false; /* NaN cannot be a key */
        lua_pushnumber(L, d);
        return true;
    }
    case UV_STRING: {
        uint32_t n;
        if (!uget(c, &n, 4) || n > c->n - c->at) return false;
        lua_pushlstring(L, (const char *)c->p + c->at, n);
        c->at += n;
        return true;
    }
    case UV_TABLE: break;
    default: return false;
    }
    uint32_t count;
    if (key || depth >= TL_USERS_DEPTH || !uget(c, &count, 4) || count > (c->n - c->at) / 2) return false;
    lua_createtable(L, 0, 0);
    for (uint32_t k = 0; k < count; k++) {
        if (!get_value(L, c, depth + 1, true)) { lua_pop(L, 1); return false; }
        if (!get_value(L, c, depth + 1, false)) { lua_pop(L, 2); return false; }
        lua_rawset(L, -3);
    }
    return true;
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

/* The engine stream at arg (a snapshot, or a string: an engine stream or
 * an envelope), and pushes the user table it brings (a new table: a copy of
 * the snapshot's, the envelope's values, or empty). Returns NULL, pushing
 * nothing, with *why set, when an envelope is not valid. */
static const void *take_stream(lua_State *L, int arg, size_t *size, const char **why)
{
    tl_snapshot *s = luaL_testudata(L, arg, TL_SNAPSHOT_CLASS);
    if (s) {
        *size = s->size;
        if (lua_getiuservalue(L, arg, 1) == LUA_TTABLE) push_copy(L, -1);
        else lua_newtable(L);
        lua_remove(L, -2);
        return s->bytes;
    }
    if (lua_type(L, arg) != LUA_TSTRING) tl_typeerror(L, arg, "tether.snapshot or string");
    size_t n;
    const unsigned char *p = (const unsigned char *)lua_tolstring(L, arg, &n);
    if (n < 4 || memcmp(p, TL_USERS_MAGIC, 4) != 0) {
        *size = n;
        lua_newtable(L);
        return p;
    }
    uint32_t version = 0;
    uint64_t len = 0;
    if (n >= TL_USERS_HEADER) {
        memcpy(&version, p + 4, 4);
        memcpy(&len, p + 8, 8);
    }
    ucur c = {p, n, TL_USERS_HEADER + (size_t)len};
    if (n < TL_USERS_HEADER || version != TL_USERS_VERSION || len > n - TL_USERS_HEADER) {
        *why = "a user-value envelope of another version, or cut short";
        return NULL;
    }
    bool ok = get_value(L, &c, 0, false);
    if (ok && (!lua_istable(L, -1) || c.at != n)) {
        lua_pop(L, 1);
        ok = false;
    }
    if (!ok) {
        *why = "its user values are corrupted";
        return NULL;
    }
    *size = (size_t)len;
    return p + TL_USERS_HEADER;
}

/* w:restore(s) → true, or nil and the reason (the world unchanged) */
static int w_restore(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_settop(L, 2);
    size_t size;
    const char *why = NULL;
    /* the new user table first: once the world is restored nothing may fail */
    const void *data = take_stream(L, 2, &size, &why);
    if (!data) {
        lua_settop(L, 2);
        lua_pushnil(L);
        lua_pushfstring(L, "restore: %s; the world is unchanged", why);
        return 2;
    }
    if (tt_world_restore(w, data, size) != TT_OK) {
        lua_pushnil(L);
        lua_pushstring(L, tt_last_error(w));
        return 2;
    }
    lua_setiuservalue(L, 1, 1);
    lua_pushboolean(L, 1);
    return 1;
}

/* Replaces the path at arg by the file's payload (a string); NULL when
 * it cannot be read, why set to the reason. */
static const char *push_file(lua_State *L, int arg, char *why, size_t whylen)
{
    const char *path = lua_tostring(L, arg);
    unsigned kind;
    size_t n;
    unsigned char *p = tt__file_read(path, &kind, &n, why, whylen);
    if (!p) return NULL;
    size_t size;
    if (!tt__file_stream(p, kind, n, &size, why, whylen)) {
        free(p);
        return NULL;
    }
    /* a userdata owns the copy first, so no Lua error can leak it */
    unsigned char *copy = lua_newuserdatauv(L, n ? n : 1, 0);
    memcpy(copy, p, n);
    free(p);
    lua_pushlstring(L, (const char *)copy, n);
    lua_remove(L, -2);
    lua_replace(L, arg);
    return path;
}

/* registry[TL_SNAPSHOT_LOADER](ud, s, is_file): the world of
 * tether.world{snapshot = s} or tether.world{file = path} */
static int load_into(lua_State *L)
{
    tl_world_ud *u = luaL_checkudata(L, 1, TL_WORLD_CLASS);
    lua_settop(L, 3);
    if (lua_toboolean(L, 3)) {
        if (lua_type(L, 2) != LUA_TSTRING)
            tl_error(L, "bad option 'file' (string expected, got %s)", tl_pushtypename(L, 2));
        char why[300];
        lua_pushstring(L, lua_tostring(L, 2));
        if (!push_file(L, 2, why, sizeof why)) tl_error(L, "'%s': %s", lua_tostring(L, 4), why);
        lua_settop(L, 2);
    }
    lua_settop(L, 2);
    if (!luaL_testudata(L, 2, TL_SNAPSHOT_CLASS) && lua_type(L, 2) != LUA_TSTRING)
        tl_error(L, "bad option 'snapshot' (tether.snapshot or string expected, got %s)", tl_pushtypename(L, 2));
    size_t size;
    const char *why = NULL;
    const void *data = take_stream(L, 2, &size, &why);
    if (!data) tl_error(L, "%s", why);
    tt_world *w = tt_world_load(data, size);
    if (!w) tl_error(L, "%s", tt_last_error(NULL));
    u->w = w;
    lua_setiuservalue(L, 1, 1);
    return 0;
}

/* s:bytes([users]) → the snapshot as a string (to write to a file): with
 * its user values unless users is false or there are none */
static int s_bytes(lua_State *L)
{
    tl_snapshot *s = luaL_checkudata(L, 1, TL_SNAPSHOT_CLASS);
    bool users = lua_isnoneornil(L, 2) || tl_checkboolean(L, 2);
    lua_settop(L, 1);
    if (!users || lua_getiuservalue(L, 1, 1) != LUA_TTABLE || (lua_pushnil(L), !lua_next(L, 2))) {
        lua_pushlstring(L, (const char *)s->bytes, s->size);
        return 1;
    }
    lua_settop(L, 2);
    ubuf b = {NULL, 0, 0, NULL};
    uint32_t version = TL_USERS_VERSION;
    uint64_t len = s->size;
    uput(&b, TL_USERS_MAGIC, 4);
    uput(&b, &version, 4);
    uput(&b, &len, 8);
    uput(&b, s->bytes, s->size);
    put_value(L, &b, 2, 0, false);
    if (b.why) {
        free(b.p);
        return tl_error(L, "a user value holds %s: only plain data can be written as bytes (s:bytes(false) leaves "
                        "the user values out)", b.why);
    }
    lua_pushlstring(L, b.p, b.n);
    free(b.p);
    return 1;
}

/* w:save(path [, users]) → true, or nil and the reason. The file holds
 * what s:bytes(users) would: raises as it does on user values that are
 * not plain data. */
static int w_save(lua_State *L)
{
    tl_check_world(L, 1);
    const char *path = tl_checkstring(L, 2);
    if (!lua_isnoneornil(L, 3)) tl_checkboolean(L, 3);
    lua_settop(L, 3);
    lua_pushcfunction(L, w_snapshot);
    lua_pushvalue(L, 1);
    lua_call(L, 1, 1);           /* 4: the snapshot */
    lua_pushcfunction(L, s_bytes);
    lua_pushvalue(L, 4);
    lua_pushvalue(L, 3);
    if (lua_pcall(L, 2, 1, 0) != LUA_OK) { /* raised as save's own error, not s:bytes' */
        const char *m = lua_tostring(L, -1);
        if (m && strncmp(m, "?: ", 3) == 0) m += 3;
        m = luaL_gsub(L, m ? m : "the user values cannot be written", "s:bytes(false)", "w:save(path, false)");
        return tl_error(L, "%s", m);
    }                            /* 5: its bytes */
    size_t n;
    const char *b = lua_tolstring(L, 5, &n);
    const unsigned kind = n >= 4 && memcmp(b, TL_USERS_MAGIC, 4) == 0 ? TT__FILE_LUA : TT__FILE_STREAM;
    char why[300];
    if (!tt__file_write(path, kind, b, n, why, sizeof why)) {
        lua_pushnil(L);
        lua_pushfstring(L, "save: %s", why);
        return 2;
    }
    lua_pushboolean(L, 1);
    return 1;
}

/* w:restore_file(path) → true, or nil and the reason (the world unchanged) */
static int w_restore_file(lua_State *L)
{
    tl_check_world(L, 1);
    tl_checkstring(L, 2);
    lua_settop(L, 2);
    lua_pushvalue(L, 2);         /* 3: the path, kept for the message */
    char why[300];
    if (!push_file(L, 2, why, sizeof why)) {
        lua_pushnil(L);
        lua_pushfstring(L, "restore_file: '%s': %s; the world is unchanged", lua_tostring(L, 3), why);
        return 2;
    }
    lua_pushcfunction(L, w_restore);
    lua_pushvalue(L, 1);
    lua_pushvalue(L, 2);
    lua_call(L, 2, 2);
    if (lua_toboolean(L, 4)) {
        lua_pushboolean(L, 1);
        return 1;
    }
    lua_pushfstring(L, "restore_file: '%s': %s", lua_tostring(L, 3), lua_tostring(L, 5));
    lua_pushnil(L);
    lua_insert(L, -2);
    return 2;
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
    lua_pushfstring(L, "tether.snapshot (" TL_I " bytes): %p", TL_IARG(s->size), (void *)s);
    return 1;
}

static const luaL_Reg snapshot_world_methods[] = { { "snapshot", w_snapshot }, { "restore", w_restore },
                                                     { "save", w_save }, { "restore_file", w_restore_file }, { NULL, NULL } };
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
