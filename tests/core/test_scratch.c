/* tether — per-step scratch is not state (issue 13, point 4): what a step
 * works in is sized before it and written before it is read, so a world
 * whose scratch is freed, or filled with garbage bytes, between every two
 * steps steps exactly as its twin that kept it: the same hash and the same
 * position bits after every step, on every reference scene (each
 * integrator, Jacobi and Gauss-Seidel, springs, each constraint kind,
 * tearing, contacts, sleeping). */
#include "test.h"
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

TEST(a_world_whose_step_scratch_is_lost_between_steps_steps_the_same)
{
    ENSURE(twins(world_free, "freed") == 0);
    ENSURE(twins(world_garbage, "garbage") == 0);
}
