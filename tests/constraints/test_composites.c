/* Composites: what each builder makes, the lattice body's centre of mass and
 * orientation against the exact rigid motion, removal, and all-or-nothing
 * creation. */
#include "test.h"
#include "tether.h"

#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

static tt_vec2 pos(const tt_world *w, tt_particle p)
{
    tt_vec2 x = {NAN, NAN};
    tt_particle_get_position(w, p, &x);
    return x;
}

TEST(lattice_spins_as_a_rigid_body_centre_and_angle_exact)
{
    tt_world_def wd = tt_world_def_default();
    wd.gravity = (tt_vec2){0, 0};
    wd.iterations = 50;
    tt_world *w = tt_world_create(&wd);
    tt_lattice_def ld = tt_lattice_def_default();
    ld.center = (tt_vec2){1, 2};
    ld.width = 2;
    ld.height = 1;
    ld.columns = 4;
    ld.rows = 3;
    ld.angle = 0.3;
    tt_composite c = tt_lattice_create(w, &ld);
    ENSURE(c.gen != 0);
    tt_vec2 cm;
    double a;
    ENSURE_OK(tt_composite_get_center(w, c, &cm));
    ENSURE_NEAR(cm.x, 1, 1e-12);
    ENSURE_NEAR(cm.y, 2, 1e-12);
    ENSURE_OK(tt_composite_get_angle(w, c, &a));
    ENSURE_NEAR(a, 0, 1e-12); /* measured from the shape as made */
    tt_particle ps[12];
    uint32_t n;
    ENSURE_OK(tt_composite_get_particles(w, c, ps, 12, &n));
    ENSURE(n == 12);
    /* spin at ω = 2 rad/s and drift at (0.5, 0): v = v0 + ω × r */
    const double om = 2.0;
    for (uint32_t i = 0; i < n; i++) {
        tt_vec2 x = pos(w, ps[i]);
        tt_particle_set_velocity(w, ps[i], (tt_vec2){0.5 - om * (x.y - 2), om * (x.x - 1)});
    }
    double rest[12];
    for (uint32_t i = 0; i < n; i++) rest[i] = hypot(pos(w, ps[i]).x - 1, pos(w, ps[i]).y - 2);
    const int steps = 60;
    for (int s = 0; s < steps; s++) tt_world_step(w, 1.0 / 240);
    double t = steps / 240.0;
    ENSURE_OK(tt_composite_get_center(w, c, &cm));
    ENSURE_NEAR(cm.x, 1 + 0.5 * t, 1e-9); /* momentum is conserved: the centre drifts exactly */
    ENSURE_NEAR(cm.y, 2, 1e-9);
    ENSURE_OK(tt_composite_get_angle(w, c, &a));
    ENSURE_NEAR(a, om * t, 0.01 * om * t); /* projection trims a little rotation energy */
    for (uint32_t i = 0; i < n; i++) /* it stays rigid: every particle keeps its distance to the centre */
        ENSURE_NEAR(hypot(pos(w, ps[i]).x - cm.x, pos(w, ps[i]).y - cm.y), rest[i], 1e-3);
    tt_world_destroy(w);
}

TEST(lattice_polygon_dropped_on_the_floor_keeps_its_shape)
{
    tt_world_def wd = tt_world_def_default();
    wd.iterations = 30;
    tt_world *w = tt_world_create(&wd);
    tt_vec2 tri[3] = {{0, 2}, {1, 2}, {0.5, 3}};
    tt_lattice_def ld = tt_lattice_def_default();
    ld.points = tri;
    ld.point_count = 3;
    tt_composite c = tt_lattice_create(w, &ld);
    ENSURE(c.gen != 0);
    ENSURE(tt_world_constraint_count(w) == 3);
    tt_bounds_def bd = tt_bounds_def_default();
    bd.min = (tt_vec2){-10, 0};
    bd.friction = 1;
    tt_bounds_create(w, &bd);
    for (int s = 0; s < 240; s++) tt_world_step(w, 1.0 / 60);
    tt_particle ps[3];
    uint32_t n;
    tt_composite_get_particles(w, c, ps, 3, &n);
    ENSURE_NEAR(pos(w, ps[0]).y, 0, 1e-4); /* landed flat on its base (within what 30 sweeps leave) */
    ENSURE_NEAR(pos(w, ps[1]).y, 0, 1e-4);
    ENSURE_NEAR(hypot(pos(w, ps[0]).x - pos(w, ps[1]).x, 0), 1, 1e-6);
    ENSURE_NEAR(pos(w, ps[2]).y, 1, 1e-4);
    double a;
    tt_composite_get_angle(w, c, &a);
    ENSURE_NEAR(a, 0, 1e-4);
    tt_world_destroy(w);
}

TEST(each_builder_makes_what_it_documents)
{
    tt_world *w = tt_world_create(NULL);
    tt_rope_def rd = tt_rope_def_default();
    rd.segments = 7;
    rd.pin_end = true;
    tt_composite rope = tt_rope_create(w, &rd);
    uint32_t np, nc;
    tt_composite_get_particles(w, rope, NULL, 0, &np);
    tt_composite_get_constraints(w, rope, NULL, 0, &nc);
    ENSURE(np == 8 && nc == 7);
    tt_particle rp[8];
    tt_composite_get_particles(w, rope, rp, 8, &np);
    bool pinned;
    tt_particle_get_pinned(w, rp[0], &pinned);
    ENSURE(pinned);
    tt_particle_get_pinned(w, rp[7], &pinned);
    ENSURE(pinned);
    ENSURE_NEAR(pos(w, rp[7]).x, 1, 1e-15);

    tt_ragdoll_def gd = tt_ragdoll_def_default();
    tt_composite doll = tt_ragdoll_create(w, &gd);
    tt_composite_get_particles(w, doll, NULL, 0, &np);
    tt_composite_get_constraints(w, doll, NULL, 0, &nc);
    ENSURE(np == 11 && nc == 13 + 6);
    tt_particle dp[11];
    tt_composite_get_particles(w, doll, dp, 11, &np);
    ENSURE(pos(w, dp[0]).y > pos(w, dp[1]).y && pos(w, dp[1]).y > pos(w, dp[2]).y); /* head, neck, pelvis */
    ENSURE(pos(w, dp[8]).y < pos(w, dp[7]).y);                                       /* foot below knee */
    ENSURE_NEAR(pos(w, dp[0]).y - pos(w, dp[8]).y, 1.8, 1e-12);
    tt_constraint dc[19];
    tt_composite_get_constraints(w, doll, dc, 19, &nc);
    for (uint32_t i = 0; i < nc; i++) { /* made satisfied */
        double e;
        tt_constraint_get_error(w, dc[i], &e);
        ENSURE(e < 1e-12);
    }

    tt_soft_body_def sd = tt_soft_body_def_default();
    sd.segments = 12;
    tt_composite soft = tt_soft_body_create(w, &sd);
    tt_composite_get_constraints(w, soft, NULL, 0, &nc);
    ENSURE(nc == 13); /* 12 edges + the area */

    tt_cloth_def cd = tt_cloth_def_default();
    cd.columns = 5;
    cd.rows = 4;
    cd.bend_stiffness = 0;
    tt_composite cloth = tt_cloth_create(w, &cd);
    tt_composite_get_constraints(w, cloth, NULL, 0, &nc);
    ENSURE(nc == 4 * 4 + 5 * 3 + 2 * 4 * 3);
    ENSURE(tt_world_composite_count(w) == 4);

    tt_lattice_def ld = tt_lattice_def_default();
    ld.columns = 1;
    ENSURE(tt_lattice_create(w, &ld).gen == 0 && strstr(tt_last_error(w), "columns"));
    rd.common.mass = 0;
    ENSURE(tt_rope_create(w, &rd).gen == 0 && strstr(tt_last_error(w), "mass"));
    cd.width = NAN;
    ENSURE(tt_cloth_create(w, &cd).gen == 0);
    tt_world_destroy(w);
}

TEST(removing_a_composite_removes_everything_it_made_and_nothing_else)
{
    tt_world *w = tt_world_create(NULL);
    tt_particle_def pd = tt_particle_def_default();
    tt_particle keep = tt_particle_create(w, &pd);
    tt_cloth_def cd = tt_cloth_def_default();
    cd.break_strain = 0.1;
    tt_composite c = tt_cloth_create(w, &cd);
    tt_constraint first;
    uint32_t n;
    tt_composite_get_constraints(w, c, &first, 1, &n);
    tt_constraint_destroy(w, first); /* already gone: destroy skips it */
    ENSURE_OK(tt_composite_destroy(w, c));
    ENSURE(tt_world_particle_count(w) == 1 && tt_particle_is_valid(w, keep));
    ENSURE(tt_world_constraint_count(w) == 0 && tt_world_composite_count(w) == 0);
    ENSURE(!tt_composite_is_valid(w, c));
    ENSURE(tt_composite_destroy(w, c) == TT_ESTALE);
    tt_vec2 cm;
    ENSURE(tt_composite_get_center(w, c, &cm) == TT_ESTALE);
    tt_world_destroy(w);
}

TEST(a_composite_that_does_not_fit_leaves_nothing_behind)
{
    tt_world_def wd = tt_world_def_default();
    wd.max_particles = 5;
    tt_world *w = tt_world_create(&wd);
    tt_rope_def rd = tt_rope_def_default();
    rd.segments = 9;
    ENSURE(tt_rope_create(w, &rd).gen == 0);
    ENSURE(strstr(tt_last_error(w), "full") != NULL);
    ENSURE(tt_world_particle_count(w) == 0);
    ENSURE(tt_world_constraint_count(w) == 0 && tt_world_composite_count(w) == 0);
    rd.segments = 4;
    ENSURE(tt_rope_create(w, &rd).gen != 0); /* the slots were given back */
    tt_world_destroy(w);
}

TEST(ragdoll_limits_hold_while_it_falls_and_lands)
{
    tt_world_def wd = tt_world_def_default();
    wd.iterations = 20;
    tt_world *w = tt_world_create(&wd);
    tt_ragdoll_def gd = tt_ragdoll_def_default();
    gd.position = (tt_vec2){0, 3};
    tt_composite doll = tt_ragdoll_create(w, &gd);
    tt_particle dp[11];
    uint32_t n;
    tt_composite_get_particles(w, doll, dp, 11, &n);
    tt_particle_set_velocity(w, dp[0], (tt_vec2){4, 0}); /* a shove at the head */
    tt_bounds_def bd = tt_bounds_def_default();
    bd.min = (tt_vec2){-10, 0};
    bd.friction = 0.5;
    tt_bounds_create(w, &bd);
    tt_constraint dc[19];
    tt_composite_get_constraints(w, doll, dc, 19, &n);
    double worst = 0;
    for (int s = 0; s < 300; s++) {
        tt_world_step(w, 1.0 / 60);
        for (uint32_t i = 0; i < n; i++) {
            double e;
            tt_constraint_get_error(w, dc[i], &e);
            worst = fmax(worst, e);
        }
    }
    ENSURE(worst < 0.05); /* bones within 5 cm, limits within 0.05 rad, every step */
    tt_vec2 cm;
    tt_composite_get_center(w, doll, &cm);
    ENSURE(cm.y < 0.6); /* it fell over */
    for (uint32_t i = 0; i < 11; i++) ENSURE(pos(w, dp[i]).y >= -1e-9);
    (void)PI;
    tt_world_destroy(w);
}
