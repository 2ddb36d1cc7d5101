/* tether — Lua images (class "tether.image"): g.new_image, the pixel methods,
 * g.image to draw one, and the rule that keeps a closed image's pixels alive
 * until the frame that draws it is rendered (tl_render_done). */
#include "lua_render.h"

#include <string.h>


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
    if (lua_getfield(L, LUA_REGISTRYINDEX, TL_IMAGES_KEY) == LUA_TTABLE) {
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

/* __gc: an image the frame still draws is reachable (TL_IMAGES_KEY), so never collected before it is rendered. */
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
    uint8_t k[4] = { tl_byte_of(tl_checknumber(L, 4, &TL_R_UNIT)), tl_byte_of(tl_checknumber(L, 5, &TL_R_UNIT)),
                     tl_byte_of(tl_checknumber(L, 6, &TL_R_UNIT)), tl_byte_of(tl_optnumber(L, 7, &TL_R_UNIT, 1.0)) };
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
    uint8_t k[4] = { tl_byte_of(tl_checknumber(L, 2, &TL_R_UNIT)), tl_byte_of(tl_checknumber(L, 3, &TL_R_UNIT)),
                     tl_byte_of(tl_checknumber(L, 4, &TL_R_UNIT)), tl_byte_of(tl_optnumber(L, 5, &TL_R_UNIT, 1.0)) };
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
    tt_canvas *c = tl_render_canvas(L);
    tt_image *img = check_image(L, 1);
    double x1 = tl_checknumber(L, 2, &TL_R_COORD), y1 = tl_checknumber(L, 3, &TL_R_COORD);
    double x2 = tl_checknumber(L, 4, &TL_R_COORD), y2 = tl_checknumber(L, 5, &TL_R_COORD);
    tt_vec2 lo = { x1 < x2 ? x1 : x2, y1 < y2 ? y1 : y2 }, hi = { x1 < x2 ? x2 : x1, y1 < y2 ? y2 : y1 };
    tl_check_canvas_result(L, c, tt_canvas_image(c, img, lo, hi));
    /* the canvas points at img until the frame is drawn: keep it from the
     * collector, and tell __close to leave the pixels to tl_render_done */
    lua_getfield(L, LUA_REGISTRYINDEX, TL_IMAGES_KEY);
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

static const luaL_Reg image_gfx_funcs[] = { { "new_image", g_new_image }, { "image", g_image }, { NULL, NULL } };

void tl_image_register(lua_State *L)
{
    if (luaL_newmetatable(L, TL_IMAGE_CLASS)) {
        tl_setfuncs(L, image_meta, "");
        lua_createtable(L, 0, 4);
        tl_setfuncs(L, image_methods, "");
        lua_setfield(L, -2, "__index");
    }
    lua_pop(L, 1);
    tl_setfuncs(L, image_gfx_funcs, "tether.gfx.");
}

void tl_render_done(lua_State *L)
{
    /* the frame is on screen: the images closed while it was made can go */
    if (lua_getfield(L, LUA_REGISTRYINDEX, TL_IMAGES_KEY) == LUA_TTABLE) {
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
    lua_setfield(L, LUA_REGISTRYINDEX, TL_IMAGES_KEY);
}


tt_image *tl_check_image(lua_State *L, int arg)
{
    return check_image(L, arg);
}
