/* The drawing library: the canvas's camera and batches (known answers), and
 * headless frames read back from PNG files (pixels where the scene puts them). */
#include "test.h"
#include "tether/render.h"

#include <png.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Reads a PNG back as RGBA; NULL on failure. */
static uint8_t *read_png(const char *path, int *w, int *h)
{
    png_image im;
    memset(&im, 0, sizeof im);
    im.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&im, path)) return NULL;
    im.format = PNG_FORMAT_RGBA;
    uint8_t *px = malloc(PNG_IMAGE_SIZE(im));
    if (!px || !png_image_finish_read(&im, NULL, px, 0, NULL)) {
        free(px);
        png_image_free(&im);
        return NULL;
    }
    *w = (int)im.width;
    *h = (int)im.height;
    return px;
}

static const uint8_t *pixel(const uint8_t *px, int w, int x, int y) { return px + ((size_t)y * w + x) * 4; }

static void tmp_png(char *path, size_t n)
{
    snprintf(path, n, "%s/tether-test-render-%d.png", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp", (int)getpid());
}

/* A frame of c rendered by hl and read back from its PNG (RGBA, *w × *h); NULL on failure. */
static uint8_t *frame(tt_headless *hl, const tt_canvas *c, int *w, int *h)
{
    char path[512];
    tmp_png(path, sizeof path);
    if (tt_headless_render(hl, c) != TT_OK || tt_headless_write_png(hl, path) != TT_OK) return NULL;
    uint8_t *px = read_png(path, w, h);
    remove(path);
    return px;
}

/* A 64 × 48 headless context; says why when there is none. */
static tt_headless *headless(void)
{
    char err[256] = "";
    tt_headless *hl = tt_headless_create(64, 48, err, sizeof err);
    if (!hl) printf("    %s\n", err);
    return hl;
}

TEST(canvas_camera_maps_world_to_pixels_and_back)
{
    tt_canvas *c = tt_canvas_create(200, 100);
    ENSURE(c != NULL);
    ENSURE_OK(tt_canvas_set_camera(c, (tt_vec2){1, 2}, 10));
    tt_vec2 p = tt_canvas_to_pixels(c, (tt_vec2){1, 2});
    ENSURE_NEAR(p.x, 100, 0);
    ENSURE_NEAR(p.y, 50, 0);
    p = tt_canvas_to_pixels(c, (tt_vec2){2, 3}); /* +1 m right, +1 m up = +10 px right, 10 px up */
    ENSURE_NEAR(p.x, 110, 0);
    ENSURE_NEAR(p.y, 40, 0);
    tt_vec2 q = tt_canvas_to_world(c, p);
    ENSURE_NEAR(q.x, 2, 1e-12);
    ENSURE_NEAR(q.y, 3, 1e-12);
    /* fit: a 10 x 2 m box into 200 x 100 px with 10 px margins → zoom min(180/10, 80/2) = 18 */
    ENSURE_OK(tt_canvas_fit(c, (tt_vec2){-5, 0}, (tt_vec2){5, 2}, 10));
    tt_vec2 ctr;
    double z;
    tt_canvas_get_camera(c, &ctr, &z);
    ENSURE_NEAR(z, 18, 1e-12);
    ENSURE_NEAR(ctr.x, 0, 0);
    ENSURE_NEAR(ctr.y, 1, 0);
    tt_canvas_destroy(c);
}

TEST(canvas_refuses_bad_input_with_a_message)
{
    tt_canvas *c = tt_canvas_create(64, 64);
    ENSURE(c != NULL);
    ENSURE(tt_canvas_create(0, 10) == NULL);
    ENSURE(tt_canvas_set_camera(c, (tt_vec2){NAN, 0}, 1) == TT_EINVAL);
    ENSURE(strstr(tt_canvas_error(c), "tt_canvas_set_camera") != NULL);
    ENSURE(tt_canvas_set_camera(c, (tt_vec2){0, 0}, 0) == TT_EINVAL);
    ENSURE(tt_canvas_circle(c, (tt_vec2){INFINITY, 0}, 1, true) == TT_EINVAL);
    ENSURE(tt_canvas_circle(c, (tt_vec2){0, 0}, -1, true) == TT_EINVAL);
    ENSURE(tt_canvas_circle(c, (tt_vec2){2e12, 0}, 1, true) == TT_EINVAL);
    ENSURE(tt_canvas_text(c, (tt_vec2){0, 0}, "x", 0) == TT_EINVAL);
    tt_vec2 two[2] = {{0, 0}, {1, 1}};
    ENSURE(tt_canvas_polygon(c, two, 2, true) == TT_EINVAL);
    ENSURE(tt_canvas_set_line_width(c, 0) == TT_EINVAL);
    ENSURE(tt_canvas_primitive_count(c) == 0); /* nothing refused was recorded */
    tt_canvas_destroy(c);
}

/* Found by the fuzzer: a denormal zoom was accepted, and g.to_world
 * divided a pixel by it into -Inf. The smallest zoom is 1e-9 px per unit,
 * so every conversion of a legal coordinate stays finite, and fit clamps to it. */
TEST(canvas_zoom_has_a_floor_and_conversions_stay_finite)
{
    tt_canvas *c = tt_canvas_create(64, 64);
    ENSURE(c != NULL);
    ENSURE(tt_canvas_set_camera(c, (tt_vec2){0, 0}, 5e-324) == TT_EINVAL);
    ENSURE(tt_canvas_set_camera(c, (tt_vec2){0, 0}, 0.5e-9) == TT_EINVAL);
    ENSURE_OK(tt_canvas_set_camera(c, (tt_vec2){-TT_MAX_VALUE, TT_MAX_VALUE}, 1e-9));
    tt_vec2 w = tt_canvas_to_world(c, (tt_vec2){-TT_MAX_VALUE, TT_MAX_VALUE});
    ENSURE(isfinite(w.x) && isfinite(w.y));
    ENSURE_OK(tt_canvas_set_camera(c, (tt_vec2){-TT_MAX_VALUE, TT_MAX_VALUE}, 1e9));
    tt_vec2 px = tt_canvas_to_pixels(c, (tt_vec2){TT_MAX_VALUE, -TT_MAX_VALUE});
    ENSURE(isfinite(px.x) && isfinite(px.y));
    /* a huge rectangle in a sliver of frame: the zoom stops at the floor */
    ENSURE_OK(tt_canvas_fit(c, (tt_vec2){-TT_MAX_VALUE, -TT_MAX_VALUE}, (tt_vec2){TT_MAX_VALUE, TT_MAX_VALUE}, 31.9999));
    double z;
    tt_canvas_get_camera(c, NULL, &z);
    ENSURE(z == 1e-9);
    tt_canvas_destroy(c);
}

TEST(canvas_batches_by_kind)
{
    tt_canvas *c = tt_canvas_create(64, 64);
    ENSURE(c != NULL);
    for (int i = 0; i < 1000; i++) ENSURE_OK(tt_canvas_circle(c, (tt_vec2){0, 0}, 0.1, true));
    ENSURE(tt_canvas_primitive_count(c) == 1000);
    ENSURE_OK(tt_canvas_circle(c, (tt_vec2){100, 0}, 1, true)); /* 100 m right of a 64 px canvas at 30 px/m: culled */
    ENSURE(tt_canvas_primitive_count(c) == 1000);
    /* a concave L-shaped hexagon: ear clipping gives n − 2 = 4 triangles */
    tt_vec2 l[6] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
    ENSURE_OK(tt_canvas_polygon(c, l, 6, true));
    ENSURE(tt_canvas_primitive_count(c) == 1004);
    /* a 100 000-point circle outline filled: a fan of n − 2 triangles, at once (no O(n³) ear search) */
    enum { BIG = 100000 };
    tt_vec2 *ring = malloc(BIG * sizeof *ring);
    ENSURE(ring != NULL);
    for (int i = 0; i < BIG; i++) ring[i] = (tt_vec2){cos(i * 2 * M_PI / BIG), sin(i * 2 * M_PI / BIG)};
    tt_result pr = tt_canvas_polygon(c, ring, BIG, true);
    free(ring);
    ENSURE_OK(pr);
    ENSURE(tt_canvas_primitive_count(c) == 1004 + BIG - 2);
    int w, h;
    tt_canvas_text_size("ab\ncde", 2, &w, &h);
    ENSURE(w == (3 * 6 - 1) * 2);
    ENSURE(h == (10 + 9) * 2); /* line pitch 10, glyphs 9 rows high with their descenders */
    tt_canvas_clear(c, (tt_color){0, 0, 0, 255});
    ENSURE(tt_canvas_primitive_count(c) == 0);
    tt_canvas_destroy(c);
}

/* The known tiny scene: black 64 x 48 canvas, camera at (0, 0), 4 px per m;
 * one red particle of radius 1 m at (3, 2) → a disc of radius 4 px centred
 * on pixel (32 + 12, 24 − 8) = (44, 16) from the top-left. */
TEST(headless_frame_shows_the_particle_where_it_is)
{
    tt_headless *hl = headless();
    ENSURE(hl != NULL);
    tt_canvas *c = tt_canvas_create(64, 48);
    tt_world *w = tt_world_create(NULL);
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){3, 2};
    pd.radius = 1;
    ENSURE(tt_particle_create(w, &pd).gen != 0);
    ENSURE_OK(tt_canvas_set_camera(c, (tt_vec2){0, 0}, 4));
    tt_canvas_clear(c, (tt_color){0, 0, 0, 255});
    tt_debug_draw dd = tt_debug_draw_default();
    dd.particle = (tt_color){255, 0, 0, 255};
    ENSURE_OK(tt_canvas_draw_world(c, w, &dd));
    int pw = 0, ph = 0;
    uint8_t *px = frame(hl, c, &pw, &ph);
    ENSURE(px != NULL);
    ENSURE(pw == 64 && ph == 48);
    /* pixel (44, 16) covers [44, 45] x [16, 17]: its centre is 0.5√2 px from the disc's centre */
    const uint8_t *in = pixel(px, pw, 44, 16), *in2 = pixel(px, pw, 42, 17);
    ENSURE(in[0] == 255 && in[1] == 0 && in[2] == 0 && in[3] == 255);
    ENSURE(in2[0] == 255 && in2[3] == 255);
    /* outside the disc: black and opaque (2 px beyond the edge, and the far corner) */
    const uint8_t *out = pixel(px, pw, 44 + 6, 16), *corner = pixel(px, pw, 2, 45);
    ENSURE(out[0] == 0 && out[3] == 255);
    ENSURE(corner[0] == 0 && corner[1] == 0 && corner[2] == 0 && corner[3] == 255);
    /* count the red pixels: a disc of radius 4 px covers about π·16 ≈ 50 */
    int red = 0;
    for (int i = 0; i < pw * ph; i++) red += px[4 * i] > 127;
    ENSURE(red >= 44 && red <= 56);
    free(px);
    tt_world_destroy(w);
    tt_canvas_destroy(c);
    tt_headless_destroy(hl);
}

/* Screen-layer text and a spring line land on the pixels they name; rows are
 * top-down in the PNG although GL reads them bottom-up. */
TEST(headless_frame_text_and_springs)
{
    tt_headless *hl = tt_headless_create(40, 30, NULL, 0);
    ENSURE(hl != NULL);
    tt_canvas *c = tt_canvas_create(40, 30);
    tt_canvas_clear(c, (tt_color){0, 0, 0, 255});
    ENSURE_OK(tt_canvas_set_layer(c, TT_LAYER_SCREEN));
    tt_canvas_set_color(c, (tt_color){0, 255, 0, 255});
    ENSURE_OK(tt_canvas_text(c, (tt_vec2){2, 3}, "I", 1)); /* 'I': top row .###. at y = 3 */
    ENSURE_OK(tt_canvas_set_layer(c, TT_LAYER_WORLD));
    /* a spring at rest from (−4, −2) to (4, −2) m at 2 px/m: a grey line along pixel row y = 15 + 4 = 19 */
    tt_world *w = tt_world_create(NULL);
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){-4, -2};
    tt_particle a = tt_particle_create(w, &pd);
    pd.position = (tt_vec2){4, -2};
    tt_particle b = tt_particle_create(w, &pd);
    tt_spring_def sd = tt_spring_def_default();
    sd.a = a;
    sd.b = b;
    ENSURE(tt_spring_create(w, &sd).gen != 0);
    ENSURE_OK(tt_canvas_set_camera(c, (tt_vec2){0, 0}, 2));
    tt_debug_draw dd = tt_debug_draw_default();
    dd.particles = false;
    ENSURE_OK(tt_canvas_draw_world(c, w, &dd));
    ENSURE_OK(tt_headless_render(hl, c));
    int pw, ph;
    const uint8_t *px = tt_headless_pixels(hl, &pw, &ph); /* bottom-up */
#define TOP(x, y) (px + ((size_t)(ph - 1 - (y)) * pw + (x)) * 4)
    ENSURE(TOP(3, 3)[1] == 255 && TOP(3, 3)[0] == 0);  /* top bar of the I */
    ENSURE(TOP(2, 3)[1] == 0);                         /* left of it */
    ENSURE(TOP(4, 6)[1] == 255);                       /* the stem, row 4 of the glyph */
    ENSURE(TOP(20, 19)[0] == 150 && TOP(20, 19)[1] == 150 && TOP(20, 19)[2] == 160); /* the spring at rest: grey */
    ENSURE(TOP(20, 22)[0] == 0);
    ENSURE(TOP(30, 19)[0] == 0);                       /* beyond its right end (x = 15 + 8 = 23) */
#undef TOP
    tt_world_destroy(w);
    tt_canvas_destroy(c);
    tt_headless_destroy(hl);
}

/* An image is drawn through a texture, its row 0 at the top. */
TEST(headless_frame_draws_an_image)
{
    tt_headless *hl = tt_headless_create(16, 16, NULL, 0);
    ENSURE(hl != NULL);
    tt_canvas *c = tt_canvas_create(16, 16);
    tt_image *img = tt_image_create(2, 2);
    ENSURE(img != NULL);
    uint8_t *p = tt_image_pixels(img);
    static const uint8_t colours[4][4] = {{255, 0, 0, 255}, {0, 255, 0, 255}, {0, 0, 255, 255}, {255, 255, 255, 255}};
    memcpy(p, colours, sizeof colours);
    tt_image_touch(img);
    tt_canvas_clear(c, (tt_color){0, 0, 0, 255});
    ENSURE_OK(tt_canvas_set_layer(c, TT_LAYER_SCREEN));
    ENSURE_OK(tt_canvas_image(c, img, (tt_vec2){0, 0}, (tt_vec2){16, 16}));
    ENSURE_OK(tt_headless_render(hl, c));
    int pw, ph;
    const uint8_t *px = tt_headless_pixels(hl, &pw, &ph);
    const uint8_t *top_left = px + ((size_t)(ph - 1 - 2) * pw + 2) * 4;
    const uint8_t *bottom_right = px + ((size_t)(ph - 1 - 13) * pw + 13) * 4;
    ENSURE(top_left[0] == 255 && top_left[1] == 0 && top_left[2] == 0);
    ENSURE(bottom_right[0] == 255 && bottom_right[1] == 255 && bottom_right[2] == 255);
    tt_image_destroy(img);
    tt_canvas_destroy(c);
    tt_headless_destroy(hl);
}

TEST(list_springs_gives_every_live_handle)
{
    tt_world *w = tt_world_create(NULL);
    tt_particle_def pd = tt_particle_def_default();
    tt_particle p[4];
    for (int i = 0; i < 4; i++) {
        pd.position = (tt_vec2){i, 0};
        p[i] = tt_particle_create(w, &pd);
    }
    tt_spring_def sd = tt_spring_def_default();
    tt_spring s[3];
    for (int i = 0; i < 3; i++) {
        sd.a = p[i];
        sd.b = p[i + 1];
        s[i] = tt_spring_create(w, &sd);
    }
    ENSURE_OK(tt_spring_destroy(w, s[1]));
    tt_spring out[4];
    ENSURE(tt_world_list_springs(w, NULL, 0) == 2);
    ENSURE(tt_world_list_springs(w, out, 4) == 2);
    ENSURE(out[0].index == s[0].index && out[0].gen == s[0].gen);
    ENSURE(out[1].index == s[2].index && out[1].gen == s[2].gen);
    ENSURE(tt_world_list_springs(w, out, 1) == 2); /* returns the count even when cap is smaller */
    tt_world_destroy(w);
}

/* Circles larger than a point sprite may be are quads: same disc, same ring. */
TEST(headless_frame_large_circles_filled_and_outlined)
{
    tt_headless *hl = tt_headless_create(200, 200, NULL, 0);
    ENSURE(hl != NULL);
    tt_canvas *c = tt_canvas_create(200, 200);
    tt_canvas_clear(c, (tt_color){0, 0, 0, 255});
    ENSURE_OK(tt_canvas_set_layer(c, TT_LAYER_SCREEN));
    ENSURE_OK(tt_canvas_circle(c, (tt_vec2){50, 50}, 45, true));   /* a point sprite (≤ 60 px) */
    ENSURE_OK(tt_canvas_set_line_width(c, 4));
    ENSURE_OK(tt_canvas_circle(c, (tt_vec2){100, 100}, 80, false)); /* a quad, outlined */
    ENSURE_OK(tt_headless_render(hl, c));
    int pw, ph;
    const uint8_t *px = tt_headless_pixels(hl, &pw, &ph);
#define AT(x, y) (px[((size_t)(ph - 1 - (y)) * pw + (x)) * 4])
    ENSURE(AT(50, 50) == 255);      /* inside the filled disc */
    ENSURE(AT(50 + 40, 50) == 255);
    ENSURE(AT(50 + 47, 50 + 20) == 0); /* just outside it: (47, 20) is 51 px from the centre */
    ENSURE(AT(100 + 78, 100) == 255); /* on the ring: radius 76…80 */
    ENSURE(AT(100 - 78, 100) == 255);
    ENSURE(AT(100, 100 + 77) == 255);
    ENSURE(AT(100 + 70, 100) == 0);   /* inside the ring */
    ENSURE(AT(100 + 83, 100) == 0);   /* outside it */
#undef AT
    tt_canvas_destroy(c);
    tt_headless_destroy(hl);
}

/* The same scene renders to the same bytes (no uninitialised memory, no
 * order that depends on anything but the calls). */
TEST(headless_frames_are_reproducible)
{
    uint8_t *first = NULL;
    for (int run = 0; run < 2; run++) {
        tt_headless *hl = tt_headless_create(96, 64, NULL, 0);
        ENSURE(hl != NULL);
        tt_canvas *c = tt_canvas_create(96, 64);
        tt_canvas_clear(c, (tt_color){10, 20, 30, 255});
        for (int i = 0; i < 200; i++) {
            tt_canvas_set_color(c, (tt_color){(uint8_t)(i * 7), (uint8_t)(i * 13), 200, 160});
            ENSURE_OK(tt_canvas_circle(c, (tt_vec2){(i * 37) % 11 - 5.0, (i * 17) % 7 - 3.0}, 0.3 + (i % 5) * 0.2, i % 3 != 0));
        }
        tt_vec2 tri[3] = {{-4, -2}, {4, -2}, {0, 3}};
        ENSURE_OK(tt_canvas_polygon(c, tri, 3, false));
        ENSURE_OK(tt_canvas_text(c, (tt_vec2){-4, 3}, "tether 0.1", 1));
        ENSURE_OK(tt_headless_render(hl, c));
        int pw, ph;
        const uint8_t *px = tt_headless_pixels(hl, &pw, &ph);
        if (run == 0) {
            first = malloc((size_t)pw * ph * 4);
            ENSURE(first != NULL);
            memcpy(first, px, (size_t)pw * ph * 4);
        } else {
            int same = memcmp(first, px, (size_t)pw * ph * 4) == 0;
            free(first);
            first = NULL;
            ENSURE(same);
        }
        tt_canvas_destroy(c);
        tt_headless_destroy(hl);
    }
}

/* Batching: 20 000 particles and their 19 999 springs, a HUD: one GL draw
 * call per layer and kind, however many primitives. */
TEST(headless_frame_batches_one_draw_call_per_kind)
{
    tt_headless *hl = tt_headless_create(320, 240, NULL, 0);
    ENSURE(hl != NULL);
    tt_canvas *c = tt_canvas_create(320, 240);
    tt_world *w = tt_world_create(NULL);
    tt_particle_def pd = tt_particle_def_default();
    tt_spring_def sd = tt_spring_def_default();
    tt_particle prev = {0, 0};
    for (int i = 0; i < 20000; i++) {
        pd.position = (tt_vec2){(i % 200) * 0.05 - 5, (i / 200) * 0.05 - 2.5};
        tt_particle p = tt_particle_create(w, &pd);
        if (i > 0) {
            sd.a = prev;
            sd.b = p;
            ENSURE(tt_spring_create(w, &sd).gen != 0);
        }
        prev = p;
    }
    tt_canvas_clear(c, (tt_color){0, 0, 0, 255});
    ENSURE_OK(tt_canvas_fit(c, (tt_vec2){-5, -2.5}, (tt_vec2){5, 2.5}, 0));
    ENSURE_OK(tt_canvas_draw_world(c, w, NULL));
    ENSURE_OK(tt_canvas_set_layer(c, TT_LAYER_SCREEN));
    ENSURE_OK(tt_canvas_text(c, (tt_vec2){4, 4}, "20000 particles", 1));
    ENSURE(tt_canvas_primitive_count(c) > 20000 + 2 * 19999);
    ENSURE_OK(tt_headless_render(hl, c));
    /* world: triangles (springs) + points (particles); screen: text */
    ENSURE(tt_headless_draw_calls(hl) == 3);
    tt_world_destroy(w);
    tt_canvas_destroy(c);
    tt_headless_destroy(hl);
}

/* Found by the Lua fuzzer (seed 1796185241, and once before unreproduced,
 * seed 1796171466): an image destroyed after a canvas recorded it for the
 * frame (a script's finalizer, or img:__gc() called by hand) was read by the
 * frame's draw after it was freed. The canvas now holds what it records:
 * the image is freed when the last canvas holding it is cleared or
 * destroyed, and the frame shows it as it was. (ASan, in the SANITIZE=1
 * build, is what sees a read after free.) */
TEST(an_image_destroyed_while_a_canvas_holds_it_is_drawn_then_freed)
{
    tt_headless *hl = tt_headless_create(8, 8, NULL, 0);
    ENSURE(hl != NULL);
    tt_canvas *c = tt_canvas_create(8, 8);
    tt_canvas_clear(c, (tt_color){0, 0, 0, 255});
    ENSURE_OK(tt_canvas_set_layer(c, TT_LAYER_SCREEN));
    tt_image *img = tt_image_create(2, 2);
    ENSURE(img != NULL);
    uint8_t *px = tt_image_pixels(img);
    for (int i = 0; i < 4; i++) px[4 * i] = 255, px[4 * i + 3] = 255; /* red */
    tt_canvas_set_color(c, (tt_color){255, 255, 255, 255});
    ENSURE_OK(tt_canvas_image(c, img, (tt_vec2){0, 0}, (tt_vec2){8, 8}));
    tt_image_destroy(img); /* held by the canvas: freed at its clear */
    ENSURE_OK(tt_headless_render(hl, c));
    int pw, ph;
    const uint8_t *out = tt_headless_pixels(hl, &pw, &ph);
    ENSURE(out[0] == 255 && out[1] == 0); /* drawn as it was */
    tt_canvas_clear(c, (tt_color){0, 0, 0, 255}); /* frees it */
    ENSURE_OK(tt_headless_render(hl, c));
    /* and held by two canvases, one destroyed: freed with the other */
    tt_canvas *d = tt_canvas_create(8, 8);
    img = tt_image_create(2, 2);
    ENSURE(img != NULL);
    ENSURE_OK(tt_canvas_image(c, img, (tt_vec2){0, 0}, (tt_vec2){8, 8}));
    ENSURE_OK(tt_canvas_image(d, img, (tt_vec2){0, 0}, (tt_vec2){8, 8}));
    tt_image_destroy(img);
    tt_canvas_destroy(d);
    ENSURE_OK(tt_headless_render(hl, c));
    tt_canvas_destroy(c);
    tt_headless_destroy(hl);
}

/* The x of the centroid of the red pixels of a frame of c, px from the left; -1 when none. */
static double red_centroid_x(tt_headless *hl, const tt_canvas *c)
{
    int pw = 0, ph = 0;
    uint8_t *px = frame(hl, c, &pw, &ph);
    if (!px) return -1;
    double sx = 0, n = 0;
    for (int i = 0; i < pw * ph; i++)
        if (px[4 * i] > 127 && px[4 * i + 1] < 64) {
            sx += i % pw + 0.5;
            n++;
        }
    free(px);
    return n > 0 ? sx / n : -1;
}

/* A particle moving at constant velocity, from x = −4 to x = 4 in one step,
 * drawn at alpha 0, 0.5 and 1: at its start, halfway and where it is (the
 * camera puts x = −4, 0, 4 at pixels 16, 32, 48). Alpha outside [0, 1]
 * or NaN is refused, nothing drawn. */
TEST(headless_frame_draws_between_the_last_two_steps_by_alpha)
{
    tt_headless *hl = headless();
    ENSURE(hl != NULL);
    tt_canvas *c = tt_canvas_create(64, 48);
    tt_world_def wd = tt_world_def_default();
    wd.gravity = (tt_vec2){0, 0};
    tt_world *w = tt_world_create(&wd);
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){-4, 0};
    pd.velocity = (tt_vec2){480, 0};
    pd.radius = 1;
    tt_particle p = tt_particle_create(w, &pd);
    ENSURE(p.gen != 0);
    ENSURE_OK(tt_world_set_interpolation(w, true));
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE_OK(tt_canvas_set_camera(c, (tt_vec2){0, 0}, 4));
    tt_debug_draw dd = tt_debug_draw_default();
    ENSURE(dd.alpha == 1.0);
    dd.particle = (tt_color){255, 0, 0, 255};
    const double alpha[3] = {0.0, 0.5, 1.0}, expect[3] = {16, 32, 48};
    for (int k = 0; k < 3; k++) {
        tt_canvas_clear(c, (tt_color){0, 0, 0, 255});
        dd.alpha = alpha[k];
        ENSURE_OK(tt_canvas_draw_world(c, w, &dd));
        double x = red_centroid_x(hl, c);
        printf("    alpha %.1f: drawn at pixel x %.2f (expected %.0f)\n", alpha[k], x, expect[k]);
        ENSURE_NEAR(x, expect[k], 0.5);
    }
    const double bad[3] = {NAN, -0.01, 1.5};
    for (int k = 0; k < 3; k++) {
        tt_canvas_clear(c, (tt_color){0, 0, 0, 255});
        dd.alpha = bad[k];
        ENSURE(tt_canvas_draw_world(c, w, &dd) == TT_EINVAL);
        ENSURE(strstr(tt_canvas_error(c), "alpha must be in [0, 1]") != NULL);
        ENSURE(tt_canvas_primitive_count(c) == 0);
    }
    tt_world_destroy(w);
    tt_canvas_destroy(c);
    tt_headless_destroy(hl);
}

/* The x of the centroid of the lit pixels of row y of a frame of c; -1 when none. */
static double lit_row_x(tt_headless *hl, const tt_canvas *c, int y)
{
    int pw = 0, ph = 0;
    uint8_t *px = frame(hl, c, &pw, &ph);
    if (!px || y >= ph) { free(px); return -1; }
    double sx = 0, n = 0;
    for (int x = 0; x < pw; x++) {
        const uint8_t *p = pixel(px, pw, x, y);
        double lum = p[0] + p[1] + p[2];
        sx += lum * (x + 0.5);
        n += lum;
    }
    free(px);
    return n > 0 ? sx / n : -1;
}

/* A spring from a pinned particle at (0, −4) to one moving from (−4, 4) to
 * (4, 4) in one step: at alpha 0 it crosses y = 0 at x = −2 (pixel 24), at
 * alpha 0.5 at x = 0 (pixel 32), at alpha 1 at x = 2 (pixel 40); row 24 is y = 0. */
TEST(headless_frame_draws_springs_between_the_last_two_steps_by_alpha)
{
    tt_headless *hl = headless();
    ENSURE(hl != NULL);
    tt_canvas *c = tt_canvas_create(64, 48);
    tt_world_def wd = tt_world_def_default();
    wd.gravity = (tt_vec2){0, 0};
    tt_world *w = tt_world_create(&wd);
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){0, -4};
    pd.pinned = true;
    tt_particle a = tt_particle_create(w, &pd);
    pd.pinned = false;
    pd.position = (tt_vec2){-4, 4};
    pd.velocity = (tt_vec2){480, 0};
    tt_particle b = tt_particle_create(w, &pd);
    tt_spring_def sd = tt_spring_def_default();
    sd.a = a;
    sd.b = b;
    sd.stiffness = 0;
    ENSURE(tt_spring_create(w, &sd).gen != 0);
    ENSURE_OK(tt_world_set_interpolation(w, true));
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE_OK(tt_canvas_set_camera(c, (tt_vec2){0, 0}, 4));
    tt_debug_draw dd = tt_debug_draw_default();
    const double alpha[3] = {0.0, 0.5, 1.0}, expect[3] = {24, 32, 40};
    for (int k = 0; k < 3; k++) {
        tt_canvas_clear(c, (tt_color){0, 0, 0, 255});
        dd.alpha = alpha[k];
        ENSURE_OK(tt_canvas_draw_world(c, w, &dd));
        double x = lit_row_x(hl, c, 24);
        printf("    alpha %.1f: the spring crosses row 24 at pixel x %.2f (expected %.0f)\n", alpha[k], x, expect[k]);
        ENSURE_NEAR(x, expect[k], 0.75);
    }
    tt_world_destroy(w);
    tt_canvas_destroy(c);
    tt_headless_destroy(hl);
}
