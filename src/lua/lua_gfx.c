/* tether — Lua drawing API: tether.gfx (circle, line, polygon, text, colour,
 * camera, HUD) and world:draw(), for the script's tether.draw(g) callback.
 *
 * The functions append to the canvas the runner hands over for the frame
 * (tl_render_begin … tl_render_end, lua_render.c); outside a frame they raise
 * "nothing to draw on". Colours are numbers in [0, 1]; positions are world
 * units through the camera, or pixels (origin top-left) after
 * g.layer("screen"). Images are in lua_image.c. */
#include "lua_render.h"

#include <stdio.h>

static const tl_range R_POS = { 0.0, TT_MAX_VALUE, false };
static const tl_range R_ZOOM = { 0.0, 1e9, true };

/* --- tether.gfx ------------------------------------------------------------- */

/* g.color(r, g, b [, a]) sets the colour; g.color() → r, g, b, a */
static int g_color(lua_State *L)
{
    tt_canvas *c = tl_render_canvas(L);
    if (lua_isnoneornil(L, 1)) {
        tt_color k = tt_canvas_get_color(c);
        lua_pushnumber(L, k.r / 255.0);
        lua_pushnumber(L, k.g / 255.0);
        lua_pushnumber(L, k.b / 255.0);
        lua_pushnumber(L, k.a / 255.0);
        return 4;
    }
    tt_color k = { tl_byte_of(tl_checknumber(L, 1, &TL_R_UNIT)), tl_byte_of(tl_checknumber(L, 2, &TL_R_UNIT)),
                   tl_byte_of(tl_checknumber(L, 3, &TL_R_UNIT)), tl_byte_of(tl_optnumber(L, 4, &TL_R_UNIT, 1.0)) };
    tt_canvas_set_color(c, k);
    return 0;
}

/* g.clear(r, g, b) — starts the frame over on this background colour */
static int g_clear(lua_State *L)
{
    tt_canvas *c = tl_render_canvas(L);
    tt_color k = { tl_byte_of(tl_checknumber(L, 1, &TL_R_UNIT)), tl_byte_of(tl_checknumber(L, 2, &TL_R_UNIT)),
                   tl_byte_of(tl_checknumber(L, 3, &TL_R_UNIT)), 255 };
    tt_canvas_clear(c, k);
    return 0;
}

static const char *const modes[] = { "fill", "line", NULL };

/* g.circle(x, y, r [, mode]) */
static int g_circle(lua_State *L)
{
    tt_canvas *c = tl_render_canvas(L);
    double x = tl_checknumber(L, 1, &TL_R_COORD), y = tl_checknumber(L, 2, &TL_R_COORD);
    double rad = tl_checknumber(L, 3, &R_POS);
    int mode = tl_checkoption(L, 4, "mode", "fill", modes);
    tl_check_canvas_result(L, c, tt_canvas_circle(c, (tt_vec2){ x, y }, rad, mode == 0));
    return 0;
}

/* g.line(x1, y1, x2, y2, …) — a polyline through 2 or more points */
static int g_line(lua_State *L)
{
    tt_canvas *c = tl_render_canvas(L);
    int n = lua_gettop(L);
    if (n < 4 || n % 2) tl_error(L, "need an even number (at least 4) of coordinates, got %d", n);
    tt_vec2 prev = { tl_checknumber(L, 1, &TL_R_COORD), tl_checknumber(L, 2, &TL_R_COORD) };
    for (int i = 3; i <= n; i += 2) {
        tt_vec2 p = { tl_checknumber(L, i, &TL_R_COORD), tl_checknumber(L, i + 1, &TL_R_COORD) };
        tl_check_canvas_result(L, c, tt_canvas_line(c, prev, p));
        prev = p;
    }
    return 0;
}

/* g.polygon({x1, y1, x2, y2, …} [, mode]) — 3 or more points */
static int g_polygon(lua_State *L)
{
    tt_canvas *c = tl_render_canvas(L);
    if (lua_type(L, 1) != LUA_TTABLE) tl_typeerror(L, 1, "table of coordinates {x1, y1, x2, y2, ...}");
    int mode = tl_checkoption(L, 2, "mode", "fill", modes);
    lua_Integer len = (lua_Integer)lua_rawlen(L, 1);
    if (len < 6 || len % 2 || len > 2000000)
        tl_argerror(L, 1, "an even number (6 to 2000000) of coordinates expected, got %d", (int)len);
    tt_vec2 *p = lua_newuserdatauv(L, (size_t)(len / 2) * sizeof *p, 0); /* freed by the GC, even on error */
    for (lua_Integer i = 1; i <= len; i++) {
        double v;
        lua_rawgeti(L, 1, i);
        if (!tl_tonumber_in(L, -1, &TL_R_COORD, &v))
            tl_argerror(L, 1, "%s at index %d", lua_tostring(L, -1), (int)i);
        lua_pop(L, 1);
        if (i % 2) p[(i - 1) / 2].x = v; else p[(i - 1) / 2].y = v;
    }
    tl_check_canvas_result(L, c, tt_canvas_polygon(c, p, (int)(len / 2), mode == 0));
    return 0;
}

/* g.text(x, y, text [, scale]) — top-left corner at (x, y); scale: font pixel size in px */
static int g_text(lua_State *L)
{
    tt_canvas *c = tl_render_canvas(L);
    double x = tl_checknumber(L, 1, &TL_R_COORD), y = tl_checknumber(L, 2, &TL_R_COORD);
    const char *s = tl_checkstring(L, 3);
    int scale = (int)tl_optinteger(L, 4, 1, 64, 1);
    tl_check_canvas_result(L, c, tt_canvas_text(c, (tt_vec2){ x, y }, s, scale));
    return 0;
}

/* g.line_width(px) */
static int g_line_width(lua_State *L)
{
    tt_canvas *c = tl_render_canvas(L);
    static const tl_range r = { 0.1, 1000.0, false };
    tl_check_canvas_result(L, c, tt_canvas_set_line_width(c, tl_checknumber(L, 1, &r)));
    return 0;
}

static const char *const layers[] = { "world", "screen", NULL };

/* g.layer("world" | "screen") */
static int g_layer(lua_State *L)
{
    tt_canvas *c = tl_render_canvas(L);
    tl_check_canvas_result(L, c, tt_canvas_set_layer(c, (tt_layer)tl_checkoption(L, 1, "layer", NULL, layers)));
    return 0;
}

/* g.camera(x, y, zoom) sets; g.camera() → x, y, zoom (pixels per world unit) */
static int g_camera(lua_State *L)
{
    tt_canvas *c = tl_render_canvas(L);
    if (lua_isnoneornil(L, 1)) {
        tt_vec2 ctr;
        double z;
        tt_canvas_get_camera(c, &ctr, &z);
        lua_pushnumber(L, ctr.x);
        lua_pushnumber(L, ctr.y);
        lua_pushnumber(L, z);
        return 3;
    }
    double x = tl_checknumber(L, 1, &TL_R_COORD), y = tl_checknumber(L, 2, &TL_R_COORD), z = tl_checknumber(L, 3, &R_ZOOM);
    tl_check_canvas_result(L, c, tt_canvas_set_camera(c, (tt_vec2){ x, y }, z));
    return 0;
}

/* g.fit(x1, y1, x2, y2 [, margin_px]) — camera so the rectangle fills the frame */
static int g_fit(lua_State *L)
{
    tt_canvas *c = tl_render_canvas(L);
    double x1 = tl_checknumber(L, 1, &TL_R_COORD), y1 = tl_checknumber(L, 2, &TL_R_COORD);
    double x2 = tl_checknumber(L, 3, &TL_R_COORD), y2 = tl_checknumber(L, 4, &TL_R_COORD);
    double m = tl_optnumber(L, 5, &R_POS, 10.0);
    if (!(x2 > x1 && y2 > y1)) tl_error(L, "the rectangle is empty: need x1 < x2 and y1 < y2");
    tl_check_canvas_result(L, c, tt_canvas_fit(c, (tt_vec2){ x1, y1 }, (tt_vec2){ x2, y2 }, m));
    return 0;
}

/* g.size() → width, height in pixels */
static int g_size(lua_State *L)
{
    int w, h;
    tt_canvas_size(tl_render_canvas(L), &w, &h);
    lua_pushinteger(L, w);
    lua_pushinteger(L, h);
    return 2;
}

/* g.to_world(px, py) → x, y;  g.to_screen(x, y) → px, py */
static int g_to_world(lua_State *L)
{
    tt_canvas *c = tl_render_canvas(L);
    tt_vec2 p = tt_canvas_to_world(c, (tt_vec2){ tl_checknumber(L, 1, &TL_R_COORD), tl_checknumber(L, 2, &TL_R_COORD) });
    lua_pushnumber(L, p.x);
    lua_pushnumber(L, p.y);
    return 2;
}

static int g_to_screen(lua_State *L)
{
    tt_canvas *c = tl_render_canvas(L);
    tt_vec2 p = tt_canvas_to_pixels(c, (tt_vec2){ tl_checknumber(L, 1, &TL_R_COORD), tl_checknumber(L, 2, &TL_R_COORD) });
    lua_pushnumber(L, p.x);
    lua_pushnumber(L, p.y);
    return 2;
}

/* g.hud(world [, text]) — time, step time, particles, springs, iterations, error (+ text) */
static int g_hud(lua_State *L)
{
    tt_canvas *c = tl_render_canvas(L);
    tt_world *w = tl_check_world(L, 1);
    const char *extra = tl_optstring(L, 2, NULL);
    tt_stats st;
    tt_world_get_stats(w, &st);
    char buf[512];
    snprintf(buf, sizeof buf,
             "t %.2f s   step %.3f ms\nparticles %u   springs %u\niterations %u   error %.1e%s%s", st.time, st.step_ms,
             st.particles, st.springs, st.iterations, st.max_error, extra ? "\n" : "", extra ? extra : "");
    lua_getfield(L, LUA_REGISTRYINDEX, "tether.render.hud_y");
    double y = lua_isnumber(L, -1) ? lua_tonumber(L, -1) : 6.0;
    lua_pop(L, 1);
    tl_render_hud_panel(c, buf, &y);
    lua_pushnumber(L, y);
    lua_setfield(L, LUA_REGISTRYINDEX, "tether.render.hud_y");
    return 0;
}

/* --- world:draw([opts]) ------------------------------------------------------ */

static const tl_range R_PX = { 0.0, 1000.0, false };
static const tl_opt draw_opts[] = {
    TL_OPT_FLAG(tt_debug_draw, "particles", particles),
    TL_OPT_FLAG(tt_debug_draw, "springs", springs),
    TL_OPT_FLAG(tt_debug_draw, "constraints", constraints),
    TL_OPT_FLAG(tt_debug_draw, "shapes", shapes),
    TL_OPT_BYHAND("color"), /* colours: opt_color */
    TL_OPT_BYHAND("pinned"),
    TL_OPT_NUM(tt_debug_draw, "min_radius", min_radius_px, &R_PX),
    TL_OPT_BYHAND("alpha"), /* its default is the frame's */
    TL_OPT_END,
};

static tt_color opt_color(lua_State *L, int arg, const char *key, tt_color def)
{
    if (!tl_getopt(L, arg, key)) return def;
    double v[4] = { 0, 0, 0, 1 };
    int n = lua_istable(L, -1) ? (int)lua_rawlen(L, -1) : 0;
    if (n < 3 || n > 4) tl_error(L, "bad option '%s' ({r, g, b [, a]} with numbers in [0, 1] expected)", key);
    for (int i = 0; i < n; i++) {
        lua_rawgeti(L, -1 - 0, i + 1);
        if (!tl_tonumber_in(L, -1, &TL_R_UNIT, &v[i])) tl_error(L, "bad option '%s' (%s at index %d)", key, lua_tostring(L, -1), i + 1);
        lua_pop(L, 1);
    }
    lua_pop(L, 1);
    return (tt_color){ tl_byte_of(v[0]), tl_byte_of(v[1]), tl_byte_of(v[2]), tl_byte_of(v[3]) };
}

static int w_draw(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_debug_draw d = tt_debug_draw_default();
    tl_readopts(L, 2, draw_opts, &d);
    tt_canvas *c = tl_render_canvas(L);
    d.particle = opt_color(L, 2, "color", d.particle);
    d.pinned = opt_color(L, 2, "pinned", d.pinned);
    d.alpha = tl_optfield_number(L, 2, "alpha", &TL_R_UNIT, tl_render_alpha(L));
    tl_render_interpolate(L, w, d.alpha);
    tl_check_canvas_result(L, c, tt_canvas_draw_world(c, w, &d));
    tl_render_remember(L, 1, c);
    return 0;
}

/* w:set_interpolation(on): keep where every particle was as each step began
 * (tt_world_set_interpolation); w:draw at alpha < 1 turns it on by itself */
static int w_set_interpolation(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tl_check_result(L, w, tt_world_set_interpolation(w, tl_checkboolean(L, 2)));
    return 0;
}

static int w_interpolation(lua_State *L)
{
    lua_pushboolean(L, tt_world_get_interpolation(tl_check_world(L, 1)));
    return 1;
}

/* --- registration ----------------------------------------------------------- */

static const luaL_Reg gfx_funcs[] = {
    { "color", g_color },         { "clear", g_clear },   { "circle", g_circle },   { "line", g_line },
    { "polygon", g_polygon },     { "text", g_text },     { "line_width", g_line_width },
    { "layer", g_layer },         { "camera", g_camera }, { "fit", g_fit },         { "size", g_size },
    { "to_world", g_to_world },   { "to_screen", g_to_screen }, { NULL, NULL }
};
/* the ones whose argument 1 is a world, pinned while they run (lua_common.h) */
static const luaL_Reg gfx_world_funcs[] = { { "hud", g_hud }, { NULL, NULL } };

static const luaL_Reg world_draw[] = { { "draw", w_draw }, { "set_interpolation", w_set_interpolation },
                                        { "interpolation", w_interpolation }, { NULL, NULL } };

void tl_render_register(lua_State *L)
{
    tl_render_track_worlds(L);

    lua_createtable(L, 0, (int)(sizeof gfx_funcs / sizeof gfx_funcs[0]));
    tl_setfuncs(L, gfx_funcs, "tether.gfx.");
    tl_setfuncs_pinned(L, gfx_world_funcs, "tether.gfx.");
    tl_image_register(L); /* the image class, g.new_image and g.image */
    lua_setfield(L, -2, "gfx");
    tl_world_add_methods(L, world_draw);
}
