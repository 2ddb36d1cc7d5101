/* tether — the runner's subcommands that are a Lua module's main(...):
 * `tether crosscheck [SCENE]` runs the Box2D cross-check from the
 * tether_box2d module found beside this program (or installed for Lua), so
 * the runner itself never links Box2D or libstdc++; `tether atlas [--quick]
 * [--out DIR] [SCRIPT]` runs the speed/accuracy atlas (lua/tether_atlas.lua)
 * with the module built into this program, over the built-in reference
 * scenes or the scene a user's script returns, with the instruction
 * counter of runner_probe.c at hand. */
#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>

#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "runner.h"

/* The folder this program is in; "." when unknown. */
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

typedef struct module_cmd {
    const char *name;   /* the subcommand, for messages */
    const char *module; /* what require loads; its main(argv[2], …) returns the exit status */
    const char *field;  /* package.path or package.cpath, prefixed with … */
    const char *where;  /* … this, where each %s is this program's folder */
    const char *hint;   /* said when the module does not load */
    lua_CFunction probe; /* preloaded as "tether_probe" when not NULL */
} module_cmd;

static int run_module(const module_cmd *c, int argc, char **argv)
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
    if (c->probe) {
        lua_pushcfunction(L, c->probe);
        lua_setfield(L, -2, "tether_probe");
    }
    lua_pop(L, 1);
    char dir[PATH_MAX];
    own_dir(dir, sizeof dir);
    lua_getglobal(L, "package");
    lua_pushfstring(L, c->where, dir, dir);
    lua_getfield(L, -2, c->field);
    lua_concat(L, 2);
    lua_setfield(L, -2, c->field);
    lua_pop(L, 1);
    lua_getglobal(L, "require");
    lua_pushstring(L, c->module);
    int status = 1;
    if (lua_pcall(L, 1, 1, 0) != LUA_OK) {
        fprintf(stderr, PROGNAME " %s: %s%s\n", c->name, c->hint, lua_tostring(L, -1));
    } else {
        lua_getfield(L, -1, "main");
        for (int i = 2; i < argc; i++) lua_pushstring(L, argv[i]);
        if (lua_pcall(L, argc - 2, 1, 0) != LUA_OK) fprintf(stderr, PROGNAME " %s: %s\n", c->name, lua_tostring(L, -1));
        else status = (int)lua_tointeger(L, -1);
    }
    lua_close(L);
    return status;
}

int tr_crosscheck(int argc, char **argv)
{
    static const module_cmd c = {"crosscheck", "tether_box2d", "cpath", "%s/?.so;%s/../lib/lua/5.4/?.so;",
                                 "the tether_box2d module (built by make beside " PROGNAME ") did not load: ", NULL};
    return run_module(&c, argc, argv);
}

/* The atlas's Lua files: the source tree's lua/ beside build/, or the installed share/lua/5.4. */
int tr_atlas(int argc, char **argv)
{
    static const module_cmd c = {"atlas", "tether_atlas", "path", "%s/../lua/?.lua;%s/../share/lua/5.4/?.lua;", "", tr_luaopen_probe};
    return run_module(&c, argc, argv);
}
