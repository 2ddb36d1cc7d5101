/* tether — the runner's pieces shared between runner.c (options, the plain
 * fixed-step loop), runner_session.c (the Lua session both ways of running
 * use) and runner_view.c (headless PNG frames and the SDL2 window). */
#ifndef TETHER_RUNNER_H
#define TETHER_RUNNER_H

#include <signal.h>
#include <stdbool.h>

#include <lua.h>

#define PROGNAME "tether"

typedef struct options {
    bool headless;
    long steps;       /* callback steps, default 600 */
    double dt;        /* s, default 1/60 */
    int script;       /* index of the script in argv, 0 if none */
    long frames;      /* frames to render (0: not given) */
    long every;       /* steps per frame, default 1 */
    const char *out;  /* folder for PNG frames (headless) */
    int width, height;/* frame / window size, default 800 x 600 */
    const char *screenshot; /* window: PNG of the last frame */
    const char *events;     /* window: scripted input, "FRAME key NAME | down X Y | move X Y | up X Y | quit" */
} options;

/* One run of the script: its Lua state and where things are on its stack. */
typedef struct session {
    lua_State *L;
    int module;       /* stack index of the tether table */
    int argtable;     /* stack index of arg */
    int nscriptargs;
    int argc;
    char **argv;
} session;

/* runner_session.c */
extern volatile sig_atomic_t g_interrupted;
extern bool g_quit;

int luaopen_tether(lua_State *L);
/* Ctrl-C from now on stops the script or the loop cleanly; a second one kills. */
void tr_catch_interrupt(void);
/* Makes the state, loads the module, runs the script; false (message
 * printed, nothing left open) on failure. */
bool tr_session_open(session *s, const options *o, int argc, char **argv);
void tr_session_close(session *s);
/* Calls tether.load(args) if defined; false on error (printed). */
bool tr_call_load(session *s);
/* Calls the function below its nargs arguments; on error prints the traceback. */
bool tr_docall(lua_State *L, int nargs, int nres);
/* Pushes tether.<name> if it is a function; nil → false; anything else → *bad. */
bool tr_get_callback(lua_State *L, int module, const char *name, bool *bad);
double tr_now_s(void);
double tr_median(double *v, size_t n);

/* runner_view.c */
int tr_run_frames(session *s, const options *o);
int tr_run_window(session *s, const options *o);
/* runner_module.c: `tether crosscheck …` (argv[1] is "crosscheck"): an exit status. */
int tr_crosscheck(int argc, char **argv);
/* `tether atlas …` (argv[1] is "atlas"): an exit status. */
int tr_atlas(int argc, char **argv);
/* The atlas's instruction counter, the Lua module "tether_probe" (runner_probe.c). */
int tr_luaopen_probe(lua_State *L);

#endif
