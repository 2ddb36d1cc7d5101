/* A mask drawn through the renderer lands where tt_mask_to_world puts its
 * pixels: the image's top row at the top of the world rectangle (mask rows
 * go down, world y up). */
#include "test.h"
#include "tether.h"
#include "tether/render.h"

TEST(headless_frame_draws_a_mask_where_its_place_says)
{
    tt_headless *hl = tt_headless_create(32, 32, NULL, 0);
    ENSURE(hl != NULL);
    tt_canvas *c = tt_canvas_create(32, 32);
    tt_mask *m = tt_mask_create(4, 4, false);
    ENSURE_OK(tt_mask_set(m, 3, 0, true)); /* the image's top-right pixel */
    tt_image *img = tt_image_from_mask(m, (tt_color){ 255, 0, 0, 255 }, (tt_color){ 0, 0, 0, 0 });
    ENSURE(img != NULL);
    tt_mask_place place = { { 10, 4 }, 1 };
    tt_vec2 lo = tt_mask_to_world(&place, (tt_vec2){ 0, 4 }), hi = tt_mask_to_world(&place, (tt_vec2){ 4, 0 });
    ENSURE(lo.x == 10 && lo.y == 0 && hi.x == 14 && hi.y == 4);
    tt_canvas_clear(c, (tt_color){ 0, 0, 0, 255 });
    ENSURE_OK(tt_canvas_fit(c, lo, hi, 0));
    ENSURE_OK(tt_canvas_image(c, img, lo, hi));
    ENSURE_OK(tt_headless_render(hl, c));
    int pw, ph;
    const uint8_t *px = tt_headless_pixels(hl, &pw, &ph); /* bottom-up */
    tt_vec2 set = tt_canvas_to_pixels(c, tt_mask_to_world(&place, (tt_vec2){ 3.5, 0.5 }));
    tt_vec2 clear = tt_canvas_to_pixels(c, tt_mask_to_world(&place, (tt_vec2){ 0.5, 3.5 }));
    ENSURE(set.x > pw / 2 && set.y < ph / 2); /* top-right on screen, as in the image */
    const uint8_t *a = px + ((size_t)(ph - 1 - (int)set.y) * pw + (int)set.x) * 4;
    const uint8_t *b = px + ((size_t)(ph - 1 - (int)clear.y) * pw + (int)clear.x) * 4;
    ENSURE(a[0] == 255 && a[1] == 0 && a[2] == 0);
    ENSURE(b[0] == 0 && b[1] == 0 && b[2] == 0);
    /* repainting follows the mask */
    ENSURE_OK(tt_mask_invert(m));
    ENSURE_OK(tt_image_paint_mask(img, m, (tt_color){ 0, 255, 0, 255 }, (tt_color){ 0, 0, 0, 0 }));
    ENSURE(tt_image_pixels(img)[3 * 4 + 3] == 0 && tt_image_pixels(img)[1] == 255);
    tt_mask *small = tt_mask_create(2, 2, false);
    ENSURE(tt_image_paint_mask(img, small, (tt_color){ 0, 0, 0, 0 }, (tt_color){ 0, 0, 0, 0 }) == TT_EINVAL);
    ENSURE(tt_image_from_mask(NULL, (tt_color){ 0, 0, 0, 0 }, (tt_color){ 0, 0, 0, 0 }) == NULL);
    tt_mask_destroy(small);
    tt_mask_destroy(m);
    tt_image_destroy(img);
    tt_canvas_destroy(c);
    tt_headless_destroy(hl);
}
