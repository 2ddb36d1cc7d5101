/* tether — masks and images in Lua: tether.mask.from_image and from_color
 * (a mask of a tether.image), m:to_image and m:paint (an image of a mask),
 * and g.mask, which draws a mask over a world rectangle through an image
 * the mask keeps (repainted only after the mask changed). */
#include "lua_mask.h"
#include "lua_render.h"


/* A colour at args arg…arg+3 (r, g, b [, a]) in [0, 1], or def when arg is none. */
static tt_color opt_color(lua_State *L, int arg, tt_color def)
{
    if (lua_isnoneornil(L, arg)) return def;
    return (tt_color){ tl_byte_of(tl_checknumber(L, arg, &TL_R_UNIT)), tl_byte_of(tl_checknumber(L, arg + 1, &TL_R_UNIT)),
                       tl_byte_of(tl_checknumber(L, arg + 2, &TL_R_UNIT)), tl_byte_of(tl_optnumber(L, arg + 3, &TL_R_UNIT, 1.0)) };
}

/* tether.mask.from_image(img [, threshold = 0.5]) — set where alpha > threshold (0…254/255) */
static int f_from_image(lua_State *L)
{
    tt_image *img = tl_check_image(L, 1);
    double t = tl_optnumber(L, 2, &(tl_range){ 0.0, 254.0 / 255.0, false }, 0.5);
    int w, h;
    tt_image_size(img, &w, &h);
    tt_mask **slot = tl_new_mask_ud(L);
    tl_mask_own(L, slot, tt_mask_from_rgba(tt_image_pixels(img), w, h, (size_t)w * 4, (int)(t * 255.0)));
    return 1;
}

/* tether.mask.from_color(img, r, g, b [, tolerance = 0, invert = false]) — set where the colour matches
 * within tolerance (0…1 per channel); invert: where it does not (a colour key) */
static int f_from_color(lua_State *L)
{
    tt_image *img = tl_check_image(L, 1);
    uint8_t key[3] = { tl_byte_of(tl_checknumber(L, 2, &TL_R_UNIT)), tl_byte_of(tl_checknumber(L, 3, &TL_R_UNIT)),
                       tl_byte_of(tl_checknumber(L, 4, &TL_R_UNIT)) };
    int tol = tl_byte_of(tl_optnumber(L, 5, &TL_R_UNIT, 0.0));
    bool invert = lua_isnoneornil(L, 6) ? false : tl_checkboolean(L, 6);
    int w, h;
    tt_image_size(img, &w, &h);
    tt_mask **slot = tl_new_mask_ud(L);
    tl_mask_own(L, slot, tt_mask_from_color(tt_image_pixels(img), w, h, (size_t)w * 4, key, tol, invert));
    return 1;
}

/* m:to_image([r, g, b, a]) → a tether.image of the mask's size: the colour (white) where set, transparent elsewhere */
static int m_to_image(lua_State *L)
{
    tt_mask *m = tl_check_mask(L, 1);
    tt_color on = opt_color(L, 2, (tt_color){ 255, 255, 255, 255 });
    int w, h;
    tt_mask_size(m, &w, &h);
    tt_image *img = tt_image_from_mask(m, on, (tt_color){ 0, 0, 0, 0 });
    if (!img) tl_error(L, "out of memory for a %dx%d image", w, h);
    tl_push_image(L, img);
    return 1;
}

/* m:paint(img [, r, g, b, a]) — repaints an image of the mask's size from the mask */
static int m_paint(lua_State *L)
{
    tt_mask *m = tl_check_mask(L, 1);
    tt_image *img = tl_check_image(L, 2);
    tt_color on = opt_color(L, 3, (tt_color){ 255, 255, 255, 255 });
    int w, h, iw, ih;
    tt_mask_size(m, &w, &h);
    tt_image_size(img, &iw, &ih);
    if (iw != w || ih != h) tl_argerror(L, 2, "image of %dx%d expected (the mask's size), got %dx%d", w, h, iw, ih);
    tt_image_paint_mask(img, m, on, (tt_color){ 0, 0, 0, 0 });
    return 0;
}

/* g.mask(m, x1, y1, x2, y2) — the mask stretched over the world rectangle, set pixels in the current colour
 * (the image's top row at the top: pixel (0, 0) at (min x, max y)) */
static int g_mask(lua_State *L)
{
    tt_canvas *c = tl_render_canvas(L);
    tl_mask_ud *u = tl_check_mask_ud(L, 1);
    double x1 = tl_checknumber(L, 2, &TL_R_COORD), y1 = tl_checknumber(L, 3, &TL_R_COORD);
    double x2 = tl_checknumber(L, 4, &TL_R_COORD), y2 = tl_checknumber(L, 5, &TL_R_COORD);
    lua_settop(L, 5);
    if (lua_getiuservalue(L, 1, 1) != LUA_TUSERDATA) { /* the first draw: make the mask's image */
        lua_pop(L, 1);
        tt_image *img = tt_image_from_mask(u->m, (tt_color){ 255, 255, 255, 255 }, (tt_color){ 0, 0, 0, 0 });
        if (!img) tl_error(L, "out of memory for the mask's image");
        tl_push_image(L, img);
        lua_pushvalue(L, -1);
        lua_setiuservalue(L, 1, 1);
        u->painted = u->version + 1;
    }
    tt_image *img = tl_check_image(L, 6);
    if (u->painted != u->version + 1) {
        tt_image_paint_mask(img, u->m, (tt_color){ 255, 255, 255, 255 }, (tt_color){ 0, 0, 0, 0 });
        u->painted = u->version + 1;
    }
    tt_vec2 lo = { x1 < x2 ? x1 : x2, y1 < y2 ? y1 : y2 }, hi = { x1 < x2 ? x2 : x1, y1 < y2 ? y2 : y1 };
    tl_check_canvas_result(L, c, tt_canvas_image(c, img, lo, hi));
    /* the canvas points at the image until the frame is drawn: keep it reachable till then */
    lua_getfield(L, LUA_REGISTRYINDEX, TL_IMAGES_KEY);
    if (lua_istable(L, -1)) {
        lua_pushvalue(L, 6);
        lua_pushboolean(L, 1);
        lua_rawset(L, -3);
    }
    return 0;
}

static const luaL_Reg draw_methods[] = { { "to_image", m_to_image }, { "paint", m_paint }, { NULL, NULL } };
static const luaL_Reg image_funcs[] = { { "from_image", f_from_image }, { "from_color", f_from_color }, { NULL, NULL } };
static const luaL_Reg gfx_funcs[] = { { "mask", g_mask }, { NULL, NULL } };

void tl_mask_draw_register(lua_State *L)
{
    tl_mask_add_methods(L, draw_methods);
    tl_mask_add_funcs(L, image_funcs);
    lua_getfield(L, -1, "gfx");
    tl_setfuncs(L, gfx_funcs, "tether.gfx.");
    lua_pop(L, 1);
}
