/* tether — the atlas's instruction counter (`tether atlas --instructions`,
 * bench/atlas_cg.sh): a Lua module "tether_probe" the runner preloads for
 * the atlas, through which it tells callgrind to count only inside the
 * timed steps and to dump each point's count apart. CPU time moves with the
 * machine's load by up to about 30 % between repeats; instructions do not,
 * so a claim that one setting costs so many times another can be checked to
 * the digit by anyone. Without Valgrind's headers, or outside Valgrind,
 * every call does nothing and running() says false. */
#include <lauxlib.h>
#include <lua.h>

#include <stdbool.h>

#include "runner.h"

#if defined(__has_include)
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define HAVE_CALLGRIND 1
#endif
#endif
#ifndef HAVE_CALLGRIND
#define RUNNING_ON_VALGRIND 0
#define CALLGRIND_TOGGLE_COLLECT
#define CALLGRIND_DUMP_STATS_AT(label) (void)(label)
#endif

static bool counting;

/* probe.count(on): counts instructions from now (true) or stops (false). */
static int p_count(lua_State *L)
{
    luaL_checktype(L, 1, LUA_TBOOLEAN);
    bool on = lua_toboolean(L, 1);
    if (on != counting) {
        CALLGRIND_TOGGLE_COLLECT;
        counting = on;
    }
    return 0;
}

/* probe.dump(label): the instructions counted since the last dump, written
 * apart under this label (callgrind's "desc: Trigger: Client Request: LABEL"). */
static int p_dump(lua_State *L)
{
    const char *label = luaL_checkstring(L, 1);
    CALLGRIND_DUMP_STATS_AT(label);
    return 0;
}

/* probe.running(): whether this process runs under Valgrind. */
static int p_running(lua_State *L)
{
    lua_pushboolean(L, RUNNING_ON_VALGRIND > 0);
    return 1;
}

int tr_luaopen_probe(lua_State *L)
{
    static const luaL_Reg fns[] = {{"count", p_count}, {"dump", p_dump}, {"running", p_running}, {NULL, NULL}};
    luaL_newlib(L, fns);
    return 1;
}
