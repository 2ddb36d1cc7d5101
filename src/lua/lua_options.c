/* tether — Lua option tables: each table a binding accepts is described
 * once, as data (tl_opt: key, kind, range, where the value goes in the
 * C definition struct, whose tt_*_def_default() holds the defaults), and
 * tl_readopts reads it. So a key is written once, and the list an
 * unknown key's error names comes from the same description. */
#include "lua_common.h"

#include <string.h>

/* Pushes how an unknown option key is named in the message: as tostring
 * writes it, but never through the key's own __tostring, whose error or
 * odd answer would hide the message. Converts a copy: lua_tostring on the
 * key itself would change a number key in place and confuse lua_next. */
static void push_key(lua_State *L, int idx)
{
    idx = lua_absindex(L, idx);
    switch (lua_type(L, idx)) {
    case LUA_TSTRING:
    case LUA_TNUMBER:
        lua_pushvalue(L, idx);
        lua_tostring(L, -1);
        break;
    case LUA_TBOOLEAN:
        lua_pushstring(L, lua_toboolean(L, idx) ? "true" : "false");
        break;
    default: {
        const char *type = tl_pushtypename(L, idx);
        lua_pushfstring(L, "%s: %p", type, lua_topointer(L, idx));
        lua_remove(L, -2);
    }
    }
}

/* Pushes "'a', 'b', 'c'": the keys of spec. */
static void push_keys(lua_State *L, const tl_opt spec[])
{
    luaL_Buffer b;
    luaL_buffinit(L, &b);
    for (const tl_opt *o = spec; o->key != NULL; o++) {
        if (o != spec) luaL_addstring(&b, ", ");
        luaL_addchar(&b, '\'');
        luaL_addstring(&b, o->key);
        luaL_addchar(&b, '\'');
    }
    luaL_pushresult(&b);
}

static bool known(const tl_opt spec[], const char *k)
{
    for (const tl_opt *o = spec; o->key != NULL; o++)
        if (strcmp(o->key, k) == 0) return true;
    return false;
}

bool tl_checkopts(lua_State *L, int arg, const tl_opt spec[])
{
    if (!tl_opttable(L, arg))
        return false;
    lua_pushnil(L);
    while (lua_next(L, arg) != 0) {
        lua_pop(L, 1); /* the value */
        if (lua_type(L, -1) != LUA_TSTRING || !known(spec, lua_tostring(L, -1))) {
            push_key(L, -1);
            push_keys(L, spec);
            tl_error(L, "unknown option '%s' (expected one of: %s)", lua_tostring(L, -2), lua_tostring(L, -1));
        }
    }
    return true;
}

bool tl_getopt(lua_State *L, int arg, const char *key)
{
    if (lua_type(L, arg) != LUA_TTABLE)
        return false;
    if (lua_getfield(L, arg, key) == LUA_TNIL) {
        lua_pop(L, 1);
        return false;
    }
    return true;
}

/* Raises "fname: bad option 'key' (<message on top of the stack>)". */
static int opterror(lua_State *L, const char *key)
{
    return tl_error(L, "bad option '%s' (%s)", key, lua_tostring(L, -1));
}

double tl_optfield_number(lua_State *L, int arg, const char *key, const tl_range *r, double def)
{
    double v = def;
    if (!tl_getopt(L, arg, key))
        return def;
    if (!tl_tonumber_in(L, -1, r, &v))
        opterror(L, key);
    lua_pop(L, 1);
    return v;
}

lua_Integer tl_optfield_integer(lua_State *L, int arg, const char *key, lua_Integer lo, lua_Integer hi, lua_Integer def)
{
    lua_Integer v = def;
    if (!tl_getopt(L, arg, key))
        return def;
    if (!tl_tointeger_in(L, -1, lo, hi, &v))
        opterror(L, key);
    lua_pop(L, 1);
    return v;
}

bool tl_optfield_boolean(lua_State *L, int arg, const char *key, bool def)
{
    bool v;
    if (!tl_getopt(L, arg, key))
        return def;
    if (lua_type(L, -1) != LUA_TBOOLEAN) {
        tl_push_expected(L, -1, "boolean", false);
        opterror(L, key);
    }
    v = lua_toboolean(L, -1) != 0;
    lua_pop(L, 1);
    return v;
}

tt_vec2 tl_optfield_vec2(lua_State *L, int arg, const char *key, const tl_range *r, tt_vec2 def)
{
    tt_vec2 v = def;
    int t;
    if (!tl_getopt(L, arg, key))
        return def;
    t = lua_gettop(L);
    if (lua_type(L, t) != LUA_TTABLE) {
        tl_push_expected(L, t, "table {x, y}", false);
        opterror(L, key);
    }
    for (int i = 1; i <= 2; i++) {
        double c = 0.0;
        lua_rawgeti(L, t, i);
        if (!tl_tonumber_in(L, -1, r, &c)) {
            lua_pushfstring(L, "index %d: %s", i, lua_tostring(L, -1));
            opterror(L, key);
        }
        lua_pop(L, 1);
        if (i == 1) v.x = c; else v.y = c;
    }
    lua_rawgeti(L, t, 3);
    if (!lua_isnil(L, -1)) {
        lua_pushliteral(L, "table {x, y} of exactly two numbers expected");
        opterror(L, key);
    }
    lua_pop(L, 2);
    return v;
}

int tl_optfield_option(lua_State *L, int arg, const char *key, const char *what, const char *const list[], int def_index)
{
    const char *name;
    if (!tl_getopt(L, arg, key))
        return def_index;
    if (lua_type(L, -1) != LUA_TSTRING) {
        tl_push_expected(L, -1, "string", false);
        opterror(L, key);
    }
    name = lua_tostring(L, -1);
    for (int i = 0; list[i] != NULL; i++)
        if (strcmp(list[i], name) == 0) {
            lua_pop(L, 1);
            return i;
        }
    tl_push_choices(L, list);
    return tl_error(L, "invalid %s '%s', expected one of: %s", what, name, lua_tostring(L, -1));
}

/* Reads one option of spec into the struct at base (holding its default).
 * The field at o->at is a real member of the type the TL_OPT_* maker
 * named, so it is read and written through a pointer of its own type. */
static void read_one(lua_State *L, int arg, const tl_opt *o, unsigned char *base)
{
    void *at = base + o->at;
    switch (o->kind) {
    case TL_OPT_NUMBER: {
        double *f = at;
        *f = tl_optfield_number(L, arg, o->key, o->range, *f);
        break;
    }
    case TL_OPT_NUMBER2: { /* given: both fields; absent: both keep theirs */
        double v = tl_optfield_number(L, arg, o->key, o->range, -1.0);
        if (v >= 0.0) *(double *)at = *(double *)(void *)(base + o->at2) = v;
        break;
    }
    case TL_OPT_U32: {
        uint32_t *f = at;
        *f = (uint32_t)tl_optfield_integer(L, arg, o->key, o->lo, o->hi, *f);
        break;
    }
    case TL_OPT_I32: {
        int *f = at;
        *f = (int)tl_optfield_integer(L, arg, o->key, o->lo, o->hi, *f);
        break;
    }
    case TL_OPT_U16: {
        uint16_t *f = at;
        *f = (uint16_t)tl_optfield_integer(L, arg, o->key, o->lo, o->hi, *f);
        break;
    }
    case TL_OPT_BOOL: {
        bool *f = at;
        *f = tl_optfield_boolean(L, arg, o->key, *f);
        break;
    }
    case TL_OPT_VEC2: {
        tt_vec2 *f = at;
        *f = tl_optfield_vec2(L, arg, o->key, o->range, *f);
        break;
    }
    case TL_OPT_ENUM: { /* an enum of the tt_ API: int-sized (TL__AT checked) */
        int *f = at;
        *f = tl_optfield_option(L, arg, o->key, o->what, o->names, *f);
        break;
    }
    case TL_OPT_OWN:
        break; /* the caller reads it */
    }
}

bool tl_readopts(lua_State *L, int arg, const tl_opt spec[], void *dst)
{
    if (!tl_checkopts(L, arg, spec))
        return false;
    for (const tl_opt *o = spec; o->key != NULL; o++) read_one(L, arg, o, dst);
    return true;
}
