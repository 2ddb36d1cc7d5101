/* tether — tether_box2d's scene functions: a named scene as a Lua table
 * (the very description both engines build from), a Box2D world built from
 * such a table, the cross-check's rows as tables; and the module's opener. */
#include "lua_box2d.h"

#include "lua/lua_common.h" /* option tables and checkers as every binding has them; Lua 5.4 and LuaJIT */

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *const shape_names[] = {"circle", "box", "polygon", "edge"};
static const char *const joint_names[] = {"revolute", "distance", "weld"};

static void set_num(lua_State *L, const char *k, double v)
{
    lua_pushnumber(L, v);
    lua_setfield(L, -2, k);
}

static void set_pair(lua_State *L, const char *k, tt_vec2 v)
{
    lua_createtable(L, 2, 0);
    lua_pushnumber(L, v.x);
    lua_rawseti(L, -2, 1);
    lua_pushnumber(L, v.y);
    lua_rawseti(L, -2, 2);
    lua_setfield(L, -2, k);
}

/* Only the keys the shape uses, so a table reads like the scene. */
static void push_body(lua_State *L, const ts_body *b)
{
    lua_createtable(L, 0, 12);
    lua_pushstring(L, shape_names[b->shape]);
    lua_setfield(L, -2, "shape");
    lua_pushboolean(L, b->dynamic);
    lua_setfield(L, -2, "dynamic");
    set_num(L, "x", b->position.x);
    set_num(L, "y", b->position.y);
    if (b->angle != 0) set_num(L, "angle", b->angle);
    if (b->velocity.x != 0 || b->velocity.y != 0) set_num(L, "vx", b->velocity.x), set_num(L, "vy", b->velocity.y);
    if (b->spin != 0) set_num(L, "spin", b->spin);
    if (b->shape == TS_CIRCLE) set_num(L, "radius", b->radius);
    if (b->shape == TS_BOX) set_num(L, "hx", b->half.x), set_num(L, "hy", b->half.y);
    if (b->shape == TS_EDGE) set_pair(L, "a", b->a), set_pair(L, "b", b->b);
    if (b->shape == TS_POLYGON) {
        lua_createtable(L, (int)(2 * b->count), 0);
        for (uint32_t i = 0; i < b->count; i++) {
            lua_pushnumber(L, b->points[i].x);
            lua_rawseti(L, -2, (lua_Integer)(2 * i + 1));
            lua_pushnumber(L, b->points[i].y);
            lua_rawseti(L, -2, (lua_Integer)(2 * i + 2));
        }
        lua_setfield(L, -2, "points");
    }
    if (b->dynamic) set_num(L, "density", b->density);
    set_num(L, "friction", b->friction);
    set_num(L, "restitution", b->restitution);
    if (b->fixed_rotation) {
        lua_pushboolean(L, 1);
        lua_setfield(L, -2, "fixed_rotation");
    }
}

/* tether_box2d.scene(name [, quick]) */
int tl_b2_scene(lua_State *L)
{
    const char *name = luaL_checkstring(L, 1);
    const bool quick = lua_toboolean(L, 2);
    ts_scene s;
    if (!ts_scene_named(&s, name, quick))
        return luaL_error(L, "tether_box2d.scene: bad argument #1 (unknown scene '%s': fall, pendulum, bounce, slope, spin, pyramid, discs, pour, pour100k)", name);
    lua_createtable(L, 0, 6);
    lua_pushstring(L, s.name);
    lua_setfield(L, -2, "name");
    set_pair(L, "gravity", s.gravity);
    set_num(L, "dt", s.dt);
    lua_pushinteger(L, s.steps);
    lua_setfield(L, -2, "steps");
    lua_createtable(L, (int)s.body_count, 0);
    for (uint32_t i = 0; i < s.body_count; i++) {
        push_body(L, &s.bodies[i]);
        lua_rawseti(L, -2, (lua_Integer)i + 1);
    }
    lua_setfield(L, -2, "bodies");
    lua_createtable(L, (int)s.joint_count, 0);
    for (uint32_t i = 0; i < s.joint_count; i++) {
        const ts_joint *j = &s.joints[i];
        lua_createtable(L, 0, 5);
        lua_pushstring(L, joint_names[j->kind]);
        lua_setfield(L, -2, "kind");
        lua_pushinteger(L, j->a + 1); /* Lua counts bodies from 1; 0 is the ground */
        lua_setfield(L, -2, "a");
        lua_pushinteger(L, j->b + 1);
        lua_setfield(L, -2, "b");
        set_pair(L, "anchor_a", j->anchor_a);
        set_pair(L, "anchor_b", j->anchor_b);
        lua_rawseti(L, -2, (lua_Integer)i + 1);
    }
    lua_setfield(L, -2, "joints");
    ts_scene_free(&s);
    return 1;
}

/* Two numbers of the pair t[key] (a table {x, y}) into out. */
static void get_pair(lua_State *L, int t, const char *fn, const char *key, double out[2])
{
    lua_getfield(L, t, key);
    if (!lua_istable(L, -1)) luaL_error(L, "%s: '%s' must be a table {x, y}", fn, key);
    for (int i = 0; i < 2; i++) {
        lua_rawgeti(L, -1, i + 1);
        if (!lua_isnumber(L, -1)) luaL_error(L, "%s: '%s'[%d] must be a number", fn, key, i + 1);
        out[i] = lua_tonumber(L, -1);
        lua_pop(L, 1);
    }
    lua_pop(L, 1);
}

static void build_joints(lua_State *L, tb_world *w, int t, const char *fn)
{
    static const char *const kinds[] = {"revolute", "distance", "weld", NULL};
    lua_getfield(L, t, "joints");
    if (lua_isnil(L, -1)) {
        lua_pop(L, 1);
        return;
    }
    if (!lua_istable(L, -1)) luaL_error(L, "%s: 'joints' must be a list of joint tables", fn);
    const int jt = lua_gettop(L);
    for (lua_Integer i = 1, n = lua_rawlen(L, jt); i <= n; i++) {
        lua_rawgeti(L, jt, i);
        const int j = lua_gettop(L);
        if (!lua_istable(L, j)) luaL_error(L, "%s: joints[%d] must be a table", fn, (int)i);
        const int kind = tl_optfield_option(L, j, "kind", "joint kind", kinds, -1);
        if (kind < 0) luaL_error(L, "%s: joints[%d]: 'kind' must be one of 'revolute', 'distance', 'weld'", fn, (int)i);
        lua_getfield(L, j, "a");
        lua_getfield(L, j, "b");
        const lua_Integer a = lua_tointeger(L, -2), b = lua_tointeger(L, -1);
        if (!lua_isinteger(L, -2) || !lua_isinteger(L, -1) || a < 0 || b < 1 || a > INT_MAX || b > INT_MAX)
            luaL_error(L, "%s: joints[%d]: 'a' and 'b' must be body numbers (a may be 0, the ground)", fn, (int)i);
        double pa[2], pb[2];
        get_pair(L, j, fn, "anchor_a", pa);
        lua_getfield(L, j, "anchor_b");
        const bool has_b = !lua_isnil(L, -1);
        lua_pop(L, 1);
        if (has_b) get_pair(L, j, fn, "anchor_b", pb);
        else pb[0] = pa[0], pb[1] = pa[1];
        if (tb_joint_create(w, (tb_joint)kind, (int)a - 1, (int)b - 1, pa, pb) < 0)
            luaL_error(L, "%s: joints[%d]: %s", fn, (int)i, tb_last_error());
        lua_settop(L, jt);
    }
    lua_pop(L, 1);
}

/* tether_box2d.build(scene [, options]): options as tether_box2d.world's
 * (its gravity is ignored: the scene's is used). */
int tl_b2_build(lua_State *L)
{
    const char *fn = "tether_box2d.build";
    luaL_checktype(L, 1, LUA_TTABLE);
    tb_world_def d = tl_b2_world_def(L, 2);
    lua_getfield(L, 1, "gravity");
    const bool has_g = !lua_isnil(L, -1);
    lua_pop(L, 1);
    if (has_g) get_pair(L, 1, fn, "gravity", d.gravity);
    tb_world *w = tl_b2_push_world(L, &d, fn);
    const int wi = lua_gettop(L);
    lua_getfield(L, 1, "bodies");
    if (!lua_istable(L, -1)) return luaL_error(L, "%s: the scene's 'bodies' must be a list of body tables", fn);
    const int bt = lua_gettop(L);
    for (lua_Integer i = 1, n = lua_rawlen(L, bt); i <= n; i++) {
        lua_rawgeti(L, bt, i);
        if (!lua_istable(L, -1)) return luaL_error(L, "%s: bodies[%d] must be a table", fn, (int)i);
        const tb_body_def b = tl_b2_body_def(L, lua_gettop(L));
        if (tb_body_create(w, &b) < 0) return luaL_error(L, "%s: bodies[%d]: %s", fn, (int)i, tb_last_error());
        lua_pop(L, 1);
    }
    lua_pop(L, 1);
    build_joints(L, w, 1, fn);
    lua_settop(L, wi);
    return 1;
}

static void push_rows(lua_State *L, const cc_report *r)
{
    lua_createtable(L, r->nrows, 0);
    for (int i = 0; i < r->nrows; i++) {
        const cc_row *w = &r->rows[i];
        lua_createtable(L, 0, 7);
        lua_pushstring(L, w->scene);
        lua_setfield(L, -2, "scene");
        lua_pushstring(L, w->measure);
        lua_setfield(L, -2, "measure");
        lua_pushstring(L, w->setting);
        lua_setfield(L, -2, "setting");
        lua_pushstring(L, w->unit);
        lua_setfield(L, -2, "unit");
        if (!isnan(w->expected)) set_num(L, "expected", w->expected);
        if (!isnan(w->box2d)) set_num(L, "box2d", w->box2d);
        if (!isnan(w->tether)) set_num(L, "tether", w->tether);
        lua_rawseti(L, -2, i + 1);
    }
}

typedef struct cc_opts {
    bool quick, print;
    int runs;
} cc_opts;
static const tl_opt cc_opt_spec[] = {
    TL_OPT_FLAG(cc_opts, "quick", quick),
    TL_OPT_FLAG(cc_opts, "print", print),
    TL_OPT_INT(cc_opts, "runs", runs, 1, 50),
    TL_OPT_END,
};

/* tether_box2d.crosscheck([scene [, {quick =, runs =, print =}]]) → rows
 * ({scene, measure, setting, unit, expected, box2d, tether}, a missing
 * number is nil) and costs ({scene, setting, box2d_ms, tether_ms}). */
int tl_b2_crosscheck(lua_State *L)
{
    const char *fn = "tether_box2d.crosscheck";
    const char *scene = luaL_optstring(L, 1, NULL);
    cc_opts o = {false, false, 0}; /* runs 0: 2 quick, else 5 */
    tl_readopts(L, 2, cc_opt_spec, &o);
    cc_report *r = lua_newuserdatauv(L, sizeof *r, 0); /* freed by Lua even if a step below raises */
    memset(r, 0, sizeof *r);
    r->quick = o.quick;
    r->runs = o.runs ? o.runs : o.quick ? 2 : 5;
    r->small = ts_tether_settings_default();
    const bool print = o.print;
    const char *why = "";
    char before[64];
    cc_load(before, sizeof before);
    if (!cc_run(r, scene, &why)) return luaL_error(L, "%s: %s", fn, why);
    if (print) cc_print(r, stdout, NULL, before);
    push_rows(L, r);
    lua_createtable(L, r->ncosts, 0);
    for (int i = 0; i < r->ncosts; i++) {
        lua_createtable(L, 0, 4);
        lua_pushstring(L, r->costs[i].scene);
        lua_setfield(L, -2, "scene");
        lua_pushstring(L, r->costs[i].setting);
        lua_setfield(L, -2, "setting");
        set_num(L, "box2d_ms", r->costs[i].box2d_med);
        if (!isnan(r->costs[i].tether_med)) set_num(L, "tether_ms", r->costs[i].tether_med);
        lua_rawseti(L, -2, i + 1);
    }
    return 2;
}

/* tether_box2d.main(arg, ...): the command line of `tether crosscheck`; its exit status. */
int tl_b2_main(lua_State *L)
{
    const int n = lua_gettop(L);
    char **argv = lua_newuserdatauv(L, (size_t)(n + 2) * sizeof *argv, 0);
    argv[0] = "crosscheck";
    for (int i = 1; i <= n; i++) argv[i] = (char *)luaL_checkstring(L, i);
    argv[n + 1] = NULL;
    fflush(stdout);
    lua_pushinteger(L, tb_crosscheck_main(n + 1, argv));
    return 1;
}

__attribute__((visibility("default"))) int luaopen_tether_box2d(lua_State *L)
{
    static const luaL_Reg lib[] = {{"world", tl_b2_world},           {"scene", tl_b2_scene}, {"build", tl_b2_build},
                                   {"crosscheck", tl_b2_crosscheck}, {"main", tl_b2_main},   {NULL, NULL}};
    luaL_checkversion(L);
    tl_b2_register(L);
    lua_newtable(L);
    tl_setfuncs(L, lib, "tether_box2d."); /* named for the option tables' errors */
    lua_pushliteral(L, "Box2D 2.4.1");
    lua_setfield(L, -2, "version");
    return 1;
}
