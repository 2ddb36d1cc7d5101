/* tether — the positions kept for drawing between steps
 * (tt_world_set_interpolation, src/core/interpolation.c): where each
 * particle was as the last step began, under every integrator; a particle
 * made or moved since is where it is; never part of the state (hash,
 * snapshot), kept across a restore. */
#include "test.h"

#include <tether.h>

#include <string.h>

/* A particle at (−4, 1) moving at (480, −60) m/s in a world without
 * gravity: one step of 1/60 s takes it to (4, 0). */
static tt_world *mover(tt_integrator in, tt_particle *p)
{
    tt_world_def wd = tt_world_def_default();
    wd.gravity = (tt_vec2){0, 0};
    wd.integrator = in;
    tt_world *w = tt_world_create(&wd);
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){-4, 1};
    pd.velocity = (tt_vec2){480, -60};
    *p = tt_particle_create(w, &pd);
    return w;
}

TEST(interpolation_keeps_where_each_step_began_under_every_integrator)
{
    for (int in = 0; in < TT_INTEGRATOR_COUNT; in++) {
        tt_particle p;
        tt_world *w = mover((tt_integrator)in, &p);
        ENSURE(!tt_world_get_interpolation(w));
        ENSURE_OK(tt_world_set_interpolation(w, true));
        ENSURE(tt_world_get_interpolation(w));
        tt_vec2 was, now;
        ENSURE_OK(tt_particle_get_previous_position(w, p, &was)); /* nothing stepped yet: where it is */
        ENSURE(was.x == -4 && was.y == 1);
        ENSURE_OK(tt_world_step(w, 1.0 / 60));
        ENSURE_OK(tt_particle_get_previous_position(w, p, &was));
        ENSURE_OK(tt_particle_get_position(w, p, &now));
        ENSURE(was.x == -4 && was.y == 1);
        ENSURE_NEAR(now.x, 4, 1e-12);
        ENSURE_NEAR(now.y, 0, 1e-12);
        ENSURE_OK(tt_world_step(w, 1.0 / 60));
        double xy[2];
        ENSURE(tt_world_read_previous_positions(w, xy, 1) == 1);
        ENSURE(xy[0] == now.x && xy[1] == now.y);
        tt_world_destroy(w);
    }
}

TEST(interpolation_a_particle_made_or_moved_since_the_step_is_where_it_is)
{
    tt_particle p;
    tt_world *w = mover(TT_VERLET, &p);
    ENSURE_OK(tt_world_set_interpolation(w, true));
    tt_world_step(w, 1.0 / 60);
    ENSURE_OK(tt_particle_set_position(w, p, (tt_vec2){10, 10}, TT_MOVE_KEEP_VELOCITY));
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){-7, 3};
    tt_particle q = tt_particle_create(w, &pd);
    for (int i = 0; i < 600; i++) tt_particle_create(w, &pd); /* the kept arrays grow with the others */
    double xy[4];
    ENSURE(tt_world_read_previous_positions(w, xy, 2) == 2);
    ENSURE(xy[0] == 10 && xy[1] == 10 && xy[2] == -7 && xy[3] == 3);
    tt_vec2 was;
    ENSURE_OK(tt_particle_get_previous_position(w, q, &was));
    ENSURE(was.x == -7 && was.y == 3);
    ENSURE(tt_particle_get_previous_position(w, q, NULL) == TT_EINVAL);
    ENSURE(tt_particle_get_previous_position(w, (tt_particle){0, 0}, &was) == TT_ESTALE);
    ENSURE(tt_world_read_previous_positions(NULL, xy, 2) == 0 && tt_world_read_previous_positions(w, NULL, 2) == 0);
    ENSURE(tt_world_set_interpolation(NULL, true) == TT_EINVAL && !tt_world_get_interpolation(NULL));
    tt_world_destroy(w);
}

TEST(interpolation_is_not_state_and_survives_a_restore)
{
    tt_particle p, p2;
    tt_world *plain = mover(TT_RK4, &p), *kept = mover(TT_RK4, &p2);
    ENSURE_OK(tt_world_set_interpolation(kept, true));
    tt_memory m0, m1;
    tt_world_get_memory(plain, &m0);
    tt_world_get_memory(kept, &m1);
    ENSURE(m1.total >= m0.total + 2 * sizeof(double) * m0.capacity); /* counted, 16 bytes a slot */
    for (int i = 0; i < 10; i++) {
        tt_world_step(plain, 1.0 / 60);
        tt_world_step(kept, 1.0 / 60);
    }
    ENSURE(tt_world_hash(plain) == tt_world_hash(kept));
    size_t a = 0, b = 0;
    tt_world_save(plain, NULL, 0, &a);
    tt_world_save(kept, NULL, 0, &b);
    ENSURE(a == b);
    unsigned char buf[4096];
    ENSURE(a <= sizeof buf);
    ENSURE_OK(tt_world_save(plain, buf, sizeof buf, &a));
    tt_world_step(kept, 1.0 / 60);
    tt_world_step(kept, 1.0 / 60); /* what it kept is now neither the saved position nor the one before */
    ENSURE_OK(tt_world_restore(kept, buf, a)); /* kept on, from the restored positions */
    ENSURE(tt_world_get_interpolation(kept));
    tt_vec2 was, now;
    ENSURE_OK(tt_particle_get_previous_position(kept, p, &was)); /* the world has the saved one's tag: p's handles */
    ENSURE_OK(tt_particle_get_position(kept, p, &now));
    ENSURE(was.x == now.x && was.y == now.y);
    ENSURE_OK(tt_world_set_interpolation(kept, false));
    ENSURE(!tt_world_get_interpolation(kept));
    tt_world_destroy(plain);
    tt_world_destroy(kept);
}
