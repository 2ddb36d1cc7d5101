/* tether — `tether atlas [--quick] [--out DIR] [SCRIPT]`: the speed/accuracy
 * atlas (lua/tether_atlas.lua) run with the module built into this
 * program, over the built-in reference scenes or the scene a user's script
 * returns: the trade measured for their game. */
#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>

#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "runner.h"

int luaopen_tether(lua_State *L);

int tr_atlas(int argc, char **argv)
{
    lua_State *L = luaL_newstate();
    if (!L) {
        fprintf(stderr, PROGNAME ": cannot create a Lua state: not enough memory\n");
        return 1;
    }
    luaL_openlibs(L);
    luaL_getsubtable(L, LUA_REGISTRYINDEX, LUA_PRELOAD_TABLE);
    lua_pushcfunction(L, luaopen_tether);
    lua_setfield(L, -2, "tether");
    lua_pop(L, 1);
    /* the atlas's Lua files: the source tree's lua/ beside build/, or the installed share/lua/5.4 */
    char dir[PATH_MAX];
    ssize_t len = readlink("/proc/self/exe", dir, sizeof dir - 1);
    if (len <= 0) len = (ssize_t)snprintf(dir, sizeof dir, "./x");
    dir[len] = 0;
    char *slash = strrchr(dir, '/');
    if (slash) *slash = 0;
    lua_getglobal(L, "package");
    lua_pushfstring(L, "%s/../lua/?.lua;%s/../share/lua/5.4/?.lua;", dir, dir);
    lua_getfield(L, -2, "path");
    lua_concat(L, 2);
    lua_setfield(L, -2, "path");
    lua_pop(L, 1);
    lua_getglobal(L, "require");
    lua_pushliteral(L, "tether_atlas");
    int status = 1;
    if (lua_pcall(L, 1, 1, 0) != LUA_OK) {
        fprintf(stderr, PROGNAME " atlas: %s\n", lua_tostring(L, -1));
    } else {
        lua_getfield(L, -1, "main");
        for (int i = 2; i < argc; i++) lua_pushstring(L, argv[i]);
        if (lua_pcall(L, argc - 2, 1, 0) != LUA_OK) fprintf(stderr, PROGNAME " atlas: %s\n", lua_tostring(L, -1));
        else status = (int)lua_tointeger(L, -1);
    }
    lua_close(L);
    return status;
}
