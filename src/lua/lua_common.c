/* tether — Lua binding helpers: argument checkers, option tables, errors.
 * See lua_common.h for the conventions. */
#include "lua_common.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

const tl_range TL_R_COORD = { -TL_MAX_ABS, TL_MAX_ABS, false };
const tl_range TL_R_NONNEG = { 0.0, TL_MAX_POS, false };
const tl_range TL_R_UNIT = { 0.0, 1.0, false };
const tl_range TL_R_MASS = { TL_MIN_MASS, TL_MAX_MASS, false };
const tl_range TL_R_DT = { TT_MIN_DT, TL_MAX_DT, false };

/* --- registration ---------------------------------------------------------- */

void tl_setfuncs(lua_State *L, const luaL_Reg *l, const char *prefix)
{
    for (; l->name != NULL; l++) {
        lua_pushfstring(L, "%s%s", prefix, l->name);
        lua_pushcclosure(L, l->func, 1);
        lua_setfield(L, -2, l->name);
    }
}

const char *tl_fname(lua_State *L)
{
    /* A C function without upvalues reads nil here (lua_upvalueindex past
     * the closure's upvalues is an acceptable index). */
    if (lua_type(L, lua_upvalueindex(1)) == LUA_TSTRING)
        return lua_tostring(L, lua_upvalueindex(1));
    return "?";
}

/* --- errors ---------------------------------------------------------------- */

/* Formats a number for a message: "%.14g", but "nan" for every NaN
 * (glibc prints the default x86 NaN as "-nan") and "inf" / "-inf". */
static const char *fmtnum(char buf[40], double v)
{
    if (isnan(v)) return "nan";
    if (isinf(v)) return v > 0 ? "inf" : "-inf";
    snprintf(buf, 40, "%.14g", v);
    return buf;
}

int tl_argerror(lua_State *L, int arg, const char *fmt, ...)
{
    va_list ap;
    const char *fname = tl_fname(L);
    va_start(ap, fmt);
    lua_pushvfstring(L, fmt, ap);
    va_end(ap);
    return luaL_error(L, "bad argument #%d to '%s' (%s)", arg, fname, lua_tostring(L, -1));
}

int tl_error(lua_State *L, const char *fmt, ...)
{
    va_list ap;
    const char *fname = tl_fname(L);
    va_start(ap, fmt);
    lua_pushvfstring(L, fmt, ap);
    va_end(ap);
    return luaL_error(L, "%s: %s", fname, lua_tostring(L, -1));
}

const char *tl_pushtypename(lua_State *L, int idx)
{
    idx = lua_absindex(L, idx);
    if (luaL_getmetafield(L, idx, "__name") == LUA_TSTRING)
        return lua_tostring(L, -1);
    if (lua_type(L, idx) == LUA_TLIGHTUSERDATA)
        lua_pushliteral(L, "light userdata");
    else
        lua_pushstring(L, luaL_typename(L, idx));
    return lua_tostring(L, -1);
}

int tl_typeerror(lua_State *L, int arg, const char *expected)
{
    const char *got = tl_pushtypename(L, arg);
    return tl_argerror(L, arg, "%s expected, got %s", expected, got);
}

/* --- validators that report instead of raising ------------------------------ */

void tl_push_expected(lua_State *L, int idx, const char *what, bool by_value)
{
    char buf[40];
    idx = lua_absindex(L, idx);
    if (by_value && lua_type(L, idx) == LUA_TNUMBER) {
        if (lua_isinteger(L, idx))
            lua_pushfstring(L, "%s expected, got " TL_I, what, TL_IARG(lua_tointeger(L, idx)));
        else
            lua_pushfstring(L, "%s expected, got %s", what, fmtnum(buf, lua_tonumber(L, idx)));
    } else {
        const char *got = tl_pushtypename(L, idx);
        lua_pushfstring(L, "%s expected, got %s", what, got);
        lua_remove(L, -2);
    }
}

/* Pushes "number in [lo, hi]" (bounds are round numbers: %g is exact). */
static void push_range(lua_State *L, const tl_range *r)
{
    char a[40], b[40];
    snprintf(a, sizeof a, "%g", r->lo);
    snprintf(b, sizeof b, "%g", r->hi);
    lua_pushfstring(L, "number in %s%s, %s]", r->lo_open ? "(" : "[", a, b);
}

bool tl_tonumber_in(lua_State *L, int idx, const tl_range *r, double *out)
{
    double v;
    idx = lua_absindex(L, idx);
    if (lua_type(L, idx) != LUA_TNUMBER) {
        tl_push_expected(L, idx, "number", false);
        return false;
    }
    v = lua_tonumber(L, idx);
    if (!isfinite(v)) {
        tl_push_expected(L, idx, "finite number", true);
        return false;
    }
    if (v > r->hi || v < r->lo || (r->lo_open && v == r->lo)) {
        push_range(L, r);
        tl_push_expected(L, idx, lua_tostring(L, -1), true);
        lua_remove(L, -2);
        return false;
    }
    /* -0 becomes +0: LuaJIT has no integer zero, so a script's -i * d at
     * i = 0 is -0 there and +0 in Lua 5.4; one script, one world in both. */
    *out = v + 0.0;
    return true;
}

bool tl_tointeger_in(lua_State *L, int idx, lua_Integer lo, lua_Integer hi, lua_Integer *out)
{
    int isint = 0;
    lua_Integer v;
    idx = lua_absindex(L, idx);
    if (lua_type(L, idx) != LUA_TNUMBER) {
        tl_push_expected(L, idx, "integer", false);
        return false;
    }
    v = lua_tointegerx(L, idx, &isint);
    if (!isint || v < lo || v > hi) {
        lua_pushfstring(L, "integer in [" TL_I ", " TL_I "]", TL_IARG(lo), TL_IARG(hi));
        tl_push_expected(L, idx, lua_tostring(L, -1), true);
        lua_remove(L, -2);
        return false;
    }
    *out = v;
    return true;
}

/* --- positional arguments -------------------------------------------------- */

double tl_checknumber(lua_State *L, int arg, const tl_range *r)
{
    double v = 0.0;
    if (!tl_tonumber_in(L, arg, r, &v))
        tl_argerror(L, arg, "%s", lua_tostring(L, -1));
    return v;
}

double tl_optnumber(lua_State *L, int arg, const tl_range *r, double def)
{
    return lua_isnoneornil(L, arg) ? def : tl_checknumber(L, arg, r);
}

lua_Integer tl_checkinteger(lua_State *L, int arg, lua_Integer lo, lua_Integer hi)
{
    lua_Integer v = 0;
    if (!tl_tointeger_in(L, arg, lo, hi, &v))
        tl_argerror(L, arg, "%s", lua_tostring(L, -1));
    return v;
}

lua_Integer tl_optinteger(lua_State *L, int arg, lua_Integer lo, lua_Integer hi, lua_Integer def)
{
    return lua_isnoneornil(L, arg) ? def : tl_checkinteger(L, arg, lo, hi);
}

bool tl_checkboolean(lua_State *L, int arg)
{
    if (lua_type(L, arg) != LUA_TBOOLEAN)
        tl_typeerror(L, arg, "boolean");
    return lua_toboolean(L, arg) != 0;
}

const char *tl_checkstring(lua_State *L, int arg)
{
    int t = lua_type(L, arg);
    if (t != LUA_TSTRING && t != LUA_TNUMBER)
        tl_typeerror(L, arg, "string");
    return lua_tostring(L, arg);
}

const char *tl_optstring(lua_State *L, int arg, const char *def)
{
    int t = lua_type(L, arg);
    if (t == LUA_TNONE || t == LUA_TNIL)
        return def;
    if (t != LUA_TSTRING && t != LUA_TNUMBER)
        tl_typeerror(L, arg, "string or nil");
    return lua_tostring(L, arg);
}

void tl_push_choices(lua_State *L, const char *const list[])
{
    luaL_Buffer b;
    luaL_buffinit(L, &b);
    for (int i = 0; list[i] != NULL; i++) {
        if (i > 0) luaL_addstring(&b, ", ");
        luaL_addchar(&b, '\'');
        luaL_addstring(&b, list[i]);
        luaL_addchar(&b, '\'');
    }
    luaL_pushresult(&b);
}

int tl_checkoption(lua_State *L, int arg, const char *what, const char *def, const char *const list[])
{
    const char *name;
    if (def != NULL && lua_isnoneornil(L, arg)) {
        name = def;
    } else {
        if (lua_type(L, arg) != LUA_TSTRING)
            tl_typeerror(L, arg, "string");
        name = lua_tostring(L, arg);
    }
    for (int i = 0; list[i] != NULL; i++)
        if (strcmp(list[i], name) == 0)
            return i;
    tl_push_choices(L, list);
    return tl_argerror(L, arg, "invalid %s '%s', expected one of: %s", what, name, lua_tostring(L, -1));
}

bool tl_opttable(lua_State *L, int arg)
{
    if (lua_isnoneornil(L, arg))
        return false;
    if (lua_type(L, arg) != LUA_TTABLE)
        tl_typeerror(L, arg, "table or nil");
    return true;
}
