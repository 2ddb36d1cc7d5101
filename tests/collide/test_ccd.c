/* Continuous detection: a particle moving 1000 radii per step at a wall a
 * tenth of a radius thick never passes with the bullet flag, and does pass
 * without it (the negative control). */
#include "test.h"
#include "collide/collide_internal.h"

/* Returns the largest x reached; the wall's near face is at x = 0. */
static double shoot(tt_integrator integ, bool bullet, double e, double *vx_after)
{
    const double r = 0.05, dt = 1.0 / 60, v = 1000 * r / dt; /* 1000 radii per step */
    tt_world_def wd = tt_world_def_default();
    wd.integrator = integ;
    wd.gravity = (tt_vec2){0, 0};
    tt_world *w = tt_world_create(&wd);
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_BOX;
    sd.half_extents = (tt_vec2){0.05 * r, 10};
    sd.position = (tt_vec2){0.05 * r, 0};
    sd.restitution = e;
    tt_shape_create(w, &sd);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = r;
    pd.position = (tt_vec2){-1000 * r * 0.37, 0.3}; /* not a whole number of steps from the wall */
    pd.velocity = (tt_vec2){v, 0};
    tt_particle p = tt_particle_create(w, &pd);
    tt_particle_set_material(w, p, e, 0, 0);
    if (bullet) tt_particle_set_bullet(w, p, true);
    double xmax = -INFINITY;
    for (int s = 0; s < 10; s++) {
        tt_world_step(w, dt);
        tt_vec2 x;
        tt_particle_get_position(w, p, &x);
        xmax = fmax(xmax, x.x);
    }
    tt_vec2 vv;
    tt_particle_get_velocity(w, p, &vv);
    *vx_after = vv.x / v;
    tt_world_destroy(w);
    return xmax;
}

TEST(bullet_never_tunnels_through_a_thin_wall)
{
    for (int k = 0; k < TT_INTEGRATOR_COUNT; k++) {
        double vx;
        double xmax = shoot((tt_integrator)k, true, 0.0, &vx);
        ENSURE(xmax <= -0.05 + 1e-9); /* the centre stays a radius short of the wall */
        ENSURE(fabs(vx) < 1e-9);      /* e = 0: stopped dead */
        xmax = shoot((tt_integrator)k, true, 1.0, &vx);
        ENSURE(xmax <= -0.05 + 1e-9);
        ENSURE_NEAR(vx, -1.0, 1e-9);  /* e = 1: comes back at full speed */
    }
}

TEST(without_the_bullet_flag_the_particle_tunnels)
{
    for (int k = 0; k < TT_INTEGRATOR_COUNT; k++) {
        double vx;
        double xmax = shoot((tt_integrator)k, false, 0.0, &vx);
        ENSURE(xmax > 1.0); /* straight through */
        ENSURE_NEAR(vx, 1.0, 1e-9);
    }
}

TEST(bullet_flag_is_per_particle_and_off_by_default)
{
    tt_world *w = tt_world_create(NULL);
    tt_particle_def pd = tt_particle_def_default();
    tt_particle a = tt_particle_create(w, &pd), b = tt_particle_create(w, &pd);
    bool on = true;
    ENSURE_OK(tt_particle_get_bullet(w, a, &on));
    ENSURE(!on);
    ENSURE(tt__collide_peek(w) == NULL); /* asking costs nothing */
    ENSURE_OK(tt_particle_set_bullet(w, b, true));
    ENSURE_OK(tt_particle_get_bullet(w, b, &on));
    ENSURE(on);
    ENSURE_OK(tt_particle_get_bullet(w, a, &on));
    ENSURE(!on);
    tt_particle_destroy(w, b);
    tt_particle c = tt_particle_create(w, &pd); /* reuses b's slot */
    ENSURE(c.index == b.index);
    ENSURE_OK(tt_particle_get_bullet(w, c, &on));
    ENSURE(!on);
    tt_world_destroy(w);
}
