/* tether — the drawing state of a Lua state and the runner's side of the
 * drawing API (lua_render.h): the canvas of the frame being made
 * (tl_render_begin … tl_render_end), the worlds drawn in it with their
 * cameras (mouse picking and dragging), and the automatic view of a script
 * without tether.draw. What a script calls is in lua_gfx.c (tether.gfx,
 * world:draw) and lua_image.c (tether.image).
 *
 * Outside a frame the drawing functions raise "nothing to draw on". */
#include "lua_render.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define STATE_KEY "tether.render"        /* registry: the tl_render userdata */
#define DRAWN_KEY "tether.render.drawn"  /* registry: worlds drawn this frame, 1…n */
#define DRAG_KEY "tether.render.drag"    /* registry: the world being dragged */
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
    double alpha;      /* the frame's interpolation factor (tl_render_set_alpha) */
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

tt_canvas *tl_render_canvas(lua_State *L)
{
    tl_render *r = state(L);
    if (!r->canvas)
        tl_error(L, "nothing to draw on: drawing works inside tether.draw(g), called by the tether runner "
                    "(a window, or --headless --out DIR)");
    return r->canvas;
}

uint8_t tl_byte_of(double v) { return (uint8_t)(v * 255.0 + 0.5); }

double tl_render_alpha(lua_State *L) { return state(L)->alpha; }

void tl_render_set_alpha(lua_State *L, double alpha)
{
    state(L)->alpha = alpha >= 0.0 && alpha <= 1.0 ? alpha : 1.0;
}

void tl_render_interpolate(lua_State *L, tt_world *w, double alpha)
{
    if (alpha != 1.0 && !tt_world_get_interpolation(w)) tl_check_result(L, w, tt_world_set_interpolation(w, true));
}

void tl_check_canvas_result(lua_State *L, tt_canvas *c, tt_result r)
{
    if (r != TT_OK) tl_error(L, "%s", tt_canvas_error(c));
}

/* The HUD panel: lines of text on a dark box at the top-left (or below the last panel). */
void tl_render_hud_panel(tt_canvas *c, const char *text, double *y)
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

/* Remembers the world at idx and the camera it is drawn with, for mouse picking. */
void tl_render_remember(lua_State *L, int idx, tt_canvas *c)
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

/* tether.world remembers what it makes (weakly), for the automatic view */
void tl_render_track_worlds(lua_State *L)
{
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
        tt_debug_draw dd = tt_debug_draw_default();
        dd.alpha = r->alpha;
        if (w && r->alpha != 1.0 && !tt_world_get_interpolation(w) && tt_world_set_interpolation(w, true) != TT_OK)
            dd.alpha = 1.0; /* no memory to keep where it was: drawn where it is */
        if (w && tt_canvas_draw_world(c, w, &dd) == TT_OK) {
            tl_render_remember(L, lua_gettop(L), c);
            if (shown++ == 0) {
                tt_stats st;
                char buf[256];
                tt_world_get_stats(w, &st);
                snprintf(buf, sizeof buf, "t %.2f s   step %.3f ms\nparticles %u   springs %u\niterations %u   error %.1e",
                         st.time, st.step_ms, st.particles, st.springs, st.iterations, st.max_error);
                tl_render_hud_panel(c, buf, &y);
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

/* --- the runner's side ------------------------------------------------------ */

void tl_render_begin(lua_State *L, tt_canvas *c)
{
    tl_render *r = state(L);
    r->canvas = c;
    r->ndrawn = 0;
    r->alpha = 1.0;
    lua_newtable(L);
    lua_setfield(L, LUA_REGISTRYINDEX, DRAWN_KEY);
    lua_newtable(L);
    lua_setfield(L, LUA_REGISTRYINDEX, TL_IMAGES_KEY);
    lua_pushnil(L);
    lua_setfield(L, LUA_REGISTRYINDEX, "tether.render.hud_y");
}

void tl_render_end(lua_State *L)
{
    state(L)->canvas = NULL;
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
