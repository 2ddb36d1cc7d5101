/* The terrains' tile map (src/collide/terrain_tiles.c) only spares the test
 * particles that could have no terrain contact: twin worlds, one with the
 * map turned off (the tt__terrains debug field no_tiles), step bit for bit
 * alike through a pour onto a floor, a pillar and a floating ledge, with
 * particles falling along the pillar at the band's edge, one buried in the
 * solid, bullets into the ground, carves and fills during the run (one
 * under the pile, one burying grains) and a snapshot → carve → restore;
 * and again with one particle too big for the map (every particle tested).
 * A terrain whose making runs out of memory leaves the world as it was. */
#include "test.h"
#include "alloc_fail.h"
#include "collide/terrain_internal.h"
#include "core/scenes.h" /* scene_save, scene_positions_digest */
#include "tether.h"

#include <stdlib.h>

#define PX 0.05 /* m per pixel */

/* 320 × 240 pixels (16 × 12 m, partial tiles at the edges) from (0, 0): a
 * floor from row 200 (y = −10), a pillar over columns 150–169 (x 7.5–8.5 m)
 * from row 120, a ledge over columns 40–99, rows 80–87, walls six pixels
 * thick; most of it empty, far from every surface. */
static tt_terrain ground(tt_world *w)
{
    tt_mask *m = tt_mask_create(320, 240, false);
    tt_mask_fill_rect(m, 0, 200, 320, 40, true);
    tt_mask_fill_rect(m, 150, 120, 20, 80, true);
    tt_mask_fill_rect(m, 40, 80, 60, 8, true);
    tt_mask_fill_rect(m, 0, 0, 6, 200, true);
    tt_mask_fill_rect(m, 314, 0, 6, 200, true);
    tt_terrain_def td = tt_terrain_def_default();
    td.solid = m;
    td.pixel = PX;
    td.friction_static = td.friction_kinetic = 0.3;
    tt_terrain t = tt_terrain_create(w, &td);
    tt_mask_destroy(m);
    return t;
}

static void circle(tt_world *w, double x, double y, double r, double vx, double vy, bool bullet)
{
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){x, y};
    pd.velocity = (tt_vec2){vx, vy};
    pd.radius = r;
    tt_particle p = tt_particle_create(w, &pd);
    if (bullet) tt_particle_set_bullet(w, p, true);
}

static tt_world *twin(bool big, tt_terrain *t)
{
    tt_world_def wd = tt_world_def_default();
    tt_world *w = tt_world_create(&wd);
    tt_collision_settings cs = tt_collision_settings_default();
    cs.particles = true;
    tt_world_set_collision(w, &cs);
    *t = ground(w);
    for (int i = 0; i < 160; i++) /* a pour from high up, radii 0.06–0.15 m */
        circle(w, 0.6 + (i % 20) * 0.74 + 0.03 * (i / 20), -0.3 - (i / 20) * 0.35, 0.06 + 0.01 * (i % 10), 0.0, 0.0, false);
    for (int k = 0; k <= 24; k++) /* falling beside the pillar (x = 7.5 m), 0–2.4 pixels beyond reach (r·1.1 + a pixel) */
        circle(w, 7.5 - 0.1 * 1.1 - PX - 0.005 * k, -6.3 - 0.12 * k, 0.1, 0.0, 0.0, false);
    circle(w, 4.0, -10.4, 0.1, 0.0, 0.0, false);         /* buried in the floor, 8 pixels deep */
    circle(w, 11.0, -0.5, 0.05, 0.0, -300.0, true);      /* bullets: into the floor, into the pillar */
    circle(w, 14.0, -8.0, 0.05, -250.0, 0.0, true);
    if (big) circle(w, 13.0, -1.0, 0.45, 0.0, 0.0, false); /* reach 0.495 m ≥ (band − 1) pixels: no map */
    return w;
}

/* One step of a twin: fills and carves at set steps. */
static void step(tt_world *w, tt_terrain t, int s)
{
    if (s == 20) tt_terrain_paint_circle(w, t, (tt_vec2){12.3, -6.0}, 0.6, true);  /* in mid-air, where grains fall */
    if (s == 100) tt_terrain_paint_circle(w, t, (tt_vec2){3.0, -10.1}, 0.5, false); /* under the pile */
    if (s == 110) tt_terrain_paint_circle(w, t, (tt_vec2){5.5, -9.9}, 0.4, true);   /* over grains */
    if (s == 120) tt_terrain_paint_circle(w, t, (tt_vec2){7.5, -9.0}, 0.3, false);  /* into the pillar */
    tt_world_step(w, 1.0 / 60);
}

static int run_twins(bool big)
{
    tt_terrain ta, tb;
    tt_world *a = twin(big, &ta), *b = twin(big, &tb);
    tt__collide_peek(b)->terr->no_tiles = true;
    int bad = 0;
    size_t size = 0;
    unsigned char *buf = NULL;
    for (int s = 0; s < 200 && !bad; s++) {
        if (s == 130) { /* snapshot → a crater under the pile → restore: the map is rebuilt with the band */
            buf = scene_save(a, &size);
            tt_terrain_paint_circle(a, ta, (tt_vec2){6.0, -10.0}, 1.2, false);
            tt_world_step(a, 1.0 / 60);
            if (!buf || tt_world_restore(a, buf, size) != TT_OK || tt_world_restore(b, buf, size) != TT_OK) bad++;
            tt__collide_peek(b)->terr->no_tiles = true; /* not state: the restore made the terrains anew */
        }
        step(a, ta, s);
        step(b, tb, s);
        if (tt_world_hash(a) != tt_world_hash(b) || scene_positions_digest(a) != scene_positions_digest(b)) {
            tt_test_fail(__FILE__, __LINE__, "%s: the twins differ after step %d", big ? "big" : "map", s + 1);
            bad++;
        }
    }
    free(buf);
    tt_world_destroy(a);
    tt_world_destroy(b);
    return bad;
}

TEST(terrain_tile_map_skips_only_particles_without_a_contact)
{
    ENSURE(run_twins(false) == 0);
    ENSURE(run_twins(true) == 0);
}

/* The map at work: the pour comes to rest on the floor (none sinks in,
 * none passes through), as without it. */
TEST(terrain_tile_map_pour_rests_on_the_floor)
{
    tt_terrain t;
    tt_world *w = twin(false, &t);
    for (int s = 0; s < 240; s++) tt_world_step(w, 1.0 / 60);
    const uint32_t n = tt_world_particle_count(w);
    double *xy = malloc(2 * (size_t)n * sizeof *xy);
    ENSURE(xy);
    const uint32_t got = tt_world_read_positions(w, xy, n);
    uint32_t inside = 0;
    for (uint32_t i = 0; i < got; i++) {
        bool solid = false;
        tt_terrain_is_solid(w, t, (tt_vec2){xy[2 * i], xy[2 * i + 1]}, &solid);
        inside += solid;
        ENSURE(xy[2 * i + 1] > -10.0); /* none fell through the floor */
    }
    ENSURE(inside == 0);
    free(xy);
    tt_world_destroy(w);
}

TEST(terrain_making_out_of_memory_leaves_the_world)
{
    tt_terrain t0;
    tt_world *w = twin(false, &t0);
    for (int s = 0; s < 5; s++) tt_world_step(w, 1.0 / 60);
    const uint64_t h = tt_world_hash(w);
    bool made = false;
    for (long k = 0; k < 64 && !made; k++) {
        tt_test_alloc_fail_from(k);
        tt_terrain t = ground(w);
        const bool refused = tt_test_alloc_ok();
        made = t.gen != 0;
        if (!made) {
            ENSURE(refused);
            ENSURE(tt_world_terrain_count(w) == 1 && tt_world_hash(w) == h);
        }
    }
    ENSURE(made && tt_world_terrain_count(w) == 2);
    tt_world_step(w, 1.0 / 60);
    tt_world_destroy(w);
}
