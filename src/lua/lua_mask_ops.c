/* tether — Lua mask methods between masks and on their shape: draw,
 * erase, the overlap family (overlap, overlap_area, overlap_mask,
 * overlap_normal), convolve, components, outline, polylines; and the world
 * method w:mask_chains, which turns a mask's outline into chain shapes. */
#include "lua_mask.h"

#include <stdlib.h>

static const tl_range R_TOL = { 0.0, 1e6, false };
static const tl_range R_PIXEL = { 0.0, TT_MAX_VALUE / TT_MASK_MAX_SIDE, true };

static void check_r(lua_State *L, tt_result r)
{
    if (r != TT_OK) tl_mask_error(L);
}

/* The other mask and the offset at args 2, 3, 4. */
static tt_mask *other_at(lua_State *L, int *dx, int *dy)
{
    tt_mask *b = tl_check_mask(L, 2);
    *dx = tl_check_offset(L, 3);
    *dy = tl_check_offset(L, 4);
    return b;
}

/* m:draw(other, dx, dy) — ORs other in with its (0, 0) on m's (dx, dy) */
static int m_draw(lua_State *L)
{
    tt_mask *a = tl_check_mask(L, 1);
    int dx, dy;
    tt_mask *b = other_at(L, &dx, &dy);
    check_r(L, tt_mask_draw(a, b, dx, dy));
    tl_mask_touch(L, 1);
    return 0;
}

/* m:erase(other, dx, dy) — clears what other, so placed, covers */
static int m_erase(lua_State *L)
{
    tt_mask *a = tl_check_mask(L, 1);
    int dx, dy;
    tt_mask *b = other_at(L, &dx, &dy);
    check_r(L, tt_mask_erase(a, b, dx, dy));
    tl_mask_touch(L, 1);
    return 0;
}

/* m:overlap(other, dx, dy) → x, y of the first overlapping pixel (m's frame), or nil */
static int m_overlap(lua_State *L)
{
    tt_mask *a = tl_check_mask(L, 1);
    int dx, dy, x, y;
    tt_mask *b = other_at(L, &dx, &dy);
    if (!tt_mask_overlap(a, b, dx, dy, &x, &y)) {
        lua_pushnil(L);
        return 1;
    }
    lua_pushinteger(L, x);
    lua_pushinteger(L, y);
    return 2;
}

/* m:overlap_area(other, dx, dy) → pixels */
static int m_overlap_area(lua_State *L)
{
    tt_mask *a = tl_check_mask(L, 1);
    int dx, dy;
    tt_mask *b = other_at(L, &dx, &dy);
    lua_pushinteger(L, (lua_Integer)tt_mask_overlap_area(a, b, dx, dy));
    return 1;
}

/* m:overlap_mask(other, dx, dy) → a mask of m's size */
static int m_overlap_mask(lua_State *L)
{
    tt_mask *a = tl_check_mask(L, 1);
    int dx, dy;
    tt_mask *b = other_at(L, &dx, &dy);
    int w, h;
    tt_mask_size(a, &w, &h);
    tl_mask_ud *u = tl_push_mask(L, w, h); /* inside the userdata: no allocation of its own, no finalizer */
    tt_mask_overlap_mask_into(u->m, a, b, dx, dy);
    return 1;
}

/* m:overlap_normal(other, dx, dy) → nx, ny: unit direction (image frame, y down) to push other out; 0, 0 when none */
static int m_overlap_normal(lua_State *L)
{
    tt_mask *a = tl_check_mask(L, 1);
    int dx, dy;
    tt_mask *b = other_at(L, &dx, &dy);
    tt_vec2 n;
    check_r(L, tt_mask_overlap_normal(a, b, dx, dy, &n));
    lua_pushnumber(L, n.x);
    lua_pushnumber(L, n.y);
    return 2;
}

/* m:convolve(other) → mask where other's bottom-right pixel may sit and overlap m */
static int m_convolve(lua_State *L)
{
    tt_mask *a = tl_check_mask(L, 1), *b = tl_check_mask(L, 2);
    tt_mask **slot = tl_new_mask_ud(L);
    tl_mask_own(L, slot, tt_mask_convolve(a, b));
    return 1;
}

/* m:components() → number of 8-connected components */
static int m_components(lua_State *L)
{
    int64_t n = tt_mask_component_count(tl_check_mask(L, 1));
    if (n < 0) tl_mask_error(L);
    lua_pushinteger(L, (lua_Integer)n);
    return 1;
}

/* m:component([x, y]) → the component at pixel (x, y), or the largest without them */
static int m_component(lua_State *L)
{
    tt_mask *m = tl_check_mask(L, 1);
    int x = -1, y = -1;
    if (!lua_isnoneornil(L, 2) || !lua_isnoneornil(L, 3)) {
        int w, h;
        tt_mask_size(m, &w, &h);
        x = (int)tl_checkinteger(L, 2, 0, w - 1);
        y = (int)tl_checkinteger(L, 3, 0, h - 1);
    }
    tt_mask **slot = tl_new_mask_ud(L);
    tl_mask_own(L, slot, tt_mask_component(m, x, y));
    return 1;
}

/* m:component_rects() → {{x, y, w, h}, …} in the order of each component's first pixel */
static int m_component_rects(lua_State *L)
{
    tt_mask *m = tl_check_mask(L, 1);
    uint32_t n;
    check_r(L, tt_mask_component_rects(m, NULL, 0, &n));
    tt_mask_rect *r = lua_newuserdatauv(L, (n ? n : 1) * sizeof *r, 0);
    check_r(L, tt_mask_component_rects(m, r, n, &n));
    lua_createtable(L, (int)n, 0);
    for (uint32_t i = 0; i < n; i++) {
        lua_createtable(L, 4, 0);
        int v[4] = { r[i].x, r[i].y, r[i].w, r[i].h };
        for (int k = 0; k < 4; k++) {
            lua_pushinteger(L, v[k]);
            lua_rawseti(L, -2, k + 1);
        }
        lua_rawseti(L, -2, (lua_Integer)i + 1);
    }
    return 1;
}

/* m:outline() → {x1, y1, x2, y2, …}: the first component's border pixels in order */
static int m_outline(lua_State *L)
{
    tt_mask *m = tl_check_mask(L, 1);
    uint32_t n;
    check_r(L, tt_mask_outline(m, NULL, 0, &n));
    int *xy = lua_newuserdatauv(L, 2 * (size_t)(n ? n : 1) * sizeof *xy, 0);
    check_r(L, tt_mask_outline(m, xy, n, &n));
    lua_createtable(L, (int)(2 * n), 0);
    for (uint32_t i = 0; i < 2 * n; i++) {
        lua_pushinteger(L, xy[i]);
        lua_rawseti(L, -2, (lua_Integer)i + 1);
    }
    return 1;
}

/* The polylines of a call, freed by the collector if the call raises while
 * copying them into tables (an allocation error), or by the call itself. */
typedef struct lines_guard {
    tt_mask_polyline *lines;
    uint32_t n;
} lines_guard;

#define LINES_CLASS "tether.mask.polylines"

static int lines_gc(lua_State *L)
{
    lines_guard *g = lua_touserdata(L, 1);
    tt_mask_polylines_free(g->lines, g->n);
    g->lines = NULL;
    g->n = 0;
    return 0;
}

/* m:polylines([tolerance = 0.5]) → {{x1, y1, …}, …}: closed outlines in pixel corner coordinates */
static int m_polylines(lua_State *L)
{
    tt_mask *m = tl_check_mask(L, 1);
    double tol = tl_optnumber(L, 2, &R_TOL, 0.5);
    lines_guard *g = lua_newuserdatauv(L, sizeof *g, 0);
    g->lines = NULL;
    g->n = 0;
    luaL_setmetatable(L, LINES_CLASS);
    check_r(L, tt_mask_polylines(m, tol, &g->lines, &g->n));
    lua_createtable(L, (int)g->n, 0);
    for (uint32_t i = 0; i < g->n; i++) {
        const tt_mask_polyline *l = &g->lines[i];
        lua_createtable(L, (int)(2 * l->count), 0);
        for (uint32_t k = 0; k < l->count; k++) {
            lua_pushnumber(L, l->points[k].x);
            lua_rawseti(L, -2, 2 * (lua_Integer)k + 1);
            lua_pushnumber(L, l->points[k].y);
            lua_rawseti(L, -2, 2 * (lua_Integer)k + 2);
        }
        lua_rawseti(L, -2, (lua_Integer)i + 1);
    }
    tt_mask_polylines_free(g->lines, g->n);
    g->lines = NULL;
    g->n = 0;
    return 1;
}

typedef struct chain_def {
    tt_mask_place place;
    double tolerance;
    tt_shape_def shape;
} chain_def;
static const tl_opt chain_opts[] = {
    TL_OPT_XY(chain_def, "origin", place.origin, &TL_R_COORD),
    TL_OPT_NUM(chain_def, "pixel", place.pixel, &R_PIXEL),
    TL_OPT_NUM(chain_def, "tolerance", tolerance, &R_TOL),
    TL_SURFACE_OPTS(chain_def, shape.),
    TL_FILTER_OPTS(chain_def, shape.),
    TL_OPT_FLAG(chain_def, "sensor", shape.sensor),
    TL_OPT_END,
};

/* w:mask_chains(m [, {origin = {x, y} (world position of pixel (0, 0)'s top-left corner), pixel = 1 (m per pixel),
 * tolerance = 0.5 (pixels), restitution =, friction =, category =, mask =, sensor =}]) → {shape, …}:
 * the mask's outline as static looped chains (image rows go down, world y up) */
static int w_mask_chains(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_mask *m = tl_check_mask(L, 2);
    lua_settop(L, 3);
    chain_def o = {tt_mask_place_default(), 0.5, tt_shape_def_default()};
    tl_readopts(L, 3, chain_opts, &o);
    const tt_mask_place p = o.place;
    const double tol = o.tolerance;
    const tt_shape_def d = o.shape;
    uint32_t n;
    tt_mask_polyline *lines;
    check_r(L, tt_mask_polylines(m, tol, &lines, &n)); /* to know how many: the chains call makes them again */
    tt_mask_polylines_free(lines, n);
    tt_shape *s = lua_newuserdatauv(L, (n ? n : 1) * sizeof *s, 0);
    check_r(L, tt_mask_to_chains(m, w, &p, tol, &d, s, n, &n));
    lua_createtable(L, (int)n, 0);
    for (uint32_t i = 0; i < n; i++) {
        lua_pushinteger(L, (lua_Integer)tt_shape_to_u64(s[i]));
        lua_rawseti(L, -2, (lua_Integer)i + 1);
    }
    return 1;
}

static const luaL_Reg ops_methods[] = {
    { "draw", m_draw },           { "erase", m_erase },           { "overlap", m_overlap },
    { "overlap_area", m_overlap_area }, { "overlap_mask", m_overlap_mask }, { "overlap_normal", m_overlap_normal },
    { "convolve", m_convolve },   { "components", m_components }, { "component", m_component },
    { "component_rects", m_component_rects }, { "outline", m_outline }, { "polylines", m_polylines },
    { NULL, NULL }
};
static const luaL_Reg world_methods[] = { { "mask_chains", w_mask_chains }, { NULL, NULL } };

void tl_mask_ops_register(lua_State *L)
{
    if (luaL_newmetatable(L, LINES_CLASS)) {
        lua_pushcfunction(L, lines_gc);
        lua_setfield(L, -2, "__gc");
    }
    lua_pop(L, 1);
    tl_mask_add_methods(L, ops_methods);
    tl_world_add_methods(L, world_methods);
}
