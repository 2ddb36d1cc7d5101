/* tether — `tether crosscheck [SCENE]`: the Box2D cross-check, run from the
 * tether_box2d Lua module found beside this program (or installed for Lua),
 * so the runner itself never links Box2D or libstdc++. */
#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>

#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "runner.h"

/* The folder this program is in, for package.cpath; "." when unknown. */
static void own_dir(char *buf, size_t n)
{
    ssize_t len = readlink("/proc/self/exe", buf, n - 1);
    if (len <= 0) {
        snprintf(buf, n, ".");
        return;
    }
    buf[len] = 0;
    char *slash = strrchr(buf, '/');
    if (slash) *slash = 0;
}

int tr_crosscheck(int argc, char **argv)
{
    lua_State *L = luaL_newstate();
    if (!L) {
        fprintf(stderr, PROGNAME ": cannot create a Lua state: not enough memory\n");
        return 1;
    }
    luaL_openlibs(L);
    char dir[PATH_MAX];
    own_dir(dir, sizeof dir);
    lua_getglobal(L, "package");
    lua_pushfstring(L, "%s/?.so;%s/../lib/lua/5.4/?.so;", dir, dir);
    lua_getfield(L, -2, "cpath");
    lua_concat(L, 2);
    lua_setfield(L, -2, "cpath");
    lua_pop(L, 1);
    lua_getglobal(L, "require");
    lua_pushliteral(L, "tether_box2d");
    int status = 1;
    if (lua_pcall(L, 1, 1, 0) != LUA_OK) {
        fprintf(stderr, PROGNAME " crosscheck: the tether_box2d module (built by make beside " PROGNAME ") did not load: %s\n",
                lua_tostring(L, -1));
    } else {
        lua_getfield(L, -1, "main");
        for (int i = 2; i < argc; i++) lua_pushstring(L, argv[i]);
        if (lua_pcall(L, argc - 2, 1, 0) != LUA_OK) fprintf(stderr, PROGNAME " crosscheck: %s\n", lua_tostring(L, -1));
        else status = (int)lua_tointeger(L, -1);
    }
    lua_close(L);
    return status;
}
