/* tether — the tether_box2d Lua module's shared readers (lua_box2d.c) and
 * its scene functions (lua_box2d_scene.c). */
#ifndef TETHER_LUA_BOX2D_H
#define TETHER_LUA_BOX2D_H

#include "box2d_scene.h"

#include <lua.h>

/* Option readers: each raises an error naming fn and the option. */
tb_world_def tl_b2_world_def(lua_State *L, int t, const char *fn);
tb_body_def tl_b2_body_def(lua_State *L, int t, const char *fn);
/* Raises naming fn when the table at t has a key not in names (NULL-terminated). */
void tl_b2_only_keys(lua_State *L, int t, const char *fn, const char *const *names);
/* The index in names (NULL-terminated) of the string t[key]; raises otherwise. */
int tl_b2_pick(lua_State *L, int t, const char *fn, const char *key, const char *const *names);
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
