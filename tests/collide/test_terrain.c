/* Terrains: particles on carvable pixel ground, checked against known
 * answers (a frictionless slope's g·sin θ, rest on a floor, a carved hole),
 * and as state (snapshot → carve → restore). */
#include "test.h"
#include "tether.h"
#include "scenes/scene.h"
#include "core/scenes.h" /* scene_save, scene_reload */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PX 0.05 /* m per pixel */

/* A mask solid below the line v = v0 + u·tan θ (pixel centres; rows go down). */
static tt_mask *slope_mask(int w, int h, double v0, double deg)
{
    tt_mask *m = tt_mask_create(w, h, false);
    const double k = tan(deg * M_PI / 180.0);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            if (y + 0.5 > v0 + (x + 0.5) * k) tt_mask_set(m, x, y, true);
    return m;
}

static tt_terrain add_terrain(tt_world *w, const tt_mask *m, double mu)
{
    tt_terrain_def td = tt_terrain_def_default();
    td.solid = m;
    td.pixel = PX;
    td.friction_static = td.friction_kinetic = mu;
    return tt_terrain_create(w, &td);
}

static tt_particle ball(tt_world *w, double x, double y, double r, double mu)
{
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){x, y};
    pd.radius = r;
    tt_particle p = tt_particle_create(w, &pd);
    tt_particle_set_material(w, p, 0.0, mu, mu);
    return p;
}

TEST(terrain_frictionless_slope_accelerates_at_g_sin30)
{
    tt_world_def wd = tt_world_def_default();
    tt_world *w = tt_world_create(&wd);
    tt_mask *m = slope_mask(900, 600, 20.0, 30.0);
    tt_terrain t = add_terrain(w, m, 0.0);
    tt_mask_destroy(m); /* the terrain holds its own copy */
    ENSURE(tt_terrain_is_valid(w, t));
    const double r = 0.2, th = M_PI / 6, g = 9.81, dt = 1.0 / 60;
    /* on the surface at u = 60 px: world surface y = −(20 + u·tan θ)·PX */
    const double sx = 60 * PX, sy = -(20.0 + 60 * tan(th)) * PX;
    tt_particle p = ball(w, sx + sin(th) * r, sy + cos(th) * r, r, 0.0);
    double prev = 0.0, v_half = 0, v_two = 0;
    for (int k = 1; k <= 120; k++) {
        ENSURE_OK(tt_world_step(w, dt));
        tt_vec2 v;
        tt_particle_get_velocity(w, p, &v);
        const double speed = sqrt(v.x * v.x + v.y * v.y);
        ENSURE(speed >= prev); /* never drops from one step to the next */
        ENSURE(v.x > 0.0);
        prev = speed;
        if (k == 30) v_half = speed;
        if (k == 120) v_two = speed;
    }
    const double a = (v_two - v_half) / 1.5;
    ENSURE_NEAR(a, g * sin(th), 0.05 * g * sin(th));
    /* and it stayed on the surface: its distance to it is its radius within a pixel */
    tt_vec2 x;
    tt_particle_get_position(w, p, &x);
    double d;
    ENSURE_OK(tt_terrain_distance(w, t, x, &d, NULL));
    ENSURE_NEAR(d, r, PX);
    tt_world_destroy(w);
}

/* A floor from row 50 to 59 (y from −2.5 to −3.0 m). */
static tt_mask *floor_mask(void)
{
    tt_mask *m = tt_mask_create(200, 100, false);
    tt_mask_fill_rect(m, 0, 50, 200, 10, true);
    return m;
}

TEST(terrain_ball_rests_on_floor_and_falls_through_a_carved_hole)
{
    tt_world_def wd = tt_world_def_default();
    tt_world *w = tt_world_create(&wd);
    tt_mask *m = floor_mask();
    tt_terrain t = add_terrain(w, m, 0.6);
    tt_mask_destroy(m);
    const double r = 0.2;
    tt_particle p = ball(w, 5.0, -1.0, r, 0.6);
    for (int k = 0; k < 180; k++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
    tt_vec2 x, v;
    tt_particle_get_position(w, p, &x);
    tt_particle_get_velocity(w, p, &v);
    ENSURE_NEAR(x.y, -2.5 + r, PX); /* rests at the floor within one pixel */
    ENSURE(fabs(v.y) < 1e-3);
    ENSURE_OK(tt_terrain_paint_circle(w, t, (tt_vec2){5.0, -2.75}, 0.6, false));
    bool solid = true;
    ENSURE_OK(tt_terrain_is_solid(w, t, (tt_vec2){5.0, -2.75}, &solid));
    ENSURE(!solid);
    for (int k = 0; k < 60; k++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
    tt_particle_get_position(w, p, &x);
    ENSURE(x.y < -3.0 - r); /* through the floor */
    tt_world_destroy(w);
}

/* The same with sleeping on: the ball falls asleep on the floor, and the
 * carve wakes it (the carve's box reaches the sleeping islands it touches). */
TEST(terrain_carve_wakes_a_ball_asleep_on_it)
{
    tt_world_def wd = tt_world_def_default();
    wd.sleep = true;
    tt_world *w = tt_world_create(&wd);
    tt_mask *m = floor_mask();
    tt_terrain t = add_terrain(w, m, 0.6);
    tt_mask_destroy(m);
    const double r = 0.2;
    tt_particle p = ball(w, 5.0, -1.0, r, 0.6);
    bool asleep = false;
    for (int k = 0; k < 600 && !asleep; k++) {
        ENSURE_OK(tt_world_step(w, 1.0 / 60));
        ENSURE_OK(tt_particle_get_asleep(w, p, &asleep));
    }
    ENSURE(asleep);
    ENSURE_OK(tt_terrain_paint_circle(w, t, (tt_vec2){5.0, -2.75}, 0.6, false));
    ENSURE_OK(tt_particle_get_asleep(w, p, &asleep));
    ENSURE(!asleep);
    for (int k = 0; k < 60; k++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
    tt_vec2 x;
    tt_particle_get_position(w, p, &x);
    ENSURE(x.y < -3.0 - r); /* through the floor */
    tt_world_destroy(w);
}

/* Found by the C fuzzer (make fuzz SANITIZE=1, seed 1796184749): a big
 * particle beside a terrain of tiny pixels is within reach of it while its
 * centre is billions of pixels away, and the pixel index was cast to int
 * unclamped (UBSan float-cast-overflow: the SANITIZE=1 build is the check). */
TEST(terrain_far_big_particle_beside_tiny_pixels)
{
    tt_world *w = tt_world_create(NULL);
    tt_mask *m = floor_mask();
    tt_terrain_def td = tt_terrain_def_default();
    td.solid = m;
    td.pixel = 1e-6;
    tt_terrain t = tt_terrain_create(w, &td);
    tt_mask_destroy(m);
    ENSURE(tt_terrain_is_valid(w, t));
    tt_particle p = ball(w, -5000.0, 0.0, 1e4, 0.0);
    ENSURE(p.gen != 0);
    for (int k = 0; k < 3; k++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
    tt_vec2 x;
    tt_particle_get_position(w, p, &x);
    ENSURE(isfinite(x.x) && isfinite(x.y));
    tt_world_destroy(w);
}

TEST(terrain_snapshot_carve_restore_is_bit_exact)
{
    tt_world_def wd = tt_world_def_default();
    tt_world *w = tt_world_create(&wd);
    tt_mask *m = floor_mask();
    tt_terrain t = add_terrain(w, m, 0.6);
    tt_particle p = ball(w, 5.0, -1.0, 0.2, 0.6);
    (void)p;
    for (int k = 0; k < 10; k++) tt_world_step(w, 1.0 / 60);
    size_t size = 0;
    unsigned char *buf = scene_save(w, &size);
    ENSURE(buf);
    const uint64_t h0 = tt_world_hash(w);
    double d0;
    tt_terrain_distance(w, t, (tt_vec2){5.0, -2.3}, &d0, NULL);
    ENSURE_OK(tt_terrain_paint_circle(w, t, (tt_vec2){5.0, -2.75}, 0.6, false));
    ENSURE(tt_world_hash(w) != h0); /* the pixels are state */
    ENSURE_OK(tt_world_restore(w, buf, size));
    ENSURE(tt_world_hash(w) == h0);
    ENSURE(tt_terrain_is_valid(w, t));
    const tt_mask *now;
    ENSURE_OK(tt_terrain_get_mask(w, t, &now));
    ENSURE(tt_mask_overlap_area(now, m, 0, 0) == tt_mask_count(m) && tt_mask_count(now) == tt_mask_count(m));
    double d1;
    tt_terrain_distance(w, t, (tt_vec2){5.0, -2.3}, &d1, NULL);
    ENSURE(d0 == d1);
    /* a loaded copy runs on as the original */
    tt_world *c = tt_world_load(buf, size);
    ENSURE(c && tt_world_hash(c) == h0);
    for (int k = 0; k < 30; k++) {
        tt_world_step(w, 1.0 / 60);
        tt_world_step(c, 1.0 / 60);
    }
    ENSURE(tt_world_hash(c) == tt_world_hash(w));
    tt_world_destroy(c);
    free(buf);
    tt_mask_destroy(m);
    tt_world_destroy(w);
}

/* The band after a carve equals the band of a terrain made from the carved pixels. */
TEST(terrain_carve_updates_the_band_as_a_rebuild_would)
{
    tt_world_def wd = tt_world_def_default();
    tt_world *w = tt_world_create(&wd);
    tt_mask *m = slope_mask(300, 200, 40.0, 20.0);
    tt_terrain t = add_terrain(w, m, 0.6);
    ENSURE_OK(tt_terrain_paint_circle(w, t, (tt_vec2){5.0, -5.0}, 1.0, false));
    ENSURE_OK(tt_terrain_paint_circle(w, t, (tt_vec2){8.0, -6.5}, 0.7, true));
    const tt_mask *now;
    tt_terrain_get_mask(w, t, &now);
    tt_terrain t2 = add_terrain(w, now, 0.6);
    double worst = 0.0;
    for (int y = 0; y < 200; y++)
        for (int x = 0; x < 300; x++) {
            tt_vec2 q = {(x + 0.5) * PX, -(y + 0.5) * PX};
            double a, b;
            tt_terrain_distance(w, t, q, &a, NULL);
            tt_terrain_distance(w, t2, q, &b, NULL);
            worst = fmax(worst, fabs(a - b));
        }
    ENSURE(worst == 0.0);
    tt_mask_destroy(m);
    tt_world_destroy(w);
}

TEST(terrain_bullet_never_crosses_a_thin_wall)
{
    tt_world_def wd = tt_world_def_default();
    wd.gravity = (tt_vec2){0, 0};
    tt_world *w = tt_world_create(&wd);
    tt_mask *m = tt_mask_create(400, 100, false);
    tt_mask_fill_rect(m, 200, 0, 2, 100, true); /* a wall two pixels thick at x = 10 m */
    add_terrain(w, m, 0.0);
    tt_mask_destroy(m);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.05;
    pd.position = (tt_vec2){1.0, -2.5};
    pd.velocity = (tt_vec2){500.0, 0.0}; /* 8 m a step */
    tt_particle p = tt_particle_create(w, &pd);
    ENSURE_OK(tt_particle_set_bullet(w, p, true));
    for (int k = 0; k < 10; k++) {
        tt_world_step(w, 1.0 / 60);
        tt_vec2 x;
        tt_particle_get_position(w, p, &x);
        ENSURE(x.x < 10.0);
    }
    tt_world_destroy(w);
}

TEST(terrain_raycast_and_events_see_the_terrain)
{
    tt_world_def wd = tt_world_def_default();
    tt_world *w = tt_world_create(&wd);
    tt_mask *m = floor_mask();
    tt_terrain t = add_terrain(w, m, 0.6);
    tt_mask_destroy(m);
    tt_ray_hit hit;
    ENSURE_OK(tt_world_raycast(w, (tt_vec2){3.0, 0.0}, (tt_vec2){3.0, -5.0}, 0xFFFF, &hit));
    ENSURE(hit.hit && hit.terrain.index == t.index && hit.terrain.gen == t.gen);
    ENSURE_NEAR(hit.point.y, -2.5, 0.3 * PX);
    ENSURE_NEAR(hit.normal.y, 1.0, 1e-6);
    tt_collision_settings cs = tt_collision_settings_default();
    cs.events = TT_EVENT_BEGIN;
    tt_world_set_collision(w, &cs);
    ball(w, 5.0, -2.0, 0.2, 0.6);
    bool seen = false;
    for (int k = 0; k < 60 && !seen; k++) {
        tt_world_step(w, 1.0 / 60);
        uint32_t n;
        const tt_contact_event *ev = tt_world_get_contact_events(w, &n);
        for (uint32_t i = 0; i < n; i++)
            if (ev[i].terrain.index == t.index && ev[i].terrain.gen == t.gen && ev[i].shape.gen == 0) seen = true;
    }
    ENSURE(seen);
    tt_world_destroy(w);
}

/* A ball resting on the floor with every event kind on: the last step's
 * records and events name the terrain, in a copy loaded from a snapshot as
 * in the original, and the next steps' events match. */
TEST(terrain_events_keep_their_terrain_through_a_snapshot)
{
    tt_world_def wd = tt_world_def_default();
    tt_world *w = tt_world_create(&wd);
    tt_mask *m = floor_mask();
    tt_terrain t = add_terrain(w, m, 0.6);
    tt_mask_destroy(m);
    tt_collision_settings cs = tt_collision_settings_default();
    cs.events = TT_EVENT_BEGIN | TT_EVENT_PERSIST | TT_EVENT_END;
    tt_world_set_collision(w, &cs);
    ball(w, 5.0, -2.25, 0.2, 0.6);
    for (int k = 0; k < 30; k++) tt_world_step(w, 1.0 / 60);
    tt_world *c = scene_reload(w);
    ENSURE(c != NULL);
    for (int k = 0; k < 3 && c; k++) {
        uint32_t nw, nc;
        const tt_contact_event *ew = tt_world_get_contact_events(w, &nw), *ec = tt_world_get_contact_events(c, &nc);
        ENSURE(nw == 1 && nc == 1 && ew[0].kind == TT_EVENT_PERSIST);
        ENSURE(ew[0].terrain.index == t.index && ew[0].terrain.gen == t.gen);
        ENSURE(ec[0].kind == ew[0].kind && ec[0].terrain.index == t.index && ec[0].terrain.gen == t.gen);
        ENSURE(ec[0].shape.gen == 0 && ec[0].b.gen == 0);
        if (k == 1) { /* lift the ball off: the END names the terrain too */
            tt_particle p = {0, 0};
            uint32_t np = 0;
            tt_world_query_point(w, (tt_vec2){5.0, -2.3}, 0xFFFF, &p, 1, &np, NULL, 0, NULL);
            tt_particle_set_position(w, p, (tt_vec2){5.0, 0.0}, TT_MOVE_RESET_VELOCITY);
            tt_particle_set_position(c, p, (tt_vec2){5.0, 0.0}, TT_MOVE_RESET_VELOCITY);
        }
        tt_world_step(w, 1.0 / 60);
        tt_world_step(c, 1.0 / 60);
        if (k == 1) {
            ew = tt_world_get_contact_events(w, &nw);
            ec = tt_world_get_contact_events(c, &nc);
            ENSURE(nw == 1 && nc == 1 && ew[0].kind == TT_EVENT_END && ec[0].kind == TT_EVENT_END);
            ENSURE(ec[0].terrain.index == t.index && ec[0].terrain.gen == t.gen);
            break;
        }
    }
    ENSURE(c && tt_world_hash(c) == tt_world_hash(w));
    tt_world_destroy(c);
    tt_world_destroy(w);
}

/* Point and box queries list the terrains with a solid pixel there. */
TEST(terrain_point_and_box_queries_list_terrains)
{
    tt_world_def wd = tt_world_def_default();
    tt_world *w = tt_world_create(&wd);
    tt_mask *m = floor_mask(); /* solid from y = -2.5 to -3.0 m, x from 0 to 10 m */
    tt_terrain t = add_terrain(w, m, 0.6);
    tt_mask_destroy(m);
    tt_terrain out[2] = {{0, 0}, {0, 0}};
    uint32_t n = 99;
    ENSURE_OK(tt_world_query_terrains(w, (tt_vec2){5.0, -2.75}, (tt_vec2){5.0, -2.75}, 0xFFFF, out, 2, &n));
    ENSURE(n == 1 && out[0].index == t.index && out[0].gen == t.gen);
    ENSURE_OK(tt_world_query_terrains(w, (tt_vec2){5.0, -2.4}, (tt_vec2){5.0, -2.4}, 0xFFFF, out, 2, &n));
    ENSURE(n == 0); /* above the floor */
    ENSURE_OK(tt_world_query_terrains(w, (tt_vec2){1.0, -2.45}, (tt_vec2){2.0, -2.0}, 0xFFFF, out, 2, &n));
    ENSURE(n == 0); /* a box wholly above it */
    ENSURE_OK(tt_world_query_terrains(w, (tt_vec2){1.0, -2.55}, (tt_vec2){2.0, -2.0}, 0xFFFF, NULL, 0, &n));
    ENSURE(n == 1); /* one reaching into it, counted with no room */
    ENSURE_OK(tt_world_query_terrains(w, (tt_vec2){-5.0, -9.0}, (tt_vec2){-1.0, 1.0}, 0xFFFF, out, 2, &n));
    ENSURE(n == 0); /* beside it */
    ENSURE_OK(tt_world_query_terrains(w, (tt_vec2){5.0, -2.75}, (tt_vec2){5.0, -2.75}, 0x0002, out, 2, &n));
    ENSURE(n == 0); /* another layer */
    ENSURE_OK(tt_terrain_paint_circle(w, t, (tt_vec2){5.0, -2.75}, 0.3, false));
    ENSURE_OK(tt_world_query_terrains(w, (tt_vec2){5.0, -2.75}, (tt_vec2){5.0, -2.75}, 0xFFFF, out, 2, &n));
    ENSURE(n == 0); /* carved */
    const uint64_t h = tt_world_hash(w);
    ENSURE(tt_world_query_terrains(w, (tt_vec2){2.0, 0.0}, (tt_vec2){1.0, 0.0}, 0xFFFF, out, 2, &n) == TT_EINVAL);
    ENSURE(tt_world_query_terrains(w, (tt_vec2){NAN, 0.0}, (tt_vec2){1.0, 0.0}, 0xFFFF, out, 2, &n) == TT_EINVAL);
    ENSURE(tt_world_query_terrains(w, (tt_vec2){0.0, 0.0}, (tt_vec2){1.0, 0.0}, 0xFFFF, NULL, 2, &n) == TT_EINVAL);
    ENSURE(tt_world_hash(w) == h);
    tt_world_destroy(w);
}

TEST(terrain_pushes_a_buried_particle_out)
{
    tt_world_def wd = tt_world_def_default();
    tt_world *w = tt_world_create(&wd);
    tt_mask *m = tt_mask_create(200, 200, false);
    tt_mask_fill_rect(m, 0, 100, 200, 100, true); /* solid from y = −5 m down */
    tt_terrain t = add_terrain(w, m, 0.6);
    tt_mask_destroy(m);
    tt_particle p = ball(w, 5.0, -5.6, 0.1, 0.6); /* 12 pixels deep: past the band */
    for (int k = 0; k < 120; k++) tt_world_step(w, 1.0 / 60);
    tt_vec2 x;
    tt_particle_get_position(w, p, &x);
    bool solid;
    tt_terrain_is_solid(w, t, x, &solid);
    ENSURE(!solid);
    ENSURE(x.y > -5.0);
    tt_world_destroy(w);
}

TEST(terrain_bad_input_and_stale_handles_leave_the_world_as_it_was)
{
    tt_world_def wd = tt_world_def_default();
    tt_world *w = tt_world_create(&wd);
    const uint64_t h0 = tt_world_hash(w);
    tt_terrain_def td = tt_terrain_def_default();
    tt_terrain t = tt_terrain_create(w, &td); /* no mask */
    ENSURE(t.gen == 0 && tt_world_hash(w) == h0);
    tt_mask *m = floor_mask();
    td.solid = m;
    td.pixel = NAN;
    ENSURE(tt_terrain_create(w, &td).gen == 0);
    td.pixel = PX;
    td.band = 1;
    ENSURE(tt_terrain_create(w, &td).gen == 0);
    ENSURE(tt_world_hash(w) == h0);
    td.band = 10;
    t = tt_terrain_create(w, &td);
    ENSURE(t.gen != 0 && tt_world_terrain_count(w) == 1);
    const uint64_t h1 = tt_world_hash(w);
    ENSURE(tt_terrain_paint_circle(w, t, (tt_vec2){NAN, 0}, 1.0, false) == TT_EINVAL);
    ENSURE(tt_terrain_paint_circle(w, t, (tt_vec2){0, 0}, -1.0, false) == TT_EINVAL);
    ENSURE(tt_terrain_paint_circle(w, t, (tt_vec2){0, 0}, 1e12, false) == TT_OK); /* everything: cost bounded by the terrain */
    ENSURE(tt_world_hash(w) != h1);
    ENSURE_OK(tt_terrain_paint_mask(w, t, m, 0, 0, true));
    ENSURE(tt_world_hash(w) == h1); /* filled back as it was */
    ENSURE(tt_terrain_paint_mask(w, t, NULL, 0, 0, true) == TT_EINVAL);
    ENSURE_OK(tt_terrain_paint_mask(w, t, m, -5000, 3000, false)); /* wholly outside: nothing */
    ENSURE(tt_world_hash(w) == h1);
    ENSURE_OK(tt_terrain_destroy(w, t));
    ENSURE(tt_terrain_destroy(w, t) == TT_ESTALE);
    ENSURE(tt_terrain_paint_circle(w, t, (tt_vec2){0, 0}, 1.0, false) == TT_ESTALE);
    ENSURE(!tt_terrain_is_valid(w, t) && tt_world_terrain_count(w) == 0);
    tt_terrain u = tt_terrain_from_u64(tt_terrain_to_u64(t));
    ENSURE(u.index == t.index && u.gen == t.gen && tt_handle_kind(tt_terrain_to_u64(t)) == TT_KIND_TERRAIN);
    tt_mask_destroy(m);
    tt_world_destroy(w);
}

/* The reference pour onto a mask bowl (src/scenes/scene_bowl.c, shared
 * with the bench's 10 000 circles for 20 s), smaller: 1 000 circles into a
 * bowl 31.6 m wide for 15 s. At rest (kinetic energy ≤ 1e-3 J/kg), no
 * centre in a solid pixel, no circle deeper than a tenth of its radius.
 * (It was 5 s, but the pile was at rest then only at that instant: 2.6e-4
 * J/kg at 5 s, 5.2e-3 at 5.5 s, 2.5e-3 at 7.5 s. With pre-stabilisation it
 * rattles at 5 s too, 5e-3, and is under 2e-5 from 12.5 s; 1.4e-9 at 15 s,
 * 1.5e-7 before.) */
TEST(terrain_pour_into_a_mask_bowl_comes_to_rest)
{
    ts_bowl b;
    const char *why = NULL;
    ENSURE_OK(ts_bowl_build(1000, 31.6, &b, &why));
    for (int s = 0; s < 900; s++) ENSURE_OK(tt_world_step(b.t.world, 1.0 / 60));
    ts_bowl_figures f;
    ts_bowl_measure(&b, &f);
    ENSURE(b.t.circle_count == 1000);
    ENSURE(f.kinetic <= 1e-3); /* J/kg */
    ENSURE(f.inside == 0);
    ENSURE(f.penetration <= 0.1);
    ts_bowl_free(&b);
}

/* The same bowl with anchored friction (tt_collision_settings.
 * anchored_friction), from three starts jittered by up to ±0.05 m: every
 * step of the second half of the 15 s within issue 19's bound (1e-3 J/kg),
 * and at rest at 15 s (under 1e-5), where the plain build's piles still
 * slide on some starts (the second: 1.6e-3 J/kg at 12.8 s, 7.5e-4 at 15 s).
 * Over seeds 1–10 (docs/collisions.md "Anchored friction"), anchored, the
 * second half's largest is 5.0e-7 … 1.5e-4 (the second start: one slip at
 * 9.7 s) and 15 s ends at 1.1e-8 … 8.4e-7; plain 1.2e-6 … 4.9e-2 and up to
 * 6.4e-3. (It asked for every step under 1e-4 while the pairs were solved
 * in the grid's order, one by one: 7.8e-7 … 3.3e-5 then.) */
TEST(terrain_pour_into_a_mask_bowl_rests_from_jittered_starts_with_anchored_friction)
{
    if (getenv("TT_MEMCHECK")) return; /* 8 s of pour: minutes under valgrind */
    for (uint64_t seed = 1; seed <= 3; seed++) {
        ts_bowl b;
        const char *why = NULL;
        ENSURE_OK(ts_bowl_build(1000, 31.6, &b, &why));
        ENSURE_OK(ts_tether_jitter(&b.t, seed, 0.05));
        tt_collision_settings cs;
        tt_world_get_collision(b.t.world, &cs);
        cs.anchored_friction = true;
        ENSURE_OK(tt_world_set_collision(b.t.world, &cs));
        double most = 0.0;
        for (int s = 1; s <= 900; s++) {
            ENSURE_OK(tt_world_step(b.t.world, 1.0 / 60));
            if (s > 450) most = fmax(most, ts_tether_kinetic_per_kg(&b.t));
        }
        ts_bowl_figures f;
        ts_bowl_measure(&b, &f);
        printf("    start %d: KE at most %.1e J/kg over 7.5-15 s, %.1e at 15 s; deepest into the bowl %.1f %% of a radius\n",
               (int)seed, most, f.kinetic, 100 * f.penetration);
        ENSURE(most <= 1e-3);
        ENSURE(f.kinetic <= 1e-5);
        ENSURE(f.inside == 0);
        ENSURE(f.penetration <= 0.1);
        ts_bowl_free(&b);
    }
}

/* A frictionless ball released on the side of a pixel half-pipe (radius
 * 5 m, 0.05 m pixels) rolls down the curve, never slower while it is
 * steeper than 12°, and up the other side to most of its height. */
TEST(terrain_ball_rolls_across_a_curved_pixel_halfpipe)
{
    tt_world_def wd = tt_world_def_default();
    tt_world *w = tt_world_create(&wd);
    tt_mask *m = tt_mask_create(240, 140, true);
    tt_mask_fill_circle(m, 120, 20, 100, false); /* centre (6, −1) m, radius 5 m */
    tt_terrain t = add_terrain(w, m, 0.0);
    tt_mask_destroy(m);
    ENSURE(t.gen != 0);
    const double R = 5.0, r = 0.2, a = -M_PI / 4; /* released 45° left of the bottom */
    const double cx = 6.0, cy = -1.0, y0 = cy - (R - r) * cos(a);
    tt_particle p = ball(w, cx + (R - r) * sin(a), y0, r, 0.0);
    double prev = 0.0, highest_right = -INFINITY;
    bool descending = true;
    for (int k = 0; k < 150; k++) {
        ENSURE_OK(tt_world_step(w, 1.0 / 60));
        tt_vec2 x, v;
        tt_particle_get_position(w, p, &x);
        tt_particle_get_velocity(w, p, &v);
        const double speed = hypot(v.x, v.y);
        if (descending && x.x < cx - 1.0) ENSURE(speed >= prev); /* down the curve, steeper than 12°: never slower */
        if (x.x >= cx) descending = false;
        if (x.x > cx) highest_right = fmax(highest_right, x.y);
        prev = speed;
    }
    const double drop = y0 - (cy - (R - r));
    /* back up to 88 % of its drop (0.94 of its energy is left at the bottom: a
     * curve of 4.8 m taken in steps of 1/60 s loses some to each projection;
     * with 4 substeps 0.98 is left) */
    ENSURE(highest_right - (cy - (R - r)) >= 0.85 * drop);
    tt_world_destroy(w);
}
