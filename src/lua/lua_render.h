/* tether — the Lua drawing API (lua_render.c, lua_gfx.c, lua_image.c): what
 * the module registers and what the runner calls around each frame. No GL
 * here: the runner owns the canvas and the back end; the module only appends
 * to the canvas. */
#ifndef TETHER_LUA_RENDER_H
#define TETHER_LUA_RENDER_H

#include "lua_common.h"
#include "tether/render.h"

/* Adds tether.gfx to the module table on the top of the stack, and
 * world:draw() to the world class (tl_world_register must have run). */
void tl_render_register(lua_State *L);
#define TL_IMAGE_CLASS "tether.image"

/* Drawing calls go to c until tl_render_end (c is cleared by the caller).
 * Images drawn stay referenced until tl_render_done, to be called once the
 * back end has drawn the canvas: it frees those closed in the meantime. */
void tl_render_begin(lua_State *L, tt_canvas *c);
/* The frame's interpolation factor (the runner's clock alpha, 0…1): where
 * between their last two steps worlds are drawn unless world:draw says;
 * 1 (the current positions) from tl_render_begin until set. */
void tl_render_set_alpha(lua_State *L, double alpha);
void tl_render_end(lua_State *L);
void tl_render_done(lua_State *L);
/* For a script without tether.draw: draws every live world it made (in the
 * order made) with a view that grows to hold all their particles, and a HUD. */
void tl_render_auto(lua_State *L);
/* Pushes a tether.image userdata that owns img (the runner's load_image). */
void tl_push_image(lua_State *L, tt_image *img);
/* Mouse picking over the worlds drawn by the last frame: the live particle
 * nearest to pixel (px, py), within max_px on screen. On success the world
 * is remembered (kept alive) as the drag target and true is returned. */
bool tl_render_pick(lua_State *L, double px, double py, double max_px, tt_particle *out);
/* The drag target's world (NULL when destroyed or none), and in *pos the
 * pixel (px, py) in its world coordinates, through the camera it was last drawn with. */
tt_world *tl_render_drag_world(lua_State *L, double px, double py, tt_vec2 *pos);
/* Forgets the drag target. */
void tl_render_drag_end(lua_State *L);

/* --- shared by the drawing files only, not for the runner --------------------- */

/* registry: image → true for those drawn this frame (kept until rendered) */
#define TL_IMAGES_KEY "tether.render.images"

/* The canvas of the frame being made; raises "nothing to draw on" outside one. */
tt_canvas *tl_render_canvas(lua_State *L);
/* A colour channel in [0, 1] as a byte. */
uint8_t tl_byte_of(double v);
/* Raises the canvas's message unless r is TT_OK. */
void tl_check_canvas_result(lua_State *L, tt_canvas *c, tt_result r);
/* Draws text in a HUD panel at height *y, and moves *y below it. */
void tl_render_hud_panel(tt_canvas *c, const char *text, double *y);
/* The frame's alpha (tl_render_set_alpha). */
double tl_render_alpha(lua_State *L);
/* Drawing w at alpha < 1 needs its previous positions: turns their keeping
 * on (tt_world_set_interpolation) the first time; raises on no memory. */
void tl_render_interpolate(lua_State *L, tt_world *w, double alpha);
/* Remembers the world at idx and the camera it is drawn with, for mouse picking. */
void tl_render_remember(lua_State *L, int idx, tt_canvas *c);
/* Wraps tether.world of the module table on the top of the stack (lua_render.c). */
void tl_render_track_worlds(lua_State *L);
/* The open image at arg (raises a type error, or "attempt to use a closed image"). */
tt_image *tl_check_image(lua_State *L, int arg);
/* Makes the image class, and adds g.new_image and g.image to the tether.gfx
 * table on the top of the stack (lua_image.c). */
void tl_image_register(lua_State *L);

#endif
