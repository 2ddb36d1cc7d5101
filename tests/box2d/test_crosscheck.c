/* tether — the Box2D cross-check (build/test_box2d, linked with Box2D): the
 * bridge refuses bad input and reproduces Box2D's known discrete answers,
 * and the agreement measured between the engines is pinned, scene by scene,
 * at the quick sizes (figures in README "Box2D cross-check"). */
#include "test.h"

#include "box2d/box2d_scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The row of scene whose measure starts with what, or NULL. */
static const cc_row *row(const cc_report *r, const char *what, const char *setting)
{
    for (int i = 0; i < r->nrows; i++)
        if (!strncmp(r->rows[i].measure, what, strlen(what)) && (!setting || !strcmp(r->rows[i].setting, setting))) return &r->rows[i];
    return NULL;
}

static cc_report *quick(const char *scene, uint32_t substeps, uint32_t iterations, uint32_t lattice)
{
    cc_report *r = calloc(1, sizeof *r);
    const char *why = "";
    r->quick = true;
    r->runs = 1;
    r->small = ts_tether_settings_default();
    r->small.substeps = substeps;
    r->small.iterations = iterations;
    r->small.lattice = lattice;
    if (!cc_run(r, scene, &why)) {
        printf("    %s: %s\n", scene, why);
        free(r);
        return NULL;
    }
    return r;
}

TEST(box2d_bridge_refuses_bad_input)
{
    ENSURE(tb_world_create(NULL) == NULL && strstr(tb_last_error(), "tb_world_create"));
    tb_world_def wd = tb_world_def_default();
    wd.velocity_iterations = 0;
    ENSURE(tb_world_create(&wd) == NULL);
    wd = tb_world_def_default();
    tb_world *w = tb_world_create(&wd);
    ENSURE(w != NULL);
    tb_body_def b = tb_body_def_default();
    b.position[0] = NAN;
    ENSURE(tb_body_create(w, &b) == -1 && strstr(tb_last_error(), "tb_body_create"));
    b = tb_body_def_default();
    b.shape = TB_POLYGON; /* a concave quadrilateral: Box2D would assert */
    b.count = 4;
    const double concave[8] = {0, 0, 2, 0, 1, 0.2, 1, 2};
    memcpy(b.points, concave, sizeof concave);
    ENSURE(tb_body_create(w, &b) == -1);
    b = tb_body_def_default();
    b.dynamic = true;
    ENSURE(tb_body_create(w, &b) == 0);
    const double at[2] = {0, 1};
    ENSURE(tb_joint_create(w, TB_REVOLUTE, 0, 0, at, NULL) == -1);
    ENSURE(tb_joint_create(w, TB_DISTANCE, TB_GROUND, 0, at, NULL) == -1); /* a distance joint needs anchor_b */
    ENSURE(tb_joint_create(w, TB_WELD, TB_GROUND, 3, at, NULL) == -1);
    ENSURE(tb_joint_create(w, TB_REVOLUTE, TB_GROUND, 0, at, NULL) == 0);
    ENSURE(!tb_world_step(w, 0) && !tb_world_step(w, NAN));
    tb_body_state st;
    ENSURE(!tb_body_state_get(w, 1, &st));
    tb_world_destroy(w);
}

/* Box2D's semi-implicit Euler, exactly: y = 10 − g·dt²·n(n+1)/2 after n steps. */
TEST(box2d_bridge_free_fall_is_box2d_discrete_answer)
{
    tb_world_def wd = tb_world_def_default();
    tb_world *w = tb_world_create(&wd);
    tb_body_def b = tb_body_def_default();
    b.shape = TB_BOX;
    b.dynamic = true;
    b.position[1] = 10;
    ENSURE(tb_body_create(w, &b) == 0);
    for (int i = 0; i < 60; i++) ENSURE(tb_world_step(w, 1.0 / 60));
    tb_body_state st;
    ENSURE(tb_body_state_get(w, 0, &st));
    ENSURE_NEAR(st.position[1], 10 - 10.0 / 3600 * 60 * 61 / 2, 1e-4);
    ENSURE_NEAR(st.mass, 1, 1e-6);
    ENSURE_NEAR(st.inertia, 1.0 / 6, 1e-6);
    tb_world_destroy(w);
}

/* Issue 17, scene 1: Box2D off by dt/t of the fall (1.7 % at 1 s), tether within 0.1 %. */
TEST(box2d_crosscheck_fall_against_the_analytic_path)
{
    cc_report *r = quick("fall", 1, 8, 4);
    ENSURE(r != NULL);
    const cc_row *drop = row(r, "dropped box", NULL), *rise = row(r, "thrown box: rise", NULL), *x = row(r, "thrown box: x", NULL);
    ENSURE(drop && rise && x);
    ENSURE_NEAR(drop->box2d / drop->expected - 1, 1.0 / 60, 1e-4);
    ENSURE(fabs(drop->tether / drop->expected - 1) <= 1e-3);
    ENSURE(fabs(rise->tether - rise->expected) <= 1e-3 * 5 && fabs(x->tether - x->expected) <= 1e-3 * 8);
    free(r);
}

/* Issue 17, scene 2: tether's period (pin + distance) within 1 % of Box2D's
 * revolute joint over the first three swings: −0.97 % at 1 × 8 (projection
 * damps the swing, so its amplitude and period drop sooner), −0.3 % at 8 × 1. */
TEST(box2d_crosscheck_pendulum_period)
{
    cc_report *r = quick("pendulum", 1, 8, 4);
    ENSURE(r != NULL);
    const cc_row *T = row(r, "period, first 3", NULL), *swing = row(r, "swing after", NULL);
    ENSURE(T && swing);
    ENSURE(fabs(T->box2d / T->expected - 1) <= 0.005); /* Box2D's bob is a disc: +0.25 % */
    ENSURE(fabs(T->tether / T->box2d - 1) <= 0.01);
    ENSURE(swing->tether < swing->box2d); /* and it loses its swing faster: 0.48 against 0.94 after 10 s */
    free(r);
    r = quick("pendulum", 8, 1, 4);
    ENSURE(r != NULL);
    T = row(r, "period, first 3", NULL);
    ENSURE(T && fabs(T->tether / T->box2d - 1) <= 0.005);
    free(r);
}

/* Issue 17, scene 6: the ten-row pyramid stands 10 s in both engines: top
 * box sideways ≤ 0.1 box width, no box turned over 5°. tether needs lattices
 * of 8 × 8 particles and 2 substeps for it (at 1 × 8 with 4 × 4 lattices
 * the upper rows slide off: the bumps of touching discs). */
TEST(box2d_crosscheck_pyramid_stands)
{
    cc_report *r = quick("pyramid", 2, 8, 8);
    ENSURE(r != NULL);
    const cc_row *drift = row(r, "top box sideways", NULL), *turn = row(r, "largest box rotation", NULL);
    const cc_row *rise = row(r, "top box height", NULL);
    ENSURE(drift && turn && rise);
    ENSURE(drift->box2d <= 0.1 && drift->tether <= 0.1);
    ENSURE(turn->box2d <= 5 && turn->tether <= 5);
    /* Box2D's boxes float on their skin (+0.015 a layer), tether's lattices nest their bumps (−0.02 a layer) */
    ENSURE(rise->box2d > 0.1 && rise->box2d < 0.2);
    ENSURE(rise->tether < -0.1 && rise->tether > -0.3);
    free(r);
}

/* Scene 7: ten rows of discs that do not turn, friction 0.3, on a floor.
 * The known answer is Box2D's: the pyramid stands (base spread and top sink
 * under 5 cm in 10 s). Tether's particles take friction from each other
 * only in the velocity pass, bounded by the contact's normal speed change,
 * which at rest is about nothing (docs/collisions.md): the base is wedged
 * apart, 8.4 m at 1 × 8, printed here, not asserted; this test pins the
 * scene's answer. With anchored friction tether stands it too (below). */
TEST(box2d_crosscheck_disc_pyramid_stands_in_box2d)
{
    cc_report *r = quick("discs", 1, 8, 4);
    ENSURE(r != NULL);
    const cc_row *spread = row(r, "base spread", NULL), *sink = row(r, "top disc sunk", NULL);
    ENSURE(spread && sink);
    printf("    discs, 10 s: base spread Box2D %.3f m, tether %.3f m; top sunk %.3f m, %.3f m\n", spread->box2d, spread->tether,
           sink->box2d, sink->tether);
    ENSURE(fabs(spread->box2d) < 0.05 && fabs(sink->box2d) < 0.05);
    ENSURE(isfinite(spread->tether) && isfinite(sink->tether));
    free(r);
}

/* The same with anchored friction (tt_collision_settings.anchored_friction):
 * tether's pyramid stands as Box2D's does, base spread and top sink under
 * 5 cm in 10 s at 1 × 8 (3.5 mm and 7.8 mm; Box2D 1.6 and 2.4 cm). */
TEST(box2d_crosscheck_disc_pyramid_stands_in_both_with_anchored_friction)
{
    cc_report *r = calloc(1, sizeof *r);
    ENSURE(r != NULL);
    r->quick = true;
    r->runs = 1;
    r->small = ts_tether_settings_default();
    r->small.anchored = true;
    const char *why = NULL;
    ENSURE(cc_run(r, "discs", &why));
    const cc_row *spread = row(r, "base spread", NULL), *sink = row(r, "top disc sunk", NULL);
    ENSURE(spread && sink);
    printf("    discs, anchored, 10 s: base spread Box2D %.3f m, tether %.4f m; top sunk %.3f m, %.4f m\n", spread->box2d,
           spread->tether, sink->box2d, sink->tether);
    ENSURE(fabs(spread->box2d) < 0.05 && fabs(sink->box2d) < 0.05);
    ENSURE(fabs(spread->tether) < 0.05 && fabs(sink->tether) < 0.05);
    ENSURE(strstr(spread->setting, "anchored") != NULL);
    free(r);
}

/* The measured gaps of scenes 3 to 5 at tether's default 1 × 8, 4 × 4
 * lattices (README "Box2D cross-check" explains each). */
TEST(box2d_crosscheck_bounce_slope_spin_gaps)
{
    cc_report *r = quick("bounce", 1, 8, 4);
    ENSURE(r != NULL);
    const cc_row *b = row(r, "1st rebound", NULL);
    ENSURE(b && fabs(b->box2d / b->expected - 1) <= 0.06); /* Box2D +4 % */
    ENSURE(b->tether > 0.4 * b->expected && b->tether < 0.6 * b->expected); /* a lattice keeps half */
    free(r);
    r = quick("slope", 1, 8, 4);
    ENSURE(r != NULL);
    const cc_row *stick = row(r, "slid in 2 s at 20", NULL), *slide = row(r, "slid in 2 s at 35", NULL), *held = row(r, "steepest", NULL);
    ENSURE(stick && slide && held);
    ENSURE(stick->box2d < 0.01 && stick->tether < 0.01);
    ENSURE(fabs(slide->box2d / slide->expected - 1) < 0.02 && fabs(slide->tether / slide->expected - 1) < 0.02);
    ENSURE(fabs(held->box2d - held->expected) <= 1.5 && fabs(held->tether - held->expected) <= 2.5);
    free(r);
    r = quick("spin", 1, 8, 4);
    ENSURE(r != NULL);
    const cc_row *turned = row(r, "turned", NULL), *kept = row(r, "angular momentum at 2 s", NULL);
    ENSURE(turned && kept);
    ENSURE_NEAR(turned->box2d, turned->expected, 1e-3);
    ENSURE_NEAR(kept->box2d, 1, 1e-4);
    /* finite iterations let the lattice stretch and give back less: 20 % of the spin lost in 2 s */
    ENSURE(kept->tether > 0.7 && kept->tether < 0.9);
    free(r);
}

/* Issue 17, scene 7 at the quick size (1 000 circles, a box 31.6 wide, 20 s). */
TEST(box2d_crosscheck_quick_pour)
{
    cc_report *r = quick("pour", 1, 8, 4);
    ENSURE(r != NULL);
    const cc_row *h18 = row(r, "pile height at 20", "1x8"), *h88 = row(r, "pile height at 20", "8x8");
    const cc_row *o88 = row(r, "max overlap at 20", "8x8"), *ke88 = row(r, "kinetic energy at 20", "8x8");
    const cc_row *c18 = row(r, "contacts per circle at 20", "1x8"), *c88 = row(r, "contacts per circle at 20", "8x8");
    ENSURE(h18 && h88 && o88 && ke88 && c18 && c88);
    /* tether packs denser than Box2D: the pile is lower by 0.99 m (1 x 8) and 0.53 m (8 x 8) of 29 m,
     * nearly hexagonal (5.54 and 5.37 contacts per circle against Box2D's 4.57), as a frictionless
     * pile packs: tether's friction between particles at rest holds little (the next test).
     * The 0.5 m is not met. (1.29 and 1.24 m lower before the speed cap of contact_cap.c,
     * which stops the sweeps squeezing circles out sideways into the gaps of the pile.) */
    ENSURE(h18->tether < h18->box2d && h18->box2d - h18->tether <= 1.1);
    ENSURE(h88->tether < h88->box2d && h88->box2d - h88->tether <= 1.1);
    ENSURE(c18->tether >= c18->box2d + 0.8 && c88->tether >= c88->box2d + 0.8);
    ENSURE(o88->tether <= 0.01 && o88->box2d <= 0.2); /* 8 x 8 at rest within 1 % of a radius */
    ENSURE(ke88->tether <= 1e-4 && ke88->box2d <= 2e-3);
    /* particles that turn (tt_world_def.spin) at 1 x 8: friction at the contact point, bounded by the load,
     * holds the pile looser: 28.50 m against Box2D's 29.04 (0.54 m lower, 5.38 contacts per circle),
     * 0.46 m above the pile without spin. The 0.5 m was met narrowly before the speed cap of
     * contact_cap.c (28.56 m, 0.48 m lower, 0.52 m above the pile without spin, which the cap raised
     * more); now missed by 0.04 m. (1 x 16: 0.59 m lower, 8 x 8: 0.37 m higher before the cap, README) */
    const cc_row *hs = row(r, "pile height at 20", "1x8 spin"), *ks = row(r, "kinetic energy at 20", "1x8 spin");
    ENSURE(hs && ks);
    ENSURE(fabs(hs->tether - hs->box2d) <= 0.6);
    ENSURE(hs->tether > h18->tether + 0.4);
    ENSURE(ks->tether <= 1e-3);
    free(r);
}

/* A small pour (200 circles into a box 11 m wide, 6 s) built in Box2D
 * body by body, so its discs can be made not to turn. */
static tb_world *b2_small_pour(const ts_scene *s, bool locked)
{
    tb_world_def wd = tb_world_def_default();
    wd.sleep = wd.continuous = false;
    tb_world *w = tb_world_create(&wd);
    for (uint32_t i = 0; w && i < s->body_count; i++) {
        const ts_body *b = &s->bodies[i];
        tb_body_def d = tb_body_def_default();
        d.shape = b->shape == TS_BOX ? TB_BOX : TB_CIRCLE;
        d.dynamic = b->dynamic;
        d.position[0] = b->position.x, d.position[1] = b->position.y;
        d.radius = b->radius;
        d.half[0] = b->half.x, d.half[1] = b->half.y;
        d.friction = b->friction;
        d.fixed_rotation = locked;
        if (tb_body_create(w, &d) != (int)i) return tb_world_destroy(w), NULL;
    }
    return w;
}

/* The small pour's pile at friction mu (circles and walls): in Box2D with
 * its discs free to turn (engine 0) or not (1), or in tether at 1 x 8 (2). */
static ts_pile small_pile(double mu, int engine)
{
    ts_scene s;
    ts_scene_pour(&s, 200, 11);
    s.steps = 360;
    for (uint32_t i = 0; i < s.body_count; i++) s.bodies[i].friction = mu;
    const uint32_t n = s.body_count - 3; /* the floor and the walls first */
    double *xy = malloc(2 * (size_t)n * sizeof *xy);
    ts_pile p = {NAN, NAN, NAN, 0, NAN};
    if (engine < 2) {
        tb_world *w = b2_small_pour(&s, engine == 1);
        for (uint32_t k = 0; w && k < s.steps; k++) tb_world_step(w, s.dt);
        if (w && xy && tb_positions(w, 3, (int)n, xy)) ts_pile_measure(xy, n, 0.5, &p);
        tb_world_destroy(w);
    } else {
        ts_tether t;
        const char *why = "";
        ts_tether_settings set = ts_tether_settings_default();
        if (ts_tether_build(&s, &set, &t, &why) == TT_OK) {
            for (uint32_t k = 0; k < s.steps; k++) tt_world_step(t.world, s.dt);
            if (xy && tt_particles_get_positions(t.world, t.circles, n, xy) == TT_OK) ts_pile_measure(xy, n, 0.5, &p);
            ts_tether_free(&t);
        }
    }
    free(xy);
    ts_scene_free(&s);
    return p;
}

/* Why tether's pour settles lower than Box2D's (issue 17): between
 * particles at rest, tether's friction holds almost nothing. It is bounded
 * by μ times the pair's normal velocity change in the velocity pass
 * (contact_response.c): an impact, or a particle's own fall onto another,
 * but not the load the pile above presses through the contact, which the
 * sweeps carry; so a resting pile packs as if frictionless, toward the
 * hexagonal packing (6 contacts per circle). Box2D's friction keeps its
 * discs in a looser packing; with its discs made not to turn (as tether's
 * particles cannot) far looser still, grains standing in columns. Measured
 * (contacts per circle / height, μ 0.3 then 0): Box2D 3.66 / 17.57 m,
 * 4.78 / 16.81 m, not turning 1.91 / 21.61 m; tether 5.00 / 17.00 m,
 * 5.18 / 16.55 m (before the speed cap of contact_cap.c; now 4.86 /
 * 17.27 m and 5.29 / 16.54 m). So bounding pair friction by the load
 * instead, as shape contacts are, is not the fix: it stands tether's grains in columns too
 * (the quick pour at 8 x 8: 35.5 m against Box2D's 29.0); rigid discs get
 * their looser-than-frictionless packing from friction and turning
 * together (README "Box2D cross-check"). When tether's particle friction
 * changes, this test says by how much. */
TEST(box2d_pile_friction_at_rest)
{
    const ts_pile b = small_pile(0.3, 0), b0 = small_pile(0, 0), bl = small_pile(0.3, 1);
    const ts_pile t = small_pile(0.3, 2), t0 = small_pile(0, 2);
    printf("    contacts per circle / height (m), mu 0.3 and 0: Box2D %.2f / %.2f, %.2f / %.2f (discs not turning: %.2f / %.2f);"
           " tether %.2f / %.2f, %.2f / %.2f\n", b.contacts, b.height, b0.contacts, b0.height, bl.contacts, bl.height, t.contacts,
           t.height, t0.contacts, t0.height);
    ENSURE(b0.contacts - b.contacts >= 0.8 && b.height > b0.height);     /* Box2D: friction loosens the pile */
    ENSURE(bl.contacts < b.contacts && bl.height > b.height);             /* more so when the discs cannot turn */
    /* tether: far less (4.86 / 17.27 m and 5.29 / 16.54 m since the speed cap of contact_cap.c) */
    ENSURE(fabs(t0.contacts - t.contacts) <= 0.6 && t.contacts >= b.contacts + 1);
}

/* A scene's fixed_rotation reaches Box2D. A disc on a 15° slope with
 * μ = 0.3 (> tan 15°): one that may turn rolls, a = (2/3)·g·sin 15°
 * (a solid disc rolling without slipping, which needs μ ≥ tan 15° / 3);
 * one that may not (as tether's particles) stays where it was put. */
TEST(box2d_scene_fixed_rotation_keeps_a_disc_from_rolling)
{
    const double a = 15 * M_PI / 180, t = 1.0;
    for (int fixed = 0; fixed < 2; fixed++) {
        ts_scene s;
        ts_scene_init(&s, "roll");
        ts_body slope = ts_box(false, (tt_vec2){0.5 * sin(a), -0.5 * cos(a)}, 20, 0.5, a);
        ENSURE(ts_scene_add_body(&s, &slope, NULL) == 0);
        ts_body disc = ts_circle(true, (tt_vec2){-0.5 * sin(a), 0.5 * cos(a)}, 0.5);
        disc.fixed_rotation = fixed;
        ENSURE(ts_scene_add_body(&s, &disc, NULL) == 1);
        tb_world_def d = tb_world_def_default();
        d.sleep = false;
        tb_world *w = tb_scene_build(&s, &d, NULL);
        ENSURE(w != NULL);
        for (int k = 0; k < 60; k++) ENSURE(tb_world_step(w, 1.0 / 60));
        tb_body_state st;
        ENSURE(tb_body_state_get(w, 1, &st));
        /* distance travelled down the slope */
        const double down = -((st.position[0] + 0.5 * sin(a)) * cos(a) + (st.position[1] - 0.5 * cos(a)) * sin(a));
        if (fixed) {
            ENSURE(fabs(down) < 1e-3 && st.spin == 0);
        } else {
            ENSURE_NEAR(down, 0.5 * (2.0 / 3.0) * 10 * sin(a) * t * t, 0.02 * 0.863);
            ENSURE(st.spin > 0); /* rolling to the left turns it anticlockwise */
        }
        tb_world_destroy(w);
        ts_scene_free(&s);
    }
}
