/* tether — position constraints as a relaxation group: the table of hooks
 * the solver and the snapshot call (each hook lives in the file that
 * constraint_internal.h names), and the making of the group on first use.
 * This file names every part of the feature; none names it back (the
 * parts find the group by its section id), so the parts stay out of a
 * circle (tests/layout.sh). */
#include "constraint_internal.h"
#include "core/stream.h"

#include <stdlib.h>
#include <string.h>

/* ---- group registration ------------------------------------------------ */

const tt__group_ops tt__constraints_ops = {
    .name = "constraints", .rank = TT__RANK_CONSTRAINTS,
    .begin_stage = TT_STAGE_SOLVE,
    .reserve = tt__cgroup_reserve,
    .begin = tt__cgroup_begin,
    .relax = tt__cgroup_relax,
    .units = tt__cgroup_units,
    .rows = tt__cgroup_rows,
    .end = tt__cgroup_end,
    .after_step = tt__cgroup_after_step,
    .undo_reserve = tt__cgroup_undo_reserve,
    .undo_mark = tt__cgroup_undo_mark,
    .undo = tt__cgroup_undo,
    .particle_removed = tt__cgroup_particle_removed,
    .memory = tt__cgroup_memory,
    .destroy = tt__cgroup_destroy,
    .scratch_free = tt__cgroup_scratch_free,
    .id = TT__CONS_ID,
    .save = tt__cgroup_save,
    .load = tt__cgroup_load,
};

/* Known to the snapshot reader before any world uses constraints: a saved
 * game with constraints loads in a program that has made none yet. */
__attribute__((constructor)) static void register_feature(void) { tt__feature_register(&tt__constraints_ops); }

tt__cgroup *tt__cgroup_make(tt_world *w)
{
    tt__cgroup *g = tt__cgroup_find(w);
    if (g) return g;
    g = calloc(1, sizeof *g);
    if (!g) return NULL;
    g->pool.tag = g->cpool.tag = w->tag; /* handles carry the world's tag */
    if (tt__group_add(w, &tt__constraints_ops, g) < 0) {
        free(g);
        return NULL;
    }
    return g;
}

bool tt__constraints_set_simd(tt_world *w, tt__simd_mode mode)
{
    if (mode != TT__SIMD_AUTO && mode != TT__SIMD_SCALAR && tt__simd_kind((uint8_t)mode) == TT__SIMD_SCALAR) return false;
    tt__cgroup *g = tt__cgroup_make(w);
    if (!g) return false;
    g->simd = (uint8_t)mode;
    return true;
}
