/* tether — per-step scratch is not state (issue 13, point 4): what a step
 * works in is sized before it and written before it is read, so a world
 * whose scratch is freed, or filled with garbage bytes, between every two
 * steps steps exactly as its twin that kept it: the same hash and the same
 * position bits after every step, on every reference scene (each
 * integrator, Jacobi and Gauss-Seidel, springs, each constraint kind,
 * tearing, contacts, sleeping). */
#include "test.h"
#include "alloc_fail.h"
#include "collide/terrain_internal.h"
#include "constraints/constraint_internal.h"
#include "core/internal.h"
#include "core/scenes.h"
#include "core/sleep_internal.h"
#include "core/spin.h"

#include <string.h>

enum { STEPS = 40, SETTLE_STEPS = 300, GARBAGE = 0xA5 };

/* Steps each scene is run for: settle's piles fall asleep, and the ball
 * dropped at step 240 wakes one of them, within 300. */
static int steps_of(scene_kind k) { return k == SCENE_SETTLE ? SETTLE_STEPS : STEPS; }

static void fill(void *p, size_t bytes)
{
    if (p) memset(p, GARBAGE, bytes);
}

/* The world's scratch as garbage, its buffers kept: the lengths are their
 * capacities, so every byte a step could read unwritten is garbage. */
static void world_garbage(tt_world *w)
{
    tt__world_scratch *s = &w->scr;
    for (int k = 0; k < TT_SCRATCH_COUNT; k++) fill(s->buf[k], (size_t)s->buf_cap[k] * sizeof(double));
    fill(s->jx, (size_t)s->jcap * sizeof(double));
    fill(s->jy, (size_t)s->jcap * sizeof(double));
    fill(s->jn, (size_t)s->jcap * sizeof(uint32_t));
    fill(s->bx, (size_t)s->bcap * sizeof(double));
    fill(s->by, (size_t)s->bcap * sizeof(double));
    fill(s->rows, (size_t)s->rows_cap * 4 * sizeof(double));
    fill(s->ends, (size_t)s->ends_cap * sizeof(uint32_t));
    tt__undo *u = &s->undo;
    double *d[] = {u->px, u->py, u->qx, u->qy, u->inv_mass};
    for (size_t k = 0; k < sizeof d / sizeof d[0]; k++) fill(d[k], (size_t)u->cap * sizeof(double));
    fill(u->flags, (size_t)u->cap * sizeof(uint16_t));
    fill(&u->stats, sizeof u->stats);
    fill(&u->dt_prev, sizeof u->dt_prev);
    fill(&u->fresh_count, sizeof u->fresh_count);
    u->flags_taken = true;
    s->substep = 0xA5A5A5A5u;
    s->step_oom = "garbage";
}

/* The constraint group's scratch as garbage: the plan builder's stamps, the area gradients, the break events' buffer,
 * the undo's copies, and lambda in every link. The plan and its hot copies
 * are a cache valid while plan_ok (setters keep it current): losing them
 * is freeing them, which world_free does. */
static void constraints_garbage(tt_world *w)
{
    tt__cgroup *g = tt__cgroup_find(w);
    if (!g) return;
    tt__cscratch *s = &g->scr;
    fill(s->stamp, (size_t)s->stamp_cap * sizeof(uint32_t));
    fill(s->grad, (size_t)s->grad_cap * 2 * sizeof(double));
    fill(s->ev_new, (size_t)s->cap_new * sizeof *s->ev_new);
    tt__cundo *u = &s->undo;
    fill(u->moving, (size_t)u->moving_cap * sizeof *u->moving);
    fill(u->eff, (size_t)u->eff_cap * sizeof(double));
    fill(u->dist, (size_t)u->dist_cap * sizeof *u->dist);
    fill(u->dx, (size_t)u->dx_cap * sizeof *u->dx);
    fill(u->slots, (size_t)u->slot_cap * sizeof *u->slots);
    fill(u->gen, (size_t)u->gen_cap * sizeof(uint32_t));
    fill(u->free_list, (size_t)u->free_cap * sizeof(uint32_t));
    fill(u->refs, (size_t)u->refs_cap * sizeof(uint32_t));
    fill(u->pair_n, (size_t)u->n_cap * sizeof(uint32_t));
    fill(u->pair_key, (size_t)u->key_cap * sizeof(uint64_t));
    for (uint32_t i = 0; i < g->ndist; i++) fill(&g->dx[i].lambda, sizeof g->dx[i].lambda);
    for (uint32_t i = 0; i < g->ngen; i++) fill(&g->gen[i].lambda, sizeof g->gen[i].lambda);
}

/* Sleeping's scratch as garbage: the undo's copies and its flags (the
 * undo mark sets them before the step reads them). */
static void sleep_garbage(tt_world *w)
{
    tt__sleep *sl = (tt__sleep *)tt__group_find_id(w, TT__ID('S', 'L', 'E', 'P'));
    if (!sl) return;
    fill(&sl->scr.undo.taken, sizeof sl->scr.undo.taken);
    fill(&sl->scr.undo.asleep, sizeof sl->scr.undo.asleep);
    double *d[] = {sl->scr.undo.rest, sl->scr.undo.held, sl->scr.undo.ax, sl->scr.undo.ay};
    for (size_t k = 0; k < sizeof d / sizeof d[0]; k++) fill(d[k], (size_t)sl->scr.undo.cap * sizeof(double));
    fill(sl->scr.undo.island, (size_t)sl->scr.undo.cap * sizeof(uint32_t));
}

/* The contacts group's scratch as garbage, its buffers kept, lengths their
 * capacities: the grid, the substep's start velocities and guard
 * positions, pre-stabilisation's start copy, the friction contacts of
 * discs that turn, the bottom-up pass's lists, pairs and their runs, the near
 * cells, the batches (their slop-less radii sums too), shape contacts, the step's records, the undo's
 * copies, and the flags begin and reserve set before they are read; the
 * terrains' update buffer. The counts (the last substep's contacts, which
 * the stats show between steps) are left. */
static void contacts_garbage(tt_world *w)
{
    tt__collide *c = tt__collide_peek(w);
    if (!c) return;
    tt__collide_scratch *s = &c->scr;
    tt__grid *g = &s->grid;
    fill(g->start, (size_t)g->cap_cells * sizeof(uint32_t));
    uint32_t *gu[] = {g->cell, g->idx, g->out_list};
    for (size_t k = 0; k < sizeof gu / sizeof gu[0]; k++) fill(gu[k], (size_t)g->cap_n * sizeof(uint32_t));
    double *gd[] = {g->sx, g->sy, g->sr};
    for (size_t k = 0; k < sizeof gd / sizeof gd[0]; k++) fill(gd[k], (size_t)g->cap_n * sizeof(double));
    fill(g->bits, g->cap_n);
    fill(s->vx0, (size_t)s->vcap * sizeof(double));
    fill(s->vy0, (size_t)s->vcap * sizeof(double));
    fill(s->gx0, (size_t)s->gcap * sizeof(double));
    fill(s->gy0, (size_t)s->gcap * sizeof(double));
    fill(s->px0, (size_t)s->pcap * sizeof(double));
    fill(s->py0, (size_t)s->pcap * sizeof(double));
    fill(s->roll, (size_t)s->roll_cap * sizeof *s->roll);
    fill(s->lift, (size_t)s->lift_cap * sizeof *s->lift);
    fill(s->lift_start, (size_t)s->lift_cap * sizeof(uint32_t));
    fill(s->lift_order, (size_t)s->lift_cap * sizeof(uint32_t));
    fill(s->pairs, (size_t)s->paircap * sizeof *s->pairs);
    fill(s->runs, (size_t)s->runs_cap * sizeof *s->runs);
    fill(s->near, s->near_cap);
    tt__batches *B = &s->bat;
    fill(B->a, (size_t)B->cap * sizeof(uint32_t));
    fill(B->b, (size_t)B->cap * sizeof(uint32_t));
    double *bd[] = {B->rs, B->lam, B->wa, B->wb, B->pre};
    for (size_t k = 0; k < sizeof bd / sizeof bd[0]; k++) fill(bd[k], (size_t)B->cap * sizeof(double));
    fill(B->solo, B->cap / 4);
    fill(B->stamp, (size_t)B->stamp_cap * sizeof(uint32_t));
    fill(B->xy, (size_t)B->xy_cap * 2 * sizeof(double));
    fill(B->q, (size_t)B->q_cap * 2 * sizeof(double));
    fill(B->v0, (size_t)B->v0_cap * 2 * sizeof(double));
    fill(s->sc, (size_t)s->sccap * sizeof *s->sc);
    fill(s->rec, (size_t)s->reccap * sizeof *s->rec);
    fill(s->undo.sx0, (size_t)s->undo.cap * sizeof(double));
    fill(s->undo.sy0, (size_t)s->undo.cap * sizeof(double));
    s->guard = s->batched = s->bounded = s->undo.ends = true;
    if (c->terr) fill(c->terr->scr.buf, c->terr->scr.cap);
}

/* The spin group's scratch as garbage: the undo's copy of the angular
 * velocities (undo_mark writes it before undo reads it). */
static void spin_garbage(tt_world *w)
{
    tt__spin *sp = tt__spin_peek(w);
    if (sp) fill(sp->undo_omega, (size_t)sp->undo_cap * sizeof(double));
}

static void world_free(tt_world *w) { tt__world_scratch_free(w); }

/* Worlds with collisions beside the reference scenes: a terrain, carved
 * as they step, under a velocity integrator (its end positions are state)
 * with bullets and events; and a cluster converging without gravity, whose
 * pair search is skipped while nothing is near (contact_skip.c). */
typedef struct local {
    tt_world *w;
    tt_terrain t;
} local;

static void local_terrain(local *l)
{
    tt_world_def d = tt_world_def_default();
    d.integrator = TT_SYMPLECTIC_EULER;
    d.substeps = 2;
    l->w = tt_world_create(&d);
    tt_mask *m = tt_mask_create(80, 40, false);
    tt_mask_fill_rect(m, 0, 20, 80, 20, true);
    tt_terrain_def td = tt_terrain_def_default();
    td.solid = m;
    td.pixel = 0.1;
    td.origin = (tt_vec2){-4.0, 2.0};
    l->t = tt_terrain_create(l->w, &td);
    tt_mask_destroy(m);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.15;
    for (int i = 0; i < 40; i++) {
        pd.position = (tt_vec2){-3.0 + (i % 10) * 0.6 + 0.05 * (i / 10), 0.5 + (i / 10) * 0.5};
        tt_particle_create(l->w, &pd);
    }
    pd.position = (tt_vec2){0.5, 3.0};
    pd.velocity = (tt_vec2){2.0, -80.0};
    tt_particle_set_bullet(l->w, tt_particle_create(l->w, &pd), true);
    tt_collision_settings cs = tt_collision_settings_default();
    cs.events = TT_EVENT_BEGIN | TT_EVENT_PERSIST | TT_EVENT_END;
    tt_world_set_collision(l->w, &cs);
}

static void local_cluster(local *l)
{
    tt_world_def d = tt_world_def_default();
    d.substeps = 2;
    d.gravity = (tt_vec2){0.0, 0.0};
    l->w = tt_world_create(&d);
    l->t = (tt_terrain){0, 0};
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.2;
    for (int i = 0; i < 64; i++) {
        const double x = i % 8, y = i / 8;
        pd.position = (tt_vec2){x, y};
        pd.velocity = (tt_vec2){-(x - 3.5) * 0.6, -(y - 3.5) * 0.6}; /* meeting in about a second */
        tt_particle_create(l->w, &pd);
    }
    tt_collision_settings cs = tt_collision_settings_default();
    tt_world_set_collision(l->w, &cs);
}

/* Discs that turn (tt_world_def.spin): a row rolling down a slope onto
 * the floor, into a pile given spin of its own. */
static void local_roll(local *l)
{
    tt_world_def d = tt_world_def_default();
    d.spin = true;
    l->w = tt_world_create(&d);
    l->t = (tt_terrain){0, 0};
    tt_collision_settings cs = tt_collision_settings_default();
    cs.friction_static = cs.friction_kinetic = 0.5;
    tt_world_set_collision(l->w, &cs);
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_AABB;
    sd.a = (tt_vec2){-8, -1};
    sd.b = (tt_vec2){8, 0};
    tt_shape_create(l->w, &sd);
    sd.type = TT_SHAPE_SEGMENT;
    sd.a = (tt_vec2){-7, 4};
    sd.b = (tt_vec2){-1, 0};
    tt_shape_create(l->w, &sd);
    tt_particle_def pd = tt_particle_def_default();
    for (int i = 0; i < 30; i++) {
        pd.radius = 0.2 + 0.02 * (i % 5);
        pd.position = i < 6 ? (tt_vec2){-6.5 + 0.9 * i, 4.0 - 0.6 * i} : (tt_vec2){1.0 + 0.45 * (i % 6), 0.3 + 0.45 * (i / 6 - 1)};
        tt_particle p = tt_particle_create(l->w, &pd);
        if (i % 7 == 3) tt_particle_set_spin(l->w, p, i % 2 ? 6.0 : -6.0);
    }
}

static void (*const locals[])(local *l) = {local_terrain, local_cluster, local_roll};
static const char *const local_names[] = {"terrain", "cluster", "roll"};
enum { LOCAL_COUNT = sizeof locals / sizeof locals[0], LOCAL_STEPS = 90 };

static int twins_local(void (*lose)(tt_world *w), const char *how)
{
    int bad = 0;
    for (int k = 0; k < LOCAL_COUNT; k++) {
        local kept, lost;
        locals[k](&kept);
        locals[k](&lost);
        for (int s = 0; s < LOCAL_STEPS && !bad; s++) {
            if (kept.t.gen && s % 10 == 5) { /* a hole where the grains lie */
                tt_terrain_paint_circle(kept.w, kept.t, (tt_vec2){-3.0 + 0.3 * (s / 10), 0.1}, 0.4, false);
                tt_terrain_paint_circle(lost.w, lost.t, (tt_vec2){-3.0 + 0.3 * (s / 10), 0.1}, 0.4, false);
            }
            lose(lost.w);
            tt_world_step(kept.w, 1.0 / 60);
            tt_world_step(lost.w, 1.0 / 60);
            if (tt_world_hash(kept.w) != tt_world_hash(lost.w) ||
                scene_positions_digest(kept.w) != scene_positions_digest(lost.w)) {
                tt_test_fail(__FILE__, __LINE__, "world %s, scratch %s: differs after step %d",
                             local_names[k], how, s + 1);
                bad++;
            }
        }
        tt_world_destroy(kept.w);
        tt_world_destroy(lost.w);
    }
    return bad;
}

/* Every scene stepped twice, one of the twins losing its scratch (lose)
 * between every two steps: the hashes and positions agree after each. */
static int twins(void (*lose)(tt_world *w), const char *how)
{
    int bad = 0;
    for (int k = 0; k < SCENE_COUNT; k++) {
        scene kept, lost;
        if (!scene_build(&kept, (scene_kind)k) || !scene_build(&lost, (scene_kind)k)) return 1;
        for (int s = 0; s < steps_of((scene_kind)k) && !bad; s++) {
            lose(lost.w);
            scene_step(&kept);
            scene_step(&lost);
            if (tt_world_hash(kept.w) != tt_world_hash(lost.w) ||
                scene_positions_digest(kept.w) != scene_positions_digest(lost.w)) {
                tt_test_fail(__FILE__, __LINE__, "scene %s, scratch %s: differs after step %d",
                             scene_name((scene_kind)k), how, s + 1);
                bad++;
            }
        }
        tt_world_destroy(kept.w);
        tt_world_destroy(lost.w);
    }
    return bad + twins_local(lose, how);
}

/* world_free frees every part's scratch: the world's and each group's
 * (their scratch_free hooks). */
TEST(a_world_whose_step_scratch_is_lost_between_steps_steps_the_same)
{
    ENSURE(twins(world_free, "freed") == 0);
    ENSURE(twins(world_garbage, "garbage") == 0);
}

TEST(a_contacts_group_whose_scratch_is_garbage_between_steps_steps_the_same)
{
    ENSURE(twins(contacts_garbage, "of the contacts, garbage") == 0);
}

TEST(a_sleeping_group_whose_undo_copies_are_garbage_between_steps_steps_the_same)
{
    ENSURE(twins(sleep_garbage, "of sleeping, garbage") == 0);
}

TEST(a_spin_group_whose_undo_copy_is_garbage_or_freed_between_steps_steps_the_same)
{
    ENSURE(twins(spin_garbage, "of spin, garbage") == 0);
    /* world_free gives the copy back (the group's scratch_free hook) */
    local l;
    local_roll(&l);
    tt_world_step(l.w, 1.0 / 60);
    const tt__spin *sp = tt__spin_peek(l.w);
    ENSURE(sp && sp->undo_cap > 0);
    world_free(l.w);
    ENSURE(sp->undo_omega == NULL && sp->undo_cap == 0);
    tt_world_destroy(l.w);
}

TEST(a_constraint_group_whose_scratch_and_lambdas_are_garbage_between_steps_steps_the_same)
{
    ENSURE(twins(constraints_garbage, "of the constraints, garbage") == 0);
}

/* A row of 16 circles asleep on the ground; then 40 grains dropped among
 * and onto them (pile), more contacts than any step made room for: the
 * step after wakes the row in its first substep (sleeping takes its undo
 * copies) and grows the contacts' arrays inside. */
static tt_world *row(bool spin)
{
    tt_world_def d = tt_world_def_default();
    d.sleep_time = 0.2;
    d.spin = spin; /* the grains' friction turns them inside the step */
    tt_world *w = tt_world_create(&d);
    tt_collision_settings cs = tt_collision_settings_default();
    tt_world_set_collision(w, &cs);
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_AABB;
    sd.a = (tt_vec2){-10, -1};
    sd.b = (tt_vec2){10, 0};
    tt_shape_create(w, &sd);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.25;
    for (int i = 0; i < 16; i++) {
        pd.position = (tt_vec2){-4.0 + 0.5 * i, 0.25};
        tt_particle_create(w, &pd);
    }
    return w;
}

static void pile(tt_world *w)
{
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.2;
    for (int i = 0; i < 40; i++) {
        pd.position = (tt_vec2){-4.0 + 0.2 * i, 0.55 + 0.1 * (i % 3)};
        tt_particle_create(w, &pd);
    }
}

/* The undo works from scratch that was lost: the row, losing its scratch
 * (lose) before every step, asleep, the pile dropped, and each allocation
 * of the next step refused in turn; a failed step leaves the hash as it
 * was, and retried, the world goes on as its twin that kept its scratch and
 * never ran out. Returns the failures; *inside: the steps that failed
 * inside (not in a reserve before it). */
static int refused_after_loss(void (*lose)(tt_world *w), const char *how, bool spin, int *inside)
{
    int bad = 0;
    bool refused = true;
    for (long n = 0; refused && !bad; n++) {
        tt_world *kept = row(spin), *lost = row(spin);
        tt_stats st = {0};
        for (int s = 0; s < 600 && st.sleeping < 16; s++) {
            lose(lost);
            tt_world_step(kept, 1.0 / 60);
            tt_world_step(lost, 1.0 / 60);
            tt_world_get_stats(lost, &st);
        }
        bad += st.sleeping < 16;
        pile(kept);
        pile(lost);
        lose(lost);
        const uint64_t h0 = tt_world_hash(lost);
        tt_test_alloc_fail_from(n);
        const tt_result r = tt_world_step(lost, 1.0 / 60);
        refused = tt_test_alloc_ok();
        if (r != TT_OK) { /* as it was, then the same step again */
            *inside += strstr(tt_last_error(lost), "inside the step") != NULL;
            bad += tt_world_hash(lost) != h0;
            bad += tt_world_step(lost, 1.0 / 60) != TT_OK;
        }
        tt_world_step(kept, 1.0 / 60);
        for (int s = 0; s < 3; s++) {
            lose(lost);
            tt_world_step(kept, 1.0 / 60);
            tt_world_step(lost, 1.0 / 60);
        }
        if (tt_world_hash(kept) != tt_world_hash(lost) || scene_positions_digest(kept) != scene_positions_digest(lost))
            bad++;
        if (bad) tt_test_fail(__FILE__, __LINE__, "scratch %s, allocation %ld refused: differs", how, n);
        tt_world_destroy(kept);
        tt_world_destroy(lost);
    }
    return bad;
}

TEST(a_step_out_of_memory_after_its_scratch_was_lost_is_put_back_as_it_began)
{
    int inside = 0;
    ENSURE(refused_after_loss(world_free, "freed", false, &inside) == 0);
    ENSURE(refused_after_loss(sleep_garbage, "of sleeping, garbage", false, &inside) == 0);
    ENSURE(refused_after_loss(world_free, "freed, turning", true, &inside) == 0);
    ENSURE(refused_after_loss(spin_garbage, "of spin, garbage", true, &inside) == 0);
    ENSURE(inside >= 2); /* the case: refused inside the step, after the waking */
}
