/* tether — Lua world methods on springs: w:spring (create), w:remove_spring,
 * w:spring_is_valid, w:spring_length, w:spring_info, w:set_spring. Handles
 * are Lua integers (tt_spring_to_u64). */
#include "lua_common.h"

static tt_spring check_spring(lua_State *L, tt_world *w, int arg)
{
    return tt_spring_from_u64(tl_checkhandle(L, w, arg, TT_KIND_SPRING));
}

static const tl_opt spring_opts[] = {
    TL_OPT_NUM(tt_spring_def, "stiffness", stiffness, &TL_R_NONNEG),
    TL_OPT_NUM(tt_spring_def, "damping", damping, &TL_R_NONNEG),
    TL_OPT_NUM(tt_spring_def, "rest", rest_length, &TL_R_NONNEG),
    TL_OPT_END,
};

/* w:spring(a, b [, opts]) → spring handle */
static int w_spring(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_spring_def def = tt_spring_def_default();
    tt_spring s;

    lua_settop(L, 4);
    def.a = tl_check_particle(L, w, 2);
    def.b = tl_check_particle(L, w, 3);
    if (def.a.index == def.b.index && def.a.gen == def.b.gen)
        tl_argerror(L, 3, "a spring needs two distinct particles");
    tl_readopts(L, 4, spring_opts, &def);

    s = tt_spring_create(w, &def);
    if (s.gen == 0)
        tl_check_result(L, w, TT_EINVAL);
    tl_push_spring(L, s);
    return 1;
}

static int w_remove_spring(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_spring s = check_spring(L, w, 2);
    tl_check_result(L, w, tt_spring_destroy(w, s));
    return 0;
}

static int w_spring_is_valid(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_pushboolean(L, tl_handle_is_live(L, w, 2, TT_KIND_SPRING));
    return 1;
}

static int w_spring_length(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_spring s = check_spring(L, w, 2);
    double len;
    tl_check_result(L, w, tt_spring_get_length(w, s, &len));
    lua_pushnumber(L, len);
    return 1;
}

/* w:spring_info(s) → {a=, b=, stiffness=, damping=, rest=} */
static int w_spring_info(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_spring s = check_spring(L, w, 2);
    tt_spring_def d;
    tl_check_result(L, w, tt_spring_get_def(w, s, &d));
    lua_createtable(L, 0, 5);
    tl_push_particle(L, d.a);
    lua_setfield(L, -2, "a");
    tl_push_particle(L, d.b);
    lua_setfield(L, -2, "b");
    lua_pushnumber(L, d.stiffness);
    lua_setfield(L, -2, "stiffness");
    lua_pushnumber(L, d.damping);
    lua_setfield(L, -2, "damping");
    lua_pushnumber(L, d.rest_length);
    lua_setfield(L, -2, "rest");
    return 1;
}

/* w:set_spring(s, {stiffness=, damping=, rest=}) — only the given fields
 * change; all are checked before any changes. */
static int w_set_spring(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_spring s = check_spring(L, w, 2);

    lua_settop(L, 3);
    if (lua_type(L, 3) != LUA_TTABLE)
        tl_typeerror(L, 3, "table");
    /* −1 marks a field that is absent: every valid value is ≥ 0 */
    tt_spring_def o = tt_spring_def_default();
    o.stiffness = o.damping = o.rest_length = -1.0;
    tl_readopts(L, 3, spring_opts, &o);
    if (o.stiffness >= 0.0) tl_check_result(L, w, tt_spring_set_stiffness(w, s, o.stiffness));
    if (o.damping >= 0.0) tl_check_result(L, w, tt_spring_set_damping(w, s, o.damping));
    if (o.rest_length >= 0.0) tl_check_result(L, w, tt_spring_set_rest_length(w, s, o.rest_length));
    return 0;
}

/* --- registration ----------------------------------------------------------- */

static const luaL_Reg spring_methods[] = {
    { "spring", w_spring },
    { "remove_spring", w_remove_spring },
    { "spring_is_valid", w_spring_is_valid },
    { "spring_length", w_spring_length },
    { "spring_info", w_spring_info },
    { "set_spring", w_set_spring },
    { NULL, NULL }
};

void tl_springs_register(lua_State *L)
{
    tl_world_add_methods(L, spring_methods);
}
