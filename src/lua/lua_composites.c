/* tether — Lua bindings of composites (rope, cloth, ragdoll, soft body,
 * lattice): world methods added to the world class by tl_composites_register
 * (called from luaopen_tether). Handles are integers (tt_composite_to_u64;
 * the constraints of one, tt_constraint_to_u64). Every argument is checked
 * here first, so the core never sees a bad value. */
#include "lua_common.h"

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

/* The options every composite takes (tt_composite_common). */
#define COMMON_OPTS(T)                                                        \
    TL_OPT_NUM(T, "mass", common.mass, &TL_R_MASS),                           \
    TL_OPT_NUM(T, "radius", common.radius, &TL_R_NONNEG),                     \
    TL_OPT_NUM(T, "stiffness", common.stiffness, &TL_R_UNIT),                    \
    TL_OPT_NUM(T, "compliance", common.compliance, &TL_R_NONNEG),             \
    TL_OPT_FLAG(T, "collide", common.collide)

static const tl_opt rope_opts[] = {
    COMMON_OPTS(tt_rope_def),
    TL_OPT_XY(tt_rope_def, "start", start, &TL_R_COORD),
    TL_OPT_XY(tt_rope_def, "finish", finish, &TL_R_COORD),
    TL_OPT_UINT(tt_rope_def, "segments", segments, 1, 100000),
    TL_OPT_FLAG(tt_rope_def, "pin_start", pin_start),
    TL_OPT_FLAG(tt_rope_def, "pin_finish", pin_finish),
    TL_OPT_FLAG(tt_rope_def, "slack", slack),
    TL_OPT_NUM(tt_rope_def, "break_strain", break_strain, &TL_R_NONNEG),
    TL_OPT_END,
};

/* w:rope({start = {x, y}, finish = {x, y}, segments, pin_start, pin_finish, slack, break_strain, …common}) → composite */
static int c_rope(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_settop(L, 2);
    tt_rope_def d = tt_rope_def_default();
    tl_readopts(L, 2, rope_opts, &d);
    push_composite(L, w, tt_rope_create(w, &d));
    return 1;
}

static const tl_opt cloth_opts[] = {
    COMMON_OPTS(tt_cloth_def),
    TL_OPT_XY(tt_cloth_def, "origin", origin, &TL_R_COORD),
    TL_OPT_NUM(tt_cloth_def, "width", width, &R_POS),
    TL_OPT_NUM(tt_cloth_def, "height", height, &R_POS),
    TL_OPT_UINT(tt_cloth_def, "columns", columns, 2, 4096),
    TL_OPT_UINT(tt_cloth_def, "rows", rows, 2, 4096),
    TL_OPT_NUM(tt_cloth_def, "shear_stiffness", shear_stiffness, &TL_R_UNIT),
    TL_OPT_NUM(tt_cloth_def, "bend_stiffness", bend_stiffness, &TL_R_UNIT),
    TL_OPT_FLAG(tt_cloth_def, "pin_top_corners", pin_top_corners),
    TL_OPT_FLAG(tt_cloth_def, "pin_top_row", pin_top_row),
    TL_OPT_NUM(tt_cloth_def, "break_strain", break_strain, &TL_R_NONNEG),
    TL_OPT_FLAG(tt_cloth_def, "long_range", long_range),
    TL_OPT_END,
};

/* w:cloth({origin = {x, y}, width, height, columns, rows, shear_stiffness, bend_stiffness,
 *          pin_top_corners, pin_top_row, break_strain, …common}) → composite */
static int c_cloth(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_settop(L, 2);
    tt_cloth_def d = tt_cloth_def_default();
    tl_readopts(L, 2, cloth_opts, &d);
    push_composite(L, w, tt_cloth_create(w, &d));
    return 1;
}

static const tl_opt ragdoll_opts[] = {
    COMMON_OPTS(tt_ragdoll_def),
    TL_OPT_XY(tt_ragdoll_def, "position", position, &TL_R_COORD),
    TL_OPT_NUM(tt_ragdoll_def, "height", height, &R_POS),
    TL_OPT_FLAG(tt_ragdoll_def, "limits", limits),
    TL_OPT_END,
};

/* w:ragdoll({position = {x, y}, height, limits, …common}) → composite */
static int c_ragdoll(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_settop(L, 2);
    tt_ragdoll_def d = tt_ragdoll_def_default();
    tl_readopts(L, 2, ragdoll_opts, &d);
    push_composite(L, w, tt_ragdoll_create(w, &d));
    return 1;
}

static const tl_opt soft_body_opts[] = {
    COMMON_OPTS(tt_soft_body_def),
    TL_OPT_XY(tt_soft_body_def, "center", center, &TL_R_COORD),
    TL_OPT_NUM(tt_soft_body_def, "ring_radius", ring_radius, &R_POS),
    TL_OPT_UINT(tt_soft_body_def, "segments", segments, 3, 65536),
    TL_OPT_NUM(tt_soft_body_def, "pressure", pressure, &R_POS),
    TL_OPT_NUM(tt_soft_body_def, "area_stiffness", area_stiffness, &TL_R_UNIT),
    TL_OPT_NUM(tt_soft_body_def, "area_compliance", area_compliance, &TL_R_NONNEG),
    TL_OPT_END,
};

/* w:soft_body({center = {x, y}, size (ring radius), segments, pressure, area_stiffness, area_compliance, …common}) */
static int c_soft_body(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_settop(L, 2);
    tt_soft_body_def d = tt_soft_body_def_default();
    tl_readopts(L, 2, soft_body_opts, &d);
    push_composite(L, w, tt_soft_body_create(w, &d));
    return 1;
}

static const tl_opt lattice_opts[] = {
    COMMON_OPTS(tt_lattice_def),
    TL_OPT_XY(tt_lattice_def, "center", center, &TL_R_COORD),
    TL_OPT_NUM(tt_lattice_def, "width", width, &R_POS),
    TL_OPT_NUM(tt_lattice_def, "height", height, &R_POS),
    TL_OPT_NUM(tt_lattice_def, "angle", angle, &TL_R_COORD),
    TL_OPT_UINT(tt_lattice_def, "columns", columns, 2, 1024),
    TL_OPT_UINT(tt_lattice_def, "rows", rows, 2, 1024),
    TL_OPT_BYHAND("points"),
    TL_OPT_END,
};

/* w:lattice({center = {x, y}, width, height, angle, columns, rows, …common})
 * or w:lattice({points = {x1, y1, x2, y2, …}, …common}) → composite */
static int c_lattice(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_settop(L, 2);
    tt_lattice_def d = tt_lattice_def_default();
    tl_readopts(L, 2, lattice_opts, &d);
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
