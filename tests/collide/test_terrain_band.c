/* A terrain's distance band against its definition, computed the slow way:
 * per pixel the Euclidean distance to the nearest pixel of the other state
 * (outside the terrain is empty) less half a pixel, clamped to ±band, then
 * averaged over 7 × 7 pixels (the edge pixel standing for those beyond);
 * and carving against its definition (the pixels whose centres lie in the
 * circle). */
#include "test.h"
#include "tether.h"

#include <stdlib.h>

/* The pixels of a w × h mask as bytes, and pixel (x, y) of them; outside empty. */
typedef struct bytes {
    int w, h;
    unsigned char *p;
} bytes;

static int px(const bytes *m, int x, int y)
{
    return x >= 0 && y >= 0 && x < m->w && y < m->h && m->p[(size_t)y * (size_t)m->w + (size_t)x];
}

/* The raw clamped distance of pixel (x, y), by looking at every pixel within the band (and the ring outside). */
static double raw_slow(const bytes *m, int x, int y, int B)
{
    const int s = px(m, x, y);
    int best = INT32_MAX;
    for (int j = -B - 1; j <= B + 1; j++)
        for (int i = -B - 1; i <= B + 1; i++)
            if (i * i + j * j < best && px(m, x + i, y + j) != s) best = i * i + j * j;
    const double d = fmin(sqrt((double)best) - 0.5, B);
    return s ? -d : d;
}

/* The blurred band of pixel (x, y) from the raw distances of every pixel. */
static double band_slow(const double *raw, int w, int h, int x, int y)
{
    double sum = 0.0;
    for (int j = -3; j <= 3; j++)
        for (int i = -3; i <= 3; i++) {
            const int u = x + i < 0 ? 0 : x + i >= w ? w - 1 : x + i, v = y + j < 0 ? 0 : y + j >= h ? h - 1 : y + j;
            sum += raw[(size_t)v * (size_t)w + (size_t)u];
        }
    return sum / 49.0;
}

/* Blobs, a thin wall, a single pixel, solid touching every border. */
static tt_mask *lumpy(int w, int h)
{
    tt_mask *m = tt_mask_create(w, h, false);
    uint32_t r = 12345;
    for (int k = 0; k < 12; k++) {
        r = r * 1664525u + 1013904223u;
        const int cx = (int)(r >> 8) % w;
        r = r * 1664525u + 1013904223u;
        const int cy = (int)(r >> 8) % h, rad = 2 + (int)(r >> 4) % 9;
        for (int y = cy - rad; y <= cy + rad; y++)
            for (int x = cx - rad; x <= cx + rad; x++)
                if (x >= 0 && y >= 0 && x < w && y < h && (x - cx) * (x - cx) + (y - cy) * (y - cy) <= rad * rad)
                    tt_mask_set(m, x, y, true);
    }
    tt_mask_fill_rect(m, 0, h - 6, w, 6, true);
    tt_mask_fill_rect(m, w / 2, 0, 1, h / 2, true);
    tt_mask_set(m, 7, 5, true);
    return m;
}

/* The band at every pixel centre, read back as the distance there (pixel 1 m). */
static double worst_error(tt_world *w, tt_terrain t, const tt_mask *m, int B)
{
    int mw, mh;
    tt_mask_size(m, &mw, &mh);
    bytes b = {mw, mh, malloc((size_t)mw * (size_t)mh)};
    for (int y = 0; y < mh; y++)
        for (int x = 0; x < mw; x++) b.p[(size_t)y * (size_t)mw + (size_t)x] = (unsigned char)tt_mask_get(m, x, y);
    double *raw = malloc((size_t)mw * (size_t)mh * sizeof *raw), worst = 0.0;
    for (int y = 0; y < mh; y++)
        for (int x = 0; x < mw; x++) raw[(size_t)y * (size_t)mw + (size_t)x] = raw_slow(&b, x, y, B);
    free(b.p);
    for (int y = 0; y < mh; y++)
        for (int x = 0; x < mw; x++) {
            double d;
            tt_terrain_distance(w, t, (tt_vec2){x + 0.5, -(y + 0.5)}, &d, NULL);
            worst = fmax(worst, fabs(d - band_slow(raw, mw, mh, x, y)));
        }
    free(raw);
    return worst;
}

TEST(terrain_band_is_the_clamped_distance_blurred)
{
    tt_world_def wd = tt_world_def_default();
    tt_world *w = tt_world_create(&wd);
    const int bands[] = {5, 10, 32};
    for (int k = 0; k < 3; k++) {
        tt_mask *m = lumpy(120 + 7 * k, 80);
        tt_terrain_def td = tt_terrain_def_default();
        td.solid = m;
        td.pixel = 1.0;
        td.band = bands[k];
        tt_terrain t = tt_terrain_create(w, &td);
        ENSURE(worst_error(w, t, m, bands[k]) < 1e-4);
        /* carved and filled: the same definition on the new pixels */
        ENSURE_OK(tt_terrain_paint_circle(w, t, (tt_vec2){40.3, -30.2}, 13.0, false));
        ENSURE_OK(tt_terrain_paint_circle(w, t, (tt_vec2){3.0, -78.0}, 6.5, false));
        ENSURE_OK(tt_terrain_paint_circle(w, t, (tt_vec2){90.0, -20.0}, 4.0, true));
        const tt_mask *now;
        ENSURE_OK(tt_terrain_get_mask(w, t, &now));
        ENSURE(worst_error(w, t, now, bands[k]) < 1e-4);
        tt_mask_destroy(m);
    }
    tt_world_destroy(w);
}

TEST(terrain_carve_takes_the_pixels_whose_centres_lie_in_the_circle)
{
    tt_world_def wd = tt_world_def_default();
    tt_world *w = tt_world_create(&wd);
    tt_mask *m = tt_mask_create(300, 200, true);
    tt_terrain_def td = tt_terrain_def_default();
    td.solid = m;
    td.pixel = 0.1;
    td.origin = (tt_vec2){-3.0, 2.0};
    tt_terrain t = tt_terrain_create(w, &td);
    const tt_vec2 c[4] = {{2.013, -3.377}, {-3.0, 2.0}, {26.95, -17.95}, {11.5, -8.25}};
    const double r[4] = {1.234, 0.75, 2.01, 0.07};
    for (int k = 0; k < 4; k++) {
        ENSURE_OK(tt_terrain_paint_circle(w, t, c[k], r[k], false));
        const tt_mask *now;
        tt_terrain_get_mask(w, t, &now);
        int wrong = 0;
        for (int y = 0; y < 200; y++)
            for (int x = 0; x < 300; x++) {
                const double dx = -3.0 + (x + 0.5) * 0.1 - c[k].x, dy = 2.0 - (y + 0.5) * 0.1 - c[k].y;
                wrong += tt_mask_get(now, x, y) == (dx * dx + dy * dy <= r[k] * r[k]);
            }
        ENSURE(wrong == 0);
        ENSURE_OK(tt_terrain_paint_circle(w, t, c[k], r[k], true));
        tt_terrain_get_mask(w, t, &now);
        ENSURE(tt_mask_count(now) == 300 * 200);
    }
    tt_mask_destroy(m);
    tt_world_destroy(w);
}
