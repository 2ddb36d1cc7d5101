/* tether — the tether_box2d Lua module's shared readers (lua_box2d.c) and
 * its scene functions (lua_box2d_scene.c). */
#ifndef TETHER_LUA_BOX2D_H
#define TETHER_LUA_BOX2D_H

#include "box2d_scene.h"

#include <lua.h>

/* Option tables (tl_readopts, src/lua/lua_options.c): each raises an error
 * naming the calling function (tl_setfuncs' upvalue) and the option. */
tb_world_def tl_b2_world_def(lua_State *L, int t);
tb_body_def tl_b2_body_def(lua_State *L, int t);
/* A new world userdata on the stack (raises on failure). */
tb_world *tl_b2_push_world(lua_State *L, const tb_world_def *d, const char *fn);

/* The world class's metatable (lua_box2d.c), and tether_box2d.world{…}. */
void tl_b2_register(lua_State *L);
int tl_b2_world(lua_State *L);
int tl_b2_scene(lua_State *L);
int tl_b2_build(lua_State *L);
int tl_b2_crosscheck(lua_State *L);
int tl_b2_main(lua_State *L);
int luaopen_tether_box2d(lua_State *L);

#endif
