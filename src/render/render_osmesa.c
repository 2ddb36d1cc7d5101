/* tether — headless back end: an off-screen OSMesa (software GL) context. */
#include "render_internal.h"

#include <GL/osmesa.h>
#include <stdlib.h>
#include <string.h>

struct tt_headless {
    OSMesaContext ctx;
    int width, height;
    uint8_t *buf;     /* the colour buffer GL draws into: RGBA, bottom-up */
    tt__gl *gl;
    char error[256];
};

static void *getproc(const char *name)
{
    OSMESAproc p = OSMesaGetProcAddress(name);
    void *v;
    memcpy(&v, &p, sizeof v);
    return v;
}

tt_headless *tt_headless_create(int width, int height, char *err, size_t n)
{
    char dummy[8];
    if (!err) { err = dummy; n = sizeof dummy; }
    if (width < 1 || height < 1 || width > 16384 || height > 16384) {
        tt__errf(err, n, "tt_headless_create: size must be in [1, 16384] x [1, 16384], got %d x %d", width, height);
        return NULL;
    }
    tt_headless *h = calloc(1, sizeof *h);
    if (!h) { tt__errf(err, n, "tt_headless_create: out of memory"); return NULL; }
    h->width = width;
    h->height = height;
    h->buf = malloc((size_t)width * height * 4);
    h->ctx = OSMesaCreateContextExt(OSMESA_RGBA, 0, 0, 0, NULL);
    if (!h->buf || !h->ctx) {
        tt__errf(err, n, "tt_headless_create: %s", h->buf ? "OSMesa could not make a context" : "out of memory");
        tt_headless_destroy(h);
        return NULL;
    }
    if (!OSMesaMakeCurrent(h->ctx, h->buf, GL_UNSIGNED_BYTE, width, height)) {
        tt__errf(err, n, "tt_headless_create: OSMesaMakeCurrent failed");
        tt_headless_destroy(h);
        return NULL;
    }
    char e[200] = "";
    h->gl = tt__gl_create(getproc, e, sizeof e);
    if (!h->gl) {
        tt__errf(err, n, "tt_headless_create: %s", e);
        tt_headless_destroy(h);
        return NULL;
    }
    return h;
}

void tt_headless_destroy(tt_headless *h)
{
    if (!h) return;
    if (h->ctx) {
        if (h->gl) OSMesaMakeCurrent(h->ctx, h->buf, GL_UNSIGNED_BYTE, h->width, h->height);
        tt__gl_destroy(h->gl);
        OSMesaDestroyContext(h->ctx);
    }
    free(h->buf);
    free(h);
}

tt_result tt_headless_render(tt_headless *h, const tt_canvas *c)
{
    if (!h) return TT_EINVAL;
    if (!c) { tt__errf(h->error, sizeof h->error, "tt_headless_render: canvas is NULL"); return TT_EINVAL; }
    if (c->width != h->width || c->height != h->height) {
        tt__errf(h->error, sizeof h->error, "tt_headless_render: canvas is %d x %d, the context %d x %d", c->width,
                 c->height, h->width, h->height);
        return TT_EINVAL;
    }
    if (OSMesaGetCurrentContext() != h->ctx && !OSMesaMakeCurrent(h->ctx, h->buf, GL_UNSIGNED_BYTE, h->width, h->height)) {
        tt__errf(h->error, sizeof h->error, "tt_headless_render: OSMesaMakeCurrent failed");
        return TT_ESTATE;
    }
    tt_result r = tt__gl_draw(h->gl, c, h->width, h->height, h->error, sizeof h->error);
    /* OSMesa renders straight into buf: waiting is enough, no read-back copy */
    tt__gl_finish(h->gl);
    return r;
}

const uint8_t *tt_headless_pixels(const tt_headless *h, int *width, int *height)
{
    if (width) *width = h ? h->width : 0;
    if (height) *height = h ? h->height : 0;
    return h ? h->buf : NULL;
}

tt_result tt_headless_write_png(tt_headless *h, const char *path)
{
    if (!h) return TT_EINVAL;
    return tt_png_write(path, h->buf, h->width, h->height, (size_t)h->width * 4, true, h->error, sizeof h->error);
}

const char *tt_headless_error(const tt_headless *h) { return h ? h->error : "headless context is NULL"; }

unsigned tt_headless_draw_calls(const tt_headless *h) { return h ? tt__gl_draw_calls(h->gl) : 0; }
