/* tether — windowed back end: an SDL2 window with an OpenGL context. */
#include "render_internal.h"

#include <SDL.h>
#include <stdlib.h>

struct tt_window {
    SDL_Window *win;
    SDL_GLContext ctx;
    tt__gl *gl;
    uint8_t *shot;
    size_t shot_cap;
    char error[256];
};

static void *getproc(const char *name) { return SDL_GL_GetProcAddress(name); }

tt_window *tt_window_open(const char *title, int width, int height, char *err, size_t n)
{
    char dummy[8];
    if (!err) { err = dummy; n = sizeof dummy; }
    if (width < 1 || height < 1 || width > 16384 || height > 16384) {
        tt__errf(err, n, "tt_window_open: size must be in [1, 16384] x [1, 16384], got %d x %d", width, height);
        return NULL;
    }
    if (SDL_InitSubSystem(SDL_INIT_VIDEO) != 0) {
        tt__errf(err, n, "tt_window_open: SDL cannot start video: %s", SDL_GetError());
        return NULL;
    }
    tt_window *w = calloc(1, sizeof *w);
    if (!w) {
        SDL_QuitSubSystem(SDL_INIT_VIDEO);
        tt__errf(err, n, "tt_window_open: out of memory");
        return NULL;
    }
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 2);
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, 1);
    SDL_GL_SetAttribute(SDL_GL_DOUBLEBUFFER, 1);
    w->win = SDL_CreateWindow(title ? title : "tether", SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, width, height,
                              SDL_WINDOW_OPENGL | SDL_WINDOW_RESIZABLE | SDL_WINDOW_ALLOW_HIGHDPI);
    if (w->win) w->ctx = SDL_GL_CreateContext(w->win);
    if (!w->win || !w->ctx) {
        tt__errf(err, n, "tt_window_open: %s", SDL_GetError());
        tt_window_close(w);
        return NULL;
    }
    SDL_GL_SetSwapInterval(1);
    char e[200] = "";
    w->gl = tt__gl_create(getproc, e, sizeof e);
    if (!w->gl) {
        tt__errf(err, n, "tt_window_open: %s", e);
        tt_window_close(w);
        return NULL;
    }
    return w;
}

void tt_window_close(tt_window *w)
{
    if (!w) return;
    if (w->ctx) {
        SDL_GL_MakeCurrent(w->win, w->ctx);
        tt__gl_destroy(w->gl);
        SDL_GL_DeleteContext(w->ctx);
    }
    if (w->win) SDL_DestroyWindow(w->win);
    free(w->shot);
    free(w);
    SDL_QuitSubSystem(SDL_INIT_VIDEO);
}

void tt_window_size(const tt_window *w, int *width, int *height)
{
    int x = 0, y = 0;
    if (w && w->win) SDL_GL_GetDrawableSize(w->win, &x, &y);
    if (width) *width = x;
    if (height) *height = y;
}

tt_result tt_window_present(tt_window *w, const tt_canvas *c, const char *screenshot)
{
    if (!w) return TT_EINVAL;
    if (!c) { tt__errf(w->error, sizeof w->error, "tt_window_present: canvas is NULL"); return TT_EINVAL; }
    int dw, dh;
    tt_window_size(w, &dw, &dh);
    if (dw < 1 || dh < 1) return TT_OK; /* minimised */
    SDL_GL_MakeCurrent(w->win, w->ctx);
    tt_result r = tt__gl_draw(w->gl, c, dw, dh, w->error, sizeof w->error);
    if (r == TT_OK && screenshot) {
        size_t need = (size_t)dw * dh * 4;
        if (need > w->shot_cap) {
            uint8_t *p = realloc(w->shot, need);
            if (!p) { tt__errf(w->error, sizeof w->error, "tt_window_present: out of memory for the screenshot"); return TT_ENOMEM; }
            w->shot = p;
            w->shot_cap = need;
        }
        tt__gl_read(w->gl, dw, dh, w->shot);
        r = tt_png_write(screenshot, w->shot, dw, dh, (size_t)dw * 4, true, w->error, sizeof w->error);
    }
    SDL_GL_SwapWindow(w->win);
    return r;
}

const char *tt_window_error(const tt_window *w) { return w ? w->error : "window is NULL"; }

unsigned tt_window_draw_calls(const tt_window *w) { return w ? tt__gl_draw_calls(w->gl) : 0; }
