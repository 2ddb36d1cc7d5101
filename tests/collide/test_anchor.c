/* tether — anchored friction (tt_collision_settings.anchored_friction,
 * collide/contact_anchor.c): a circle on a circle holds inside Coulomb's
 * cone and slides outside it, a pyramid of circles stands, and the anchors
 * are state: saved, loaded, dropped with their particle, put back with a
 * step that runs out of memory, refused when a stream holds bad ones. */
#include "test.h"
#include "alloc_fail.h"
#include "collide/collide_internal.h"
#include "core/stream.h" /* tt__hash_bytes: to reseal a stream changed by hand */

#include <math.h>
#include <stdlib.h>
#include <string.h>

static uint32_t sweeps = 8; /* 1: the pairs one by one, not in batches */

static tt_world *world(bool anchored, double mu)
{
    tt_world_def wd = tt_world_def_default();
    wd.gravity = (tt_vec2){0, -10};
    wd.substeps = 1;
    wd.iterations = sweeps;
    wd.sleep = false;
    tt_world *w = tt_world_create(&wd);
    tt_collision_settings cs = tt_collision_settings_default();
    cs.friction_static = cs.friction_kinetic = mu;
    cs.anchored_friction = anchored;
    tt_world_set_collision(w, &cs);
    return w;
}

/* A circle (radius 0.5) resting on a pinned one, their centres at angle
 * atan(slope) from the vertical, μ = 0.6; how far it moved in 2 s, m. */
static double on_a_circle(bool anchored, double slope)
{
    tt_world *w = world(anchored, 0.6);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.5;
    pd.pinned = true;
    tt_particle_create(w, &pd);
    const double th = atan(slope);
    pd.pinned = false;
    pd.position = (tt_vec2){sin(th), cos(th)};
    tt_particle p = tt_particle_create(w, &pd);
    for (int s = 0; s < 120; s++) tt_world_step(w, 1.0 / 60);
    tt_vec2 x;
    tt_particle_get_position(w, p, &x);
    tt_world_destroy(w);
    return hypot(x.x - sin(th), x.y - cos(th));
}

/* Coulomb: it sticks while tan θ < μ and slides when greater, as it does
 * without anchors (the friction of the sweeps is not added to the velocity
 * pass's: held by both, it stuck at tan θ = 0.8). */
TEST(anchored_friction_holds_a_circle_on_a_circle_inside_the_friction_cone)
{
    for (int one = 0; one < 2; one++) { /* batched sweeps, then a single sweep: the pair sweep's own path */
        sweeps = one ? 1 : 8;
        const double held = on_a_circle(true, 0.4), slid = on_a_circle(true, 0.8), plain = on_a_circle(false, 0.8);
        printf("    1 x %u, μ = 0.6, 2 s: moved %.2e m at tan θ = 0.4; at 0.8 %.2f m (%.2f without anchors)\n", sweeps, held,
               slid, plain);
        ENSURE(held < 1e-3);
        ENSURE(slid > 0.5 * plain && slid > 1.0);
    }
    sweeps = 8;
}

/* A pyramid of `rows` rows (as tests/core/scenes.c's), μ given, 1 × 8. */
static tt_world *pyramid(bool anchored, double mu, int rows, tt_particle *ps)
{
    tt_world *w = world(anchored, mu);
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_AABB;
    sd.a = (tt_vec2){-40, -1};
    sd.b = (tt_vec2){40, 0};
    sd.friction_static = sd.friction_kinetic = mu;
    tt_shape_create(w, &sd);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.5;
    const double sp = 1.02, dy = sqrt(1.0 - 0.25 * sp * sp);
    int i = 0;
    for (int r = 0; r < rows; r++)
        for (int k = 0; k < rows - r; k++) {
            pd.position = (tt_vec2){(k - 0.5 * (rows - r - 1)) * sp, 0.5 + r * dy};
            ps[i++] = tt_particle_create(w, &pd);
        }
    return w;
}

/* How far the base of a pyramid spread in `steps`, m. */
static double spread(bool anchored, double mu, int steps)
{
    tt_particle ps[55];
    tt_world *w = pyramid(anchored, mu, 10, ps);
    for (int s = 0; s < steps; s++) tt_world_step(w, 1.0 / 60);
    tt_vec2 l, r;
    tt_particle_get_position(w, ps[0], &l);
    tt_particle_get_position(w, ps[9], &r);
    tt_world_destroy(w);
    return r.x - l.x - 9 * 1.02;
}

/* Ten rows at μ = 0.3 for 10 s: Box2D 2.4.1 (discs that do not turn)
 * spreads its base 1.4 cm; anchored, the base holds within that; without
 * anchors it spreads metres. Without friction (μ = 0) the anchors hold
 * nothing: the pyramid falls flat. */
TEST(anchored_friction_holds_a_pyramid_of_circles_and_only_with_friction)
{
    const double held = spread(true, 0.3, 600), plain = spread(false, 0.3, 600), none = spread(true, 0.0, 600);
    printf("    10 rows, 10 s: base spread %.4f m anchored, %.2f m without, %.2f m anchored at μ = 0\n", held, plain, none);
    ENSURE(fabs(held) < 0.014);
    ENSURE(plain > 1.0);
    ENSURE(none > 5.0);
}

/* The velocity pass reads each pair's anchor after the table has kept
 * the touching pairs (anchored_unrub: whether a pair at its bound slipped):
 * it must read the pair's own, not the next touching pair's, which keeping
 * wrote over it wherever a pair before it did not touch. Two pairs, one a
 * hair out of touch (in reach: listed, no push), one resting; after a
 * step each unit still holds where its own pair began. */
TEST(anchored_friction_reads_each_pairs_own_anchor_after_the_sweeps)
{
    sweeps = 1; /* the pairs are the units, in the list's order */
    int checked = 0;
    for (int flip = 0; flip < 2; flip++) { /* either pair first in the list */
        tt_world *w = world(true, 0.6);
        tt_particle_def pd = tt_particle_def_default();
        pd.radius = 0.5;
        const double xo = flip ? 5.0 : -5.0, gap = 1.02, rest = 0.999;
        pd.pinned = true;
        pd.position = (tt_vec2){xo, 0.0};
        tt_particle_create(w, &pd);
        pd.position = (tt_vec2){0.0, 0.0};
        tt_particle_create(w, &pd);
        pd.pinned = false;
        pd.position = (tt_vec2){xo, gap};
        tt_particle_create(w, &pd);
        pd.position = (tt_vec2){0.0, rest};
        tt_particle_create(w, &pd);
        ENSURE(tt_world_step(w, 1.0 / 60) == TT_OK);
        const tt__collide *c = tt__collide_peek(w);
        ENSURE(c && c->scr.anc.on && !c->scr.batched && c->scr.npairs == 2);
        for (uint32_t k = 0; k < 2; k++) {
            uint32_t a, b;
            double lam;
            ENSURE(tt__anc_unit(c, k, &a, &b, &lam));
            const bool far = a % 2 == 0; /* slots 0, 2: the pair out of touch */
            ENSURE(far == (lam == 0.0));
            ENSURE(fabs(fabs(c->scr.anc.rxy[2 * k + 1]) - (far ? gap : rest)) < 1e-12);
            ENSURE(c->scr.anc.rxy[2 * k] == 0.0);
            checked += far && k == 0;
        }
        tt_world_destroy(w);
    }
    ENSURE(checked == 1); /* the case that was wrong: the pair out of touch first */
    sweeps = 8;
}

/* Anchored friction in the sweeps' vector lanes and the velocity pass's,
 * and in scalar code: the same bits. A pyramid with circles dropped on it
 * from 12 m (impacts, slipping, pairs that stick), with the world's
 * friction or, mat, each particle's own. */
static uint64_t lanes_run(tt__simd_mode mode, bool mat)
{
    tt_particle ps[55];
    tt_world *w = pyramid(true, 0.4, 10, ps);
    if (!tt__contacts_set_simd(w, mode)) {
        tt_world_destroy(w);
        return 0;
    }
    tt_particle_def pd = tt_particle_def_default();
    for (int j = 0; j < 30; j++) {
        pd.radius = 0.3 + 0.01 * j;
        pd.position = (tt_vec2){-4.5 + 0.31 * j, 12.0 + (j % 4)};
        tt_particle p = tt_particle_create(w, &pd);
        if (mat) tt_particle_set_material(w, p, 0.1 * (j % 3), 0.1 + 0.03 * j, 0.05 + 0.02 * j);
    }
    for (int j = 0; mat && j < 55; j += 3) tt_particle_set_material(w, ps[j], 0.0, 0.8, 0.5);
    for (int s = 0; s < 240; s++) tt_world_step(w, 1.0 / 60);
    const uint64_t h = tt_world_hash(w);
    tt_world_destroy(w);
    return h;
}

TEST(anchored_friction_is_bit_identical_in_vector_lanes_and_scalar_code)
{
    const tt__simd_mode modes[] = {TT__SIMD_AUTO, TT__SIMD_AVX2, TT__SIMD_AVX512};
    int ran = 0;
    for (int mat = 0; mat < 2; mat++) {
        const uint64_t ref = lanes_run(TT__SIMD_SCALAR, mat);
        ENSURE(ref != 0);
        for (int m = 0; m < 3; m++) {
            const uint64_t h = lanes_run(modes[m], mat);
            if (h == 0) continue; /* not in this build or on this processor */
            ENSURE(h == ref);
            ran++;
        }
    }
    printf("    anchored: %d vector kernel run(s) give the scalar code's bits\n", ran);
}

static unsigned char *save(const tt_world *w, size_t *n)
{
    tt_world_save(w, NULL, 0, n); /* the size, with TT_ENOMEM */
    unsigned char *b = malloc(*n);
    if (b && tt_world_save(w, b, *n, NULL) != TT_OK) {
        free(b);
        return NULL;
    }
    return b;
}

static uint32_t anchors(const tt_world *w) { return tt__collide_peek(w)->anc.n; }

static tt_result set_warm(tt_world *w, double warm)
{
    tt_collision_settings cs;
    tt_world_get_collision(w, &cs);
    cs.warm_start = warm;
    return tt_world_set_collision(w, &cs);
}

/* The anchors are in the stream (24 bytes each and a header of 8), a world
 * loaded from it goes on as the original, a removed particle takes its
 * anchors with it, and turning the setting off drops them all. */
TEST(anchors_are_saved_loaded_and_dropped_with_their_particle)
{
    tt_particle ps[36];
    tt_world *w = pyramid(true, 0.3, 8, ps);
    for (int s = 0; s < 30; s++) tt_world_step(w, 1.0 / 60);
    const uint32_t n = anchors(w);
    ENSURE(n > 50); /* 8 rows: 77 touching pairs with the pyramid whole */
    size_t on, off;
    unsigned char *b = save(w, &on);
    ENSURE(b != NULL);
    tt_world *v = tt_world_load(b, on);
    ENSURE(v != NULL);
    ENSURE(tt_world_hash(v) == tt_world_hash(w));
    ENSURE(anchors(v) == n);
    for (int s = 0; s < 60; s++) {
        ENSURE_OK(tt_world_step(w, 1.0 / 60));
        ENSURE_OK(tt_world_step(v, 1.0 / 60));
    }
    ENSURE(tt_world_hash(v) == tt_world_hash(w));
    const uint32_t before = anchors(w), gone = ps[10].index;
    ENSURE_OK(tt_particle_destroy(w, ps[10]));
    ENSURE_OK(tt_particle_destroy(v, ps[10]));
    const tt__anchors *t = &tt__collide_peek(w)->anc;
    ENSURE(t->n < before);
    for (uint32_t e = 0; e < t->n; e++) ENSURE((uint32_t)(t->e[e].key >> 32) != gone && (uint32_t)t->e[e].key != gone);
    for (int s = 0; s < 60; s++) {
        ENSURE_OK(tt_world_step(w, 1.0 / 60));
        ENSURE_OK(tt_world_step(v, 1.0 / 60));
    }
    ENSURE(tt_world_hash(v) == tt_world_hash(w));
    tt_collision_settings cs;
    tt_world_get_collision(w, &cs);
    const size_t with = (free(save(w, &on)), on);
    cs.anchored_friction = false;
    ENSURE_OK(tt_world_set_collision(w, &cs));
    free(save(w, &off));
    ENSURE(anchors(w) == 0);
    ENSURE(with == off + 8 + 24 * (size_t)anchors(v));
    tt_world_destroy(v);
    tt_world_destroy(w);
    free(b);
}

/* Every allocation of a step refused in turn, from the first on: the step
 * fails with the world as it was (anchors included), and the same step
 * retried makes the world its twin's, which never ran out. The first step
 * (the anchors' table made) and the 21st, after a ball fell on the
 * pyramid's side (more pairs than the table had room for). */
TEST(out_of_memory_in_an_anchored_step_leaves_the_world_as_it_was)
{
    int refusals = 0;
    for (long k = 0, at = 0, warm = 0; warm < 2; k++) { /* without, then with warm start (its corrections put back too) */
        tt_particle pa[37], pb[37];
        tt_world *a = pyramid(true, 0.3, 8, pa), *b = pyramid(true, 0.3, 8, pb);
        if (warm) set_warm(a, 0.75), set_warm(b, 0.75);
        tt_particle_def pd = tt_particle_def_default();
        pd.radius = 0.45;
        pd.position = (tt_vec2){-2.4, 4.0};
        pd.velocity = (tt_vec2){0, -8};
        pa[36] = tt_particle_create(a, &pd);
        pb[36] = tt_particle_create(b, &pd);
        for (int s = 0; s < at; s++) tt_world_step(a, 1.0 / 60), tt_world_step(b, 1.0 / 60);
        const uint64_t h0 = tt_world_hash(a);
        tt_test_alloc_fail_from(k);
        const tt_result r = tt_world_step(a, 1.0 / 60);
        const bool refused = tt_test_alloc_ok();
        if (r != TT_OK) {
            ENSURE(refused && r == TT_ENOMEM);
            ENSURE(tt_world_hash(a) == h0);
            ENSURE_OK(tt_world_step(a, 1.0 / 60));
            refusals++;
        }
        ENSURE_OK(tt_world_step(b, 1.0 / 60));
        for (int s = 0; s < 5; s++) {
            ENSURE_OK(tt_world_step(a, 1.0 / 60));
            ENSURE_OK(tt_world_step(b, 1.0 / 60));
        }
        ENSURE(tt_world_hash(a) == tt_world_hash(b));
        tt_world_destroy(a);
        tt_world_destroy(b);
        if (!refused) k = -1, at += 20; /* the step made no more allocations: the next step */
        if (at > 20) at = 0, warm++;
    }
    printf("    %d allocations refused in turn, each failed its step whole\n", refusals);
    ENSURE(refusals > 0);
}

/* The stream's checksum remade after a change by hand. */
static void reseal(unsigned char *b, size_t n)
{
    const uint64_t sum = tt__hash_bytes(b + 32, n - 32);
    memcpy(b + 24, &sum, 8);
}

/* The anchors' section found by its marker and count (the last of the
 * collision section, which is not the stream's last). */
static size_t find_anchors(const unsigned char *b, size_t n, uint32_t count)
{
    const uint32_t id = TT__ID('A', 'N', 'C', 'H');
    for (size_t at = 32; at + 8 <= n; at++)
        if (!memcmp(b + at, &id, 4) && !memcmp(b + at + 4, &count, 4)) return at + 8;
    return 0;
}

/* Anchors out of order, naming a particle past the last, or not finite:
 * refused, nothing made. */
TEST(a_stream_with_bad_anchors_is_refused)
{
    tt_particle ps[36];
    tt_world *w = pyramid(true, 0.3, 8, ps);
    for (int s = 0; s < 30; s++) tt_world_step(w, 1.0 / 60);
    size_t n;
    unsigned char *b = save(w, &n), *c = malloc(n);
    ENSURE(b && c);
    const size_t at = find_anchors(b, n, anchors(w));
    ENSURE(at > 0);
    for (int kind = 0; kind < 3; kind++) {
        memcpy(c, b, n);
        if (kind == 0) memcpy(c + at, b + at + 24, 8), memcpy(c + at + 24, b + at, 8); /* the first two swapped */
        if (kind == 1) { /* the last pair: 35 and 36 of 36, still in order */
            const uint64_t past = ((uint64_t)35 << 32) | 36u;
            memcpy(c + at + 24 * (size_t)(anchors(w) - 1), &past, 8);
        }
        if (kind == 2) {
            const double nan = NAN;
            memcpy(c + at + 8, &nan, 8);
        }
        reseal(c, n);
        tt_world *v = tt_world_load(c, n);
        ENSURE(v == NULL);
    }
    memcpy(c, b, n);
    tt_world *v = tt_world_load(c, n);
    ENSURE(v != NULL);
    tt_world_destroy(v);
    tt_world_destroy(w);
    free(b);
    free(c);
}

/* Warm start's corrections, in the anchors' table: checked, in the stream
 * (a section of 16 bytes and 8 an anchor, only while on), read back (a
 * world loaded goes on as the original; loaded with the corrections
 * zeroed, it does not), refused when bad, and dropped when it is turned
 * off. */
TEST(warm_start_is_checked_saved_and_loaded)
{
    tt_particle ps[36];
    tt_world *w = pyramid(true, 0.3, 8, ps);
    const uint64_t h0 = tt_world_hash(w);
    const double bad[] = {NAN, INFINITY, -0.1, 1.5};
    for (int k = 0; k < 4; k++) {
        ENSURE(set_warm(w, bad[k]) == TT_EINVAL);
        ENSURE(tt_world_hash(w) == h0);
    }
    ENSURE_OK(set_warm(w, 0.75));
    for (int s = 0; s < 30; s++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
    size_t n, off;
    unsigned char *b = save(w, &n), *c = malloc(n);
    ENSURE(b && c);
    const uint32_t na = anchors(w), id = TT__ID('W', 'A', 'R', 'M');
    ENSURE(na > 50);
    size_t at = 0; /* the corrections: after the id, the setting and the count */
    for (size_t i = 32; i + 16 <= n && !at; i++)
        if (!memcmp(b + i, &id, 4) && !memcmp(b + i + 12, &na, 4)) at = i + 16;
    ENSURE(at > 0);
    tt_world *v = tt_world_load(b, n);
    memcpy(c, b, n);
    memset(c + at, 0, 8 * (size_t)na); /* every correction +0: a stream as valid */
    reseal(c, n);
    tt_world *z = tt_world_load(c, n);
    ENSURE(v && z && tt_world_hash(v) == tt_world_hash(w));
    for (int s = 0; s < 60; s++) {
        ENSURE_OK(tt_world_step(w, 1.0 / 60));
        ENSURE_OK(tt_world_step(v, 1.0 / 60));
        ENSURE_OK(tt_world_step(z, 1.0 / 60));
    }
    ENSURE(tt_world_hash(v) == tt_world_hash(w));
    ENSURE(tt_world_hash(z) != tt_world_hash(w));
    for (int kind = 0; kind < 3; kind++) { /* a correction below 0, not finite; the setting 0 */
        memcpy(c, b, n);
        const double x = kind == 0 ? -1e-3 : kind == 1 ? NAN : 0.0;
        memcpy(c + (kind == 2 ? at - 12 : at), &x, 8);
        reseal(c, n);
        ENSURE(tt_world_load(c, n) == NULL);
    }
    free(save(w, &n));
    ENSURE_OK(set_warm(w, 0.0));
    free(save(w, &off));
    ENSURE(n == off + 16 + 8 * (size_t)anchors(w));
    const tt__anchors *t = &tt__collide_peek(w)->anc;
    for (uint32_t e = 0; e < t->n; e++) ENSURE(t->e[e].lm == 0.0);
    tt_world_destroy(z);
    tt_world_destroy(v);
    tt_world_destroy(w);
    free(b);
    free(c);
}

/* Extremes: μ = 100, radii 0, 1e-6 and 0.3 mixed, masses 1 and 1e4 side
 * by side, the heap 1e7 m from the origin in the corner of a floor and a
 * wall, steps of 1e-5, 1/60 and 0.1 s, without stacking, with 10 (whose
 * pushes keep a particle off the shapes it leans on, and move one wedged
 * in the corner not at all), and with 10 and the whole of the last
 * substep's corrections first (warm start 1): every position and velocity stays finite
 * and, up to 1/60 s, no circle ends under the floor by more than its
 * radius. (At 0.1 s the points and the 1e-6 m circles fall through the
 * floor 1 m thick, a metre a step, with or without anchors: they are not
 * bullets.) */
TEST(anchored_friction_extremes_stay_finite)
{
    const double dts[] = {1e-5, 1.0 / 60, 0.1}, far = 1e7;
    for (int k = 0; k < 9; k++) {
        tt_world *w = world(true, 100.0);
        tt_collision_settings cs;
        tt_world_get_collision(w, &cs);
        cs.stacking = k < 3 ? 0.0 : 10.0;
        cs.warm_start = k < 6 ? 0.0 : 1.0;
        ENSURE_OK(tt_world_set_collision(w, &cs));
        tt_shape_def sd = tt_shape_def_default();
        sd.type = TT_SHAPE_AABB;
        sd.a = (tt_vec2){far - 5, far - 1};
        sd.b = (tt_vec2){far + 5, far};
        sd.friction_static = sd.friction_kinetic = 100;
        tt_shape_create(w, &sd);
        sd.a = (tt_vec2){far - 5, far};
        sd.b = (tt_vec2){far - 2.3, far + 10}; /* the first column touches it */
        tt_shape_create(w, &sd);
        tt_particle ps[40];
        tt_particle_def pd = tt_particle_def_default();
        for (int i = 0; i < 40; i++) {
            pd.radius = i % 4 == 0 ? 0.0 : i % 4 == 1 ? 1e-6 : 0.3;
            pd.mass = i % 3 ? 1.0 : 1e4;
            pd.position = (tt_vec2){far - 2 + (i % 8) * 0.5, far + 0.2 + (i / 8) * 0.4};
            ps[i] = tt_particle_create(w, &pd);
        }
        for (int s = 0; s < 60; s++) ENSURE_OK(tt_world_step(w, dts[k % 3]));
        for (int i = 0; i < 40; i++) {
            tt_vec2 x, v;
            double r;
            tt_particle_get_position(w, ps[i], &x);
            tt_particle_get_velocity(w, ps[i], &v);
            tt_particle_get_radius(w, ps[i], &r);
            ENSURE(isfinite(x.x) && isfinite(x.y) && isfinite(v.x) && isfinite(v.y));
            ENSURE(x.y >= far - r - 1e-6 || dts[k % 3] > 1.0 / 60);
        }
        tt_world_destroy(w);
    }
}
