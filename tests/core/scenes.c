/* tether — reference scenes for the golden and snapshot tests (scenes.h). */
#include "core/scenes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const names[SCENE_COUNT] = {"pour", "cloth", "zoo", "integrators", "settle", "roll", "pyramid"};

const char *scene_name(scene_kind k) { return (unsigned)k < SCENE_COUNT ? names[k] : "?"; }

static uint64_t lcg_state;
static double rnd(void)
{
    lcg_state = lcg_state * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(lcg_state >> 11) / 9007199254740992.0;
}

static tt_shape aabb(tt_world *w, double ax, double ay, double bx, double by)
{
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_AABB;
    sd.a = (tt_vec2){ax, ay};
    sd.b = (tt_vec2){bx, by};
    return tt_shape_create(w, &sd);
}

static bool build_pour(scene *sc)
{
    tt_world *w = sc->w;
    tt_collision_settings cs = tt_collision_settings_default();
    cs.friction_static = cs.friction_kinetic = 0.3;
    cs.events = TT_EVENT_BEGIN | TT_EVENT_PERSIST | TT_EVENT_END;
    if (tt_world_set_collision(w, &cs) != TT_OK) return false;
    aabb(w, -11, -1, 11, 0);
    aabb(w, -11, 0, -10, 40);
    aabb(w, 10, 0, 11, 40);
    tt_particle_def pd = tt_particle_def_default();
    for (int i = 0; i < 300; i++) {
        pd.radius = 0.3 + 0.2 * rnd();
        pd.position = (tt_vec2){-9.5 + (i % 19) * 1.05 + ((i / 19) % 2) * 0.05, 0.6 + (i / 19) * 1.05};
        pd.category = (uint16_t)(i % 3 == 0 ? 2 : 1);
        pd.mask = (uint16_t)(i % 7 == 0 ? 0xFFFD : 0xFFFF);
        tt_particle p = tt_particle_create(w, &pd);
        if (i < 8) sc->p[i] = p;
    }
    tt_particle_set_material(w, sc->p[1], 0.5, 0.9, 0.8);
    tt_world_set_pair_collision(w, sc->p[2], sc->p[3], false);
    pd.radius = 0.2;
    pd.position = (tt_vec2){0, 30};
    pd.velocity = (tt_vec2){3, -60};
    sc->p[7] = tt_particle_create(w, &pd);
    return tt_particle_set_bullet(w, sc->p[7], true) == TT_OK;
}

static bool build_cloth(scene *sc)
{
    tt_world *w = sc->w;
    tt_world_set_substeps(w, 4);
    tt_world_set_iterations(w, 4);
    tt_world_set_wind(w, (tt_vec2){0.4, 0});
    tt_collision_settings cs = tt_collision_settings_default();
    cs.particles = false;
    if (tt_world_set_collision(w, &cs) != TT_OK) return false;
    tt_cloth_def cd = tt_cloth_def_default();
    cd.common.radius = 0.05;
    cd.origin = (tt_vec2){-2, 4};
    cd.width = cd.height = 4;
    cd.columns = cd.rows = 14;
    cd.shear_stiffness = 0.1;
    cd.break_strain = 0.25;
    if (!tt_cloth_create(w, &cd).gen) return false;
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_CIRCLE;
    sd.position = (tt_vec2){0.3, 1.5};
    sd.radius = 0.7;
    sc->s[0] = tt_shape_create(w, &sd);
    sd.type = TT_SHAPE_CAPSULE;
    sd.position = (tt_vec2){0, -2};
    sd.a = (tt_vec2){-3, 0};
    sd.b = (tt_vec2){3, 0.5};
    sd.radius = 0.2;
    sc->s[1] = tt_shape_create(w, &sd);
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){0.4, 6};
    pd.radius = 0.4;
    pd.mass = 30;
    sc->p[0] = tt_particle_create(w, &pd);
    return sc->s[0].gen && sc->s[1].gen && sc->p[0].gen;
}

static bool zoo_shapes(scene *sc)
{
    tt_world *w = sc->w;
    static const tt_vec2 terrain[] = {{-12, 1}, {-8, -1}, {-4, 0}, {0, -2}, {4, 0}, {8, -1}, {12, 2}};
    static const tt_vec2 wedge[] = {{0, 0}, {1.5, 0}, {0.2, 1}};
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_CHAIN;
    sd.points = terrain;
    sd.count = 7;
    sd.friction_static = 0.8;
    bool ok = tt_shape_create(w, &sd).gen;
    sd = tt_shape_def_default();
    sd.type = TT_SHAPE_SEGMENT;
    sd.a = (tt_vec2){-12, -3};
    sd.b = (tt_vec2){12, -3};
    ok = ok && tt_shape_create(w, &sd).gen;
    sd.type = TT_SHAPE_BOX;
    sd.position = (tt_vec2){-6, 3};
    sd.angle = 0.3;
    sd.half_extents = (tt_vec2){1, 0.25};
    sd.restitution = 0.4;
    sc->s[0] = tt_shape_create(w, &sd); /* kinematic: the driver moves it */
    sd = tt_shape_def_default();
    sd.type = TT_SHAPE_POLYGON;
    sd.points = wedge;
    sd.count = 3;
    sd.position = (tt_vec2){5, 1};
    sd.sensor = true;
    sc->s[1] = tt_shape_create(w, &sd);
    ok = ok && aabb(w, 9, -1, 10, 3).gen;
    return ok && sc->s[0].gen && sc->s[1].gen;
}

static bool zoo_constraints(scene *sc)
{
    tt_world *w = sc->w;
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.15;
    tt_particle q[6];
    for (int i = 0; i < 6; i++) {
        pd.position = (tt_vec2){-3 + i * 0.9, 6 + 0.3 * (i % 2)};
        q[i] = tt_particle_create(w, &pd);
    }
    tt_distance_def dd = tt_distance_def_default();
    dd.a = q[0];
    dd.b = q[1];
    dd.mode = TT_DISTANCE_MAX;
    dd.max_rate = 0.5;
    sc->c[0] = tt_distance_create(w, &dd); /* a winch the driver reels in */
    dd.a = q[1];
    dd.b = q[2];
    dd.mode = TT_DISTANCE_RIGID;
    dd.max_rate = 0;
    dd.compliance = 1e-4;
    dd.break_strain = 0.5;
    tt_distance_create(w, &dd);
    tt_pin_def pin = tt_pin_def_default();
    pin.particle = q[0];
    sc->c[1] = tt_pin_create(w, &pin);
    tt_angle_def ad = tt_angle_def_default();
    ad.a = q[0];
    ad.b = q[1];
    ad.c = q[2];
    tt_angle_create(w, &ad);
    tt_collinear_def cd = tt_collinear_def_default();
    cd.a = q[3];
    cd.b = q[4];
    cd.c = q[5];
    cd.compliance = 1e-3;
    tt_collinear_create(w, &cd);
    tt_area_def ar = tt_area_def_default();
    ar.particles = &q[2];
    ar.count = 3;
    ar.pressure = 1.2;
    tt_area_create(w, &ar);
    tt_bounds_def bd = tt_bounds_def_default();
    bd.min = (tt_vec2){-11.5, -2.9};
    bd.max = (tt_vec2){11.5, 30};
    bd.friction = 0.1;
    sc->c[2] = tt_bounds_create(w, &bd);
    tt_bounds_def bo = tt_bounds_def_default();
    bo.particles = &q[3];
    bo.count = 3;
    bo.min = (tt_vec2){1, 8};
    bo.max = (tt_vec2){2, 9};
    bo.outside = true;
    tt_bounds_create(w, &bo);
    for (int i = 0; i < 6; i++) sc->p[i] = q[i];
    return sc->c[0].gen && sc->c[1].gen && sc->c[2].gen;
}

static bool zoo_composites(scene *sc)
{
    tt_world *w = sc->w;
    tt_rope_def rd = tt_rope_def_default();
    rd.start = (tt_vec2){6, 9};
    rd.finish = (tt_vec2){9, 9};
    rd.segments = 12;
    rd.common.radius = 0.1;
    rd.slack = true;
    bool ok = tt_rope_create(w, &rd).gen;
    tt_ragdoll_def gd = tt_ragdoll_def_default();
    gd.position = (tt_vec2){-7, 8};
    gd.common.radius = 0.12;
    ok = ok && tt_ragdoll_create(w, &gd).gen;
    tt_soft_body_def sb = tt_soft_body_def_default();
    sb.center = (tt_vec2){2, 12};
    sb.ring_radius = 1;
    sb.segments = 12;
    sb.pressure = 1.1;
    sb.common.radius = 0.2;
    ok = ok && tt_soft_body_create(w, &sb).gen;
    tt_lattice_def ld = tt_lattice_def_default();
    ld.center = (tt_vec2){-1, 15};
    ld.width = 1.2;
    ld.height = 0.8;
    ld.columns = 3;
    ld.rows = 2;
    ld.common.radius = 0.3;
    ld.angle = 0.2;
    return ok && tt_lattice_create(w, &ld).gen;
}

static bool build_zoo(scene *sc)
{
    tt_world *w = sc->w;
    tt_world_set_substeps(w, 2);
    tt_collision_settings cs = tt_collision_settings_default();
    cs.restitution = 0.2;
    cs.events = TT_EVENT_BEGIN | TT_EVENT_END;
    if (tt_world_set_collision(w, &cs) != TT_OK) return false;
    if (!zoo_shapes(sc) || !zoo_constraints(sc) || !zoo_composites(sc)) return false;
    tt_spring_def sd = tt_spring_def_default();
    sd.a = sc->p[4];
    sd.b = sc->p[5];
    sd.stiffness = 50;
    sd.damping = 0.3;
    sc->sp = tt_spring_create(w, &sd);
    tt_particle_def pd = tt_particle_def_default();
    for (int i = 0; i < 40; i++) { /* made and partly removed: free lists and generations */
        pd.position = (tt_vec2){-10 + i * 0.5, 20 + rnd()};
        pd.radius = 0.2;
        pd.user = (uint64_t)i * 77;
        tt_particle p = tt_particle_create(w, &pd);
        if (i % 3 == 0) tt_particle_destroy(w, p);
        else if (i == 4) sc->p[6] = p;
    }
    return sc->sp.gen && sc->p[6].gen;
}

static bool build_integrators(scene *sc)
{
    tt_world *w = sc->w;
    tt_world_set_damping(w, 0.05);
    tt_world_set_solver_order(w, TT_JACOBI);
    tt_particle_def pd = tt_particle_def_default();
    pd.pinned = true;
    pd.position = (tt_vec2){0, 10};
    tt_particle prev = tt_particle_create(w, &pd);
    pd.pinned = false;
    for (int i = 1; i < 30; i++) {
        pd.position = (tt_vec2){i * 0.5, 10 - 0.1 * i};
        pd.mass = 0.5 + rnd();
        pd.velocity = (tt_vec2){rnd() - 0.5, 0};
        tt_particle p = tt_particle_create(w, &pd);
        tt_spring_def sd = tt_spring_def_default();
        sd.a = prev;
        sd.b = p;
        sd.stiffness = 150 + 50 * rnd();
        sd.damping = 0.1;
        sd.rest_length = 0.5;
        tt_spring s = tt_spring_create(w, &sd);
        if (i == 10) {
            tt_distance_def dd = tt_distance_def_default();
            dd.a = prev;
            dd.b = p;
            tt_distance_create(w, &dd);
        }
        if (i < 8) sc->p[i] = p;
        if (i == 1) sc->sp = s;
        prev = p;
    }
    return true;
}

/* Two bins 4 m wide side by side, 16 circles in each: both piles fall
 * asleep within 300 steps, as two islands (the wall between them joins
 * nothing). The driver drops a ball into the left bin (settle_drop). */
static bool build_settle(scene *sc)
{
    tt_world *w = sc->w;
    tt_collision_settings cs = tt_collision_settings_default();
    if (tt_world_set_collision(w, &cs) != TT_OK) return false;
    sc->s[0] = aabb(w, -4.5, -1, 4.5, 0);
    aabb(w, -4.5, 0, -4, 6);
    aabb(w, -0.25, 0, 0.25, 6);
    aabb(w, 4, 0, 4.5, 6);
    tt_particle_def pd = tt_particle_def_default();
    for (int i = 0; i < 32; i++) {
        const int bin = i / 16, k = i % 16;
        pd.radius = 0.25 + 0.1 * rnd();
        pd.position = (tt_vec2){(bin ? 0.75 : -3.5) + (k % 4) * 0.9 + 0.1 * rnd(), 0.5 + (k / 4) * 0.8};
        tt_particle p = tt_particle_create(w, &pd);
        if (i % 4 == 0) sc->p[i / 4] = p;
    }
    return sc->s[0].gen && sc->p[7].gen;
}

/* At step 240 a ball falls into the left bin: it wakes the left pile's
 * island, not the right one's. */
static void drive_settle(scene *sc, uint64_t s)
{
    if (s != 240) return;
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.4;
    pd.mass = 3;
    pd.position = (tt_vec2){-2, 5.5};
    pd.velocity = (tt_vec2){0, -4};
    tt_particle_create(sc->w, &pd);
}

/* Discs that turn (tt_world_def.spin): six roll down a slope onto the
 * floor, into a pile of 24 against a wall; the driver spins two of them and
 * kicks one (drive_roll). Pins friction at the contact point
 * (collide/contact_roll.c) and the spin state. */
static bool build_roll(scene *sc)
{
    tt_world *w = sc->w;
    tt_collision_settings cs = tt_collision_settings_default();
    cs.friction_static = 0.5;
    cs.friction_kinetic = 0.4;
    if (tt_world_set_collision(w, &cs) != TT_OK) return false;
    sc->s[0] = aabb(w, -10, -1, 10, 0);
    aabb(w, 8, 0, 9, 4);
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_SEGMENT;
    sd.a = (tt_vec2){-9, 5};
    sd.b = (tt_vec2){-2, 0};
    sc->s[1] = tt_shape_create(w, &sd);
    const double len = sqrt(74.0), nx = 5 / len, ny = 7 / len; /* the slope's upward normal */
    tt_particle_def pd = tt_particle_def_default();
    for (int i = 0; i < 30; i++) {
        pd.radius = 0.25 + 0.1 * rnd();
        if (i < 6) {
            const double t = 0.08 + 0.13 * i;
            pd.position = (tt_vec2){-9 + 7 * t + (pd.radius + 0.01) * nx, 5 - 5 * t + (pd.radius + 0.01) * ny};
        } else {
            const int k = i - 6;
            pd.position = (tt_vec2){2.5 + (k % 6) * 0.72 + 0.05 * rnd(), 0.4 + (k / 6) * 0.72};
        }
        tt_particle p = tt_particle_create(w, &pd);
        if (i % 4 == 0) sc->p[i / 4] = p;
    }
    return sc->s[1].gen && sc->p[7].gen;
}

/* Two discs given spin, one each way, every second; a kick into the pile at step 100. */
static void drive_roll(scene *sc, uint64_t s)
{
    if (s % 60 == 0) tt_particle_set_spin(sc->w, sc->p[s % 120 ? 6 : 0], s % 120 ? -8.0 : 6.0);
    if (s == 100) tt_particle_apply_impulse(sc->w, sc->p[7], (tt_vec2){-1.5, 2});
}

/* A pyramid of eight rows of circles (radius 0.5, the bottom row 1.02 m
 * apart, μ = 0.3) on a floor, held by anchored friction
 * (collide/contact_anchor.c); sleeping off, so the anchors are worked every
 * step. The driver turns the warm start on (contact_warm.c), removes one
 * circle of the third row and drops a ball on the top (drive_pyramid). */
static bool build_pyramid(scene *sc)
{
    tt_world *w = sc->w;
    tt_collision_settings cs = tt_collision_settings_default();
    cs.friction_static = cs.friction_kinetic = 0.3;
    cs.anchored_friction = true;
    if (tt_world_set_collision(w, &cs) != TT_OK || tt_world_set_sleep(w, false, 0.0, 0.0) != TT_OK) return false;
    sc->s[0] = aabb(w, -20, -1, 20, 0);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.5;
    const int rows = 8;
    const double sp = 1.02, dy = sqrt(1.0 - 0.25 * sp * sp);
    int i = 0;
    for (int r = 0; r < rows; r++)
        for (int k = 0; k < rows - r; k++, i++) {
            pd.position = (tt_vec2){(k - 0.5 * (rows - r - 1)) * sp, 0.5 + r * dy};
            tt_particle p = tt_particle_create(w, &pd);
            if (i % 5 == 0 && i / 5 < 8) sc->p[i / 5] = p;
        }
    return sc->s[0].gen && sc->p[7].gen;
}

/* Step 30: warm start 0.75 (its corrections then in the stream); step 60:
 * a circle of the third row goes (sc->p[4], the 21st, its anchors with
 * it); step 200: a ball of 3 kg lands on the top. */
static void drive_pyramid(scene *sc, uint64_t s)
{
    if (s == 30) {
        tt_collision_settings cs;
        tt_world_get_collision(sc->w, &cs);
        cs.warm_start = 0.75;
        tt_world_set_collision(sc->w, &cs);
    }
    if (s == 60) tt_particle_destroy(sc->w, sc->p[4]);
    if (s != 200) return;
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.4;
    pd.mass = 3;
    pd.position = (tt_vec2){0.3, 9};
    tt_particle_create(sc->w, &pd);
}

bool scene_build(scene *sc, scene_kind k)
{
    memset(sc, 0, sizeof *sc);
    sc->kind = k;
    lcg_state = 2026 + (uint64_t)k;
    tt_world_def wd = tt_world_def_default();
    if (k == SCENE_POUR || k == SCENE_SETTLE || k == SCENE_ROLL || k == SCENE_PYRAMID) wd.gravity = (tt_vec2){0, -10};
    wd.spin = k == SCENE_ROLL;
    sc->w = tt_world_create(&wd);
    if (!sc->w) return false;
    switch (k) {
    case SCENE_POUR: return build_pour(sc);
    case SCENE_CLOTH: return build_cloth(sc);
    case SCENE_ZOO: return build_zoo(sc);
    case SCENE_INTEGRATORS: return build_integrators(sc);
    case SCENE_SETTLE: return build_settle(sc);
    case SCENE_ROLL: return build_roll(sc);
    case SCENE_PYRAMID: return build_pyramid(sc);
    default: return false;
    }
}

static void drive_zoo(scene *sc, uint64_t s)
{
    tt_world *w = sc->w;
    double t = (double)s / 60;
    tt_shape_set_transform(w, sc->s[0], (tt_vec2){-6 + sin(t), 3}, 0.3 + 0.2 * sin(0.5 * t));
    if (s % 100 == 10) tt_distance_set_length(w, sc->c[0], s % 200 == 10 ? 0.4 : 1.5);
    if (s % 90 == 0) tt_pin_set_anchor(w, sc->c[1], (tt_vec2){-3 + 0.5 * sin(t), 6});
    if (s % 50 == 25) tt_particle_apply_impulse(w, sc->p[5], (tt_vec2){0.5, 2});
    if (s == 150) tt_particle_set_filter(w, sc->p[6], 2, 0xFFFE);
    if (s == 200) tt_particle_set_position(w, sc->p[4], (tt_vec2){0, 12}, TT_MOVE_RESET_VELOCITY);
}

static void drive_integrators(scene *sc, uint64_t s)
{
    tt_world *w = sc->w;
    static const tt_integrator order[] = {TT_VERLET, TT_RK4, TT_LEAPFROG, TT_EULER, TT_SYMPLECTIC_EULER};
    if (s % 60 == 0) tt_world_set_integrator(w, order[(s / 60) % 5]);
    if (s % 120 == 60) tt_world_set_solver_order(w, (s / 120) % 2 ? TT_GAUSS_SEIDEL : TT_JACOBI);
    tt_particle_apply_force(w, sc->p[3], (tt_vec2){sin((double)s * 0.1), 1});
    if (s % 45 == 0) tt_world_explode(w, (tt_vec2){5, 9}, 4, 0.3);
    if (s % 70 == 0) tt_spring_set_rest_length(w, sc->sp, 0.4 + 0.1 * (double)(s % 3));
}

void scene_step(scene *sc)
{
    tt_stats st;
    tt_world_get_stats(sc->w, &st);
    uint64_t s = st.steps;
    switch (sc->kind) {
    case SCENE_POUR:
        if (s % 40 == 0) tt_world_explode(sc->w, (tt_vec2){0, 2}, 3, 2);
        break;
    case SCENE_CLOTH:
        tt_shape_set_transform(sc->w, sc->s[0], (tt_vec2){0.3 + 0.8 * sin((double)s / 40), 1.5}, 0);
        break;
    case SCENE_ZOO: drive_zoo(sc, s); break;
    case SCENE_INTEGRATORS: drive_integrators(sc, s); break;
    case SCENE_SETTLE: drive_settle(sc, s); break;
    case SCENE_ROLL: drive_roll(sc, s); break;
    case SCENE_PYRAMID: drive_pyramid(sc, s); break;
    default: break;
    }
    tt_world_step(sc->w, 1.0 / 60);
}

/* A small world with one of nearly everything, for the byte-by-byte tests. */
tt_world *scene_small_world(void)
{
    tt_world *w = tt_world_create(NULL);
    tt_collision_settings cs = tt_collision_settings_default();
    cs.events = TT_EVENT_BEGIN | TT_EVENT_PERSIST | TT_EVENT_END;
    cs.anchored_friction = true; /* its anchors in the stream */
    tt_world_set_collision(w, &cs);
    static const tt_vec2 tri[] = {{-3, -1}, {3, -1}, {0, -0.5}};
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_POLYGON;
    sd.points = tri;
    sd.count = 3;
    tt_shape_create(w, &sd);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.3;
    tt_particle p[5];
    for (int i = 0; i < 5; i++) {
        pd.position = (tt_vec2){i * 0.5 - 1, -0.2 + 0.1 * (i % 2)};
        p[i] = tt_particle_create(w, &pd);
    }
    tt_particle_destroy(w, tt_particle_create(w, &pd));
    tt_particle_set_material(w, p[0], 0.5, 0.2, 0.1);
    tt_particle_set_bullet(w, p[1], true);
    tt_world_set_pair_collision(w, p[3], p[4], false);
    tt_spring_def sp = tt_spring_def_default();
    sp.a = p[0];
    sp.b = p[1];
    tt_spring_create(w, &sp);
    tt_distance_def dd = tt_distance_def_default();
    dd.a = p[1];
    dd.b = p[2];
    tt_constraint d = tt_distance_create(w, &dd);
    tt_distance_set_length(w, d, 0.3);
    tt_area_def ad = tt_area_def_default();
    ad.particles = &p[2];
    ad.count = 3;
    tt_area_create(w, &ad);
    tt_bounds_def bd = tt_bounds_def_default();
    bd.particles = &p[3];
    bd.count = 2;
    tt_bounds_create(w, &bd);
    tt_rope_def rd = tt_rope_def_default();
    rd.segments = 2;
    tt_rope_create(w, &rd);
    tt_world_step(w, 1.0 / 60);
    tt_world_step(w, 1.0 / 60);
    return w;
}

uint64_t scene_positions_digest(const tt_world *w)
{
    uint32_t n = tt_world_particle_count(w);
    double *xy = malloc((2 * (size_t)n + 1) * sizeof *xy);
    uint64_t h = 0xcbf29ce484222325ull;
    if (!xy) return 0;
    n = tt_world_read_positions(w, xy, n);
    const unsigned char *b = (const unsigned char *)xy;
    for (size_t i = 0; i < 2 * (size_t)n * sizeof *xy; i++) {
        h ^= b[i];
        h *= 0x100000001b3ull;
    }
    free(xy);
    return h;
}

void scene_spring_network(tt_world *w, int cols, int rows)
{
    const int n = cols * rows;
    tt_particle *p = malloc((size_t)n * sizeof *p);
    if (!p) return;
    for (int i = 0; i < n; i++) {
        tt_particle_def pd = tt_particle_def_default();
        pd.position = (tt_vec2){(i % cols) * 0.5, -(i / cols) * 0.5};
        pd.pinned = i < cols;
        p[i] = tt_particle_create(w, &pd);
    }
    for (int i = 0; i < n; i++) {
        tt_spring_def sd = tt_spring_def_default();
        sd.stiffness = 200;
        sd.damping = 0;
        sd.a = p[i];
        if (i % cols + 1 < cols) { sd.b = p[i + 1]; tt_spring_create(w, &sd); }
        if (i + cols < n) { sd.b = p[i + cols]; tt_spring_create(w, &sd); }
    }
    free(p);
}

unsigned char *scene_save(const tt_world *w, size_t *size)
{
    size_t n = 0;
    if (tt_world_save(w, NULL, 0, &n) != TT_ENOMEM || n == 0) return NULL;
    unsigned char *b = malloc(n);
    if (b && tt_world_save(w, b, n, size) != TT_OK) {
        free(b);
        return NULL;
    }
    return b;
}

tt_world *scene_reload(const tt_world *w)
{
    size_t n = 0;
    unsigned char *b = scene_save(w, &n);
    tt_world *c = b ? tt_world_load(b, n) : NULL;
    if (!c) printf("    the world's own stream did not %s: %s\n", b ? "load" : "save", tt_last_error(b ? NULL : w));
    free(b);
    return c;
}
