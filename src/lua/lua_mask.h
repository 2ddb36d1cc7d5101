/* tether — the Lua mask class (tether.mask), shared by lua_mask.c (the
 * class, constructors, pixels), lua_mask_ops.c (overlap, shape, outlines,
 * chains) and lua_mask_draw.c (images and g.mask). */
#ifndef TETHER_LUA_MASK_H
#define TETHER_LUA_MASK_H

#include "lua_common.h"

#define TL_MASK_CLASS "tether.mask"

/* The userdata: m is NULL only while a constructor has not finished (an
 * error there leaves a harmless empty userdata for the collector). version
 * counts changes, so g.mask repaints its cached image only when needed. The
 * user value 1 holds that image. A mask has no close or destroy method, so
 * nothing a call runs (an option table's __index, a finalizer) can free a
 * mask another call is using. */
typedef struct tl_mask_ud {
    tt_mask *m;
    uint64_t version;
    uint64_t painted; /* version + 1 of the mask when its cached image was painted; 0: never */
} tl_mask_ud;

/* The mask at arg (raises "tether.mask expected, got …"). */
tl_mask_ud *tl_check_mask_ud(lua_State *L, int arg);
tt_mask *tl_check_mask(lua_State *L, int arg);
/* Pushes a new mask userdata that will own the mask made by make(arg) — the
 * userdata first, so an allocation error cannot leak the mask. Raises
 * "fname: <tt_mask_last_error()>" when m is NULL. */
tl_mask_ud *tl_new_mask_ud(lua_State *L);
void tl_mask_own(lua_State *L, tl_mask_ud *u, tt_mask *m);
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
