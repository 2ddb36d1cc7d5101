/* tether — the canvas: camera, colour, and per-kind vertex arrays. No GL here:
 * a draw call only appends vertices (in pixels) to the array of its kind. */
#include "render_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_SIDE 16384

int tt__errf(char *buf, size_t n, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int r = vsnprintf(buf, n, fmt, ap);
    va_end(ap);
    return r;
}

static tt_result fail(const tt_canvas *c, tt_result code, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static tt_result fail(const tt_canvas *c, tt_result code, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(((tt_canvas *)c)->error, sizeof c->error, fmt, ap);
    va_end(ap);
    return code;
}

static bool fin(double x) { return x - x == 0.0 && fabs(x) <= TT_MAX_VALUE; }
static bool vok(tt_vec2 v) { return fin(v.x) && fin(v.y); }

/* Grows an array so n + more elements fit. */
static bool reserve(void **v, size_t *cap, size_t n, size_t more, size_t elem)
{
    if (n + more <= *cap) return true;
    size_t nc = *cap ? *cap : 1024;
    while (nc < n + more) nc *= 2;
    void *p = realloc(*v, nc * elem);
    if (!p) return false;
    *v = p;
    *cap = nc;
    return true;
}
#define RESERVE(arr, more) reserve((void **)&(arr).v, &(arr).cap, (arr).n, (more), sizeof *(arr).v)

tt_canvas *tt_canvas_create(int width, int height)
{
    if (width < 1 || height < 1 || width > MAX_SIDE || height > MAX_SIDE) return NULL;
    tt_canvas *c = calloc(1, sizeof *c);
    if (!c) return NULL;
    c->width = width;
    c->height = height;
    c->background = (tt_color){0, 0, 0, 255};
    c->center = (tt_vec2){0, 0};
    c->zoom = 30.0;
    c->color = (tt_color){255, 255, 255, 255};
    c->layer = TT_LAYER_WORLD;
    c->line_width = 1.5;
    return c;
}

static void release_images(tt_canvas *c);

void tt_canvas_destroy(tt_canvas *c)
{
    if (!c) return;
    release_images(c);
    for (int l = 0; l < 2; l++) {
        free(c->layers[l].tris.v);
        free(c->layers[l].circles.v);
        free(c->layers[l].points.v);
        free(c->layers[l].text.v);
        free(c->layers[l].images.v);
    }
    free(c);
}

const char *tt_canvas_error(const tt_canvas *c) { return c ? c->error : "canvas is NULL"; }

tt_result tt_canvas_resize(tt_canvas *c, int width, int height)
{
    if (!c) return TT_EINVAL;
    if (width < 1 || height < 1 || width > MAX_SIDE || height > MAX_SIDE)
        return fail(c, TT_EINVAL, "tt_canvas_resize: size must be in [1, %d] x [1, %d], got %d x %d", MAX_SIDE, MAX_SIDE,
                    width, height);
    c->width = width;
    c->height = height;
    return TT_OK;
}

void tt_canvas_size(const tt_canvas *c, int *width, int *height)
{
    if (width) *width = c ? c->width : 0;
    if (height) *height = c ? c->height : 0;
}

static void image_free(tt_image *img)
{
    free(img->rgba);
    free(img);
}

/* The canvas lets go of the images it recorded: one destroyed meanwhile is
 * freed by the last canvas that held it. */
static void release_images(tt_canvas *c)
{
    for (int l = 0; l < 2; l++) {
        tt__layer *L = &c->layers[l];
        for (size_t i = 0; i < L->images.n; i++) {
            tt_image *img = L->images.v[i].img;
            if (--img->held == 0 && img->doomed) image_free(img);
        }
        L->images.n = 0;
    }
}

void tt_canvas_clear(tt_canvas *c, tt_color background)
{
    if (!c) return;
    c->background = background;
    release_images(c);
    for (int l = 0; l < 2; l++) {
        c->layers[l].tris.n = 0;
        c->layers[l].circles.n = 0;
        c->layers[l].points.n = 0;
        c->layers[l].text.n = 0;
    }
    c->oom = false;
}

tt_result tt_canvas_set_camera(tt_canvas *c, tt_vec2 center, double zoom)
{
    if (!c) return TT_EINVAL;
    if (!vok(center)) return fail(c, TT_EINVAL, "tt_canvas_set_camera: centre must be finite, |x| <= %g", TT_MAX_VALUE);
    /* a floor as well as a ceiling: pixel ↔ world conversions of any legal value stay finite */
    if (!(zoom >= 1e-9 && zoom <= 1e9)) return fail(c, TT_EINVAL, "tt_canvas_set_camera: zoom must be in [1e-09, 1e+09] px per unit, got %g", zoom);
    c->center = center;
    c->zoom = zoom;
    return TT_OK;
}

void tt_canvas_get_camera(const tt_canvas *c, tt_vec2 *center, double *zoom)
{
    if (center) *center = c ? c->center : (tt_vec2){0, 0};
    if (zoom) *zoom = c ? c->zoom : 0.0;
}

tt_result tt_canvas_fit(tt_canvas *c, tt_vec2 lo, tt_vec2 hi, double margin_px)
{
    if (!c) return TT_EINVAL;
    if (!vok(lo) || !vok(hi)) return fail(c, TT_EINVAL, "tt_canvas_fit: corners must be finite, |x| <= %g", TT_MAX_VALUE);
    if (!(hi.x > lo.x && hi.y > lo.y)) return fail(c, TT_EINVAL, "tt_canvas_fit: the rectangle is empty (hi must be above and right of lo)");
    if (!(margin_px >= 0.0 && 2 * margin_px < c->width && 2 * margin_px < c->height))
        return fail(c, TT_EINVAL, "tt_canvas_fit: margin must be in [0, half the smaller side), got %g", margin_px);
    double zx = (c->width - 2 * margin_px) / (hi.x - lo.x), zy = (c->height - 2 * margin_px) / (hi.y - lo.y);
    double z = zx < zy ? zx : zy;
    if (z > 1e9) z = 1e9;
    if (z < 1e-9) z = 1e-9;
    return tt_canvas_set_camera(c, (tt_vec2){0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y)}, z);
}

tt_vec2 tt_canvas_to_pixels(const tt_canvas *c, tt_vec2 p)
{
    return (tt_vec2){0.5 * c->width + (p.x - c->center.x) * c->zoom, 0.5 * c->height - (p.y - c->center.y) * c->zoom};
}

tt_vec2 tt_canvas_to_world(const tt_canvas *c, tt_vec2 px)
{
    return (tt_vec2){c->center.x + (px.x - 0.5 * c->width) / c->zoom, c->center.y - (px.y - 0.5 * c->height) / c->zoom};
}

void tt_canvas_set_color(tt_canvas *c, tt_color color) { if (c) c->color = color; }
tt_color tt_canvas_get_color(const tt_canvas *c) { return c ? c->color : (tt_color){0, 0, 0, 0}; }

tt_result tt_canvas_set_layer(tt_canvas *c, tt_layer layer)
{
    if (!c) return TT_EINVAL;
    if (layer != TT_LAYER_WORLD && layer != TT_LAYER_SCREEN) return fail(c, TT_EINVAL, "tt_canvas_set_layer: unknown layer %d", (int)layer);
    c->layer = layer;
    return TT_OK;
}

tt_layer tt_canvas_get_layer(const tt_canvas *c) { return c ? c->layer : TT_LAYER_WORLD; }

tt_result tt_canvas_set_line_width(tt_canvas *c, double px)
{
    if (!c) return TT_EINVAL;
    if (!(px >= 0.1 && px <= 1000.0)) return fail(c, TT_EINVAL, "tt_canvas_set_line_width: width must be in [0.1, 1000] px, got %g", px);
    c->line_width = px;
    return TT_OK;
}

/* Layer point → pixel, and the layer's length scale. */
static inline void to_px(const tt_canvas *c, tt_vec2 p, float *x, float *y)
{
    if (c->layer == TT_LAYER_WORLD) {
        *x = (float)(0.5 * c->width + (p.x - c->center.x) * c->zoom);
        *y = (float)(0.5 * c->height - (p.y - c->center.y) * c->zoom);
    } else {
        *x = (float)p.x;
        *y = (float)p.y;
    }
}
static inline double scale_of(const tt_canvas *c) { return c->layer == TT_LAYER_WORLD ? c->zoom : 1.0; }
static inline void put_rgba(uint8_t *d, tt_color k) { d[0] = k.r; d[1] = k.g; d[2] = k.b; d[3] = k.a; }

static tt_result oom(tt_canvas *c, const char *fn)
{
    c->oom = true;
    return fail(c, TT_ENOMEM, "%s: out of memory", fn);
}

/* Appends one circle; the hot path of a debug draw (no checks: callers check). */
static inline bool add_circle(tt_canvas *c, float cx, float cy, float r, float inner, tt_color k)
{
    if (cx + r + 1.0f < 0.0f || cy + r + 1.0f < 0.0f || cx - r - 1.0f > (float)c->width || cy - r - 1.0f > (float)c->height)
        return true; /* entirely off the canvas: culled */
    tt__layer *L = &c->layers[c->layer];
    if (r <= TT__POINT_MAX_RADIUS) {
        if (!RESERVE(L->points, 1)) return false;
        tt__vpoint *p = L->points.v + L->points.n++;
        p->x = cx;
        p->y = cy;
        p->r = r;
        p->inner = inner;
        put_rgba(p->rgba, k);
        return true;
    }
    if (!RESERVE(L->circles, 4)) return false;
    float e = r + 0.5f; /* room for the anti-aliased edge, which ends at r + 0.5 */
    static const float sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
    tt__vcircle *v = L->circles.v + L->circles.n;
    for (int i = 0; i < 4; i++) {
        v[i].x = cx + sx[i] * e;
        v[i].y = cy + sy[i] * e;
        v[i].lx = sx[i] * e;
        v[i].ly = sy[i] * e;
        v[i].r = r;
        v[i].inner = inner;
        put_rgba(v[i].rgba, k);
    }
    L->circles.n += 4;
    return true;
}

tt_result tt_canvas_circle(tt_canvas *c, tt_vec2 center, double radius, bool filled)
{
    if (!c) return TT_EINVAL;
    if (!vok(center)) return fail(c, TT_EINVAL, "tt_canvas_circle: centre must be finite, |x| <= %g", TT_MAX_VALUE);
    if (!(radius >= 0.0 && radius <= TT_MAX_VALUE)) return fail(c, TT_EINVAL, "tt_canvas_circle: radius must be in [0, %g], got %g", TT_MAX_VALUE, radius);
    float x, y;
    to_px(c, center, &x, &y);
    double r = radius * scale_of(c);
    if (r > 4.0 * (c->width + c->height)) r = 4.0 * (c->width + c->height); /* no bigger than needed to cover the canvas */
    float inner = filled ? -1.0f : (float)(r - c->line_width);
    if (!filled && inner < 0.0f) inner = 0.0f;
    if (!add_circle(c, x, y, (float)r, inner, c->color)) return oom(c, "tt_canvas_circle");
    return TT_OK;
}

/* A quad along a → b, `w` px wide, as two triangles. */
static bool add_segment(tt__layer *L, int into_text, float ax, float ay, float bx, float by, float w, tt_color ca,
                        tt_color cb)
{
    tt__solid_array *arr = into_text ? &L->text : &L->tris;
    if (!reserve((void **)&arr->v, &arr->cap, arr->n, 6, sizeof *arr->v)) return false;
    float dx = bx - ax, dy = by - ay, len = sqrtf(dx * dx + dy * dy);
    float nx, ny;
    if (len > 0.0f) {
        nx = -dy / len * 0.5f * w;
        ny = dx / len * 0.5f * w;
    } else { /* a dot */
        nx = 0.0f;
        ny = 0.5f * w;
        ax -= 0.5f * w;
        bx += 0.5f * w;
    }
    tt__vsolid *v = arr->v + arr->n;
    float px[4] = {ax + nx, bx + nx, bx - nx, ax - nx}, py[4] = {ay + ny, by + ny, by - ny, ay - ny};
    static const int idx[6] = {0, 1, 2, 0, 2, 3};
    for (int i = 0; i < 6; i++) {
        int k = idx[i];
        v[i].x = px[k];
        v[i].y = py[k];
        put_rgba(v[i].rgba, (k == 1 || k == 2) ? cb : ca);
    }
    arr->n += 6;
    return true;
}

tt_result tt_canvas_line2(tt_canvas *c, tt_vec2 a, tt_vec2 b, tt_color ca, tt_color cb)
{
    if (!c) return TT_EINVAL;
    if (!vok(a) || !vok(b)) return fail(c, TT_EINVAL, "tt_canvas_line: ends must be finite, |x| <= %g", TT_MAX_VALUE);
    float ax, ay, bx, by;
    to_px(c, a, &ax, &ay);
    to_px(c, b, &bx, &by);
    if (!add_segment(&c->layers[c->layer], 0, ax, ay, bx, by, (float)c->line_width, ca, cb)) return oom(c, "tt_canvas_line");
    return TT_OK;
}

tt_result tt_canvas_line(tt_canvas *c, tt_vec2 a, tt_vec2 b)
{
    if (!c) return TT_EINVAL;
    return tt_canvas_line2(c, a, b, c->color, c->color);
}

static double cross(const float *x, const float *y, int a, int b, int d)
{
    return (double)(x[b] - x[a]) * (y[d] - y[a]) - (double)(y[b] - y[a]) * (x[d] - x[a]);
}

static bool in_triangle(const float *x, const float *y, int a, int b, int d, int p, double sign)
{
    return sign * cross(x, y, a, b, p) >= 0 && sign * cross(x, y, b, d, p) >= 0 && sign * cross(x, y, d, a, p) >= 0;
}

static bool add_tri(tt__layer *L, const float *x, const float *y, int a, int b, int d, tt_color k)
{
    if (!RESERVE(L->tris, 3)) return false;
    tt__vsolid *v = L->tris.v + L->tris.n;
    int id[3] = {a, b, d};
    for (int i = 0; i < 3; i++) {
        v[i].x = x[id[i]];
        v[i].y = y[id[i]];
        put_rgba(v[i].rgba, k);
    }
    L->tris.n += 3;
    return true;
}

tt_result tt_canvas_polygon(tt_canvas *c, const tt_vec2 *pts, int n, bool filled)
{
    const char *fn = "tt_canvas_polygon";
    if (!c) return TT_EINVAL;
    if (!pts || n < 3 || n > 1000000) return fail(c, TT_EINVAL, "%s: need 3 to 1000000 points, got %d", fn, pts ? n : 0);
    for (int i = 0; i < n; i++)
        if (!vok(pts[i])) return fail(c, TT_EINVAL, "%s: point %d must be finite, |x| <= %g", fn, i, TT_MAX_VALUE);
    float *x = malloc((size_t)n * 2 * sizeof *x);
    int *idx = malloc((size_t)n * sizeof *idx);
    if (!x || !idx) { free(x); free(idx); return oom(c, fn); }
    float *y = x + n;
    for (int i = 0; i < n; i++) to_px(c, pts[i], &x[i], &y[i]);
    tt__layer *L = &c->layers[c->layer];
    bool ok = true;
    if (!filled) {
        for (int i = 0; i < n && ok; i++) {
            int j = (i + 1) % n;
            ok = add_segment(L, 0, x[i], y[i], x[j], y[j], (float)c->line_width, c->color, c->color);
        }
    } else {
        /* ear clipping (worst case O(n³): only up to 256 points, plenty for shapes);
         * a fan when no ear is found (self-crossing input) or for longer outlines */
        double area = 0;
        for (int i = 0; i < n; i++) {
            int j = (i + 1) % n;
            area += (double)x[i] * y[j] - (double)x[j] * y[i];
        }
        double sign = area >= 0 ? 1.0 : -1.0;
        for (int i = 0; i < n; i++) idx[i] = i;
        int m = n > 256 ? 0 : n;
        if (m == 0)
            for (int i = 1; i + 1 < n && ok; i++) ok = add_tri(L, x, y, 0, i, i + 1, c->color);
        while (m > 3 && ok) {
            bool cut = false;
            for (int i = 0; i < m && !cut; i++) {
                int a = idx[(i + m - 1) % m], b = idx[i], d = idx[(i + 1) % m];
                if (sign * cross(x, y, a, b, d) <= 0) continue; /* reflex (or flat) corner */
                bool empty = true;
                for (int k = 0; k < m && empty; k++) {
                    int p = idx[k];
                    if (p != a && p != b && p != d && in_triangle(x, y, a, b, d, p, sign)) empty = false;
                }
                if (!empty) continue;
                ok = add_tri(L, x, y, a, b, d, c->color);
                memmove(idx + i, idx + i + 1, (size_t)(m - i - 1) * sizeof *idx);
                m--;
                cut = true;
            }
            if (!cut) { /* no ear: fan the rest */
                for (int i = 1; i + 1 < m && ok; i++) ok = add_tri(L, x, y, idx[0], idx[i], idx[i + 1], c->color);
                m = 0;
            }
        }
        if (m == 3 && ok) ok = add_tri(L, x, y, idx[0], idx[1], idx[2], c->color);
    }
    free(x);
    free(idx);
    return ok ? TT_OK : oom(c, fn);
}

void tt_canvas_text_size(const char *text, int scale, int *width, int *height)
{
    int cols = 0, best = 0, lines = text && *text ? 1 : 0;
    for (const char *s = text ? text : ""; *s; s++) {
        if (*s == '\n') { lines++; cols = 0; continue; }
        cols++;
        if (cols > best) best = cols;
    }
    if (width) *width = best ? (best * TT_FONT_ADVANCE - 1) * scale : 0;
    if (height) *height = lines ? ((lines - 1) * TT_FONT_LINE + TT_FONT_H) * scale : 0;
}

tt_result tt_canvas_text(tt_canvas *c, tt_vec2 pos, const char *text, int scale)
{
    if (!c) return TT_EINVAL;
    if (!text) return fail(c, TT_EINVAL, "tt_canvas_text: text is NULL");
    if (!vok(pos)) return fail(c, TT_EINVAL, "tt_canvas_text: position must be finite, |x| <= %g", TT_MAX_VALUE);
    if (scale < 1 || scale > 64) return fail(c, TT_EINVAL, "tt_canvas_text: scale must be in [1, 64], got %d", scale);
    float x0, y0;
    to_px(c, pos, &x0, &y0);
    x0 = floorf(x0 + 0.5f); /* whole pixels: crisp glyphs */
    y0 = floorf(y0 + 0.5f);
    tt__layer *L = &c->layers[c->layer];
    float s = (float)scale, cx = x0, cy = y0;
    for (const unsigned char *p = (const unsigned char *)text; *p; p++) {
        if (*p == '\n') { cx = x0; cy += TT_FONT_LINE * s; continue; }
        const uint8_t *g = tt__font_glyph(*p);
        for (int row = 0; row < TT_FONT_H; row++) {
            /* one quad per run of set pixels in the row */
            int col = 0;
            while (col < TT_FONT_W) {
                if (!(g[row] & (0x10 >> col))) { col++; continue; }
                int start = col;
                while (col < TT_FONT_W && (g[row] & (0x10 >> col))) col++;
                float ya = cy + (row + 0.5f) * s;
                if (!add_segment(L, 1, cx + start * s, ya, cx + col * s, ya, s, c->color, c->color)) return oom(c, "tt_canvas_text");
            }
        }
        cx += TT_FONT_ADVANCE * s;
    }
    return TT_OK;
}

tt_result tt_canvas_image(tt_canvas *c, tt_image *img, tt_vec2 lo, tt_vec2 hi)
{
    if (!c) return TT_EINVAL;
    if (!img) return fail(c, TT_EINVAL, "tt_canvas_image: image is NULL");
    if (!vok(lo) || !vok(hi)) return fail(c, TT_EINVAL, "tt_canvas_image: corners must be finite, |x| <= %g", TT_MAX_VALUE);
    tt__layer *L = &c->layers[c->layer];
    if (!RESERVE(L->images, 1)) return oom(c, "tt_canvas_image");
    tt__imgdraw *d = &L->images.v[L->images.n++];
    d->img = img;
    img->held++; /* until the next clear: a destroy meanwhile waits for it (release_images) */
    /* image row 0 is its top: in the world layer (y up) the top is at hi.y, on the screen at lo.y */
    double top = c->layer == TT_LAYER_WORLD ? hi.y : lo.y, bottom = c->layer == TT_LAYER_WORLD ? lo.y : hi.y;
    tt_vec2 corner[4] = {{lo.x, top}, {hi.x, top}, {hi.x, bottom}, {lo.x, bottom}};
    static const float u[4] = {0, 1, 1, 0}, v[4] = {0, 0, 1, 1};
    for (int i = 0; i < 4; i++) {
        to_px(c, corner[i], &d->q[i].x, &d->q[i].y);
        d->q[i].u = u[i];
        d->q[i].v = v[i];
        put_rgba(d->q[i].rgba, c->color);
    }
    return TT_OK;
}

size_t tt_canvas_primitive_count(const tt_canvas *c)
{
    if (!c) return 0;
    size_t n = 0;
    for (int l = 0; l < 2; l++)
        n += c->layers[l].tris.n / 3 + c->layers[l].circles.n / 4 + c->layers[l].points.n + c->layers[l].text.n / 3 + c->layers[l].images.n;
    return n;
}

/* --- images (pixels only; PNG reading is in render_png.c) ------------------ */

static uint64_t g_next_image_id = 1; /* drawing state, never simulation state */

tt_image *tt_image_create(int width, int height)
{
    if (width < 1 || height < 1 || width > MAX_SIDE || height > MAX_SIDE) return NULL;
    tt_image *img = calloc(1, sizeof *img);
    if (!img) return NULL;
    img->rgba = calloc((size_t)width * height, 4);
    if (!img->rgba) { free(img); return NULL; }
    img->width = width;
    img->height = height;
    img->id = __atomic_fetch_add(&g_next_image_id, 1, __ATOMIC_RELAXED);
    return img;
}

void tt_image_destroy(tt_image *img)
{
    if (!img) return;
    if (img->held) img->doomed = true; /* a canvas still draws it this frame: freed when it lets go */
    else image_free(img);
}

void tt_image_size(const tt_image *img, int *width, int *height)
{
    if (width) *width = img ? img->width : 0;
    if (height) *height = img ? img->height : 0;
}

uint8_t *tt_image_pixels(tt_image *img) { return img ? img->rgba : NULL; }
void tt_image_touch(tt_image *img) { if (img) img->version++; }
