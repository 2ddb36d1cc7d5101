/* tether — one run of a script (runner.h's session): the Lua state with the
 * module loaded and tether.runner, tether.quit and tether.gfx.load_image
 * added, the script run with its arguments, and the calls into it that the
 * fixed-step loop (runner.c) and the frames and the window (runner_view.c)
 * share: callbacks with a traceback on error, Ctrl-C, the clock. Both of
 * those use this file and it uses neither, so the runner has no circle. */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lua.h>
#include <lauxlib.h>
#include <lualib.h>

#include "lua/lua_render.h"
#include "runner.h"
#include "tether/render.h"

/* --- Ctrl-C: stop the loop (or the script) cleanly, as lua.c does --------- */

static lua_State *g_state = NULL;
volatile sig_atomic_t g_interrupted = 0;

static void stop_hook(lua_State *L, lua_Debug *ar)
{
    (void)ar;
    lua_sethook(L, NULL, 0, 0);
    luaL_error(L, "interrupted!");
}

static void on_sigint(int sig)
{
    int flag = LUA_MASKCALL | LUA_MASKRET | LUA_MASKLINE | LUA_MASKCOUNT;
    signal(sig, SIG_DFL); /* a second Ctrl-C kills the process */
    g_interrupted = 1;
    if (g_state != NULL)
        lua_sethook(g_state, stop_hook, flag, 1);
}

void tr_catch_interrupt(void)
{
    signal(SIGINT, on_sigint);
}

/* --- helpers --------------------------------------------------------------- */

double tr_now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* Message handler: adds a traceback to the error (as lua.c's msghandler). */
static int msghandler(lua_State *L)
{
    const char *msg = lua_tostring(L, 1);
    if (msg == NULL) {
        if (luaL_callmeta(L, 1, "__tostring") && lua_type(L, -1) == LUA_TSTRING)
            return 1;
        msg = lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1));
    }
    luaL_traceback(L, L, msg, 1);
    return 1;
}

/* Calls the function below its nargs arguments; on error prints the
 * traceback and returns false. */
bool tr_docall(lua_State *L, int nargs, int nres)
{
    int base = lua_gettop(L) - nargs;
    int status;
    lua_pushcfunction(L, msghandler);
    lua_insert(L, base);
    g_state = L;
    status = lua_pcall(L, nargs, nres, base);
    g_state = NULL;
    lua_remove(L, base);
    if (status != LUA_OK) {
        fprintf(stderr, PROGNAME ": %s\n", lua_tostring(L, -1));
        fflush(stderr);
        lua_pop(L, 1);
        return false;
    }
    return true;
}

/* Pushes module field `name` if it is a function and returns true; nil is
 * false; anything else is an error (returned as status 2 in *bad). */
bool tr_get_callback(lua_State *L, int module, const char *name, bool *bad)
{
    int t = lua_getfield(L, module, name);
    if (t == LUA_TFUNCTION)
        return true;
    if (t != LUA_TNIL) {
        fprintf(stderr, PROGNAME ": tether.%s must be a function, got %s\n", name, luaL_typename(L, -1));
        *bad = true;
    }
    lua_pop(L, 1);
    return false;
}

/* tether.quit() — ends the update loop after the current call. */
bool g_quit = false;

static int l_quit(lua_State *L)
{
    (void)L;
    g_quit = true;
    return 0;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double tr_median(double *v, size_t n)
{
    if (n == 0)
        return 0.0;
    qsort(v, n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

bool tr_call_load(session *s)
{
    bool bad = false;
    if (tr_get_callback(s->L, s->module, "load", &bad)) {
        lua_createtable(s->L, s->nscriptargs, 0);
        for (int i = 1; i <= s->nscriptargs; i++) {
            lua_rawgeti(s->L, s->argtable, i);
            lua_rawseti(s->L, -2, i);
        }
        if (!tr_docall(s->L, 1, 0))
            return false;
    }
    return !bad;
}

/* tether.gfx.load_image(path) → image, or nil and a message (runner only: it needs libpng) */
static int l_load_image(lua_State *L)
{
    const char *path = tl_checkstring(L, 1);
    char err[512];
    tt_image *img = tt_image_load_png(path, err, sizeof err);
    if (!img) {
        lua_pushnil(L);
        lua_pushstring(L, err);
        return 2;
    }
    tl_push_image(L, img);
    return 1;
}

/* The runner-only drawing functions (tether.gfx.load_image) into the module's gfx table. */
static void register_gfx(lua_State *L, int module)
{
    static const luaL_Reg funcs[] = { { "load_image", l_load_image }, { NULL, NULL } };
    lua_getfield(L, module, "gfx");
    tl_setfuncs(L, funcs, "tether.gfx.");
    lua_pop(L, 1);
}

bool tr_session_open(session *s, const options *o, int argc, char **argv)
{
    lua_State *L;
    const char *script = argv[o->script];

    memset(s, 0, sizeof *s);
    s->argc = argc;
    s->argv = argv;
    L = luaL_newstate();
    if (L == NULL) {
        fprintf(stderr, PROGNAME ": cannot create a Lua state: not enough memory\n");
        return false;
    }
    luaL_openlibs(L);

    /* package.preload.tether = luaopen_tether; tether = require "tether" */
    luaL_getsubtable(L, LUA_REGISTRYINDEX, LUA_PRELOAD_TABLE);
    lua_pushcfunction(L, luaopen_tether);
    lua_setfield(L, -2, "tether");
    lua_pop(L, 1);
    lua_getglobal(L, "require");
    lua_pushliteral(L, "tether");
    if (!tr_docall(L, 1, 1)) {
        lua_close(L);
        return false;
    }
    lua_pushcfunction(L, l_quit);
    lua_setfield(L, -2, "quit");
    /* tether.runner: how this run shows the script (read-only by convention) */
    lua_createtable(L, 0, 8);
    lua_pushstring(L, o->out != NULL ? "frames" : o->headless ? "headless" : "window");
    lua_setfield(L, -2, "mode");
    lua_pushinteger(L, o->width);
    lua_setfield(L, -2, "width");
    lua_pushinteger(L, o->height);
    lua_setfield(L, -2, "height");
    lua_pushnumber(L, o->dt);
    lua_setfield(L, -2, "dt");
    if (o->frames > 0) {
        lua_pushinteger(L, o->frames);
        lua_setfield(L, -2, "frames");
    }
    lua_pushinteger(L, o->every);
    lua_setfield(L, -2, "every");
    if (o->out != NULL) {
        lua_pushstring(L, o->out);
        lua_setfield(L, -2, "out");
    }
    lua_setfield(L, -2, "runner");
    register_gfx(L, lua_gettop(L));
    lua_pushvalue(L, -1);
    lua_setglobal(L, "tether");
    s->module = lua_gettop(L);

    /* arg: arg[0] = script, arg[1..] = its arguments, arg[-k] = what came before */
    s->nscriptargs = argc - o->script - 1;
    lua_createtable(L, s->nscriptargs, o->script + 1);
    for (int i = 0; i < argc; i++) {
        lua_pushstring(L, argv[i]);
        lua_rawseti(L, -2, i - o->script);
    }
    lua_pushvalue(L, -1);
    lua_setglobal(L, "arg");
    s->argtable = lua_gettop(L);

    /* the script, called with its arguments as ... */
    if (luaL_loadfile(L, strcmp(script, "-") == 0 ? NULL : script) != LUA_OK) {
        fprintf(stderr, PROGNAME ": %s\n", lua_tostring(L, -1));
        lua_close(L);
        return false;
    }
    luaL_checkstack(L, s->nscriptargs + 3, "too many arguments to script");
    for (int i = 1; i <= s->nscriptargs; i++)
        lua_rawgeti(L, s->argtable, i);
    if (!tr_docall(L, s->nscriptargs, 0)) {
        lua_close(L);
        return false;
    }
    s->L = L;
    return true;
}

void tr_session_close(session *s)
{
    if (s->L != NULL)
        lua_close(s->L);
    s->L = NULL;
}
