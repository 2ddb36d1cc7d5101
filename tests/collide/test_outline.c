/* Shape outlines and listing, as the debug draw reads them. */
#include "test.h"
#include "tether.h"

TEST(shape_outlines_are_in_world_coordinates)
{
    tt_world *w = tt_world_create(NULL);
    ENSURE(tt_world_list_shapes(w, NULL, 0) == 0);
    tt_shape_def d = tt_shape_def_default();
    d.type = TT_SHAPE_BOX;
    d.position = (tt_vec2){2, 3};
    d.angle = M_PI / 2;
    d.half_extents = (tt_vec2){1, 0.5};
    tt_shape box = tt_shape_create(w, &d);
    d = tt_shape_def_default();
    d.type = TT_SHAPE_CIRCLE;
    d.position = (tt_vec2){-1, 0};
    d.radius = 2;
    d.sensor = true;
    tt_shape circle = tt_shape_create(w, &d);
    d = tt_shape_def_default(); /* segment (0,0)–(1,0) */
    tt_shape seg = tt_shape_create(w, &d);

    tt_shape ids[4];
    ENSURE(tt_world_list_shapes(w, ids, 4) == 3);
    ENSURE(ids[0].index == box.index && ids[1].index == circle.index && ids[2].index == seg.index);

    tt_vec2 p[64];
    uint32_t n;
    bool closed;
    ENSURE_OK(tt_shape_get_outline(w, box, p, 64, &n, &closed));
    ENSURE(n == 4 && closed);
    ENSURE_NEAR(p[0].x, 2 + 0.5, 1e-12); /* local (−1, −0.5) turned a quarter: (0.5, −1) */
    ENSURE_NEAR(p[0].y, 3 - 1, 1e-12);
    ENSURE_OK(tt_shape_get_outline(w, circle, p, 64, &n, &closed));
    ENSURE(n == 32 && closed);
    for (uint32_t k = 0; k < n; k++) ENSURE_NEAR(hypot(p[k].x + 1, p[k].y), 2, 1e-12);
    bool sensor;
    ENSURE_OK(tt_shape_get_sensor(w, circle, &sensor));
    ENSURE(sensor);
    ENSURE_OK(tt_shape_get_outline(w, seg, NULL, 0, &n, &closed)); /* count only */
    ENSURE(n == 2 && !closed);

    ENSURE_OK(tt_shape_destroy(w, seg));
    ENSURE(tt_shape_get_outline(w, seg, p, 64, &n, &closed) == TT_ESTALE);
    ENSURE(tt_shape_get_sensor(w, seg, &sensor) == TT_ESTALE);
    ENSURE(tt_shape_get_outline(w, box, p, 64, NULL, &closed) == TT_EINVAL);
    ENSURE(tt_world_list_shapes(w, ids, 4) == 2);
    ENSURE(tt_world_list_shapes(NULL, ids, 4) == 0);
    tt_world_destroy(w);
}
