/* tether — the runner's two ways of showing a script: headless PNG frames
 * (OSMesa) and an interactive SDL2 window. Both call tether.update(dt) at a
 * fixed dt and tether.draw(g) once per frame, g being tether.gfx. */
#include <errno.h>
#include <stdint.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <SDL.h>

#include "lua/lua_render.h"
#include "runner.h"
#include "tether/render.h"

static const tt_color BACKGROUND = { 18, 20, 28, 255 };

/* mkdir -p */
static bool make_dirs(const char *path)
{
    char buf[4096];
    size_t n = strlen(path);
    if (n == 0 || n >= sizeof buf)
        return false;
    memcpy(buf, path, n + 1);
    for (size_t i = 1; i <= n; i++) {
        if (buf[i] == '/' || buf[i] == '\0') {
            char c = buf[i];
            buf[i] = '\0';
            if (mkdir(buf, 0777) != 0 && errno != EEXIST)
                return false;
            buf[i] = c;
        }
    }
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

/* One tether.update(dt); false on a script error or a missing callback. */
static bool update_once(session *s, const options *o, bool *has_update)
{
    bool bad = false;
    if (!*has_update)
        return true;
    if (!tr_get_callback(s->L, s->module, "update", &bad)) {
        if (!bad)
            fprintf(stderr, PROGNAME ": tether.update disappeared\n");
        return false;
    }
    lua_pushnumber(s->L, o->dt);
    return tr_docall(s->L, 1, 0);
}

/* Clears c and lets the script draw on it, worlds at `alpha` between their
 * last two steps (the window's clock; 1 headless); false on a script error. */
static bool draw_frame(session *s, tt_canvas *c, double alpha)
{
    bool bad = false, ok = true;
    tt_canvas_clear(c, BACKGROUND);
    tt_canvas_set_layer(c, TT_LAYER_WORLD);
    tt_canvas_set_color(c, (tt_color){ 255, 255, 255, 255 });
    tl_render_begin(s->L, c);
    tl_render_set_alpha(s->L, alpha);
    if (tr_get_callback(s->L, s->module, "draw", &bad)) {
        lua_getfield(s->L, s->module, "gfx");
        ok = tr_docall(s->L, 1, 0);
    } else if (!bad) {
        tl_render_auto(s->L); /* no tether.draw: every world the script made */
    }
    tl_render_end(s->L);
    tt_canvas_set_layer(c, TT_LAYER_WORLD);
    return ok && !bad;
}

static bool call_unload(session *s)
{
    bool bad = false;
    if (tr_get_callback(s->L, s->module, "unload", &bad))
        return tr_docall(s->L, 0, 0);
    return !bad;
}

static void progress_bar(long done, long total, double elapsed, bool tty, long *next_line)
{
    double eta = done > 0 ? elapsed / (double)done * (double)(total - done) : 0.0;
    if (tty) {
        char bar[31];
        int fill = (int)(30 * done / total);
        for (int i = 0; i < 30; i++)
            bar[i] = i < fill ? '#' : '.';
        bar[30] = '\0';
        fprintf(stderr, "\033[K" PROGNAME ": [%s] %ld/%ld frames, %.1f fps, ETA %.1f s\r", bar, done, total,
                elapsed > 0 ? (double)done / elapsed : 0.0, eta);
        fflush(stderr);
    } else if (done >= *next_line) { /* a log file gets a line per quarter */
        fprintf(stderr, PROGNAME ": %ld/%ld frames, ETA %.1f s\n", done, total, eta);
        *next_line += (total + 3) / 4;
    }
}

int tr_run_frames(session *s, const options *o)
{
    char err[256] = "", path[4200];
    long frames = 0, steps = 0, next_line = 0;
    bool ok = true, bad = false, has_update, tty = isatty(STDERR_FILENO) != 0;
    double *phys = NULL, *draw = NULL, *png = NULL;
    tt_headless *hl = NULL;
    tt_canvas *c = NULL;
    int status = 1;

    if (!make_dirs(o->out)) {
        fprintf(stderr, PROGNAME ": cannot make the folder '%s': %s\n", o->out, strerror(errno));
        return 1;
    }
    hl = tt_headless_create(o->width, o->height, err, sizeof err);
    c = tt_canvas_create(o->width, o->height);
    phys = malloc((size_t)o->frames * sizeof *phys);
    draw = malloc((size_t)o->frames * sizeof *draw);
    png = malloc((size_t)o->frames * sizeof *png);
    if (!hl || !c || !phys || !draw || !png) {
        fprintf(stderr, PROGNAME ": cannot render headless: %s\n", hl ? "out of memory" : err);
        goto done;
    }
    if (!tr_call_load(s))
        goto done;
    has_update = tr_get_callback(s->L, s->module, "update", &bad);
    if (has_update)
        lua_pop(s->L, 1);
    double t0 = tr_now_s();
    while (frames < o->frames && ok && !g_quit && !g_interrupted) {
        double a = tr_now_s();
        for (long k = 0; k < o->every && ok && !g_quit; k++, steps += has_update)
            ok = update_once(s, o, &has_update);
        if (!ok)
            break;
        double b = tr_now_s();
        ok = draw_frame(s, c, 1.0);
        if (!ok)
            break;
        tt_result rr = tt_headless_render(hl, c);
        tl_render_done(s->L);
        if (rr != TT_OK) {
            fprintf(stderr, PROGNAME ": %s\n", tt_headless_error(hl));
            ok = false;
            break;
        }
        double d = tr_now_s();
        snprintf(path, sizeof path, "%s/frame_%05ld.png", o->out, frames);
        if (tt_headless_write_png(hl, path) != TT_OK) {
            fprintf(stderr, PROGNAME ": %s\n", tt_headless_error(hl));
            ok = false;
            break;
        }
        double e = tr_now_s();
        phys[frames] = (b - a) * 1e3 / (double)o->every;
        draw[frames] = (d - b) * 1e3;
        png[frames] = (e - d) * 1e3;
        frames++;
        progress_bar(frames, o->frames, e - t0, tty, &next_line);
    }
    if (tty)
        fprintf(stderr, "\033[K");
    if (ok && g_interrupted)
        fprintf(stderr, PROGNAME ": interrupted after %ld frames\n", frames);
    if (ok)
        ok = call_unload(s);
    if (ok) {
        double total = tr_now_s() - t0;
        printf(PROGNAME ": %ld frames %dx%d in %s/ (%ld steps of %.6f s): physics median %.3f ms/step, "
               "draw median %.2f ms/frame, PNG median %.2f ms/frame, total %.2f s\n",
               frames, o->width, o->height, o->out, steps, o->dt, tr_median(phys, (size_t)frames),
               tr_median(draw, (size_t)frames), tr_median(png, (size_t)frames), total);
        fflush(stdout);
        status = 0;
    }
done:
    free(phys);
    free(draw);
    free(png);
    tt_canvas_destroy(c);
    tt_headless_destroy(hl);
    return status;
}

/* --- the window --------------------------------------------------------------- */

/* Scripted input (--events FILE): SDL events pushed at given frames, so the
 * window's keys and mouse can be driven by a test. */
typedef struct scripted {
    long frame;
    SDL_Event ev;
} scripted;

static scripted *read_events(const char *path, size_t *count)
{
    FILE *f = fopen(path, "r");
    scripted *v = NULL;
    size_t n = 0, cap = 0;
    char line[256];
    int lineno = 0;
    *count = 0;
    if (!f) {
        fprintf(stderr, PROGNAME ": --events: cannot open '%s': %s\n", path, strerror(errno));
        return NULL;
    }
    while (fgets(line, sizeof line, f)) {
        long frame;
        char kind[16], name[64];
        int x = 0, y = 0, got;
        lineno++;
        if (line[0] == '#' || strspn(line, " \t\r\n") == strlen(line))
            continue;
        got = sscanf(line, "%ld %15s %63s %d", &frame, kind, name, &y);
        if (got < 2 || frame < 0)
            goto bad;
        if (n == cap) {
            size_t nc = cap ? cap * 2 : 16;
            scripted *p = realloc(v, nc * sizeof *p);
            if (!p)
                goto bad;
            v = p;
            cap = nc;
        }
        scripted *e = &v[n];
        memset(e, 0, sizeof *e);
        e->frame = frame;
        if (strcmp(kind, "key") == 0 && got >= 3) {
            SDL_Keycode k = SDL_GetKeyFromName(name);
            if (k == SDLK_UNKNOWN)
                goto bad;
            e->ev.type = SDL_KEYDOWN;
            e->ev.key.state = SDL_PRESSED;
            e->ev.key.keysym.sym = k;
        } else if (strcmp(kind, "quit") == 0) {
            e->ev.type = SDL_QUIT;
        } else if (strcmp(kind, "resize") == 0 && sscanf(line, "%ld %15s %d %d", &frame, kind, &x, &y) == 4 &&
                   x >= 16 && y >= 16 && x <= 8192 && y <= 8192) {
            e->ev.type = SDL_USEREVENT; /* not pushed: the window is resized as a user would */
            e->ev.user.code = 1;
            e->ev.user.data1 = (void *)(intptr_t)x;
            e->ev.user.data2 = (void *)(intptr_t)y;
        } else if ((strcmp(kind, "down") == 0 || strcmp(kind, "up") == 0 || strcmp(kind, "move") == 0) &&
                   sscanf(line, "%ld %15s %d %d", &frame, kind, &x, &y) == 4) {
            if (strcmp(kind, "move") == 0) {
                e->ev.type = SDL_MOUSEMOTION;
                e->ev.motion.x = x;
                e->ev.motion.y = y;
            } else {
                e->ev.type = kind[0] == 'd' ? SDL_MOUSEBUTTONDOWN : SDL_MOUSEBUTTONUP;
                e->ev.button.button = SDL_BUTTON_LEFT;
                e->ev.button.state = kind[0] == 'd' ? SDL_PRESSED : SDL_RELEASED;
                e->ev.button.x = x;
                e->ev.button.y = y;
            }
        } else {
            goto bad;
        }
        n++;
    }
    fclose(f);
    *count = n;
    return v ? v : calloc(1, sizeof *v);
bad:
    fprintf(stderr, PROGNAME ": --events: %s:%d: expected 'FRAME key NAME', 'FRAME down|move|up X Y' or 'FRAME quit'\n",
            path, lineno);
    fclose(f);
    free(v);
    return NULL;
}

typedef struct drag {
    bool active, was_pinned;
    tt_particle p;
    double mx, my;         /* cursor, drawable pixels */
    tt_vec2 pos, prev;     /* cursor in world units, now and one frame ago */
    double vt;             /* real seconds between them */
} drag;

/* Moves the dragged particle to the cursor (a pin that follows it). */
static void drag_apply(session *s, drag *d)
{
    if (!d->active)
        return;
    tt_vec2 pos;
    tt_world *w = tl_render_drag_world(s->L, d->mx, d->my, &pos);
    if (!w || !tt_particle_is_valid(w, d->p)) {
        d->active = false;
        tl_render_drag_end(s->L);
        return;
    }
    d->pos = pos;
    tt_particle_set_position(w, d->p, pos, TT_MOVE_RESET_VELOCITY);
}

/* Lets go: the particle gets its mass back and the cursor's velocity. */
static void drag_release(session *s, drag *d)
{
    if (!d->active)
        return;
    tt_vec2 pos;
    tt_world *w = tl_render_drag_world(s->L, d->mx, d->my, &pos);
    if (w && tt_particle_is_valid(w, d->p) && !d->was_pinned) {
        tt_particle_set_pinned(w, d->p, false);
        if (d->vt > 0) {
            tt_vec2 v = { (d->pos.x - d->prev.x) / d->vt, (d->pos.y - d->prev.y) / d->vt };
            double sp = hypot(v.x, v.y), cap = 50.0;
            if (sp > cap) {
                v.x *= cap / sp;
                v.y *= cap / sp;
            }
            if (isfinite(v.x) && isfinite(v.y))
                tt_particle_set_velocity(w, d->p, v);
        }
    }
    d->active = false;
    tl_render_drag_end(s->L);
}

static void status_line(tt_canvas *c, const tt_clock *clock, double fps, bool dragging)
{
    char buf[256];
    int w, h, scale;
    tt_canvas_size(c, &w, &h);
    scale = h >= 700 ? 2 : 1;
    snprintf(buf, sizeof buf, "%s x%g  %.0f fps%s%s | space pause  s step  -/+ speed  0 normal  r reset  drag: move",
             clock->paused ? "PAUSED" : "running", clock->scale, fps, clock->capped ? "  [too slow: time dropped]" : "",
             dragging ? "  [dragging]" : "");
    tt_canvas_set_layer(c, TT_LAYER_SCREEN);
    tt_canvas_set_color(c, (tt_color){ 0, 0, 0, 160 });
    tt_vec2 box[4] = { { 0, h - 12.0 * scale }, { (double)w, h - 12.0 * scale }, { (double)w, (double)h }, { 0, (double)h } };
    tt_canvas_polygon(c, box, 4, true);
    tt_canvas_set_color(c, (tt_color){ 220, 220, 220, 255 });
    tt_canvas_text(c, (tt_vec2){ 4, h - 10.0 * scale }, buf, scale);
    tt_canvas_set_layer(c, TT_LAYER_WORLD);
}

/* What the window's loop keeps from frame to frame besides the script. */
typedef struct window_state {
    bool quit, has_update;
    tt_clock clock;        /* real frame time into steps of the script's dt: pause, speed, single steps */
    long steps;
    drag d;
} window_state;

/* Pushes the scripted events due at this frame; a resize is done at once,
 * as a user would do it. */
static void push_scripted(scripted *events, size_t nevents, size_t *next_event, long frames)
{
    while (*next_event < nevents && events[*next_event].frame <= frames) {
        SDL_Event *e = &events[(*next_event)++].ev;
        if (e->type == SDL_USEREVENT && e->user.code == 1)
            SDL_SetWindowSize(SDL_GL_GetCurrentWindow(), (int)(intptr_t)e->user.data1, (int)(intptr_t)e->user.data2);
        else
            SDL_PushEvent(e);
    }
}

/* The keys; true when r asks for the script from scratch. */
static bool on_key(window_state *ws, SDL_Keycode key)
{
    bool reset = false;
    switch (key) {
    case SDLK_ESCAPE: case SDLK_q: ws->quit = true; break;
    case SDLK_SPACE: case SDLK_p: tt_clock_set_paused(&ws->clock, !ws->clock.paused); break;
    case SDLK_s: case SDLK_RIGHT: tt_clock_set_paused(&ws->clock, true); tt_clock_request_step(&ws->clock); break;
    case SDLK_MINUS: case SDLK_KP_MINUS: tt_clock_set_scale(&ws->clock, fmax(ws->clock.scale / 2, 1.0 / 16)); break;
    case SDLK_PLUS: case SDLK_EQUALS: case SDLK_KP_PLUS: tt_clock_set_scale(&ws->clock, fmin(ws->clock.scale * 2, 8)); break;
    case SDLK_0: case SDLK_1: tt_clock_set_scale(&ws->clock, 1.0); break;
    case SDLK_r: reset = true; break;
    default: break;
    }
    return reset;
}

/* Takes the particle under the cursor (x, y window pixels; drawable
 * pixels are sx, sy of them), pinned while it is dragged. */
static void drag_begin(session *s, drag *d, int x, int y, double sx, double sy)
{
    d->mx = x * sx;
    d->my = y * sy;
    if (tl_render_pick(s->L, d->mx, d->my, 40.0 * sx, &d->p)) {
        tt_world *w = tl_render_drag_world(s->L, d->mx, d->my, &d->pos);
        d->prev = d->pos;
        d->vt = 0;
        d->active = w != NULL;
        if (w) {
            tt_particle_get_pinned(w, d->p, &d->was_pinned);
            tt_particle_set_pinned(w, d->p, true);
        }
    }
}

/* The window's events since the last frame; true when the script is to
 * start from scratch. */
static bool poll_events(session *s, window_state *ws, double sx, double sy)
{
    SDL_Event ev;
    bool reset = false;
    while (SDL_PollEvent(&ev)) {
        switch (ev.type) {
        case SDL_QUIT:
            ws->quit = true;
            break;
        case SDL_KEYDOWN:
            if (on_key(ws, ev.key.keysym.sym))
                reset = true;
            break;
        case SDL_MOUSEBUTTONDOWN:
            if (ev.button.button == SDL_BUTTON_LEFT && !ws->d.active)
                drag_begin(s, &ws->d, ev.button.x, ev.button.y, sx, sy);
            break;
        case SDL_MOUSEBUTTONUP:
            if (ev.button.button == SDL_BUTTON_LEFT)
                drag_release(s, &ws->d);
            break;
        case SDL_MOUSEMOTION:
            ws->d.mx = ev.motion.x * sx;
            ws->d.my = ev.motion.y * sy;
            break;
        default:
            break;
        }
    }
    return reset;
}

/* The script from scratch: a new Lua state; false when it fails. */
static bool restart(session *s, const options *o, window_state *ws)
{
    bool bad = false;
    ws->d.active = false;
    bool ok = call_unload(s);
    tr_session_close(s);
    if (!ok || !tr_session_open(s, o, s->argc, s->argv))
        return false;
    ok = tr_call_load(s);
    ws->has_update = ok && tr_get_callback(s->L, s->module, "update", &bad);
    if (ws->has_update)
        lua_pop(s->L, 1);
    const tt_clock was = ws->clock; /* a fresh start keeps the speed and the pause */
    tt_clock_init(&ws->clock, o->dt, 8);
    tt_clock_set_scale(&ws->clock, was.scale);
    tt_clock_set_paused(&ws->clock, was.paused);
    return ok;
}

/* Steps the physics through `real` seconds of the clock; false on a script error. */
static bool advance(session *s, const options *o, window_state *ws, double real)
{
    bool ok = true;
    if (ws->d.active) {
        ws->d.prev = ws->d.pos;
        ws->d.vt = real * ws->clock.scale;
    }
    drag_apply(s, &ws->d);
    uint32_t n = 0;
    tt_clock_advance(&ws->clock, real, &n); /* at most 8 steps: slower than real time, the rest is dropped */
    for (uint32_t k = 0; ok && k < n; k++) {
        drag_apply(s, &ws->d);
        ok = update_once(s, o, &ws->has_update);
        ws->steps++;
    }
    return ok;
}

int tr_run_window(session *s, const options *o)
{
    char err[256] = "", title[512];
    const char *script = s->argv[o->script];
    snprintf(title, sizeof title, "tether - %s", script);
    tt_window *win = tt_window_open(title, o->width, o->height, err, sizeof err);
    if (!win) {
        fprintf(stderr, PROGNAME ": cannot open a window: %s\n" PROGNAME
                ": use --headless (with --out DIR for PNG frames)\n", err);
        return 1;
    }
    tt_canvas *c = tt_canvas_create(o->width, o->height);
    if (!c) {
        tt_window_close(win);
        fprintf(stderr, PROGNAME ": out of memory\n");
        return 1;
    }
    window_state ws;
    memset(&ws, 0, sizeof ws);
    bool ok = tr_call_load(s), bad = false;
    ws.has_update = ok && tr_get_callback(s->L, s->module, "update", &bad);
    if (ws.has_update)
        lua_pop(s->L, 1);
    tt_clock_init(&ws.clock, o->dt, 8);
    double t_prev = tr_now_s(), t0 = t_prev, fps = 0.0;
    long frames = 0;
    size_t nevents = 0, next_event = 0;
    scripted *events = NULL;
    if (ok && o->events && !(events = read_events(o->events, &nevents)))
        ok = false;

    while (ok && !ws.quit && !g_quit && !g_interrupted) {
        int ww, wh, dw, dh;
        tt_window_size(win, &dw, &dh);
        SDL_GetWindowSize(SDL_GL_GetCurrentWindow(), &ww, &wh);
        double sx = ww > 0 ? (double)dw / ww : 1.0, sy = wh > 0 ? (double)dh / wh : 1.0;
        push_scripted(events, nevents, &next_event, frames);
        if (poll_events(s, &ws, sx, sy)) {
            ok = restart(s, o, &ws);
            continue;
        }
        double now = tr_now_s(), real = now - t_prev;
        t_prev = now;
        if (real > 0.25)
            real = 0.25; /* after a stall: slow down rather than spiral */
        fps = fps == 0.0 ? 1.0 / fmax(real, 1e-6) : 0.95 * fps + 0.05 / fmax(real, 1e-6);
        ok = advance(s, o, &ws, real);
        if (!ok)
            break;
        if (dw > 0 && dh > 0)
            tt_canvas_resize(c, dw, dh);
        ok = draw_frame(s, c, tt_clock_alpha(&ws.clock));
        status_line(c, &ws.clock, fps, ws.d.active);
        frames++;
        bool last = o->frames > 0 && frames >= o->frames;
        if (tt_window_present(win, c, last ? o->screenshot : NULL) != TT_OK) {
            fprintf(stderr, PROGNAME ": %s\n", tt_window_error(win));
            ok = false;
        }
        tl_render_done(s->L);
        if (last)
            break;
        double spent = tr_now_s() - now;
        if (spent < 0.004)
            SDL_Delay(4); /* without vsync, do not spin */
    }
    if (ok && !g_interrupted)
        ok = call_unload(s);
    else if (g_interrupted)
        fprintf(stderr, PROGNAME ": interrupted\n");
    if (ok) {
        printf(PROGNAME ": window: %ld frames, %ld steps of %.6f s in %.2f s%s%s\n", frames, ws.steps, o->dt,
               tr_now_s() - t0, o->screenshot && o->frames > 0 && frames >= o->frames ? ", screenshot " : "",
               o->screenshot && o->frames > 0 && frames >= o->frames ? o->screenshot : "");
        fflush(stdout);
    }
    free(events);
    tt_canvas_destroy(c);
    tt_window_close(win);
    return ok ? 0 : 1;
}
