/* Masks themselves: sizes and their limits, pixels, whole-mask operations,
 * shapes drawn in, images and colour keys, rotated and scaled copies. */
#include "test.h"
#include "tether.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

TEST(mask_create_refuses_bad_sizes)
{
    ENSURE(tt_mask_create(0, 5, false) == NULL);
    ENSURE(strstr(tt_mask_last_error(), "tt_mask_create") != NULL);
    ENSURE(tt_mask_create(5, -1, false) == NULL);
    ENSURE(tt_mask_create(TT_MASK_MAX_SIDE + 1, 1, false) == NULL);
    tt_mask *m = tt_mask_create(TT_MASK_MAX_SIDE, 1, true);
    ENSURE(m != NULL && tt_mask_count(m) == TT_MASK_MAX_SIDE);
    ENSURE(tt_mask_last_error()[0] == '\0');
    tt_mask_destroy(m);
    tt_mask_destroy(NULL);
    ENSURE(tt_mask_copy(NULL) == NULL);
    ENSURE(tt_mask_size(NULL, NULL, NULL) == TT_EINVAL);
    ENSURE(tt_mask_count(NULL) == 0);
}

/* Found by the C API fuzzer: abs(INT_MIN) is INT_MIN, so a rect at x = INT_MIN
 * passed the ±TT_MASK_MAX_OFFSET check (and UBSan reported the negation). */
TEST(mask_fill_rect_refuses_the_most_negative_int)
{
    tt_mask *m = tt_mask_create(8, 8, false);
    ENSURE(tt_mask_fill_rect(m, INT_MIN, 0, 4, 4, true) == TT_EINVAL);
    ENSURE(tt_mask_fill_rect(m, 0, INT_MIN, 4, 4, true) == TT_EINVAL);
    ENSURE(tt_mask_fill_rect(m, -TT_MASK_MAX_OFFSET - 1, 0, 4, 4, true) == TT_EINVAL);
    ENSURE_OK(tt_mask_fill_rect(m, -TT_MASK_MAX_OFFSET, 0, 4, 4, true)); /* the limit itself: nothing inside */
    ENSURE(tt_mask_count(m) == 0);
    tt_mask_destroy(m);
}

TEST(mask_pixels_and_whole_mask_operations)
{
    tt_mask *m = tt_mask_create(65, 3, false);
    int w, h;
    ENSURE_OK(tt_mask_size(m, &w, &h));
    ENSURE(w == 65 && h == 3);
    ENSURE_OK(tt_mask_set(m, 64, 2, true));
    ENSURE_OK(tt_mask_set(m, 3, 1, true));
    ENSURE(tt_mask_get(m, 64, 2) == 1 && tt_mask_get(m, 63, 2) == 0);
    ENSURE(tt_mask_get(m, 65, 0) == -1 && tt_mask_get(m, 0, -1) == -1);
    ENSURE(tt_mask_set(m, 65, 0, true) == TT_EINVAL);
    ENSURE(tt_mask_count(m) == 2);
    tt_mask_rect r;
    ENSURE_OK(tt_mask_bounding_rect(m, &r));
    ENSURE(r.x == 3 && r.y == 1 && r.w == 62 && r.h == 2);
    tt_vec2 c;
    ENSURE_OK(tt_mask_centroid(m, &c));
    ENSURE_NEAR(c.x, 33.5, 1e-12);
    ENSURE_NEAR(c.y, 1.5, 1e-12);
    tt_mask *k = tt_mask_copy(m);
    ENSURE_OK(tt_mask_invert(m));
    ENSURE(tt_mask_count(m) == 65 * 3 - 2);
    ENSURE_OK(tt_mask_fill(m));
    ENSURE(tt_mask_count(m) == 65 * 3);
    ENSURE_OK(tt_mask_clear(m));
    ENSURE(tt_mask_count(m) == 0);
    ENSURE_OK(tt_mask_bounding_rect(m, &r));
    ENSURE(r.w == 0 && r.h == 0);
    ENSURE(tt_mask_count(k) == 2 && tt_mask_get(k, 3, 1) == 1);
    ENSURE(tt_mask_bounding_rect(k, NULL) == TT_EINVAL);
    tt_mask_destroy(m);
    tt_mask_destroy(k);
}

TEST(mask_shapes_fill_pixel_centres)
{
    tt_mask *m = tt_mask_create(200, 200, false);
    ENSURE_OK(tt_mask_fill_circle(m, 100, 100, 60, true));
    ENSURE_NEAR((double)tt_mask_count(m), M_PI * 3600, M_PI * 3600 * 0.005);
    ENSURE(tt_mask_get(m, 100, 40) == 1 && tt_mask_get(m, 100, 39) == 0);
    ENSURE_OK(tt_mask_fill_rect(m, -10, -10, 20, 20, false)); /* clipped */
    ENSURE_OK(tt_mask_fill_rect(m, 0, 0, 10, 10, true));
    ENSURE(tt_mask_get(m, 9, 9) == 1 && tt_mask_get(m, 10, 9) == 0);
    ENSURE_OK(tt_mask_clear(m));
    tt_vec2 tri[3] = { { 0, 0 }, { 100, 0 }, { 0, 100 } };
    ENSURE_OK(tt_mask_fill_polygon(m, tri, 3, true));
    ENSURE_NEAR((double)tt_mask_count(m), 5000, 60);
    ENSURE(tt_mask_fill_circle(m, NAN, 0, 1, true) == TT_EINVAL);
    ENSURE(tt_mask_fill_circle(m, 0, 0, -1, true) == TT_EINVAL);
    ENSURE(tt_mask_fill_rect(m, 0, 0, -1, 1, true) == TT_EINVAL);
    tri[1].x = INFINITY;
    ENSURE(tt_mask_fill_polygon(m, tri, 3, true) == TT_EINVAL);
    ENSURE(tt_mask_fill_polygon(m, tri, 2, true) == TT_EINVAL);
    ENSURE(tt_mask_fill_polygon(m, NULL, 3, true) == TT_EINVAL);
    tt_mask_destroy(m);
}

TEST(mask_from_images_by_alpha_and_colour)
{
    uint8_t px[2 * 3 * 4] = { 0 }; /* 3 wide, 2 high */
    px[3] = 128;                   /* (0, 0) alpha 128 */
    px[4 * 4 + 3] = 127;           /* (1, 1) alpha 127 */
    px[4 * 2 + 0] = 250;           /* (2, 0) red 250 */
    tt_mask *m = tt_mask_from_rgba(px, 3, 2, 12, 127);
    ENSURE(m && tt_mask_count(m) == 1 && tt_mask_get(m, 0, 0) == 1);
    tt_mask_destroy(m);
    ENSURE(tt_mask_from_rgba(px, 3, 2, 11, 127) == NULL);
    ENSURE(tt_mask_from_rgba(px, 3, 2, 12, 255) == NULL);
    ENSURE(tt_mask_from_rgba(NULL, 3, 2, 12, 0) == NULL);
    const uint8_t red[3] = { 255, 0, 0 };
    m = tt_mask_from_color(px, 3, 2, 12, red, 5, false);
    ENSURE(m && tt_mask_count(m) == 1 && tt_mask_get(m, 2, 0) == 1);
    tt_mask_destroy(m);
    m = tt_mask_from_color(px, 3, 2, 12, red, 5, true); /* colour key: everything but red */
    ENSURE(m && tt_mask_count(m) == 5 && tt_mask_get(m, 2, 0) == 0);
    tt_mask_destroy(m);
    ENSURE(tt_mask_from_color(px, 3, 2, 12, red, 256, false) == NULL);
}

TEST(mask_rotated_and_scaled_copies)
{
    tt_mask *m = tt_mask_create(40, 10, false);
    ENSURE_OK(tt_mask_fill_rect(m, 0, 0, 10, 10, true)); /* a block at the left end */
    tt_mask *r = tt_mask_rotated(m, M_PI / 2);           /* counter-clockwise on screen: the left end goes down */
    int w, h;
    ENSURE_OK(tt_mask_size(r, &w, &h));
    ENSURE(w == 10 && h == 40);
    ENSURE(tt_mask_count(r) == 100);
    ENSURE(tt_mask_get(r, 5, 35) == 1 && tt_mask_get(r, 5, 5) == 0);
    tt_mask_destroy(r);
    r = tt_mask_rotated(m, 2 * M_PI);
    ENSURE_OK(tt_mask_size(r, &w, &h));
    ENSURE(w == 40 && h == 10 && tt_mask_count(r) == 100 && tt_mask_get(r, 0, 0) == 1);
    tt_mask_destroy(r);
    r = tt_mask_rotated(m, M_PI / 4);
    ENSURE_NEAR((double)tt_mask_count(r), 100, 12);
    tt_mask_destroy(r);
    ENSURE(tt_mask_rotated(m, NAN) == NULL);
    ENSURE(tt_mask_rotated(NULL, 0) == NULL);
    tt_mask *s = tt_mask_scaled(m, 80, 5);
    ENSURE(s && tt_mask_count(s) == 100 && tt_mask_get(s, 19, 4) == 1 && tt_mask_get(s, 20, 0) == 0);
    tt_mask_destroy(s);
    ENSURE(tt_mask_scaled(m, 0, 5) == NULL);
    tt_mask_destroy(m);
}

TEST(mask_components_outline_and_convolve)
{
    tt_mask *m = tt_mask_create(20, 10, false);
    ENSURE_OK(tt_mask_fill_rect(m, 1, 1, 3, 3, true));  /* 9 pixels */
    ENSURE_OK(tt_mask_set(m, 4, 4, true));              /* touches it at a corner: the same component */
    ENSURE_OK(tt_mask_fill_rect(m, 10, 2, 5, 5, true)); /* 25 pixels */
    ENSURE(tt_mask_component_count(m) == 2);
    tt_mask_rect rects[2];
    uint32_t n;
    ENSURE_OK(tt_mask_component_rects(m, rects, 2, &n));
    ENSURE(n == 2 && rects[0].x == 1 && rects[0].w == 4 && rects[0].h == 4 && rects[1].x == 10 && rects[1].w == 5);
    tt_mask *c = tt_mask_component(m, -1, -1);
    ENSURE(c && tt_mask_count(c) == 25);
    tt_mask_destroy(c);
    c = tt_mask_component(m, 4, 4);
    ENSURE(c && tt_mask_count(c) == 10);
    tt_mask_destroy(c);
    c = tt_mask_component(m, 0, 0);
    ENSURE(c && tt_mask_count(c) == 0);
    tt_mask_destroy(c);
    ENSURE(tt_mask_component(m, 20, 0) == NULL);
    int xy[64];
    ENSURE_OK(tt_mask_outline(m, xy, 32, &n));
    /* clockwise on screen round the 3×3 block's border, out to the corner pixel and back */
    static const int want[] = { 1, 1, 2, 1, 3, 1, 3, 2, 3, 3, 4, 4, 3, 3, 2, 3, 1, 3, 1, 2 };
    ENSURE(n == 10);
    for (int i = 0; i < 20; i++) ENSURE(xy[i] == want[i]);
    for (uint32_t i = 0; i < n; i++) ENSURE(!(xy[2 * i] == 2 && xy[2 * i + 1] == 2)); /* never the inside */
    tt_mask *b = tt_mask_create(2, 2, true);
    tt_mask *v = tt_mask_convolve(m, b);
    ENSURE_OK(tt_mask_size(v, &xy[0], &xy[1]));
    ENSURE(xy[0] == 21 && xy[1] == 11);
    /* B's bottom-right on (x, y) overlaps A exactly where A dilated by B is set */
    ENSURE(tt_mask_get(v, 0, 0) == 0 && tt_mask_get(v, 1, 1) == 1 && tt_mask_get(v, 5, 5) == 1 && tt_mask_get(v, 6, 6) == 0);
    tt_mask_destroy(v);
    tt_mask_destroy(b);
    tt_mask_destroy(m);
}

TEST(mask_in_caller_memory)
{
    size_t n = tt_mask_footprint(70, 3);
    ENSURE(n > 0 && tt_mask_footprint(0, 3) == 0 && tt_mask_footprint(3, TT_MASK_MAX_SIDE + 1) == 0);
    uint64_t *mem = malloc(n);
    memset(mem, 0xff, n);
    ENSURE(tt_mask_init(mem, n - 1, 70, 3) == NULL);
    ENSURE(tt_mask_init(NULL, n, 70, 3) == NULL);
    ENSURE(tt_mask_init((char *)mem + 1, n, 70, 3) == NULL); /* misaligned */
    tt_mask *m = tt_mask_init(mem, n, 70, 3);
    ENSURE(m && tt_mask_count(m) == 0); /* cleared, whatever the memory held */
    tt_mask *a = tt_mask_create(70, 3, true), *b = tt_mask_create(5, 5, true);
    ENSURE_OK(tt_mask_copy_into(m, a));
    ENSURE(tt_mask_count(m) == 210);
    ENSURE(tt_mask_copy_into(m, b) == TT_EINVAL);
    ENSURE_OK(tt_mask_overlap_mask_into(m, a, b, 66, 1)); /* every pixel written: the old ones go */
    ENSURE(tt_mask_count(m) == 8 && tt_mask_get(m, 66, 1) == 1 && tt_mask_get(m, 0, 0) == 0);
    ENSURE(tt_mask_overlap_mask_into(m, b, a, 0, 0) == TT_EINVAL); /* not b's size */
    ENSURE(tt_mask_overlap_mask_into(a, a, b, 0, 0) == TT_EINVAL); /* out is a */
    ENSURE(tt_mask_overlap_mask_into(NULL, a, b, 0, 0) == TT_EINVAL);
    ENSURE_OK(tt_mask_overlap_mask_into(m, a, b, 500, 0));
    ENSURE(tt_mask_count(m) == 0);
    tt_mask_destroy(a);
    tt_mask_destroy(b);
    free(mem);
}
