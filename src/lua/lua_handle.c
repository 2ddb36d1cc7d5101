/* tether — the one place where handles cross the Lua boundary: pushed as
 * integers that carry their kind (tether/base.h has the bit budget), and
 * checked on the way back in for type, kind and liveness. */
#include "lua_common.h"

static const char *const kind_names[] = {"handle", "particle", "spring", "constraint", "shape", "composite", "terrain"};

const char *tl_kind_name(tt_kind k)
{
    return (unsigned)k < sizeof kind_names / sizeof kind_names[0] ? kind_names[k] : kind_names[0];
}

/* Every handle pushed comes from the world (made, listed, reported), so its
 * fields fit the budget: packed here without the checks of tt_*_to_u64,
 * which would cost a bulk read of 100 000 handles 15 % more instructions. */
#define PACK(k, h) ((lua_Integer)(((uint64_t)(k) << TT__HANDLE_KIND_SHIFT) | ((uint64_t)(h).gen << TT_HANDLE_INDEX_BITS) | (h).index))
void tl_push_particle(lua_State *L, tt_particle p) { lua_pushinteger(L, PACK(TT_KIND_PARTICLE, p)); }
void tl_push_spring(lua_State *L, tt_spring s) { lua_pushinteger(L, PACK(TT_KIND_SPRING, s)); }
void tl_push_constraint(lua_State *L, tt_constraint c) { lua_pushinteger(L, PACK(TT_KIND_CONSTRAINT, c)); }
void tl_push_shape(lua_State *L, tt_shape s) { lua_pushinteger(L, PACK(TT_KIND_SHAPE, s)); }
void tl_push_composite(lua_State *L, tt_composite c) { lua_pushinteger(L, PACK(TT_KIND_COMPOSITE, c)); }
void tl_push_terrain(lua_State *L, tt_terrain t) { lua_pushinteger(L, PACK(TT_KIND_TERRAIN, t)); }

static inline bool live(const tt_world *w, tt_kind k, uint64_t u)
{
    switch (k) {
    case TT_KIND_PARTICLE: return tt_particle_is_valid(w, tt_particle_from_u64(u));
    case TT_KIND_SPRING: return tt_spring_is_valid(w, tt_spring_from_u64(u));
    case TT_KIND_CONSTRAINT: return tt_constraint_is_valid(w, tt_constraint_from_u64(u));
    case TT_KIND_SHAPE: return tt_shape_is_valid(w, tt_shape_from_u64(u));
    case TT_KIND_COMPOSITE: return tt_composite_is_valid(w, tt_composite_from_u64(u));
    case TT_KIND_TERRAIN: return tt_terrain_is_valid(w, tt_terrain_from_u64(u));
    default: return false;
    }
}

/* Why the value at idx is no live handle of kind: pushes the message. */
static bool refuse(lua_State *L, int idx, tt_kind kind, lua_Integer v, bool isint)
{
    tt_kind k = isint ? tt_handle_kind((uint64_t)v) : TT_KIND_NONE;
    if (!isint) {
        idx = lua_absindex(L, idx);
        lua_pushfstring(L, "%s handle", tl_kind_name(kind));
        tl_push_expected(L, idx, lua_tostring(L, -1), true);
        lua_remove(L, -2);
    } else if (k == TT_KIND_NONE) {
        lua_pushfstring(L, "%s handle expected, got " TL_I, tl_kind_name(kind), TL_IARG(v));
    } else if (k != kind) {
        lua_pushfstring(L, "%s expected, got %s", tl_kind_name(kind), tl_kind_name(k));
    } else {
        lua_pushfstring(L, "stale %s handle", tl_kind_name(kind));
    }
    return false;
}

/* Numbers are accepted as long as they hold an integer exactly, so a handle
 * that went through a float (LuaJIT, JSON, a saved game) still works. The
 * kind test also refuses negatives and everything from 2^53 up. */
bool tl_tohandle(lua_State *L, int idx, const tt_world *w, tt_kind kind, uint64_t *out)
{
    int isint = 0;
    lua_Integer v = lua_type(L, idx) == LUA_TNUMBER ? lua_tointegerx(L, idx, &isint) : 0;
    if (!isint || (uint64_t)v >> TT__HANDLE_KIND_SHIFT != (uint64_t)kind || (w != NULL && !live(w, kind, (uint64_t)v)))
        return refuse(L, idx, kind, v, isint);
    *out = (uint64_t)v;
    return true;
}

uint64_t tl_checkhandle(lua_State *L, const tt_world *w, int arg, tt_kind kind)
{
    uint64_t u = 0;
    if (!tl_tohandle(L, arg, w, kind, &u))
        tl_argerror(L, arg, "%s", lua_tostring(L, -1));
    return u;
}

bool tl_handle_is_live(lua_State *L, const tt_world *w, int arg, tt_kind kind)
{
    uint64_t u = 0;
    int isint = 0;
    lua_Integer v = lua_type(L, arg) == LUA_TNUMBER ? lua_tointegerx(L, arg, &isint) : 0;
    /* The null handle, or any integer that is no handle, names nothing live;
     * a handle of another kind is a mistake worth an error. */
    if (isint && tt_handle_kind((uint64_t)v) == TT_KIND_NONE)
        return false;
    if (!tl_tohandle(L, arg, NULL, kind, &u))
        tl_argerror(L, arg, "%s", lua_tostring(L, -1));
    return live(w, kind, u);
}

tt_particle tl_check_particle(lua_State *L, tt_world *w, int arg)
{
    return tt_particle_from_u64(tl_checkhandle(L, w, arg, TT_KIND_PARTICLE));
}
