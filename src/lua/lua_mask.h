/* tether — the Lua mask class (tether.mask), shared by lua_mask.c (the
 * class, constructors, pixels), lua_mask_ops.c (overlap, shape, outlines,
 * chains) and lua_mask_draw.c (images and g.mask). */
#ifndef TETHER_LUA_MASK_H
#define TETHER_LUA_MASK_H

#include "lua_common.h"

#define TL_MASK_CLASS "tether.mask"

/* The userdata: the mask itself lies inside it, after this header
 * (tt_mask_init), so the collector knows what a mask weighs and frees it
 * with no finalizer; m is NULL only while the userdata is being made.
 * version counts changes, so g.mask repaints its cached image only when
 * needed; the user value 1 holds that image. A mask has no close or destroy
 * method, so nothing a call runs (an option table's __index, a finalizer)
 * can free a mask another call is using. */
typedef struct tl_mask_ud {
    tt_mask *m;
    uint64_t version;
    uint64_t painted; /* version + 1 of the mask when its cached image was painted; 0: never */
} tl_mask_ud;

/* The mask at arg (raises "tether.mask expected, got …"). */
tl_mask_ud *tl_check_mask_ud(lua_State *L, int arg);
tt_mask *tl_check_mask(lua_State *L, int arg);
/* Pushes a new mask userdata holding a clear w×h mask (w, h already checked). */
tl_mask_ud *tl_push_mask(lua_State *L, int w, int h);
/* For masks whose size only the C call knows: pushes a holder (call it
 * before the C call, so that no allocation error can come between the
 * C mask's making and its owner), then tl_mask_own pushes the mask userdata
 * with a copy of m and frees m (the holder's finalizer frees it if a call
 * raises in between). Raises "fname: <tt_mask_last_error()>" when m is NULL. */
tt_mask **tl_new_mask_ud(lua_State *L);
tl_mask_ud *tl_mask_own(lua_State *L, tt_mask **slot, tt_mask *m);
/* Raises "fname: <tt_mask_last_error() without its C function's name>". */
int tl_mask_error(lua_State *L);
/* An offset coordinate at arg (integer within ±TT_MASK_MAX_OFFSET). */
int tl_check_offset(lua_State *L, int arg);
/* Marks the mask at arg changed. */
void tl_mask_touch(lua_State *L, int arg);

/* Adds methods to the mask class (after tl_mask_register). */
void tl_mask_add_methods(lua_State *L, const luaL_Reg *methods);
/* Adds functions to tether.mask in the module table on the top of the stack (after tl_mask_register). */
void tl_mask_add_funcs(lua_State *L, const luaL_Reg *funcs);

/* Each called by luaopen_tether with the module table on the top of the stack, in this order: */
void tl_mask_register(lua_State *L);      /* lua_mask.c: the class, tether.mask */
void tl_mask_ops_register(lua_State *L);  /* lua_mask_ops.c: overlaps, outlines, w:mask_chains */
void tl_mask_draw_register(lua_State *L); /* lua_mask_draw.c: images, tether.mask.from_image/from_color, g.mask */

#endif
