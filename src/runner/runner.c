/* tether — the runner: runs a Lua script with the tether module loaded.
 *
 *   tether [--headless] [--steps N] [--dt DT] [--frames N] [--every K] [--out DIR]
 *          [--size WxH] [--screenshot FILE] [--events FILE] [--help] [--version] script.lua [args…]
 *   tether crosscheck [--quick] [--out DIR] [SCENE]     (runner_module.c)
 *   tether atlas [--quick] [--out DIR] [SCRIPT]          (runner_module.c)
 *
 * Opens the standard libraries, preloads the module (package.preload.tether)
 * and sets the global `tether` to it, sets `arg` as lua5.4 does, and runs the
 * script. If the script defined tether.update, calls tether.load(args) (if
 * defined), then tether.update(dt) at a fixed dt for N steps (or until
 * tether.quit()), then tether.unload() (if defined), and prints one summary
 * line. A script without callbacks just runs. An error prints the traceback
 * and exits with status 1.
 *
 * With a tether.draw(g) callback the script is also seen: in a window
 * (SDL2, the default when the script has callbacks) or, with --headless
 * --out DIR, as PNG frames DIR/frame_00000.png … (runner_view.c). The
 * session both use (the Lua state, calls into the script, Ctrl-C) is
 * runner_session.c. */
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
#include "runner.h"

#define MAX_STEPS 10000000L

static void usage(FILE *f)
{
    fprintf(f,
            "usage: " PROGNAME " [options] script.lua [args...]\n"
            "Runs a Lua 5.4 script with the tether physics module loaded (global 'tether').\n"
            "If the script defines tether.update(dt), it is called at a fixed step:\n"
            "tether.load(args) first, tether.unload() last; tether.quit() stops early.\n"
            "Options:\n"
            "  --headless   no window; with --out, frames go to PNG files\n"
            "  --steps N    number of tether.update calls, 1..%ld (default 600; headless, no --out)\n"
            "  --dt DT      fixed step in seconds, 0 < DT <= 10 (default 1/60)\n"
            "  --frames N   frames to draw, 1..1000000: headless, N PNG files; in a window, quit after N\n"
            "  --every K    tether.update calls per frame with --out, 1..100000 (default 1)\n"
            "  --out DIR    (with --headless) write DIR/frame_00000.png ... (default 60 frames)\n"
            "  --size WxH   frame or window size in pixels (default 800x600)\n"
            "  --screenshot FILE  (window) write the last frame shown to FILE (PNG)\n"
            "  --events FILE      (window) scripted input: lines 'FRAME key NAME', 'FRAME down X Y',\n"
            "               'FRAME move X Y', 'FRAME up X Y', 'FRAME quit' (X, Y window pixels)\n"
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

static void default_options(options *o)
{
    o->headless = false;
    o->steps = 600;
    o->dt = 1.0 / 60.0;
    o->script = 0;
    o->frames = 0;
    o->every = 1;
    o->out = NULL;
    o->width = 800;
    o->height = 600;
    o->screenshot = NULL;
    o->events = NULL;
}

/* What an option parser returns besides an exit status: the option was
 * taken (go on with the next argument), or it is not one of its own. */
enum { OPT_NEXT = -1, OPT_NOT_MINE = -2 };

/* The numeric options, --steps, --dt, --frames, --every, at argv[*i]
 * (*i moves past a separate value). */
static int parse_number_option(int argc, char **argv, int *i, options *o)
{
    const char *a = argv[*i];
    const char *val = NULL;
    char *end = NULL;
    if (strncmp(a, "--steps", 7) == 0 && (a[7] == '\0' || a[7] == '=')) {
        val = a[7] == '=' ? a + 8 : (*i + 1 < argc ? argv[++*i] : NULL);
        if (val == NULL)
            return bad_usage("%s needs a value", "--steps");
        errno = 0;
        o->steps = strtol(val, &end, 10);
        if (errno != 0 || end == val || *end != '\0' || o->steps < 1 || o->steps > MAX_STEPS)
            return bad_usage("--steps: an integer in [1, 10000000] expected, got '%s'", val);
        return OPT_NEXT;
    }
    if (strncmp(a, "--dt", 4) == 0 && (a[4] == '\0' || a[4] == '=')) {
        val = a[4] == '=' ? a + 5 : (*i + 1 < argc ? argv[++*i] : NULL);
        if (val == NULL)
            return bad_usage("%s needs a value", "--dt");
        errno = 0;
        o->dt = strtod(val, &end);
        if (errno != 0 || end == val || *end != '\0' || !isfinite(o->dt) || o->dt <= 0.0 || o->dt > 10.0)
            return bad_usage("--dt: a number in (0, 10] expected, got '%s'", val);
        return OPT_NEXT;
    }
    if (strncmp(a, "--frames", 8) == 0 && (a[8] == '\0' || a[8] == '=')) {
        val = a[8] == '=' ? a + 9 : (*i + 1 < argc ? argv[++*i] : NULL);
        if (val == NULL)
            return bad_usage("%s needs a value", "--frames");
        errno = 0;
        o->frames = strtol(val, &end, 10);
        if (errno != 0 || end == val || *end != '\0' || o->frames < 1 || o->frames > 1000000)
            return bad_usage("--frames: an integer in [1, 1000000] expected, got '%s'", val);
        return OPT_NEXT;
    }
    if (strncmp(a, "--every", 7) == 0 && (a[7] == '\0' || a[7] == '=')) {
        val = a[7] == '=' ? a + 8 : (*i + 1 < argc ? argv[++*i] : NULL);
        if (val == NULL)
            return bad_usage("%s needs a value", "--every");
        errno = 0;
        o->every = strtol(val, &end, 10);
        if (errno != 0 || end == val || *end != '\0' || o->every < 1 || o->every > 100000)
            return bad_usage("--every: an integer in [1, 100000] expected, got '%s'", val);
        return OPT_NEXT;
    }
    return OPT_NOT_MINE;
}

/* The options naming a folder or a file, --out, --screenshot, --events,
 * and --size, at argv[*i] (*i moves past a separate value). */
static int parse_name_option(int argc, char **argv, int *i, options *o)
{
    const char *a = argv[*i];
    const char *val = NULL;
    char *end = NULL;
    if (strncmp(a, "--out", 5) == 0 && (a[5] == '\0' || a[5] == '=')) {
        val = a[5] == '=' ? a + 6 : (*i + 1 < argc ? argv[++*i] : NULL);
        if (val == NULL || *val == '\0')
            return bad_usage("%s needs a folder", "--out");
        o->out = val;
        return OPT_NEXT;
    }
    if (strncmp(a, "--screenshot", 12) == 0 && (a[12] == '\0' || a[12] == '=')) {
        val = a[12] == '=' ? a + 13 : (*i + 1 < argc ? argv[++*i] : NULL);
        if (val == NULL || *val == '\0')
            return bad_usage("%s needs a file name", "--screenshot");
        o->screenshot = val;
        return OPT_NEXT;
    }
    if (strncmp(a, "--events", 8) == 0 && (a[8] == '\0' || a[8] == '=')) {
        val = a[8] == '=' ? a + 9 : (*i + 1 < argc ? argv[++*i] : NULL);
        if (val == NULL || *val == '\0')
            return bad_usage("%s needs a file name", "--events");
        o->events = val;
        return OPT_NEXT;
    }
    if (strncmp(a, "--size", 6) == 0 && (a[6] == '\0' || a[6] == '=')) {
        long w, h;
        val = a[6] == '=' ? a + 7 : (*i + 1 < argc ? argv[++*i] : NULL);
        if (val == NULL)
            return bad_usage("%s needs a value", "--size");
        errno = 0;
        w = strtol(val, &end, 10);
        if (errno == 0 && end != val && (*end == 'x' || *end == 'X')) {
            const char *hs = end + 1;
            h = strtol(hs, &end, 10);
            if (errno == 0 && end != hs && *end == '\0' && w >= 16 && w <= 8192 && h >= 16 && h <= 8192) {
                o->width = (int)w;
                o->height = (int)h;
                return OPT_NEXT;
            }
        }
        return bad_usage("--size: WxH with each side in [16, 8192] expected, got '%s'", val);
    }
    return OPT_NOT_MINE;
}

/* Parses the options; returns -1 to go on, or an exit status. */
static int parse_args(int argc, char **argv, options *o)
{
    int i;
    default_options(o);
    for (i = 1; i < argc; i++) {
        const char *a = argv[i];
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
        int st = parse_number_option(argc, argv, &i, o);
        if (st == OPT_NOT_MINE)
            st = parse_name_option(argc, argv, &i, o);
        if (st == OPT_NOT_MINE)
            return bad_usage("unknown option '%s'", a);
        if (st != OPT_NEXT)
            return st;
    }
    if (i >= argc)
        return bad_usage("%s", "no script given");
    if (o->headless && o->frames > 0 && o->out == NULL)
        return bad_usage("%s", "--frames with --headless needs --out DIR (where the PNG frames go)");
    if (!o->headless && o->out != NULL)
        return bad_usage("%s", "--out needs --headless (a window shows its frames; --screenshot saves one)");
    if (o->headless && o->events != NULL)
        return bad_usage("%s", "--events is for the window");
    if (o->headless && o->screenshot != NULL)
        return bad_usage("%s", "--screenshot is for the window; headless frames go to --out DIR");
    if (o->out != NULL && o->frames == 0)
        o->frames = 60;
    o->script = i;
    return -1;
}


/* The fixed-step loop. Returns the exit status. */
static int run_loop(session *s, const options *o)
{
    lua_State *L = s->L;
    int module = s->module;
    bool bad = false, ok = true, progress = isatty(STDERR_FILENO) != 0, shown = false;
    double *ms = NULL, total = 0.0, t0, next_progress = 1.0;
    size_t cap = 0;
    long done = 0;

    if (!tr_call_load(s))
        return 1;

    t0 = tr_now_s();
    while (done < o->steps && !g_quit && !g_interrupted) {
        double a, b;
        if (!tr_get_callback(L, module, "update", &bad)) {
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
        a = tr_now_s();
        ok = tr_docall(L, 1, 0);
        b = tr_now_s();
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
    if (ok && tr_get_callback(L, module, "unload", &bad))
        ok = tr_docall(L, 0, 0);
    if (bad)
        ok = false;

    if (!ok) {
        /* the traceback has been printed: no summary after a script error */
    } else if (done > 0) {
        double median, p95;
        size_t n = (size_t)done, k;
        median = tr_median(ms, n); /* sorts ms: the p95 is read from it */
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


/* A window can open: an X11 or Wayland display, or a video driver chosen explicitly. */
static bool has_display(void)
{
    const char *v[] = { "DISPLAY", "WAYLAND_DISPLAY", "SDL_VIDEODRIVER" };
    for (int i = 0; i < 3; i++) {
        const char *e = getenv(v[i]);
        if (e != NULL && *e != '\0')
            return true;
    }
    return false;
}

int main(int argc, char **argv)
{
    options o;
    session s;
    int status;
    bool has_update, has_draw, bad = false;

    if (argc > 1 && strcmp(argv[1], "crosscheck") == 0)
        return tr_crosscheck(argc, argv);
    if (argc > 1 && strcmp(argv[1], "atlas") == 0)
        return tr_atlas(argc, argv);
    status = parse_args(argc, argv, &o);
    if (status >= 0)
        return status;
    tr_catch_interrupt();
    if (!tr_session_open(&s, &o, argc, argv))
        return 1;

    status = 0;
    has_update = tr_get_callback(s.L, s.module, "update", &bad);
    if (has_update)
        lua_pop(s.L, 1);
    has_draw = tr_get_callback(s.L, s.module, "draw", &bad);
    if (has_draw)
        lua_pop(s.L, 1);
    if (bad)
        status = 1;
    else if (o.out != NULL)
        status = tr_run_frames(&s, &o);
    else if (!o.headless && (has_update || has_draw) && !has_display() && o.frames == 0 && o.screenshot == NULL &&
             o.events == NULL) {
        /* no display to open a window on (a CI job, ssh): the plain loop, as --headless */
        fprintf(stderr, PROGNAME ": no display (DISPLAY and WAYLAND_DISPLAY are not set): running headless; "
                        "--headless --out DIR writes PNG frames\n");
        if (has_update)
            status = run_loop(&s, &o);
    } else if (!o.headless && (has_update || has_draw))
        status = tr_run_window(&s, &o);
    else if (has_update)
        status = run_loop(&s, &o);
    tr_session_close(&s);
    return status;
}
