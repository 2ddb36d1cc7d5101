/* tether — per-step scratch is not state (issue 13, point 4): what a step
 * works in is sized before it and written before it is read, so a world
 * whose scratch is freed, or filled with garbage bytes, between every two
 * steps steps exactly as its twin that kept it: the same hash and the same
 * position bits after every step, on every reference scene (each
 * integrator, Jacobi and Gauss-Seidel, springs, each constraint kind,
 * tearing, contacts, sleeping). */
#include "test.h"
#include "constraints/constraint_internal.h"
#include "core/internal.h"
#include "core/scenes.h"

#include <string.h>

enum { STEPS = 40, GARBAGE = 0xA5 };

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

static void world_free(tt_world *w) { tt__world_scratch_free(w); }

/* Every scene stepped twice, one of the twins losing its scratch (lose)
 * between every two steps: the hashes and positions agree after each. */
static int twins(void (*lose)(tt_world *w), const char *how)
{
    int bad = 0;
    for (int k = 0; k < SCENE_COUNT; k++) {
        scene kept, lost;
        if (!scene_build(&kept, (scene_kind)k) || !scene_build(&lost, (scene_kind)k)) return 1;
        for (int s = 0; s < STEPS && !bad; s++) {
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
    return bad;
}

/* world_free frees every part's scratch: the world's and each group's
 * (their scratch_free hooks). */
TEST(a_world_whose_step_scratch_is_lost_between_steps_steps_the_same)
{
    ENSURE(twins(world_free, "freed") == 0);
    ENSURE(twins(world_garbage, "garbage") == 0);
}

TEST(a_constraint_group_whose_scratch_and_lambdas_are_garbage_between_steps_steps_the_same)
{
    ENSURE(twins(constraints_garbage, "of the constraints, garbage") == 0);
}
