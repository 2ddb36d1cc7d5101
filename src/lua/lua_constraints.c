/* tether — Lua bindings of constraints: world methods added to the world
 * class by tl_constraints_register (called from luaopen_tether). Handles are
 * integers (tt_constraint_to_u64). Every argument is checked here first, so
 * the core never sees a bad value. */
#include "lua_common.h"

#include <string.h>

#define PI 3.14159265358979323846

static const tl_range R_ANGLE = {-PI, PI, false};
static const tl_range R_POS = {0.0, TT_MAX_VALUE, true};

static const char *const kind_names[] = {"distance", "pin", "bounds", "angle", "area", "collinear", NULL};
static const char *const mode_names[] = {"rigid", "max", "min", NULL};

static tt_constraint check_constraint(lua_State *L, tt_world *w, int arg)
{
    return tt_constraint_from_u64(tl_checkhandle(L, w, arg, TT_KIND_CONSTRAINT));
}

static void push_constraint(lua_State *L, tt_world *w, tt_constraint c)
{
    if (c.gen == 0) tl_check_result(L, w, TT_EINVAL);
    tl_push_constraint(L, c);
}

/* Raises about argument arg, or about option `opt` when it is not NULL. */
static void list_error(lua_State *L, int arg, const char *opt, const char *msg)
{
    if (opt) tl_error(L, "bad option '%s' (%s)", opt, msg);
    tl_argerror(L, arg, "%s", msg);
}

/* A table of live particle handles at stack index idx (argument arg, or the
 * value of option opt), into a userdata buffer left on the stack. */
static tt_particle *check_handle_list(lua_State *L, tt_world *w, int idx, const char *opt, uint32_t min, uint32_t max,
                                      uint32_t *n)
{
    if (lua_type(L, idx) != LUA_TTABLE) {
        if (!opt) tl_typeerror(L, idx, "table of particle handles");
        list_error(L, idx, opt, "table of particle handles expected");
    }
    lua_Integer len = (lua_Integer)lua_rawlen(L, idx);
    if (len < (lua_Integer)min || len > (lua_Integer)max) {
        lua_pushfstring(L, "%d to %d particle handles expected, got %d", (int)min, (int)max, (int)len);
        list_error(L, idx, opt, lua_tostring(L, -1));
    }
    tt_particle *ps = lua_newuserdatauv(L, (size_t)len * sizeof *ps + 1, 0);
    for (lua_Integer i = 1; i <= len; i++) {
        uint64_t h;
        lua_rawgeti(L, idx, i);
        if (!tl_tohandle(L, -1, w, TT_KIND_PARTICLE, &h)) {
            lua_pushfstring(L, "index %d: %s", (int)i, lua_tostring(L, -1));
            list_error(L, idx, opt, lua_tostring(L, -1));
        }
        ps[i - 1] = tt_particle_from_u64(h);
        lua_pop(L, 1);
    }
    *n = (uint32_t)len;
    return ps;
}

/* The stiffness/compliance pair of every constraint's options. */
#define SOFT_OPTS(T) TL_OPT_NUM(T, "stiffness", stiffness, &TL_R_UNIT), TL_OPT_NUM(T, "compliance", compliance, &TL_R_NONNEG)

/* --- constraints ------------------------------------------------------------- */

static const tl_opt distance_opts[] = {
    TL_OPT_NUM(tt_distance_def, "length", length, &TL_R_NONNEG),
    TL_OPT_CHOICE(tt_distance_def, "mode", mode, "mode", mode_names),
    SOFT_OPTS(tt_distance_def),
    TL_OPT_NUM(tt_distance_def, "break_strain", break_strain, &TL_R_NONNEG),
    TL_OPT_FLAG(tt_distance_def, "collide", collide),
    TL_OPT_NUM(tt_distance_def, "max_rate", max_rate, &TL_R_NONNEG),
    TL_OPT_END,
};

/* w:distance(a, b [, {length, mode, stiffness, compliance, break_strain, collide, max_rate}]) → constraint */
static int c_distance(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_settop(L, 4);
    tt_distance_def d = tt_distance_def_default();
    d.a = tl_check_particle(L, w, 2);
    d.b = tl_check_particle(L, w, 3);
    if (d.a.index == d.b.index) tl_argerror(L, 3, "a distance constraint needs two distinct particles");
    tl_readopts(L, 4, distance_opts, &d);
    push_constraint(L, w, tt_distance_create(w, &d));
    return 1;
}

static const tl_opt pin_opts[] = {
    TL_OPT_XY(tt_pin_def, "anchor", anchor, &TL_R_COORD),
    SOFT_OPTS(tt_pin_def),
    TL_OPT_NUM(tt_pin_def, "max_rate", max_rate, &TL_R_NONNEG),
    TL_OPT_END,
};

/* w:pin(p [, {anchor = {x, y}, stiffness, compliance, max_rate}]) → constraint */
static int c_pin(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_settop(L, 3);
    tt_pin_def d = tt_pin_def_default();
    d.particle = tl_check_particle(L, w, 2);
    if (tl_getopt(L, 3, "anchor")) { /* an anchor given: there, not where the particle is */
        lua_pop(L, 1);
        d.anchor_here = false;
    }
    tl_readopts(L, 3, pin_opts, &d);
    push_constraint(L, w, tt_pin_create(w, &d));
    return 1;
}

static const tl_opt bounds_opts[] = {
    TL_OPT_BYHAND("particles"),
    TL_OPT_FLAG(tt_bounds_def, "outside", outside),
    TL_OPT_NUM(tt_bounds_def, "friction", friction, &TL_R_UNIT),
    TL_OPT_END,
};

/* w:bounds(xmin, ymin, xmax, ymax [, {particles = {…}, outside, friction}]) → constraint */
static int c_bounds(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_settop(L, 6);
    tt_bounds_def d = tt_bounds_def_default();
    d.min.x = tl_checknumber(L, 2, &TL_R_COORD);
    d.min.y = tl_checknumber(L, 3, &TL_R_COORD);
    d.max.x = tl_checknumber(L, 4, &TL_R_COORD);
    d.max.y = tl_checknumber(L, 5, &TL_R_COORD);
    if (!(d.min.x < d.max.x)) tl_argerror(L, 4, "xmax must be greater than xmin");
    if (!(d.min.y < d.max.y)) tl_argerror(L, 5, "ymax must be greater than ymin");
    tl_readopts(L, 6, bounds_opts, &d);
    if (tl_getopt(L, 6, "particles")) {
        d.particles = check_handle_list(L, w, lua_gettop(L), "particles", 1, 1u << 30, &d.count);
    }
    push_constraint(L, w, tt_bounds_create(w, &d));
    return 1;
}

static const tl_opt angle_opts[] = {
    TL_OPT_NUM(tt_angle_def, "min", min, &R_ANGLE),
    TL_OPT_NUM(tt_angle_def, "max", max, &R_ANGLE),
    SOFT_OPTS(tt_angle_def),
    TL_OPT_END,
};

/* w:angle(a, b, c [, {min, max, stiffness, compliance}]) → constraint; min/max default to the angle now */
static int c_angle(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_settop(L, 5);
    tt_angle_def d = tt_angle_def_default();
    d.a = tl_check_particle(L, w, 2);
    d.b = tl_check_particle(L, w, 3);
    d.c = tl_check_particle(L, w, 4);
    if (d.a.index == d.b.index || d.b.index == d.c.index || d.a.index == d.c.index)
        tl_argerror(L, 4, "an angle constraint needs three distinct particles");
    tl_readopts(L, 5, angle_opts, &d);
    bool has_min = tl_getopt(L, 5, "min");
    if (has_min) lua_pop(L, 1);
    bool has_max = tl_getopt(L, 5, "max");
    if (has_max) lua_pop(L, 1);
    if (has_min != has_max) tl_error(L, "give both 'min' and 'max', or neither (the angle now)");
    d.use_current = !has_min;
    push_constraint(L, w, tt_angle_create(w, &d));
    return 1;
}

static const tl_opt area_opts[] = {
    TL_OPT_NUM(tt_area_def, "area", area, &TL_R_COORD),
    TL_OPT_NUM(tt_area_def, "pressure", pressure, &R_POS),
    SOFT_OPTS(tt_area_def),
    TL_OPT_END,
};

/* w:area({p1, p2, p3, …} [, {area, pressure, stiffness, compliance}]) → constraint */
static int c_area(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_settop(L, 3);
    tt_area_def d = tt_area_def_default();
    d.particles = check_handle_list(L, w, 2, NULL, 3, 65536, &d.count);
    if (tl_getopt(L, 3, "area")) { /* an area given: that one, not the area now */
        lua_pop(L, 1);
        d.use_current = false;
    }
    tl_readopts(L, 3, area_opts, &d);
    push_constraint(L, w, tt_area_create(w, &d));
    return 1;
}

static const tl_opt collinear_opts[] = {SOFT_OPTS(tt_collinear_def), TL_OPT_END};

/* w:collinear(a, b, c [, {stiffness, compliance}]) → constraint */
static int c_collinear(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_settop(L, 5);
    tt_collinear_def d = tt_collinear_def_default();
    d.a = tl_check_particle(L, w, 2);
    d.b = tl_check_particle(L, w, 3);
    d.c = tl_check_particle(L, w, 4);
    if (d.a.index == d.b.index || d.b.index == d.c.index || d.a.index == d.c.index)
        tl_argerror(L, 4, "a collinear constraint needs three distinct particles");
    tl_readopts(L, 5, collinear_opts, &d);
    push_constraint(L, w, tt_collinear_create(w, &d));
    return 1;
}

static int c_remove_constraint(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tl_check_result(L, w, tt_constraint_destroy(w, check_constraint(L, w, 2)));
    return 0;
}

static int c_constraint_is_valid(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_pushboolean(L, tl_handle_is_live(L, w, 2, TT_KIND_CONSTRAINT));
    return 1;
}

static int c_constraint_kind(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_constraint_kind k;
    tl_check_result(L, w, tt_constraint_get_kind(w, check_constraint(L, w, 2), &k));
    lua_pushstring(L, kind_names[k - 1]);
    return 1;
}

/* w:constraint_error(c) → error now: m (distance, pin, bounds, collinear), rad (angle), m² (area) */
static int c_constraint_error(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    double e;
    tl_check_result(L, w, tt_constraint_get_error(w, check_constraint(L, w, 2), &e));
    lua_pushnumber(L, e);
    return 1;
}

static int c_constraint_particles(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_constraint c = check_constraint(L, w, 2);
    uint32_t n;
    tl_check_result(L, w, tt_constraint_get_particles(w, c, NULL, 0, &n));
    tt_particle *ps = tl_scratch(L, (size_t)n * sizeof *ps + 1);
    tl_check_result(L, w, tt_constraint_get_particles(w, c, ps, n, &n));
    lua_createtable(L, (int)n, 0);
    for (uint32_t i = 0; i < n; i++) {
        tl_push_particle(L, ps[i]);
        lua_rawseti(L, -2, (lua_Integer)i + 1);
    }
    return 1;
}

/* What set_constraint was given: −1 (and no anchor) for what it was not. */
typedef struct set_def {
    double stiffness, compliance, length, max_rate;
    tt_vec2 anchor;
} set_def;
static const tl_opt set_opts[] = {
    SOFT_OPTS(set_def),
    TL_OPT_NUM(set_def, "length", length, &TL_R_NONNEG),
    TL_OPT_XY(set_def, "anchor", anchor, &TL_R_COORD),
    TL_OPT_BYHAND("box"),
    TL_OPT_NUM(set_def, "max_rate", max_rate, &TL_R_NONNEG),
    TL_OPT_END,
};

/* w:set_constraint(c, {stiffness, compliance, length, anchor = {x, y}, box = {xmin, ymin, xmax, ymax}, max_rate})
 * — every field is checked (value and kind) before anything changes. */
static int c_set_constraint(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_constraint c = check_constraint(L, w, 2);
    lua_settop(L, 3);
    if (lua_type(L, 3) != LUA_TTABLE) tl_typeerror(L, 3, "table");
    set_def o = {-1, -1, -1, -1, {0, 0}};
    tl_readopts(L, 3, set_opts, &o);
    tt_constraint_kind kind;
    tt_constraint_get_kind(w, c, &kind);
    bool has_anchor = tl_getopt(L, 3, "anchor");
    if (has_anchor) lua_pop(L, 1);
    double box[4] = {0, 0, 0, 0};
    bool has_box = tl_getopt(L, 3, "box");
    if (has_box) {
        int t = lua_gettop(L);
        if (lua_type(L, t) != LUA_TTABLE) tl_error(L, "bad option 'box' (table {xmin, ymin, xmax, ymax} expected)");
        for (int i = 0; i < 4; i++) {
            lua_rawgeti(L, t, i + 1);
            if (!tl_tonumber_in(L, -1, &TL_R_COORD, &box[i]))
                tl_error(L, "bad option 'box' (table {xmin, ymin, xmax, ymax} expected)");
            lua_pop(L, 1);
        }
        lua_pop(L, 1);
        if (!(box[0] < box[2] && box[1] < box[3])) tl_error(L, "bad option 'box' (need xmin < xmax and ymin < ymax)");
    }
    if ((o.stiffness >= 0 || o.compliance >= 0) && kind == TT_CONSTRAINT_BOUNDS) tl_error(L, "bounds have no stiffness or compliance");
    if (o.length >= 0 && kind != TT_CONSTRAINT_DISTANCE) tl_error(L, "'length' is for distance constraints");
    if (has_anchor && kind != TT_CONSTRAINT_PIN) tl_error(L, "'anchor' is for pins");
    if (has_box && kind != TT_CONSTRAINT_BOUNDS) tl_error(L, "'box' is for bounds");
    if (o.max_rate >= 0 && kind != TT_CONSTRAINT_DISTANCE && kind != TT_CONSTRAINT_PIN)
        tl_error(L, "'max_rate' is for distance constraints and pins");
    if (o.max_rate >= 0) tl_check_result(L, w, tt_constraint_set_max_rate(w, c, o.max_rate));
    if (o.stiffness >= 0) tl_check_result(L, w, tt_constraint_set_stiffness(w, c, o.stiffness));
    if (o.compliance >= 0) tl_check_result(L, w, tt_constraint_set_compliance(w, c, o.compliance));
    if (o.length >= 0) tl_check_result(L, w, tt_distance_set_length(w, c, o.length));
    if (has_anchor) tl_check_result(L, w, tt_pin_set_anchor(w, c, o.anchor));
    if (has_box) tl_check_result(L, w, tt_bounds_set_box(w, c, (tt_vec2){box[0], box[1]}, (tt_vec2){box[2], box[3]}));
    return 0;
}

/* w:pin_anchor(c) → x, y */
static int c_pin_anchor(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_constraint c = check_constraint(L, w, 2);
    tt_vec2 a;
    tt_result r = tt_pin_get_anchor(w, c, &a);
    if (r != TT_OK) tl_argerror(L, 2, "a pin expected");
    lua_pushnumber(L, a.x);
    lua_pushnumber(L, a.y);
    return 2;
}

/* w:rest_length(c) → m (distance constraints) */
static int c_rest_length(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_constraint c = check_constraint(L, w, 2);
    double len;
    if (tt_distance_get_length(w, c, &len) != TT_OK) tl_argerror(L, 2, "a distance constraint expected");
    lua_pushnumber(L, len);
    return 1;
}

static int c_constraint_count(lua_State *L)
{
    lua_pushinteger(L, (lua_Integer)tt_world_constraint_count(tl_check_world(L, 1)));
    return 1;
}

/* w:constraint_lines([t]) → {x1, y1, x2, y2, …}, n — distance constraints, then pins to their anchors.
 * A given table is reused (its tail cleared), so drawing every frame allocates nothing. */
static int c_constraint_lines(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_settop(L, 2);
    bool reuse = tl_opttable(L, 2);
    uint32_t n = tt_world_read_constraint_lines(w, NULL, 0);
    double *xy = tl_scratch(L, (size_t)n * 4 * sizeof *xy + 1);
    n = tt_world_read_constraint_lines(w, xy, n);
    if (reuse) lua_pushvalue(L, 2);
    else lua_createtable(L, (int)(4 * n), 0);
    int t = lua_gettop(L);
    for (uint32_t i = 0; i < 4 * n; i++) {
        lua_pushnumber(L, xy[i]);
        lua_rawseti(L, t, (lua_Integer)i + 1);
    }
    for (lua_Integer i = (lua_Integer)4 * n + 1; reuse; i++) { /* clear the old tail */
        if (lua_rawgeti(L, t, i) == LUA_TNIL) { lua_pop(L, 1); break; }
        lua_pop(L, 1);
        lua_pushnil(L);
        lua_rawseti(L, t, i);
    }
    lua_pushinteger(L, (lua_Integer)n);
    return 2;
}

/* w:break_events() → {{constraint=, a=, b=, length=, strain=}, …} of the last step */
static int c_break_events(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    const tt_break_event *live;
    uint32_t n;
    tl_check_result(L, w, tt_world_get_break_events(w, &live, &n));
    /* the world's own array changes if Lua code steps the world while the tables are made */
    tt_break_event *ev = tl_scratch(L, (size_t)n * sizeof *ev + 1);
    if (n > 0) memcpy(ev, live, (size_t)n * sizeof *ev);
    lua_createtable(L, (int)n, 0);
    for (uint32_t i = 0; i < n; i++) {
        lua_createtable(L, 0, 5);
        tl_push_constraint(L, ev[i].constraint);
        lua_setfield(L, -2, "constraint");
        tl_push_particle(L, ev[i].a);
        lua_setfield(L, -2, "a");
        tl_push_particle(L, ev[i].b);
        lua_setfield(L, -2, "b");
        lua_pushnumber(L, ev[i].length);
        lua_setfield(L, -2, "length");
        lua_pushnumber(L, ev[i].strain);
        lua_setfield(L, -2, "strain");
        lua_rawseti(L, -2, (lua_Integer)i + 1);
    }
    return 1;
}

static const luaL_Reg constraint_methods[] = {
    {"distance", c_distance},
    {"pin", c_pin},
    {"bounds", c_bounds},
    {"angle", c_angle},
    {"area", c_area},
    {"collinear", c_collinear},
    {"remove_constraint", c_remove_constraint},
    {"constraint_is_valid", c_constraint_is_valid},
    {"constraint_kind", c_constraint_kind},
    {"constraint_error", c_constraint_error},
    {"constraint_particles", c_constraint_particles},
    {"set_constraint", c_set_constraint},
    {"pin_anchor", c_pin_anchor},
    {"rest_length", c_rest_length},
    {"constraint_count", c_constraint_count},
    {"constraint_lines", c_constraint_lines},
    {"break_events", c_break_events},
    {NULL, NULL}};

void tl_constraints_register(lua_State *L) { tl_world_add_methods(L, constraint_methods); }
