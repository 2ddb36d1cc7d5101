/* tether — Lua drawing API: tether.gfx (circle, line, polygon, text, colour,
 * camera, HUD) and world:draw(), for the script's tether.draw(g) callback.
 *
 * The functions append to the canvas the runner hands over for the frame
 * (tl_render_begin … tl_render_end); outside a frame they raise "nothing to
 * draw on". Colours are numbers in [0, 1]; positions are world units through
 * the camera, or pixels (origin top-left) after g.layer("screen"). */
#include "lua_render.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define STATE_KEY "tether.render"        /* registry: the tl_render userdata */
#define DRAWN_KEY "tether.render.drawn"  /* registry: worlds drawn this frame, 1…n */
#define DRAG_KEY "tether.render.drag"    /* registry: the world being dragged */
#define IMAGES_KEY "tether.render.images" /* registry: image → true for those drawn this frame (kept until rendered) */
#define WORLDS_KEY "tether.render.worlds" /* registry: every world made, 1…n, weak values */

typedef struct drawn {
    tt_vec2 center;
    double zoom;
    int width, height;
} drawn;

typedef struct tl_render {
    tt_canvas *canvas; /* NULL outside a frame */
    drawn *drawn;      /* camera of each world drawn this frame (worlds in DRAWN_KEY) */
    size_t ndrawn, cap;
    drawn drag_cam;    /* camera when the drag started */
    lua_Integer nworlds;   /* worlds made so far (keys of WORLDS_KEY) */
    tt_vec2 auto_lo, auto_hi; /* what the automatic view has shown so far */
    bool auto_set;
} tl_render;

static int state_gc(lua_State *L)
{
    tl_render *r = lua_touserdata(L, 1);
    free(r->drawn);
    r->drawn = NULL;
    return 0;
}

static tl_render *state(lua_State *L)
{
    tl_render *r;
    if (lua_getfield(L, LUA_REGISTRYINDEX, STATE_KEY) == LUA_TUSERDATA) {
        r = lua_touserdata(L, -1);
        lua_pop(L, 1);
        return r;
    }
    lua_pop(L, 1);
    r = lua_newuserdatauv(L, sizeof *r, 0);
    memset(r, 0, sizeof *r);
    lua_createtable(L, 0, 1);
    lua_pushcfunction(L, state_gc);
    lua_setfield(L, -2, "__gc");
    lua_setmetatable(L, -2);
    lua_setfield(L, LUA_REGISTRYINDEX, STATE_KEY);
    return r;
}

static tt_canvas *canvas(lua_State *L)
{
    tl_render *r = state(L);
    if (!r->canvas)
        tl_error(L, "nothing to draw on: drawing works inside tether.draw(g), called by the tether runner "
                    "(a window, or --headless --out DIR)");
    return r->canvas;
}

static const tl_range R_UNIT = { 0.0, 1.0, false };
static const tl_range R_POS = { 0.0, TT_MAX_VALUE, false };
static const tl_range R_ZOOM = { 0.0, 1e9, true };

static uint8_t byte_of(double v) { return (uint8_t)(v * 255.0 + 0.5); }

static void check_canvas_result(lua_State *L, tt_canvas *c, tt_result r)
{
    if (r != TT_OK) tl_error(L, "%s", tt_canvas_error(c));
}

/* --- tether.gfx ------------------------------------------------------------- */

/* g.color(r, g, b [, a]) sets the colour; g.color() → r, g, b, a */
static int g_color(lua_State *L)
{
    tt_canvas *c = canvas(L);
    if (lua_isnoneornil(L, 1)) {
        tt_color k = tt_canvas_get_color(c);
        lua_pushnumber(L, k.r / 255.0);
        lua_pushnumber(L, k.g / 255.0);
        lua_pushnumber(L, k.b / 255.0);
        lua_pushnumber(L, k.a / 255.0);
        return 4;
    }
    tt_color k = { byte_of(tl_checknumber(L, 1, &R_UNIT)), byte_of(tl_checknumber(L, 2, &R_UNIT)),
                   byte_of(tl_checknumber(L, 3, &R_UNIT)), byte_of(tl_optnumber(L, 4, &R_UNIT, 1.0)) };
    tt_canvas_set_color(c, k);
    return 0;
}

/* g.clear(r, g, b) — starts the frame over on this background colour */
static int g_clear(lua_State *L)
{
    tt_canvas *c = canvas(L);
    tt_color k = { byte_of(tl_checknumber(L, 1, &R_UNIT)), byte_of(tl_checknumber(L, 2, &R_UNIT)),
                   byte_of(tl_checknumber(L, 3, &R_UNIT)), 255 };
    tt_canvas_clear(c, k);
    return 0;
}

static const char *const modes[] = { "fill", "line", NULL };

/* g.circle(x, y, r [, mode]) */
static int g_circle(lua_State *L)
{
    tt_canvas *c = canvas(L);
    double x = tl_checknumber(L, 1, &TL_R_COORD), y = tl_checknumber(L, 2, &TL_R_COORD);
    double rad = tl_checknumber(L, 3, &R_POS);
    int mode = tl_checkoption(L, 4, "mode", "fill", modes);
    check_canvas_result(L, c, tt_canvas_circle(c, (tt_vec2){ x, y }, rad, mode == 0));
    return 0;
}

/* g.line(x1, y1, x2, y2, …) — a polyline through 2 or more points */
static int g_line(lua_State *L)
{
    tt_canvas *c = canvas(L);
    int n = lua_gettop(L);
    if (n < 4 || n % 2) tl_error(L, "need an even number (at least 4) of coordinates, got %d", n);
    tt_vec2 prev = { tl_checknumber(L, 1, &TL_R_COORD), tl_checknumber(L, 2, &TL_R_COORD) };
    for (int i = 3; i <= n; i += 2) {
        tt_vec2 p = { tl_checknumber(L, i, &TL_R_COORD), tl_checknumber(L, i + 1, &TL_R_COORD) };
        check_canvas_result(L, c, tt_canvas_line(c, prev, p));
        prev = p;
    }
    return 0;
}

/* g.polygon({x1, y1, x2, y2, …} [, mode]) — 3 or more points */
static int g_polygon(lua_State *L)
{
    tt_canvas *c = canvas(L);
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
    check_canvas_result(L, c, tt_canvas_polygon(c, p, (int)(len / 2), mode == 0));
    return 0;
}

/* g.text(x, y, text [, scale]) — top-left corner at (x, y); scale: font pixel size in px */
static int g_text(lua_State *L)
{
    tt_canvas *c = canvas(L);
    double x = tl_checknumber(L, 1, &TL_R_COORD), y = tl_checknumber(L, 2, &TL_R_COORD);
    const char *s = tl_checkstring(L, 3);
    int scale = (int)tl_optinteger(L, 4, 1, 64, 1);
    check_canvas_result(L, c, tt_canvas_text(c, (tt_vec2){ x, y }, s, scale));
    return 0;
}

/* g.line_width(px) */
static int g_line_width(lua_State *L)
{
    tt_canvas *c = canvas(L);
    static const tl_range r = { 0.1, 1000.0, false };
    check_canvas_result(L, c, tt_canvas_set_line_width(c, tl_checknumber(L, 1, &r)));
    return 0;
}

static const char *const layers[] = { "world", "screen", NULL };

/* g.layer("world" | "screen") */
static int g_layer(lua_State *L)
{
    tt_canvas *c = canvas(L);
    check_canvas_result(L, c, tt_canvas_set_layer(c, (tt_layer)tl_checkoption(L, 1, "layer", NULL, layers)));
    return 0;
}

/* g.camera(x, y, zoom) sets; g.camera() → x, y, zoom (pixels per world unit) */
static int g_camera(lua_State *L)
{
    tt_canvas *c = canvas(L);
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
    check_canvas_result(L, c, tt_canvas_set_camera(c, (tt_vec2){ x, y }, z));
    return 0;
}

/* g.fit(x1, y1, x2, y2 [, margin_px]) — camera so the rectangle fills the frame */
static int g_fit(lua_State *L)
{
    tt_canvas *c = canvas(L);
    double x1 = tl_checknumber(L, 1, &TL_R_COORD), y1 = tl_checknumber(L, 2, &TL_R_COORD);
    double x2 = tl_checknumber(L, 3, &TL_R_COORD), y2 = tl_checknumber(L, 4, &TL_R_COORD);
    double m = tl_optnumber(L, 5, &R_POS, 10.0);
    if (!(x2 > x1 && y2 > y1)) tl_error(L, "the rectangle is empty: need x1 < x2 and y1 < y2");
    check_canvas_result(L, c, tt_canvas_fit(c, (tt_vec2){ x1, y1 }, (tt_vec2){ x2, y2 }, m));
    return 0;
}

/* g.size() → width, height in pixels */
static int g_size(lua_State *L)
{
    int w, h;
    tt_canvas_size(canvas(L), &w, &h);
    lua_pushinteger(L, w);
    lua_pushinteger(L, h);
    return 2;
}

/* g.to_world(px, py) → x, y;  g.to_screen(x, y) → px, py */
static int g_to_world(lua_State *L)
{
    tt_canvas *c = canvas(L);
    tt_vec2 p = tt_canvas_to_world(c, (tt_vec2){ tl_checknumber(L, 1, &TL_R_COORD), tl_checknumber(L, 2, &TL_R_COORD) });
    lua_pushnumber(L, p.x);
    lua_pushnumber(L, p.y);
    return 2;
}

static int g_to_screen(lua_State *L)
{
    tt_canvas *c = canvas(L);
    tt_vec2 p = tt_canvas_to_pixels(c, (tt_vec2){ tl_checknumber(L, 1, &TL_R_COORD), tl_checknumber(L, 2, &TL_R_COORD) });
    lua_pushnumber(L, p.x);
    lua_pushnumber(L, p.y);
    return 2;
}

/* The HUD panel: lines of text on a dark box at the top-left (or below the last panel). */
static void hud_panel(tt_canvas *c, const char *text, double *y)
{
    int h;
    tt_canvas_size(c, NULL, &h);
    int scale = h >= 500 ? 2 : 1, tw, th;
    tt_canvas_text_size(text, scale, &tw, &th);
    tt_layer layer = tt_canvas_get_layer(c);
    tt_color k = tt_canvas_get_color(c);
    tt_canvas_set_layer(c, TT_LAYER_SCREEN);
    double pad = 3.0 * scale, x = 6.0;
    tt_vec2 box[4] = { { x, *y }, { x + tw + 2 * pad, *y }, { x + tw + 2 * pad, *y + th + 2 * pad }, { x, *y + th + 2 * pad } };
    tt_canvas_set_color(c, (tt_color){ 0, 0, 0, 150 });
    tt_canvas_polygon(c, box, 4, true);
    tt_canvas_set_color(c, (tt_color){ 230, 230, 230, 255 });
    tt_canvas_text(c, (tt_vec2){ x + pad, *y + pad }, text, scale);
    *y += th + 2 * pad + 4;
    tt_canvas_set_layer(c, layer);
    tt_canvas_set_color(c, k);
}

/* g.hud(world [, text]) — time, step time, particles, springs, iterations, error (+ text) */
static int g_hud(lua_State *L)
{
    tt_canvas *c = canvas(L);
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
    hud_panel(c, buf, &y);
    lua_pushnumber(L, y);
    lua_setfield(L, LUA_REGISTRYINDEX, "tether.render.hud_y");
    return 0;
}

/* --- world:draw([opts]) ------------------------------------------------------ */

static const char *const draw_opts[] = { "particles", "springs", "constraints", "shapes", "color", "pinned", "min_radius", NULL };

static tt_color opt_color(lua_State *L, int arg, const char *key, tt_color def)
{
    if (!tl_getopt(L, arg, key)) return def;
    double v[4] = { 0, 0, 0, 1 };
    int n = lua_istable(L, -1) ? (int)lua_rawlen(L, -1) : 0;
    if (n < 3 || n > 4) tl_error(L, "bad option '%s' ({r, g, b [, a]} with numbers in [0, 1] expected)", key);
    for (int i = 0; i < n; i++) {
        lua_rawgeti(L, -1 - 0, i + 1);
        if (!tl_tonumber_in(L, -1, &R_UNIT, &v[i])) tl_error(L, "bad option '%s' (%s at index %d)", key, lua_tostring(L, -1), i + 1);
        lua_pop(L, 1);
    }
    lua_pop(L, 1);
    return (tt_color){ byte_of(v[0]), byte_of(v[1]), byte_of(v[2]), byte_of(v[3]) };
}

/* Remembers the world at idx and the camera it is drawn with, for mouse picking. */
static void remember(lua_State *L, int idx, tt_canvas *c)
{
    tl_render *r = state(L);
    if (r->ndrawn == r->cap) {
        size_t nc = r->cap ? r->cap * 2 : 8;
        drawn *p = realloc(r->drawn, nc * sizeof *p);
        if (!p) return; /* not pickable this frame: harmless */
        r->drawn = p;
        r->cap = nc;
    }
    tt_canvas_get_camera(c, &r->drawn[r->ndrawn].center, &r->drawn[r->ndrawn].zoom);
    tt_canvas_size(c, &r->drawn[r->ndrawn].width, &r->drawn[r->ndrawn].height);
    r->ndrawn++;
    lua_getfield(L, LUA_REGISTRYINDEX, DRAWN_KEY);
    lua_pushvalue(L, idx);
    lua_rawseti(L, -2, (lua_Integer)r->ndrawn);
    lua_pop(L, 1);
}

static int w_draw(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tl_checkopts(L, 2, draw_opts);
    tt_canvas *c = canvas(L);
    tt_debug_draw d = tt_debug_draw_default();
    d.particles = tl_optfield_boolean(L, 2, "particles", d.particles);
    d.springs = tl_optfield_boolean(L, 2, "springs", d.springs);
    d.constraints = tl_optfield_boolean(L, 2, "constraints", d.constraints);
    d.shapes = tl_optfield_boolean(L, 2, "shapes", d.shapes);
    static const tl_range r_px = { 0.0, 1000.0, false };
    d.min_radius_px = tl_optfield_number(L, 2, "min_radius", &r_px, d.min_radius_px);
    d.particle = opt_color(L, 2, "color", d.particle);
    d.pinned = opt_color(L, 2, "pinned", d.pinned);
    check_canvas_result(L, c, tt_canvas_draw_world(c, w, &d));
    remember(L, 1, c);
    return 0;
}

/* --- images ------------------------------------------------------------------ */

/* A closed image drawn in the frame being made keeps its pixels until the
 * frame is rendered (tl_render_done): the canvas points at them. */
typedef struct li_image {
    tt_image *img; /* NULL once freed */
    bool closed;   /* by __close: no more use from Lua, whether freed yet or not */
} li_image;

/* The image userdata at arg, closed or not. */
static li_image *check_image_ud(lua_State *L, int arg)
{
    li_image *u = luaL_testudata(L, arg, TL_IMAGE_CLASS);
    if (u == NULL) tl_typeerror(L, arg, TL_IMAGE_CLASS);
    return u;
}

static tt_image *check_image(lua_State *L, int arg)
{
    li_image *u = check_image_ud(L, arg);
    if (u->closed) tl_argerror(L, arg, "attempt to use a closed image");
    return u->img;
}

/* Is the image at idx drawn in the frame being made (or made and not yet rendered)? */
static bool in_frame(lua_State *L, int idx)
{
    bool listed = false;
    idx = lua_absindex(L, idx);
    if (lua_getfield(L, LUA_REGISTRYINDEX, IMAGES_KEY) == LUA_TTABLE) {
        lua_pushvalue(L, idx);
        listed = lua_rawget(L, -2) != LUA_TNIL;
        lua_pop(L, 1);
    }
    lua_pop(L, 1);
    return listed;
}

/* __close: frees the pixels now, or once the frame that draws them is rendered. */
static int img_close(lua_State *L)
{
    li_image *u = check_image_ud(L, 1);
    u->closed = true;
    if (!in_frame(L, 1)) {
        tt_image_destroy(u->img);
        u->img = NULL;
    }
    return 0;
}

/* __gc: an image the frame still draws is reachable (IMAGES_KEY), so never collected before it is rendered. */
static int img_gc(lua_State *L)
{
    li_image *u = check_image_ud(L, 1);
    tt_image_destroy(u->img);
    u->img = NULL;
    u->closed = true;
    return 0;
}

static int img_tostring(lua_State *L)
{
    li_image *u = check_image_ud(L, 1);
    int w, h;
    if (u->closed) {
        lua_pushfstring(L, TL_IMAGE_CLASS " (closed): %p", (void *)u);
        return 1;
    }
    tt_image_size(u->img, &w, &h);
    lua_pushfstring(L, TL_IMAGE_CLASS " (%dx%d): %p", w, h, (void *)u);
    return 1;
}

void tl_push_image(lua_State *L, tt_image *img)
{
    li_image *u = lua_newuserdatauv(L, sizeof *u, 0); /* harmless until img is stored */
    u->img = NULL;
    u->closed = false;
    luaL_setmetatable(L, TL_IMAGE_CLASS);
    u->img = img;
}

/* g.new_image(width, height) → image, transparent black */
static int g_new_image(lua_State *L)
{
    int w = (int)tl_checkinteger(L, 1, 1, 8192), h = (int)tl_checkinteger(L, 2, 1, 8192);
    li_image *u = lua_newuserdatauv(L, sizeof *u, 0);
    u->img = NULL;
    u->closed = false;
    luaL_setmetatable(L, TL_IMAGE_CLASS);
    u->img = tt_image_create(w, h);
    if (!u->img) tl_error(L, "out of memory for a %dx%d image", w, h);
    return 1;
}

/* img:size() → width, height */
static int img_size(lua_State *L)
{
    int w, h;
    tt_image_size(check_image(L, 1), &w, &h);
    lua_pushinteger(L, w);
    lua_pushinteger(L, h);
    return 2;
}

static uint8_t *pixel_at(lua_State *L, tt_image *img)
{
    int w, h;
    tt_image_size(img, &w, &h);
    lua_Integer x = tl_checkinteger(L, 2, 0, w - 1), y = tl_checkinteger(L, 3, 0, h - 1);
    return tt_image_pixels(img) + ((size_t)y * (size_t)w + (size_t)x) * 4;
}

/* img:set_pixel(x, y, r, g, b [, a]) — x in [0, width − 1], y in [0, height − 1] from the top */
static int img_set_pixel(lua_State *L)
{
    tt_image *img = check_image(L, 1);
    uint8_t *p = pixel_at(L, img);
    uint8_t k[4] = { byte_of(tl_checknumber(L, 4, &R_UNIT)), byte_of(tl_checknumber(L, 5, &R_UNIT)),
                     byte_of(tl_checknumber(L, 6, &R_UNIT)), byte_of(tl_optnumber(L, 7, &R_UNIT, 1.0)) };
    memcpy(p, k, 4);
    tt_image_touch(img);
    return 0;
}

/* img:pixel(x, y) → r, g, b, a */
static int img_pixel(lua_State *L)
{
    const uint8_t *p = pixel_at(L, check_image(L, 1));
    for (int i = 0; i < 4; i++) lua_pushnumber(L, p[i] / 255.0);
    return 4;
}

/* img:fill(r, g, b [, a]) */
static int img_fill(lua_State *L)
{
    tt_image *img = check_image(L, 1);
    uint8_t k[4] = { byte_of(tl_checknumber(L, 2, &R_UNIT)), byte_of(tl_checknumber(L, 3, &R_UNIT)),
                     byte_of(tl_checknumber(L, 4, &R_UNIT)), byte_of(tl_optnumber(L, 5, &R_UNIT, 1.0)) };
    int w, h;
    tt_image_size(img, &w, &h);
    uint8_t *p = tt_image_pixels(img);
    for (size_t i = 0; i < (size_t)w * (size_t)h; i++) memcpy(p + 4 * i, k, 4);
    tt_image_touch(img);
    return 0;
}

/* g.image(img, x1, y1, x2, y2) — stretched over the rectangle, tinted by the colour (white: as is) */
static int g_image(lua_State *L)
{
    tt_canvas *c = canvas(L);
    tt_image *img = check_image(L, 1);
    double x1 = tl_checknumber(L, 2, &TL_R_COORD), y1 = tl_checknumber(L, 3, &TL_R_COORD);
    double x2 = tl_checknumber(L, 4, &TL_R_COORD), y2 = tl_checknumber(L, 5, &TL_R_COORD);
    tt_vec2 lo = { x1 < x2 ? x1 : x2, y1 < y2 ? y1 : y2 }, hi = { x1 < x2 ? x2 : x1, y1 < y2 ? y2 : y1 };
    check_canvas_result(L, c, tt_canvas_image(c, img, lo, hi));
    /* the canvas points at img until the frame is drawn: keep it from the
     * collector, and tell __close to leave the pixels to tl_render_done */
    lua_getfield(L, LUA_REGISTRYINDEX, IMAGES_KEY);
    if (lua_istable(L, -1)) {
        lua_pushvalue(L, 1);
        lua_pushboolean(L, 1);
        lua_rawset(L, -3);
    }
    lua_pop(L, 1);
    return 0;
}

static const luaL_Reg image_methods[] = {
    { "size", img_size }, { "set_pixel", img_set_pixel }, { "pixel", img_pixel }, { "fill", img_fill }, { NULL, NULL }
};
static const luaL_Reg image_meta[] = { { "__gc", img_gc }, { "__close", img_close }, { "__tostring", img_tostring }, { NULL, NULL } };

/* --- every world, for scripts without tether.draw ----------------------------- */

/* tether.world(...): the module's constructor, and the world is remembered. */
static int l_world_tracked(lua_State *L)
{
    int n = lua_gettop(L);
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, n, 1);
    tl_render *r = state(L);
    if (lua_getfield(L, LUA_REGISTRYINDEX, WORLDS_KEY) == LUA_TTABLE) {
        lua_pushvalue(L, -2);
        lua_rawseti(L, -2, ++r->nworlds);
    }
    lua_pop(L, 1);
    return 1;
}

void tl_render_auto(lua_State *L)
{
    tl_render *r = state(L);
    tt_canvas *c = r->canvas;
    if (!c) return;
    lua_getfield(L, LUA_REGISTRYINDEX, WORLDS_KEY);
    int t = lua_gettop(L);
    int shown = 0;
    /* the view grows to hold every particle seen so far (it never jumps back) */
    for (lua_Integer k = 1; k <= r->nworlds && lua_istable(L, t); k++) {
        lua_rawgeti(L, t, k);
        tt_world *w = tl_toworld(L, -1);
        lua_pop(L, 1);
        if (!w) continue;
        uint32_t n = tt_world_particle_count(w);
        double *xy = malloc((2 * (size_t)n + 2) * sizeof *xy);
        if (!xy) continue;
        n = tt_world_read_positions(w, xy, n);
        for (uint32_t i = 0; i < n; i++) {
            tt_vec2 p = { xy[2 * i], xy[2 * i + 1] };
            if (!(fabs(p.x) < 1e9 && fabs(p.y) < 1e9)) continue;
            if (!r->auto_set) { r->auto_lo = r->auto_hi = p; r->auto_set = true; }
            r->auto_lo.x = fmin(r->auto_lo.x, p.x); r->auto_lo.y = fmin(r->auto_lo.y, p.y);
            r->auto_hi.x = fmax(r->auto_hi.x, p.x); r->auto_hi.y = fmax(r->auto_hi.y, p.y);
        }
        free(xy);
    }
    if (r->auto_set) {
        tt_vec2 lo = r->auto_lo, hi = r->auto_hi;
        double ex = 1.2 * fmax(1.0, hi.x - lo.x), ey = 1.2 * fmax(1.0, hi.y - lo.y), cx = 0.5 * (lo.x + hi.x), cy = 0.5 * (lo.y + hi.y);
        int W, H;
        tt_canvas_size(c, &W, &H);
        double margin = fmin(30.0, 0.2 * fmin(W, H));
        tt_canvas_fit(c, (tt_vec2){ cx - 0.5 * ex, cy - 0.5 * ey }, (tt_vec2){ cx + 0.5 * ex, cy + 0.5 * ey }, margin);
    }
    double y = 6.0;
    for (lua_Integer k = 1; k <= r->nworlds && lua_istable(L, t); k++) {
        lua_rawgeti(L, t, k);
        tt_world *w = tl_toworld(L, -1);
        if (w && tt_canvas_draw_world(c, w, NULL) == TT_OK) {
            remember(L, lua_gettop(L), c);
            if (shown++ == 0) {
                tt_stats st;
                char buf[256];
                tt_world_get_stats(w, &st);
                snprintf(buf, sizeof buf, "t %.2f s   step %.3f ms\nparticles %u   springs %u\niterations %u   error %.1e",
                         st.time, st.step_ms, st.particles, st.springs, st.iterations, st.max_error);
                hud_panel(c, buf, &y);
            }
        }
        lua_pop(L, 1);
    }
    lua_pop(L, 1);
    tt_layer layer = tt_canvas_get_layer(c);
    tt_canvas_set_layer(c, TT_LAYER_SCREEN);
    tt_canvas_set_color(c, (tt_color){ 170, 170, 170, 255 });
    tt_canvas_text(c, (tt_vec2){ 8, y + 2 }, shown ? "no tether.draw(g): every world, automatic view"
                                                   : "no tether.draw(g) and no world: nothing to show", 1);
    tt_canvas_set_layer(c, layer);
}

/* --- registration and the runner's side ------------------------------------ */

static const luaL_Reg gfx_funcs[] = {
    { "color", g_color },         { "clear", g_clear },   { "circle", g_circle },   { "line", g_line },
    { "polygon", g_polygon },     { "text", g_text },     { "line_width", g_line_width },
    { "layer", g_layer },         { "camera", g_camera }, { "fit", g_fit },         { "size", g_size },
    { "to_world", g_to_world },   { "to_screen", g_to_screen },
    { "new_image", g_new_image }, { "image", g_image },   { NULL, NULL }
};
/* the ones whose argument 1 is a world, pinned while they run (lua_common.h) */
static const luaL_Reg gfx_world_funcs[] = { { "hud", g_hud }, { NULL, NULL } };

static const luaL_Reg world_draw[] = { { "draw", w_draw }, { NULL, NULL } };

void tl_render_register(lua_State *L)
{
    if (luaL_newmetatable(L, TL_IMAGE_CLASS)) {
        tl_setfuncs(L, image_meta, "");
        lua_createtable(L, 0, 4);
        tl_setfuncs(L, image_methods, "");
        lua_setfield(L, -2, "__index");
    }
    lua_pop(L, 1);
    /* tether.world remembers what it makes (weakly), for the automatic view */
    lua_newtable(L);
    lua_createtable(L, 0, 1);
    lua_pushliteral(L, "v");
    lua_setfield(L, -2, "__mode");
    lua_setmetatable(L, -2);
    lua_setfield(L, LUA_REGISTRYINDEX, WORLDS_KEY);
    state(L)->nworlds = 0;
    lua_getfield(L, -1, "world");
    lua_pushcclosure(L, l_world_tracked, 1);
    lua_setfield(L, -2, "world");

    lua_createtable(L, 0, (int)(sizeof gfx_funcs / sizeof gfx_funcs[0]));
    tl_setfuncs(L, gfx_funcs, "tether.gfx.");
    tl_setfuncs_pinned(L, gfx_world_funcs, "tether.gfx.");
    lua_setfield(L, -2, "gfx");
    tl_world_add_methods(L, world_draw);
}

void tl_render_begin(lua_State *L, tt_canvas *c)
{
    tl_render *r = state(L);
    r->canvas = c;
    r->ndrawn = 0;
    lua_newtable(L);
    lua_setfield(L, LUA_REGISTRYINDEX, DRAWN_KEY);
    lua_newtable(L);
    lua_setfield(L, LUA_REGISTRYINDEX, IMAGES_KEY);
    lua_pushnil(L);
    lua_setfield(L, LUA_REGISTRYINDEX, "tether.render.hud_y");
}

void tl_render_end(lua_State *L)
{
    state(L)->canvas = NULL;
}

void tl_render_done(lua_State *L)
{
    /* the frame is on screen: the images closed while it was made can go */
    if (lua_getfield(L, LUA_REGISTRYINDEX, IMAGES_KEY) == LUA_TTABLE) {
        lua_pushnil(L);
        while (lua_next(L, -2) != 0) {
            li_image *u = lua_touserdata(L, -2);
            lua_pop(L, 1);
            if (u != NULL && u->closed) {
                tt_image_destroy(u->img);
                u->img = NULL;
            }
        }
    }
    lua_pop(L, 1);
    lua_pushnil(L);
    lua_setfield(L, LUA_REGISTRYINDEX, IMAGES_KEY);
}

bool tl_render_pick(lua_State *L, double px, double py, double max_px, tt_particle *out)
{
    tl_render *r = state(L);
    double best = max_px * max_px;
    size_t best_world = 0;
    tt_particle best_p = { 0, 0 };
    lua_getfield(L, LUA_REGISTRYINDEX, DRAWN_KEY);
    for (size_t k = 0; k < r->ndrawn && lua_istable(L, -1); k++) {
        lua_rawgeti(L, -1, (lua_Integer)k + 1);
        tt_world *w = tl_toworld(L, -1);
        lua_pop(L, 1);
        if (!w) continue;
        const drawn *d = &r->drawn[k];
        uint32_t n = tt_world_particle_count(w);
        tt_particle *ids = malloc(((size_t)n + 1) * sizeof *ids);
        double *xy = malloc((2 * (size_t)n + 2) * sizeof *xy);
        if (ids && xy) {
            n = tt_world_list_particles(w, ids, n);
            tt_world_read_positions(w, xy, n);
            for (uint32_t i = 0; i < n; i++) {
                double dx = 0.5 * d->width + (xy[2 * i] - d->center.x) * d->zoom - px;
                double dy = 0.5 * d->height - (xy[2 * i + 1] - d->center.y) * d->zoom - py;
                double e = dx * dx + dy * dy;
                if (e < best) {
                    best = e;
                    best_world = k + 1;
                    best_p = ids[i];
                }
            }
        }
        free(ids);
        free(xy);
    }
    if (best_world) {
        lua_rawgeti(L, -1, (lua_Integer)best_world);
        lua_setfield(L, LUA_REGISTRYINDEX, DRAG_KEY);
        r->drag_cam = r->drawn[best_world - 1];
        *out = best_p;
    }
    lua_pop(L, 1);
    return best_world != 0;
}

tt_world *tl_render_drag_world(lua_State *L, double px, double py, tt_vec2 *pos)
{
    tl_render *r = state(L);
    lua_getfield(L, LUA_REGISTRYINDEX, DRAG_KEY);
    tt_world *w = tl_toworld(L, -1);
    drawn cam = r->drag_cam;
    if (w) { /* the camera it was drawn with last */
        lua_getfield(L, LUA_REGISTRYINDEX, DRAWN_KEY);
        for (size_t k = 0; k < r->ndrawn && lua_istable(L, -1); k++) {
            lua_rawgeti(L, -1, (lua_Integer)k + 1);
            if (lua_rawequal(L, -1, -3)) cam = r->drawn[k];
            lua_pop(L, 1);
        }
        lua_pop(L, 1);
    }
    lua_pop(L, 1);
    pos->x = cam.center.x + (px - 0.5 * cam.width) / cam.zoom;
    pos->y = cam.center.y - (py - 0.5 * cam.height) / cam.zoom;
    return w;
}

void tl_render_drag_end(lua_State *L)
{
    lua_pushnil(L);
    lua_setfield(L, LUA_REGISTRYINDEX, DRAG_KEY);
}
