/* tether — Lua masks (class "tether.mask"): tether.mask.new, from_string,
 * load, circle, rect, polygon; the pixel methods (size, get, set, count,
 * clear, fill, invert, bounding_rect, centroid, copy, rotated, scaled,
 * to_string, save, fill_circle, fill_rect, fill_polygon), __gc and
 * __tostring. Overlaps and outlines are in lua_mask_ops.c, images in
 * lua_mask_draw.c. Mask pixel (0, 0) is the image's top-left; y goes down. */
#include "lua_mask.h"

#include <math.h>
#include <string.h>

static const tl_range R_FILL = { -1e6, 1e6, false };
static const tl_range R_RADIUS = { 0.0, 1e6, false };
static const tl_range R_ANGLE = { -1e6, 1e6, false };

tl_mask_ud *tl_check_mask_ud(lua_State *L, int arg)
{
    tl_mask_ud *u = luaL_testudata(L, arg, TL_MASK_CLASS);
    if (u == NULL || u->m == NULL) tl_typeerror(L, arg, TL_MASK_CLASS);
    return u;
}

tt_mask *tl_check_mask(lua_State *L, int arg)
{
    return tl_check_mask_ud(L, arg)->m;
}

/* Where a mask lies in its userdata: after the header, 16-byte aligned as Lua aligns the block. */
#define HEAD ((sizeof(tl_mask_ud) + 15) / 16 * 16)

tl_mask_ud *tl_push_mask(lua_State *L, int w, int h)
{
    size_t bytes = tt_mask_footprint(w, h);
    tl_mask_ud *u = lua_newuserdatauv(L, HEAD + bytes, 1);
    u->m = NULL;
    u->version = 0;
    u->painted = 0;
    luaL_setmetatable(L, TL_MASK_CLASS);
    u->m = tt_mask_init((unsigned char *)u + HEAD, bytes, w, h);
    if (!u->m) tl_mask_error(L);
    return u;
}

#define HOLDER_CLASS "tether.mask.holder"

/* __gc of a holder: the C mask it still holds when a call raised */
static int holder_gc(lua_State *L)
{
    tt_mask **slot = lua_touserdata(L, 1);
    tt_mask_destroy(*slot);
    *slot = NULL;
    return 0;
}

tt_mask **tl_new_mask_ud(lua_State *L)
{
    tt_mask **slot = lua_newuserdatauv(L, sizeof *slot, 0);
    *slot = NULL;
    luaL_setmetatable(L, HOLDER_CLASS);
    return slot;
}

tl_mask_ud *tl_mask_own(lua_State *L, tt_mask **slot, tt_mask *m)
{
    *slot = m;
    if (!m) tl_mask_error(L);
    int w, h;
    tt_mask_size(m, &w, &h);
    tl_mask_ud *u = tl_push_mask(L, w, h);
    tt_mask_copy_into(u->m, m);
    tt_mask_destroy(m);
    *slot = NULL;
    return u;
}

int tl_mask_error(lua_State *L)
{
    /* the Lua error names the Lua function; the C one's name would only confuse */
    const char *msg = tt_mask_last_error(), *colon = strstr(msg, ": ");
    if (strncmp(msg, "tt_mask_", 8) == 0 && colon) msg = colon + 2;
    return tl_error(L, "%s", msg);
}

int tl_check_offset(lua_State *L, int arg)
{
    return (int)tl_checkinteger(L, arg, -TT_MASK_MAX_OFFSET, TT_MASK_MAX_OFFSET);
}

void tl_mask_touch(lua_State *L, int arg)
{
    tl_check_mask_ud(L, arg)->version++;
}

/* Raises "fname: <tt_mask_last_error()>" unless r is TT_OK. */
static void check_r(lua_State *L, tt_result r)
{
    if (r != TT_OK) tl_mask_error(L);
}

static int m_tostring(lua_State *L)
{
    tl_mask_ud *u = tl_check_mask_ud(L, 1);
    int w, h;
    tt_mask_size(u->m, &w, &h);
    lua_pushfstring(L, TL_MASK_CLASS " (%dx%d): %p", w, h, (void *)u);
    return 1;
}

/* tether.mask.new(width, height [, filled]) */
static int f_new(lua_State *L)
{
    int w = (int)tl_checkinteger(L, 1, 1, TT_MASK_MAX_SIDE), h = (int)tl_checkinteger(L, 2, 1, TT_MASK_MAX_SIDE);
    bool filled = lua_isnoneornil(L, 3) ? false : tl_checkboolean(L, 3);
    tl_mask_ud *u = tl_push_mask(L, w, h);
    if (filled) tt_mask_fill(u->m);
    return 1;
}

/* Is c a set ('#', 'x', 'X', '1') or clear ('.', '0', '-', ' ') pixel? −1 if neither. */
static int pixel_char(char c)
{
    if (c == '#' || c == 'x' || c == 'X' || c == '1') return 1;
    if (c == '.' || c == '0' || c == '-' || c == ' ') return 0;
    return -1;
}

/* tether.mask.from_string("#..\n.#.") — rows top to bottom, '#' set, '.' clear */
static int f_from_string(lua_State *L)
{
    const char *s = tl_checkstring(L, 1);
    size_t n = lua_rawlen(L, 1);
    if (n && s[n - 1] == '\n') n--;
    size_t w = 0, h = 1, col = 0;
    for (size_t i = 0; i < n; i++) {
        if (s[i] == '\n') {
            if (h == 1) w = col;
            else if (col != w) tl_argerror(L, 1, "row %d has %d pixels, row 1 has %d", (int)h, (int)col, (int)w);
            h++;
            col = 0;
        } else if (pixel_char(s[i]) < 0) {
            tl_argerror(L, 1, "unexpected character '%c' in row %d (expected '#' or '.')", s[i], (int)h);
        } else {
            col++;
        }
    }
    if (h == 1) w = col;
    else if (col != w) tl_argerror(L, 1, "row %d has %d pixels, row 1 has %d", (int)h, (int)col, (int)w);
    if (w < 1 || w > TT_MASK_MAX_SIDE || h > TT_MASK_MAX_SIDE)
        tl_argerror(L, 1, "a mask of %d x %d pixels: each side must be 1…%d", (int)w, (int)h, TT_MASK_MAX_SIDE);
    tl_mask_ud *u = tl_push_mask(L, (int)w, (int)h);
    for (size_t i = 0, x = 0, y = 0; i < n; i++) {
        if (s[i] == '\n') { y++; x = 0; continue; }
        if (pixel_char(s[i])) tt_mask_set(u->m, (int)x, (int)y, true);
        x++;
    }
    return 1;
}

/* tether.mask.load(path [, threshold = 127]) — set where alpha > threshold */
static int f_load(lua_State *L)
{
    const char *path = tl_checkstring(L, 1);
    int t = (int)tl_optinteger(L, 2, 0, 254, 127);
    tt_mask **slot = tl_new_mask_ud(L);
    tl_mask_own(L, slot, tt_mask_load_png(path, t));
    return 1;
}

/* tether.mask.circle(radius) — a (2·ceil(r))² mask holding a disc of radius r at its centre */
static int f_circle(lua_State *L)
{
    double r = tl_checknumber(L, 1, &(tl_range){ 0.5, TT_MASK_MAX_SIDE / 2, false });
    int side = 2 * (int)ceil(r);
    tl_mask_ud *u = tl_push_mask(L, side, side);
    check_r(L, tt_mask_fill_circle(u->m, side / 2.0, side / 2.0, r, true));
    return 1;
}

/* tether.mask.rect(width, height) — every pixel set */
static int f_rect(lua_State *L)
{
    int w = (int)tl_checkinteger(L, 1, 1, TT_MASK_MAX_SIDE), h = (int)tl_checkinteger(L, 2, 1, TT_MASK_MAX_SIDE);
    tt_mask_fill(tl_push_mask(L, w, h)->m);
    return 1;
}

/* The points {x1, y1, …} at arg (3…1e6 of them, |v| ≤ 1e6) in a Lua-owned buffer. */
static tt_vec2 *check_points(lua_State *L, int arg, uint32_t *count)
{
    if (lua_type(L, arg) != LUA_TTABLE) tl_typeerror(L, arg, "table of coordinates {x1, y1, x2, y2, ...}");
    lua_Integer n = (lua_Integer)lua_rawlen(L, arg);
    if (n % 2 != 0) tl_argerror(L, arg, "an even number of coordinates expected, got %d", (int)n);
    if (n / 2 < 3 || n / 2 > 1000000) tl_argerror(L, arg, "between 3 and 1000000 points expected, got %d", (int)(n / 2));
    tt_vec2 *p = lua_newuserdatauv(L, (size_t)(n / 2) * sizeof *p, 0);
    for (lua_Integer k = 1; k <= n; k++) {
        double v;
        lua_rawgeti(L, arg, k);
        if (!tl_tonumber_in(L, -1, &R_FILL, &v)) tl_argerror(L, arg, "%s at index %d", lua_tostring(L, -1), (int)k);
        lua_pop(L, 1);
        if (k % 2) p[(k - 1) / 2].x = v; else p[(k - 1) / 2].y = v;
    }
    *count = (uint32_t)(n / 2);
    return p;
}

/* tether.mask.polygon({x1, y1, …}) — a mask from (0, 0) to the points' largest x, y, the polygon filled */
static int f_polygon(lua_State *L)
{
    uint32_t n;
    tt_vec2 *p = check_points(L, 1, &n);
    double mx = 0, my = 0;
    for (uint32_t i = 0; i < n; i++) {
        if (p[i].x > mx) mx = p[i].x;
        if (p[i].y > my) my = p[i].y;
    }
    int w = (int)ceil(mx), h = (int)ceil(my);
    if (w < 1 || h < 1 || w > TT_MASK_MAX_SIDE || h > TT_MASK_MAX_SIDE)
        tl_argerror(L, 1, "the points span %d x %d pixels: each side must be 1…%d", w, h, TT_MASK_MAX_SIDE);
    tl_mask_ud *u = tl_push_mask(L, w, h);
    check_r(L, tt_mask_fill_polygon(u->m, p, n, true));
    return 1;
}

/* m:size() → width, height */
static int m_size(lua_State *L)
{
    int w, h;
    tt_mask_size(tl_check_mask(L, 1), &w, &h);
    lua_pushinteger(L, w);
    lua_pushinteger(L, h);
    return 2;
}

/* The pixel (x, y) at args 2, 3, inside m. */
static void check_xy(lua_State *L, tt_mask *m, int *x, int *y)
{
    int w, h;
    tt_mask_size(m, &w, &h);
    *x = (int)tl_checkinteger(L, 2, 0, w - 1);
    *y = (int)tl_checkinteger(L, 3, 0, h - 1);
}

/* m:get(x, y) → boolean */
static int m_get(lua_State *L)
{
    tt_mask *m = tl_check_mask(L, 1);
    int x, y;
    check_xy(L, m, &x, &y);
    lua_pushboolean(L, tt_mask_get(m, x, y) == 1);
    return 1;
}

/* m:set(x, y [, value = true]) */
static int m_set(lua_State *L)
{
    tt_mask *m = tl_check_mask(L, 1);
    int x, y;
    check_xy(L, m, &x, &y);
    bool v = lua_isnoneornil(L, 4) ? true : tl_checkboolean(L, 4);
    tt_mask_set(m, x, y, v);
    tl_mask_touch(L, 1);
    return 0;
}

static int m_count(lua_State *L)
{
    lua_pushinteger(L, (lua_Integer)tt_mask_count(tl_check_mask(L, 1)));
    return 1;
}

static int m_clear(lua_State *L)  { tt_mask_clear(tl_check_mask(L, 1));  tl_mask_touch(L, 1); return 0; }
static int m_fill(lua_State *L)   { tt_mask_fill(tl_check_mask(L, 1));   tl_mask_touch(L, 1); return 0; }
static int m_invert(lua_State *L) { tt_mask_invert(tl_check_mask(L, 1)); tl_mask_touch(L, 1); return 0; }

/* m:bounding_rect() → x, y, width, height (0, 0, 0, 0 when empty) */
static int m_bounding_rect(lua_State *L)
{
    tt_mask_rect r;
    tt_mask_bounding_rect(tl_check_mask(L, 1), &r);
    lua_pushinteger(L, r.x);
    lua_pushinteger(L, r.y);
    lua_pushinteger(L, r.w);
    lua_pushinteger(L, r.h);
    return 4;
}

/* m:centroid() → x, y (mean pixel indices; 0, 0 when empty) */
static int m_centroid(lua_State *L)
{
    tt_vec2 c;
    tt_mask_centroid(tl_check_mask(L, 1), &c);
    lua_pushnumber(L, c.x);
    lua_pushnumber(L, c.y);
    return 2;
}

static int m_copy(lua_State *L)
{
    tt_mask *m = tl_check_mask(L, 1);
    int w, h;
    tt_mask_size(m, &w, &h);
    tt_mask_copy_into(tl_push_mask(L, w, h)->m, m);
    return 1;
}

/* m:rotated(angle) — radians, counter-clockwise as seen on screen */
static int m_rotated(lua_State *L)
{
    tt_mask *m = tl_check_mask(L, 1);
    double a = tl_checknumber(L, 2, &R_ANGLE);
    tt_mask **slot = tl_new_mask_ud(L);
    tl_mask_own(L, slot, tt_mask_rotated(m, a));
    return 1;
}

/* m:scaled(width, height) */
static int m_scaled(lua_State *L)
{
    tt_mask *m = tl_check_mask(L, 1);
    int w = (int)tl_checkinteger(L, 2, 1, TT_MASK_MAX_SIDE), h = (int)tl_checkinteger(L, 3, 1, TT_MASK_MAX_SIDE);
    tt_mask **slot = tl_new_mask_ud(L);
    tl_mask_own(L, slot, tt_mask_scaled(m, w, h));
    return 1;
}

/* m:to_string() → rows of '#' (set) and '.' (clear) joined by "\n" */
static int m_to_string(lua_State *L)
{
    tt_mask *m = tl_check_mask(L, 1);
    int w, h;
    tt_mask_size(m, &w, &h);
    luaL_Buffer b;
    luaL_buffinit(L, &b);
    for (int y = 0; y < h; y++) {
        if (y) luaL_addchar(&b, '\n');
        for (int x = 0; x < w; x++) luaL_addchar(&b, tt_mask_get(m, x, y) ? '#' : '.');
    }
    luaL_pushresult(&b);
    return 1;
}

/* m:save(path) — a grey+alpha PNG, set pixels opaque white */
static int m_save(lua_State *L)
{
    tt_mask *m = tl_check_mask(L, 1);
    check_r(L, tt_mask_save_png(m, tl_checkstring(L, 2)));
    return 0;
}

/* m:fill_circle(cx, cy, r [, value = true]) — pixel units, centres inside */
static int m_fill_circle(lua_State *L)
{
    tt_mask *m = tl_check_mask(L, 1);
    double cx = tl_checknumber(L, 2, &R_FILL), cy = tl_checknumber(L, 3, &R_FILL), r = tl_checknumber(L, 4, &R_RADIUS);
    bool v = lua_isnoneornil(L, 5) ? true : tl_checkboolean(L, 5);
    check_r(L, tt_mask_fill_circle(m, cx, cy, r, v));
    tl_mask_touch(L, 1);
    return 0;
}

/* m:fill_rect(x, y, width, height [, value = true]) */
static int m_fill_rect(lua_State *L)
{
    tt_mask *m = tl_check_mask(L, 1);
    int x = tl_check_offset(L, 2), y = tl_check_offset(L, 3);
    int w = (int)tl_checkinteger(L, 4, 0, TT_MASK_MAX_OFFSET), h = (int)tl_checkinteger(L, 5, 0, TT_MASK_MAX_OFFSET);
    bool v = lua_isnoneornil(L, 6) ? true : tl_checkboolean(L, 6);
    check_r(L, tt_mask_fill_rect(m, x, y, w, h, v));
    tl_mask_touch(L, 1);
    return 0;
}

/* m:fill_polygon({x1, y1, …} [, value = true]) */
static int m_fill_polygon(lua_State *L)
{
    tt_mask *m = tl_check_mask(L, 1);
    lua_settop(L, 3);
    uint32_t n;
    tt_vec2 *p = check_points(L, 2, &n);
    bool v = lua_isnoneornil(L, 3) ? true : tl_checkboolean(L, 3);
    check_r(L, tt_mask_fill_polygon(m, p, n, v));
    tl_mask_touch(L, 1);
    return 0;
}

static const luaL_Reg mask_methods[] = {
    { "size", m_size },         { "get", m_get },           { "set", m_set },
    { "count", m_count },       { "clear", m_clear },       { "fill", m_fill },
    { "invert", m_invert },     { "bounding_rect", m_bounding_rect }, { "centroid", m_centroid },
    { "copy", m_copy },         { "rotated", m_rotated },   { "scaled", m_scaled },
    { "to_string", m_to_string }, { "save", m_save },       { "fill_circle", m_fill_circle },
    { "fill_rect", m_fill_rect }, { "fill_polygon", m_fill_polygon }, { NULL, NULL }
};
static const luaL_Reg mask_meta[] = { { "__tostring", m_tostring }, { NULL, NULL } };
static const luaL_Reg mask_funcs[] = { { "new", f_new },       { "from_string", f_from_string }, { "load", f_load },
                                       { "circle", f_circle }, { "rect", f_rect },               { "polygon", f_polygon },
                                       { NULL, NULL } };

void tl_mask_register(lua_State *L)
{
    if (luaL_newmetatable(L, TL_MASK_CLASS)) {
        tl_setfuncs(L, mask_meta, "");
        lua_createtable(L, 0, 48);
        tl_setfuncs(L, mask_methods, "");
        lua_setfield(L, -2, "__index");
    }
    lua_pop(L, 1);
    if (luaL_newmetatable(L, HOLDER_CLASS)) {
        lua_pushcfunction(L, holder_gc);
        lua_setfield(L, -2, "__gc");
    }
    lua_pop(L, 1);
    lua_createtable(L, 0, 8);
    tl_setfuncs(L, mask_funcs, "tether.mask.");
    lua_setfield(L, -2, "mask");
}

void tl_mask_add_methods(lua_State *L, const luaL_Reg *methods)
{
    luaL_getmetatable(L, TL_MASK_CLASS);
    lua_getfield(L, -1, "__index");
    tl_setfuncs(L, methods, "");
    lua_pop(L, 2);
}

void tl_mask_add_funcs(lua_State *L, const luaL_Reg *funcs)
{
    lua_getfield(L, -1, "mask");
    tl_setfuncs(L, funcs, "tether.mask.");
    lua_pop(L, 1);
}
