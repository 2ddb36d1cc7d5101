/* tether — the runner: runs a Lua script with the tether module loaded.
 *
 *   tether [--headless] [--steps N] [--dt DT] [--help] [--version] script.lua [args…]
 *
 * Opens the standard libraries, preloads the module (package.preload.tether)
 * and sets the global `tether` to it, sets `arg` as lua5.4 does, and runs the
 * script. If the script defined tether.update, calls tether.load(args) (if
 * defined), then tether.update(dt) at a fixed dt for N steps (or until
 * tether.quit()), then tether.unload() (if defined), and prints one summary
 * line. A script without callbacks just runs. An error prints the traceback
 * and exits with status 1. */
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <lua.h>
#include <lauxlib.h>
#include <lualib.h>

#include "tether.h"

int luaopen_tether(lua_State *L);

#define PROGNAME "tether"
#define MAX_STEPS 10000000L

typedef struct options {
    bool headless;
    long steps;       /* callback steps, default 600 */
    double dt;        /* s, default 1/60 */
    int script;       /* index of the script in argv, 0 if none */
} options;

/* --- Ctrl-C: stop the loop (or the script) cleanly, as lua.c does --------- */

static lua_State *g_state = NULL;
static volatile sig_atomic_t g_interrupted = 0;

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

/* --- helpers --------------------------------------------------------------- */

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static void usage(FILE *f)
{
    fprintf(f,
            "usage: " PROGNAME " [options] script.lua [args...]\n"
            "Runs a Lua 5.4 script with the tether physics module loaded (global 'tether').\n"
            "If the script defines tether.update(dt), it is called at a fixed step:\n"
            "tether.load(args) first, tether.unload() last; tether.quit() stops early.\n"
            "Options:\n"
            "  --headless   no window (the default for now: the window arrives with the renderer)\n"
            "  --steps N    number of tether.update calls, 1..%ld (default 600)\n"
            "  --dt DT      fixed step in seconds, 0 < DT <= 10 (default 1/60)\n"
            "  --help       show this help and exit\n"
            "  --version    show the version and exit\n"
            "  --           stop handling options\n",
            MAX_STEPS);
}

static int bad_usage(const char *fmt, const char *what)
{
    fprintf(stderr, PROGNAME ": ");
    fprintf(stderr, fmt, what);
    fprintf(stderr, "\n");
    usage(stderr);
    return 2;
}

/* Parses the options; returns -1 to go on, or an exit status. */
static int parse_args(int argc, char **argv, options *o)
{
    int i;
    o->headless = false;
    o->steps = 600;
    o->dt = 1.0 / 60.0;
    o->script = 0;
    for (i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *val = NULL;
        char *end = NULL;
        if (strcmp(a, "--") == 0) {
            i++;
            break;
        }
        if (a[0] != '-' || a[1] == '\0') /* a script name, or "-" for stdin */
            break;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            return 0;
        }
        if (strcmp(a, "--version") == 0 || strcmp(a, "-v") == 0) {
            printf(PROGNAME " %s (%s)\n", tt_version(), LUA_RELEASE);
            return 0;
        }
        if (strcmp(a, "--headless") == 0) {
            o->headless = true;
            continue;
        }
        if (strncmp(a, "--steps", 7) == 0 && (a[7] == '\0' || a[7] == '=')) {
            val = a[7] == '=' ? a + 8 : (i + 1 < argc ? argv[++i] : NULL);
            if (val == NULL)
                return bad_usage("%s needs a value", "--steps");
            errno = 0;
            o->steps = strtol(val, &end, 10);
            if (errno != 0 || end == val || *end != '\0' || o->steps < 1 || o->steps > MAX_STEPS)
                return bad_usage("--steps: an integer in [1, 10000000] expected, got '%s'", val);
            continue;
        }
        if (strncmp(a, "--dt", 4) == 0 && (a[4] == '\0' || a[4] == '=')) {
            val = a[4] == '=' ? a + 5 : (i + 1 < argc ? argv[++i] : NULL);
            if (val == NULL)
                return bad_usage("%s needs a value", "--dt");
            errno = 0;
            o->dt = strtod(val, &end);
            if (errno != 0 || end == val || *end != '\0' || !isfinite(o->dt) || o->dt <= 0.0 || o->dt > 10.0)
                return bad_usage("--dt: a number in (0, 10] expected, got '%s'", val);
            continue;
        }
        return bad_usage("unknown option '%s'", a);
    }
    if (i >= argc)
        return bad_usage("%s", "no script given");
    o->script = i;
    return -1;
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
static bool docall(lua_State *L, int nargs, int nres)
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
static bool get_callback(lua_State *L, int module, const char *name, bool *bad)
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
static bool g_quit = false;

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

/* The fixed-step loop. Returns the exit status. */
static int run_loop(lua_State *L, int module, const options *o, int nscriptargs, int argtable)
{
    bool bad = false, ok = true, progress = isatty(STDERR_FILENO) != 0, shown = false;
    double *ms = NULL, total = 0.0, t0, next_progress = 1.0;
    size_t cap = 0;
    long done = 0;

    if (!o->headless)
        fprintf(stderr, PROGNAME ": no window yet (it arrives with the renderer): running headless\n");

    if (get_callback(L, module, "load", &bad)) {
        lua_createtable(L, nscriptargs, 0);
        for (int i = 1; i <= nscriptargs; i++) {
            lua_rawgeti(L, argtable, i);
            lua_rawseti(L, -2, i);
        }
        if (!docall(L, 1, 0))
            return 1;
    }
    if (bad)
        return 1;

    t0 = now_s();
    while (done < o->steps && !g_quit && !g_interrupted) {
        double a, b;
        if (!get_callback(L, module, "update", &bad)) {
            if (!bad)
                fprintf(stderr, PROGNAME ": tether.update disappeared at step %ld\n", done + 1);
            ok = false;
            break;
        }
        if ((size_t)done == cap) {
            size_t ncap = cap == 0 ? 1024 : cap * 2;
            double *p;
            if (ncap > (size_t)o->steps) ncap = (size_t)o->steps;
            p = realloc(ms, ncap * sizeof *p);
            if (p == NULL) {
                fprintf(stderr, PROGNAME ": out of memory\n");
                free(ms);
                return 1;
            }
            ms = p;
            cap = ncap;
        }
        lua_pushnumber(L, o->dt);
        a = now_s();
        ok = docall(L, 1, 0);
        b = now_s();
        if (!ok)
            break;
        ms[done++] = (b - a) * 1e3;
        total += (b - a) * 1e3;
        if (progress && b - t0 >= next_progress) {
            double eta = (b - t0) / (double)done * (double)(o->steps - done);
            /* ends with \r: the cursor waits at column 0, so a line the
             * script prints next overwrites the progress line */
            fprintf(stderr, "\033[K" PROGNAME ": step %ld/%ld (%.0f%%), ETA %.1f s\r", done, o->steps,
                    100.0 * (double)done / (double)o->steps, eta);
            fflush(stderr);
            shown = true;
            next_progress = b - t0 + 0.25;
        }
    }
    if (shown) {
        fprintf(stderr, "\033[K");
        fflush(stderr);
    }
    if (ok && g_interrupted)
        fprintf(stderr, PROGNAME ": interrupted after %ld steps\n", done);
    if (ok && get_callback(L, module, "unload", &bad))
        ok = docall(L, 0, 0);
    if (bad)
        ok = false;

    if (!ok) {
        /* the traceback has been printed: no summary after a script error */
    } else if (done > 0) {
        double median, p95;
        size_t n = (size_t)done, k;
        qsort(ms, n, sizeof *ms, cmp_double);
        median = n % 2 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
        k = (size_t)ceil(0.95 * (double)n);
        p95 = ms[k > 0 ? k - 1 : 0];
        printf(PROGNAME ": %ld steps of %.6f s, median %.3f ms/step, p95 %.3f ms, total %.1f ms\n",
               done, o->dt, median, p95, total);
    } else {
        printf(PROGNAME ": 0 steps of %.6f s\n", o->dt);
    }
    fflush(stdout);
    free(ms);
    return ok ? 0 : 1;
}

int main(int argc, char **argv)
{
    options o;
    lua_State *L;
    int status, module, argtable, nscriptargs;
    const char *script;
    bool has_update, bad = false;

    status = parse_args(argc, argv, &o);
    if (status >= 0)
        return status;
    script = argv[o.script];

    L = luaL_newstate();
    if (L == NULL) {
        fprintf(stderr, PROGNAME ": cannot create a Lua state: not enough memory\n");
        return 1;
    }
    signal(SIGINT, on_sigint);
    luaL_openlibs(L);

    /* package.preload.tether = luaopen_tether; tether = require "tether" */
    luaL_getsubtable(L, LUA_REGISTRYINDEX, LUA_PRELOAD_TABLE);
    lua_pushcfunction(L, luaopen_tether);
    lua_setfield(L, -2, "tether");
    lua_pop(L, 1);
    lua_getglobal(L, "require");
    lua_pushliteral(L, "tether");
    if (!docall(L, 1, 1)) {
        lua_close(L);
        return 1;
    }
    lua_pushcfunction(L, l_quit);
    lua_setfield(L, -2, "quit");
    lua_pushvalue(L, -1);
    lua_setglobal(L, "tether");
    module = lua_gettop(L);

    /* arg: arg[0] = script, arg[1..] = its arguments, arg[-k] = what came before */
    nscriptargs = argc - o.script - 1;
    lua_createtable(L, nscriptargs, o.script + 1);
    for (int i = 0; i < argc; i++) {
        lua_pushstring(L, argv[i]);
        lua_rawseti(L, -2, i - o.script);
    }
    lua_pushvalue(L, -1);
    lua_setglobal(L, "arg");
    argtable = lua_gettop(L);

    /* the script, called with its arguments as ... */
    if (luaL_loadfile(L, strcmp(script, "-") == 0 ? NULL : script) != LUA_OK) {
        fprintf(stderr, PROGNAME ": %s\n", lua_tostring(L, -1));
        lua_close(L);
        return 1;
    }
    luaL_checkstack(L, nscriptargs + 3, "too many arguments to script");
    for (int i = 1; i <= nscriptargs; i++)
        lua_rawgeti(L, argtable, i);
    if (!docall(L, nscriptargs, 0)) {
        lua_close(L);
        return 1;
    }

    status = 0;
    has_update = get_callback(L, module, "update", &bad);
    if (has_update) {
        lua_pop(L, 1);
        status = run_loop(L, module, &o, nscriptargs, argtable);
    } else if (bad) {
        status = 1;
    }
    lua_close(L);
    return status;
}
