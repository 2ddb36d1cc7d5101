/* tether — terrain benchmark: the cost of a carve in a big terrain (issue
 * 19: a radius-20-pixel crater in 2048 × 1024 pixels, target ≤ 50 µs), the
 * reference pour onto a mask floor against the same floor as a chain shape,
 * the two worlds stepped in turn (A B A B) so the machine's load falls on both, and
 * the reference pour (10 000 circles, 20 s) onto a mask bowl with its rest
 * figures (src/scenes/scene_bowl.c, shared with the tests), beside the same
 * bowl in Box2D. */
#include "bench.h"

#include "box2d/box2d_scene.h"
#include "scenes/scene.h"
#include "tether.h"

#include <math.h>
#include <stdlib.h>

static void carve(FILE *csv)
{
    tt_world_def wd = tt_world_def_default();
    tt_world *w = tt_world_create(&wd);
    tt_mask *m = tt_mask_create(2048, 1024, false);
    tt_mask_fill_rect(m, 0, 300, 2048, 724, true);
    tt_terrain_def td = tt_terrain_def_default();
    td.solid = m;
    double t0 = bench_now_ns();
    tt_terrain t = tt_terrain_create(w, &td);
    const double make_ms = (bench_now_ns() - t0) * 1e-6;
    enum { N = 400 };
    double us[N];
    for (int k = 0; k < N; k++) { /* scattered craters, each filled back so the ground stays */
        const tt_vec2 c = {(100 + (k * 97) % 1800) * td.pixel, -(320 + (k * 31) % 600) * td.pixel};
        const double a = bench_now_ns();
        tt_terrain_paint_circle(w, t, c, 20 * td.pixel, false);
        us[k] = (bench_now_ns() - a) * 1e-3;
        tt_terrain_paint_circle(w, t, c, 20 * td.pixel, true);
    }
    const double med = bench_median(us, N);
    printf("  carve r = 20 px in 2048 x 1024: median %.1f us (min %.1f, max %.1f) over %d; making it %.0f ms"
           " (target <= 50 us)\n", med, us[0], us[N - 1], N, make_ms);
    fprintf(csv, "carve,%.3f,%.3f,%.3f,%.3f\n", med, us[0], us[N - 1], make_ms);
    tt_mask_destroy(m);
    tt_world_destroy(w);
}

/* The reference pour into a U, once as a chain floor and once as a mask
 * floor (src/scenes/scene_floor.c), stepped in turns of CHUNK steps. */
static void pour(FILE *csv)
{
    enum { N = 10000, CHUNK = 30 };
    ts_tether t[2];
    const char *why = NULL;
    for (int k = 0; k < 2; k++)
        if (ts_floor_build(N, 100, k == 1, &t[k], &why) != TT_OK) {
            printf("  pour onto a floor: %s\n", why ? why : "failed");
            if (k == 1) ts_tether_free(&t[0]);
            return;
        }
    const uint32_t steps = 1200;
    double ns[2] = {0, 0}, contacts[2] = {0, 0}, pairs[2] = {0, 0};
    for (uint32_t s = 0; s < steps; s += CHUNK)
        for (int k = 0; k < 2; k++)
            for (int j = 0; j < CHUNK; j++) {
                const double a = bench_now_ns();
                tt_world_step(t[k].world, 1.0 / 60);
                ns[k] += bench_now_ns() - a;
                tt_collision_stats st;
                tt_world_get_collision_stats(t[k].world, &st);
                contacts[k] += st.shape_contacts;
                pairs[k] += st.pair_contacts;
            }
    static const char *name[2] = {"chain floor", "mask floor"};
    for (int k = 0; k < 2; k++) {
        double lowest = INFINITY, *xy = malloc(2 * N * sizeof *xy);
        uint32_t n = tt_world_read_positions(t[k].world, xy, N);
        for (uint32_t i = 0; i < n; i++) lowest = fmin(lowest, xy[2 * i + 1]);
        ts_pile pile;
        ts_pile_measure(xy, n, 0.5, &pile);
        free(xy);
        const double ke = ts_tether_kinetic_per_kg(&t[k]);
        printf("  reference pour (%d circles, 20 s), %s: %.3f ms/step, %.0f static contacts/step, lowest centre"
               " %.4f m (r 0.5), overlap max %.1f %% mean %.2f %%, KE %.2e J/kg\n", N, name[k], ns[k] / steps * 1e-6,
               contacts[k] / steps, lowest, 100 * pile.max_overlap, 100 * pile.mean_overlap, ke);
        fprintf(csv, "%s,%.4f,%.1f,%.5f,%.3e\n", name[k], ns[k] / steps * 1e-6, contacts[k] / steps, lowest, ke);
        ts_tether_free(&t[k]);
    }
    /* per particle-contact: the step's time over its contacts (pairs and the floor's) */
    const double per[2] = {ns[0] / (contacts[0] + pairs[0]), ns[1] / (contacts[1] + pairs[1])};
    printf("  mask / chain: %.2fx per step, %.2fx per particle-contact (%.1f against %.1f ns; target <= 1.1x)\n",
           ns[1] / ns[0], per[1] / per[0], per[1], per[0]);
    fprintf(csv, "per contact,%.3f,%.3f,%.4f,0\n", per[0], per[1], per[1] / per[0]);
}

/* The same bowl in Box2D 2.4.1 as 400 edges (8/3 iterations, sleeping and
 * continuous off), with circles that do not turn, as tether's particles
 * (k = 0), and circles that do (k = 1); NULL where it cannot be built. */
static tb_world *box2d_bowl(int k)
{
    ts_scene sc;
    const char *why = NULL;
    tb_world *w = NULL;
    tb_world_def d = tb_world_def_default();
    d.sleep = d.continuous = false;
    if (ts_scene_bowl(&sc, 10000, 100, 400, k == 0, &why)) w = tb_scene_build(&sc, &d, &why);
    if (!w) printf("  bowl in Box2D: %s\n", why ? why : "failed");
    ts_scene_free(&sc);
    return w;
}

/* Every circle's place and speed at the end, for bench/bowl.gp: engine 0
 * tether, 1 and 2 the Box2D bowls, 3 tether with anchored friction. */
static void circles_csv(FILE *f, int engine, const ts_bowl *b, const tb_world *w)
{
    for (uint32_t i = 0; i < b->t.circle_count; i++) {
        double x, y, vx, vy;
        if (engine == 0 || engine == 3) {
            tt_vec2 p, v;
            tt_particle_get_position(b->t.world, b->t.circles[i], &p);
            tt_particle_get_velocity(b->t.world, b->t.circles[i], &v);
            x = p.x, y = p.y, vx = v.x, vy = v.y;
        } else {
            tb_body_state st;
            if (!tb_body_state_get(w, (int)i, &st)) continue;
            x = st.position[0], y = st.position[1], vx = st.velocity[0], vy = st.velocity[1];
        }
        fprintf(f, "%d,%.4f,%.4f,%.3e\n", engine, x, y, sqrt(vx * vx + vy * vy));
    }
}

static void box2d_figures(const tb_world *w, uint32_t n, double *ke, ts_pile *pile)
{
    double *xy = malloc(2 * (size_t)n * sizeof *xy);
    /* the circles are the scene's first n bodies, before the edges */
    const bool ok = xy && tb_positions(w, 0, (int)n, xy);
    ts_pile_measure(ok ? xy : NULL, ok ? n : 0, 0.5, pile);
    *ke = tb_world_kinetic_energy(w) / tb_world_mass(w);
    free(xy);
}

/* The reference pour onto a mask bowl: 10 000 circles, 20 s; tether, the
 * two Box2D bowls and tether with anchored friction take turns 30 steps at
 * a time, each step timed. */
static void bowl(FILE *csv, const char *dir)
{
    ts_bowl b, ba;
    const char *why = NULL;
    if (ts_bowl_build(10000, 100, &b, &why) != TT_OK || ts_bowl_build(10000, 100, &ba, &why) != TT_OK) {
        printf("  bowl: %s\n", why ? why : "failed");
        return;
    }
    tt_collision_settings cs;
    tt_world_get_collision(ba.t.world, &cs);
    cs.anchored_friction = true;
    tt_world_set_collision(ba.t.world, &cs);
    tb_world *b2[2] = {box2d_bowl(0), box2d_bowl(1)};
    double ns[4] = {0, 0, 0, 0};
    for (uint32_t s = 0; s < b.steps; s += 30) {
        const uint32_t m = b.steps - s < 30 ? b.steps - s : 30;
        double a = bench_now_ns();
        for (uint32_t j = 0; j < m; j++) tt_world_step(b.t.world, 1.0 / 60);
        ns[0] += bench_now_ns() - a;
        a = bench_now_ns();
        for (uint32_t j = 0; j < m; j++) tt_world_step(ba.t.world, 1.0 / 60);
        ns[3] += bench_now_ns() - a;
        for (int k = 0; k < 2; k++) {
            if (!b2[k]) continue;
            a = bench_now_ns();
            for (uint32_t j = 0; j < m; j++) tb_world_step(b2[k], 1.0 / 60);
            ns[1 + k] += bench_now_ns() - a;
        }
    }
    const double ms = ns[0] * 1e-6 / b.steps;
    ts_bowl_figures f;
    ts_bowl_measure(&b, &f);
    printf("  reference pour (10 000 circles, 20 s) onto a mask bowl 100 m wide: %.2f ms/step; KE %.2e J/kg"
           " (target <= 1e-3), centres in solid pixels %u (target 0), deepest into the bowl %.1f %% of a radius"
           " (target <= 10 %%), circle overlap max %.1f %% mean %.2f %%\n",
           ms, f.kinetic, f.inside, 100 * f.penetration, 100 * f.max_overlap, 100 * f.mean_overlap);
    fprintf(csv, "bowl,%.4f,%.3e,%.5f,%.5f\n", ms, f.kinetic, f.penetration, f.max_overlap);
    FILE *cc = bench_csv(dir, "bowl.csv", "engine,x,y,speed");
    circles_csv(cc, 0, &b, NULL);
    static const char *const what[2] = {"circles that do not turn (as tether's)", "circles that turn"};
    for (int k = 0; k < 2; k++) {
        if (!b2[k]) continue;
        double ke;
        ts_pile pile;
        box2d_figures(b2[k], b.t.circle_count, &ke, &pile);
        printf("  the same in Box2D 2.4.1 (400 edges, 8/3, sleeping and continuous off), %s: %.2f ms/step"
               " (tether %.1fx as fast); KE %.2e J/kg, circle overlap max %.1f %% mean %.2f %%\n",
               what[k], ns[1 + k] * 1e-6 / b.steps, ns[1 + k] / ns[0], ke, 100 * pile.max_overlap, 100 * pile.mean_overlap);
        fprintf(csv, "bowl box2d %s,%.4f,%.3e,0,%.5f\n", k ? "turning" : "fixed", ns[1 + k] * 1e-6 / b.steps, ke,
                pile.max_overlap);
        circles_csv(cc, 1 + k, &b, b2[k]);
        tb_world_destroy(b2[k]);
    }
    ts_bowl_measure(&ba, &f);
    printf("  tether with anchored friction (tt_collision_settings.anchored_friction): %.2f ms/step (%.2fx plain tether's"
           " time); KE %.2e J/kg, centres in solid pixels %u, deepest into the bowl %.1f %% of a radius, circle overlap"
           " max %.1f %% mean %.2f %%\n",
           ns[3] * 1e-6 / b.steps, ns[3] / ns[0], f.kinetic, f.inside, 100 * f.penetration, 100 * f.max_overlap,
           100 * f.mean_overlap);
    fprintf(csv, "bowl anchored,%.4f,%.3e,%.5f,%.5f\n", ns[3] * 1e-6 / b.steps, f.kinetic, f.penetration, f.max_overlap);
    circles_csv(cc, 3, &ba, NULL);
    fclose(cc);
    ts_bowl_free(&b);
    ts_bowl_free(&ba);
}

void bench_terrain(const char *dir)
{
    printf("\nterrain (carving; a pour onto a mask floor and onto a chain, in turn)\n");
    FILE *csv = bench_csv(dir, "terrain.csv", "what,a,b,c,d");
    carve(csv);
    pour(csv);
    bowl(csv, dir);
    fclose(csv);
}
