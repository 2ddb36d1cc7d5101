/* tether — Lua bindings of composites (rope, cloth, ragdoll, soft body,
 * lattice): world methods added to the world class by tl_composites_register
 * (called from luaopen_tether). Handles are integers (tt_composite_to_u64;
 * the constraints of one, tt_constraint_to_u64). Every argument is checked
 * here first, so the core never sees a bad value. */
#include "lua_common.h"

static const tl_range R_UNIT = {0.0, 1.0, false};
static const tl_range R_POS = {0.0, TT_MAX_VALUE, true};

static tt_composite check_composite(lua_State *L, tt_world *w, int arg)
{
    return tt_composite_from_u64(tl_checkhandle(L, w, arg, TT_KIND_COMPOSITE));
}

static void push_composite(lua_State *L, tt_world *w, tt_composite c)
{
    if (c.gen == 0) tl_check_result(L, w, TT_EINVAL);
    tl_push_composite(L, c);
}

#define COMMON_KEYS "mass", "radius", "stiffness", "compliance", "collide"

static void common_opts(lua_State *L, int arg, tt_composite_common *k)
{
    k->mass = tl_optfield_number(L, arg, "mass", &TL_R_MASS, k->mass);
    k->radius = tl_optfield_number(L, arg, "radius", &TL_R_NONNEG, k->radius);
    k->stiffness = tl_optfield_number(L, arg, "stiffness", &R_UNIT, k->stiffness);
    k->compliance = tl_optfield_number(L, arg, "compliance", &TL_R_NONNEG, k->compliance);
    k->collide = tl_optfield_boolean(L, arg, "collide", k->collide);
}

static const char *const rope_opts[] = {COMMON_KEYS, "start", "finish", "segments", "pin_start", "pin_finish", "slack", "break_strain", NULL};

/* w:rope({start = {x, y}, finish = {x, y}, segments, pin_start, pin_finish, slack, break_strain, …common}) → composite */
static int c_rope(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_settop(L, 2);
    tt_rope_def d = tt_rope_def_default();
    tl_checkopts(L, 2, rope_opts);
    common_opts(L, 2, &d.common);
    d.start = tl_optfield_vec2(L, 2, "start", &TL_R_COORD, d.start);
    d.finish = tl_optfield_vec2(L, 2, "finish", &TL_R_COORD, d.finish);
    d.segments = (uint32_t)tl_optfield_integer(L, 2, "segments", 1, 100000, d.segments);
    d.pin_start = tl_optfield_boolean(L, 2, "pin_start", d.pin_start);
    d.pin_finish = tl_optfield_boolean(L, 2, "pin_finish", d.pin_finish);
    d.slack = tl_optfield_boolean(L, 2, "slack", d.slack);
    d.break_strain = tl_optfield_number(L, 2, "break_strain", &TL_R_NONNEG, d.break_strain);
    push_composite(L, w, tt_rope_create(w, &d));
    return 1;
}

static const char *const cloth_opts[] = {COMMON_KEYS, "origin", "width", "height", "columns", "rows", "shear_stiffness",
                                         "bend_stiffness", "pin_top_corners", "pin_top_row", "break_strain", NULL};

/* w:cloth({origin = {x, y}, width, height, columns, rows, shear_stiffness, bend_stiffness,
 *          pin_top_corners, pin_top_row, break_strain, …common}) → composite */
static int c_cloth(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_settop(L, 2);
    tt_cloth_def d = tt_cloth_def_default();
    tl_checkopts(L, 2, cloth_opts);
    common_opts(L, 2, &d.common);
    d.origin = tl_optfield_vec2(L, 2, "origin", &TL_R_COORD, d.origin);
    d.width = tl_optfield_number(L, 2, "width", &R_POS, d.width);
    d.height = tl_optfield_number(L, 2, "height", &R_POS, d.height);
    d.columns = (uint32_t)tl_optfield_integer(L, 2, "columns", 2, 4096, d.columns);
    d.rows = (uint32_t)tl_optfield_integer(L, 2, "rows", 2, 4096, d.rows);
    d.shear_stiffness = tl_optfield_number(L, 2, "shear_stiffness", &R_UNIT, d.shear_stiffness);
    d.bend_stiffness = tl_optfield_number(L, 2, "bend_stiffness", &R_UNIT, d.bend_stiffness);
    d.pin_top_corners = tl_optfield_boolean(L, 2, "pin_top_corners", d.pin_top_corners);
    d.pin_top_row = tl_optfield_boolean(L, 2, "pin_top_row", d.pin_top_row);
    d.break_strain = tl_optfield_number(L, 2, "break_strain", &TL_R_NONNEG, d.break_strain);
    push_composite(L, w, tt_cloth_create(w, &d));
    return 1;
}

static const char *const ragdoll_opts[] = {COMMON_KEYS, "position", "height", "limits", NULL};

/* w:ragdoll({position = {x, y}, height, limits, …common}) → composite */
static int c_ragdoll(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_settop(L, 2);
    tt_ragdoll_def d = tt_ragdoll_def_default();
    tl_checkopts(L, 2, ragdoll_opts);
    common_opts(L, 2, &d.common);
    d.position = tl_optfield_vec2(L, 2, "position", &TL_R_COORD, d.position);
    d.height = tl_optfield_number(L, 2, "height", &R_POS, d.height);
    d.limits = tl_optfield_boolean(L, 2, "limits", d.limits);
    push_composite(L, w, tt_ragdoll_create(w, &d));
    return 1;
}

static const char *const soft_body_opts[] = {COMMON_KEYS, "center", "ring_radius", "segments", "pressure", "area_stiffness",
                                             "area_compliance", NULL};

/* w:soft_body({center = {x, y}, size (ring radius), segments, pressure, area_stiffness, area_compliance, …common}) */
static int c_soft_body(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_settop(L, 2);
    tt_soft_body_def d = tt_soft_body_def_default();
    tl_checkopts(L, 2, soft_body_opts);
    common_opts(L, 2, &d.common);
    d.center = tl_optfield_vec2(L, 2, "center", &TL_R_COORD, d.center);
    d.ring_radius = tl_optfield_number(L, 2, "ring_radius", &R_POS, d.ring_radius);
    d.segments = (uint32_t)tl_optfield_integer(L, 2, "segments", 3, 65536, d.segments);
    d.pressure = tl_optfield_number(L, 2, "pressure", &R_POS, d.pressure);
    d.area_stiffness = tl_optfield_number(L, 2, "area_stiffness", &R_UNIT, d.area_stiffness);
    d.area_compliance = tl_optfield_number(L, 2, "area_compliance", &TL_R_NONNEG, d.area_compliance);
    push_composite(L, w, tt_soft_body_create(w, &d));
    return 1;
}

static const char *const lattice_opts[] = {COMMON_KEYS, "center", "width", "height", "angle", "columns", "rows", "points", NULL};

/* w:lattice({center = {x, y}, width, height, angle, columns, rows, …common})
 * or w:lattice({points = {x1, y1, x2, y2, …}, …common}) → composite */
static int c_lattice(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_settop(L, 2);
    tt_lattice_def d = tt_lattice_def_default();
    tl_checkopts(L, 2, lattice_opts);
    common_opts(L, 2, &d.common);
    d.center = tl_optfield_vec2(L, 2, "center", &TL_R_COORD, d.center);
    d.width = tl_optfield_number(L, 2, "width", &R_POS, d.width);
    d.height = tl_optfield_number(L, 2, "height", &R_POS, d.height);
    d.angle = tl_optfield_number(L, 2, "angle", &TL_R_COORD, d.angle);
    d.columns = (uint32_t)tl_optfield_integer(L, 2, "columns", 2, 1024, d.columns);
    d.rows = (uint32_t)tl_optfield_integer(L, 2, "rows", 2, 1024, d.rows);
    tt_vec2 pts[64];
    if (tl_getopt(L, 2, "points")) {
        int t = lua_gettop(L);
        lua_Integer n = lua_type(L, t) == LUA_TTABLE ? (lua_Integer)lua_rawlen(L, t) : -1;
        if (n < 6 || n > 128 || n % 2)
            tl_error(L, "bad option 'points' (table {x1, y1, x2, y2, …} of 3 to 64 points expected)");
        for (lua_Integer i = 0; i < n; i++) {
            double v;
            lua_rawgeti(L, t, i + 1);
            if (!tl_tonumber_in(L, -1, &TL_R_COORD, &v))
                tl_error(L, "bad option 'points' (index %d: %s)", (int)i + 1, lua_tostring(L, -1));
            lua_pop(L, 1);
            if (i % 2) pts[i / 2].y = v;
            else pts[i / 2].x = v;
        }
        d.points = pts;
        d.point_count = (uint32_t)(n / 2);
    }
    push_composite(L, w, tt_lattice_create(w, &d));
    return 1;
}

static int c_remove_composite(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tl_check_result(L, w, tt_composite_destroy(w, check_composite(L, w, 2)));
    return 0;
}

static int c_composite_is_valid(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_pushboolean(L, tl_handle_is_live(L, w, 2, TT_KIND_COMPOSITE));
    return 1;
}

/* w:composite_particles(h) → {p1, p2, …} in creation order */
static int c_composite_particles(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_composite c = check_composite(L, w, 2);
    uint32_t n;
    tt_composite_get_particles(w, c, NULL, 0, &n);
    tt_particle *ps = tl_scratch(L, (size_t)n * sizeof *ps + 1);
    tt_composite_get_particles(w, c, ps, n, &n);
    lua_createtable(L, (int)n, 0);
    for (uint32_t i = 0; i < n; i++) {
        tl_push_particle(L, ps[i]);
        lua_rawseti(L, -2, (lua_Integer)i + 1);
    }
    return 1;
}

/* w:composite_constraints(h) → {c1, c2, …} in creation order (torn ones are stale) */
static int c_composite_constraints(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_composite c = check_composite(L, w, 2);
    uint32_t n;
    tt_composite_get_constraints(w, c, NULL, 0, &n);
    tt_constraint *cs = tl_scratch(L, (size_t)n * sizeof *cs + 1);
    tt_composite_get_constraints(w, c, cs, n, &n);
    lua_createtable(L, (int)n, 0);
    for (uint32_t i = 0; i < n; i++) {
        tl_push_constraint(L, cs[i]);
        lua_rawseti(L, -2, (lua_Integer)i + 1);
    }
    return 1;
}

/* w:composite_center(h) → x, y (centre of mass) */
static int c_composite_center(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_vec2 c;
    tl_check_result(L, w, tt_composite_get_center(w, check_composite(L, w, 2), &c));
    lua_pushnumber(L, c.x);
    lua_pushnumber(L, c.y);
    return 2;
}

/* w:composite_angle(h) → rad, the rotation from the rest shape */
static int c_composite_angle(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    double a;
    tl_check_result(L, w, tt_composite_get_angle(w, check_composite(L, w, 2), &a));
    lua_pushnumber(L, a);
    return 1;
}

static int c_composite_count(lua_State *L)
{
    lua_pushinteger(L, (lua_Integer)tt_world_composite_count(tl_check_world(L, 1)));
    return 1;
}

static const luaL_Reg composite_methods[] = {
    {"rope", c_rope},
    {"cloth", c_cloth},
    {"ragdoll", c_ragdoll},
    {"soft_body", c_soft_body},
    {"lattice", c_lattice},
    {"remove_composite", c_remove_composite},
    {"composite_is_valid", c_composite_is_valid},
    {"composite_particles", c_composite_particles},
    {"composite_constraints", c_composite_constraints},
    {"composite_center", c_composite_center},
    {"composite_angle", c_composite_angle},
    {"composite_count", c_composite_count},
    {NULL, NULL}};

void tl_composites_register(lua_State *L) { tl_world_add_methods(L, composite_methods); }
