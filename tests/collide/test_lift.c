/* tether — the bottom-up velocity pass (collide/contact_lift.c) with a
 * particle that has no height: a step can leave a position NaN or
 * infinite inside it (the guard stops that particle after the velocity
 * pass), and the pass sorts its pairs into bands by height. The C API
 * fuzzer found the band of a NaN height taken as an integer (undefined
 * behaviour: the sanitizer build stops there), and an infinite position
 * made its partner's normal NaN, and so the partner's velocity. The pass
 * on the positions a step left, one of them replaced by NaN, then ±inf:
 * every other particle's velocity stays finite. */
#include "test.h"
#include "collide/collide_internal.h"

#include <math.h>

TEST(the_lift_takes_a_particle_with_no_height)
{
    const double bad[] = {NAN, INFINITY, -INFINITY};
    for (int k = 0; k < 3; k++) {
        tt_world_def wd = tt_world_def_default();
        wd.iterations = 8;
        wd.sleep = false;
        tt_world *w = tt_world_create(&wd);
        ENSURE(w != NULL);
        tt_collision_settings cs = tt_collision_settings_default();
        ENSURE_OK(tt_world_set_collision(w, &cs));
        tt_particle_def pd = tt_particle_def_default();
        pd.radius = 0.5;
        tt_particle ps[12];
        for (int i = 0; i < 12; i++) {
            pd.position = (tt_vec2){(i % 3) * 0.95, (i / 3) * 0.9};
            ps[i] = tt_particle_create(w, &pd);
        }
        ENSURE_OK(tt_world_step(w, 1.0 / 60));
        tt__collide *c = tt__collide_get(w, false, "test");
        ENSURE(c && c->scr.batched && c->scr.bat.n > 0);
        w->px[ps[7].index] = bad[k];
        tt__contacts_lift(w, c, 0.1);
        for (int i = 0; i < 12; i++) {
            if (i == 7) continue;
            const tt_vec2 v = tt__velocity(w, ps[i].index);
            ENSURE(isfinite(v.x) && isfinite(v.y));
        }
        tt_world_destroy(w);
    }
}
