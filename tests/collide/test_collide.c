/* The public collision settings (src/collide/collide.c): what the
 * per-particle material takes and refuses, and that a refusal leaves the
 * world exactly as it was. */
#include "test.h"
#include "tether.h"

#include <math.h>
#include <string.h>

/* A ball resting on a floor after a few steps, its material set: a world
 * whose stream holds the collision state and the material. */
static tt_world *ball_on_floor(tt_particle *p)
{
    tt_world *w = tt_world_create(NULL);
    tt_collision_settings cs = tt_collision_settings_default();
    tt_world_set_collision(w, &cs);
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_AABB;
    sd.a = (tt_vec2){-5, -1};
    sd.b = (tt_vec2){5, 0};
    tt_shape_create(w, &sd);
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){0, 1};
    pd.radius = 0.5;
    *p = tt_particle_create(w, &pd);
    tt_particle_set_material(w, *p, 0.25, 0.5, 0.375);
    for (int s = 0; s < 10; s++) tt_world_step(w, 1.0 / 60);
    return w;
}

/* Restitution in [0, 1], each friction in [0, 1e30]: NaN, infinities and
 * anything outside are refused with TT_EINVAL and a message naming the
 * value, before the world is touched (same hash, same material); the ends
 * of each range are taken; a stale handle is TT_ESTALE before any value is
 * looked at. */
TEST(particle_material_refuses_out_of_range_values_and_leaves_the_world_as_it_was)
{
    static const struct { double e, fs, fk; const char *names; } bad[] = {
        {-0.1, 0.5, 0.5, "restitution"}, {1.0000001, 0.5, 0.5, "restitution"},
        {NAN, 0.5, 0.5, "restitution"}, {INFINITY, 0.5, 0.5, "restitution"},
        {0.5, -1e-300, 0.5, "static friction"}, {0.5, NAN, 0.5, "static friction"},
        {0.5, INFINITY, 0.5, "static friction"}, {0.5, 2e30, 0.5, "static friction"},
        {0.5, 0.5, -1, "kinetic friction"}, {0.5, 0.5, NAN, "kinetic friction"},
        {0.5, 0.5, -INFINITY, "kinetic friction"}, {0.5, 0.5, 2e30, "kinetic friction"},
    };
    tt_particle p;
    tt_world *w = ball_on_floor(&p);
    ENSURE(w);
    const uint64_t h0 = tt_world_hash(w);
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        ENSURE(tt_particle_set_material(w, p, bad[k].e, bad[k].fs, bad[k].fk) == TT_EINVAL);
        ENSURE(strstr(tt_last_error(w), "tt_particle_set_material") && strstr(tt_last_error(w), bad[k].names));
        ENSURE(tt_world_hash(w) == h0);
        double e, fs, fk;
        ENSURE_OK(tt_particle_get_material(w, p, &e, &fs, &fk));
        ENSURE(e == 0.25 && fs == 0.5 && fk == 0.375);
    }
    ENSURE_OK(tt_particle_set_material(w, p, 0, 0, 0));
    ENSURE_OK(tt_particle_set_material(w, p, 1, 1e30, 1e30));
    double e, fs, fk;
    ENSURE_OK(tt_particle_get_material(w, p, &e, &fs, &fk));
    ENSURE(e == 1 && fs == (double)1e30f && fk == (double)1e30f);
    tt_particle_destroy(w, p);
    ENSURE(tt_particle_set_material(w, p, 2, 0, 0) == TT_ESTALE);
    tt_world_destroy(w);
}

/* A refusal in a world that never had collisions does not switch them on:
 * its stream (hash) is the same and the settings still say off. */
TEST(a_refused_particle_material_does_not_switch_collisions_on)
{
    tt_world *w = tt_world_create(NULL);
    ENSURE(w);
    tt_particle_def pd = tt_particle_def_default();
    tt_particle p = tt_particle_create(w, &pd);
    const uint64_t h0 = tt_world_hash(w);
    ENSURE(tt_particle_set_material(w, p, 0.5, -1, 0.5) == TT_EINVAL);
    ENSURE(tt_world_hash(w) == h0);
    tt_collision_settings cs;
    ENSURE_OK(tt_world_get_collision(w, &cs));
    ENSURE(!cs.particles);
    tt_world_destroy(w);
}
