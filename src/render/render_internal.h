/* tether — private declarations of the drawing library (render_*.c). */
#ifndef TETHER_RENDER_INTERNAL_H
#define TETHER_RENDER_INTERNAL_H

#include "tether/render.h"

#include <stdarg.h>

/* Vertex formats, all in pixels (origin top-left, y down), colour packed
 * as bytes r, g, b, a in memory. */
typedef struct tt__vsolid {   /* lines, polygons, text: plain triangles */
    float x, y;
    uint8_t rgba[4];
} tt__vsolid;

typedef struct tt__vcircle {  /* one corner of a circle's quad */
    float x, y;               /* corner position, px */
    float lx, ly;             /* corner relative to the centre, px */
    float r, inner;           /* outer radius; inner radius (−1 when filled), px */
    uint8_t rgba[4];
} tt__vcircle;

typedef struct tt__vpoint {  /* a small circle as one point sprite */
    float x, y;               /* centre, px */
    float r, inner;           /* outer radius; inner radius (−1 when filled), px */
    uint8_t rgba[4];
} tt__vpoint;

typedef struct tt__vtex {     /* textured quads */
    float x, y, u, v;
    uint8_t rgba[4];
} tt__vtex;

typedef struct tt__solid_array { tt__vsolid *v; size_t n, cap; } tt__solid_array;
typedef struct tt__circle_array { tt__vcircle *v; size_t n, cap; } tt__circle_array;
typedef struct tt__point_array { tt__vpoint *v; size_t n, cap; } tt__point_array;

/* Circles up to this radius (px) are point sprites (one vertex each); larger ones are quads. */
#ifndef TT__POINT_MAX_RADIUS
#define TT__POINT_MAX_RADIUS 60.0f
#endif

typedef struct tt__imgdraw {
    tt_image *img;
    tt__vtex q[4];            /* corners: lo-lo, hi-lo, hi-hi, lo-hi */
} tt__imgdraw;

typedef struct tt__layer {
    tt__solid_array tris;     /* 3 per triangle */
    tt__point_array points;   /* small circles: 1 vertex each */
    tt__circle_array circles; /* large circles: 4 per circle, corners in quad order */
    tt__solid_array text;     /* 3 per triangle */
    struct { tt__imgdraw *v; size_t n, cap; } images;
} tt__layer;

struct tt_canvas {
    int width, height;
    tt_color background;
    tt_vec2 center;
    double zoom;
    tt_color color;
    tt_layer layer;
    double line_width;
    tt__layer layers[2];
    bool oom;                 /* an append failed since the last clear */
    char error[200];
};

struct tt_image {
    int width, height;
    uint8_t *rgba;
    uint64_t id;              /* unique per image, for the back ends' texture caches */
    uint32_t version;         /* bumped by tt_image_touch */
    uint32_t held;            /* records of it in canvases since their last clear */
    bool doomed;              /* destroyed while held: the last canvas to let go frees it */
};

/* The built-in font: 9 rows per glyph (7 above the baseline, 2 of descenders),
 * bit 4 = leftmost column (render_font.c). */
enum { TT_FONT_W = 5, TT_FONT_H = 9, TT_FONT_ADVANCE = 6, TT_FONT_LINE = 10 };
const uint8_t *tt__font_glyph(int ch);

/* The GL drawing shared by both back ends (render_gl.c). The functions are
 * loaded through getproc, so one process can hold an OSMesa context and a
 * GLX one without mixing their entry points. */
typedef struct tt__gl tt__gl;
tt__gl *tt__gl_create(void *(*getproc)(const char *name), char *err, size_t n);
void tt__gl_destroy(tt__gl *g);
/* Draws c into the current framebuffer of size w × h. */
tt_result tt__gl_draw(tt__gl *g, const tt_canvas *c, int w, int h, char *err, size_t n);
/* Reads the framebuffer (RGBA, bottom-up) into out (w·h·4 bytes). */
void tt__gl_read(tt__gl *g, int w, int h, uint8_t *out);
/* Waits until drawing is done. */
void tt__gl_finish(tt__gl *g);
/* glDraw* calls the last tt__gl_draw made. */
unsigned tt__gl_draw_calls(const tt__gl *g);

int tt__errf(char *buf, size_t n, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

#endif
