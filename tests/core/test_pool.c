/* The handle allocator: the handle budget of tether/base.h holds up under
 * the churn of a long-running game. */
#include "test.h"
#include "tether.h"
#include "core/pool.h"

#include <stdlib.h>

/* A game that creates and removes 10 000 particles every second, for 24
 * hours: 864 million handles. Slots are reused until their reuse counter
 * would wrap, then retired; the pool must never come near its 2^24 slots.
 * Only the pool hands out handles, so the churn runs on the pool itself
 * (a world adds ~0.3 µs a particle: 5 minutes here). */
TEST(a_day_of_churn_at_ten_thousand_a_second_never_runs_out_of_handles)
{
    /* 1.7 billion pool operations on one array: minutes under valgrind
     * (`make memcheck`), which the other pool tests cover */
    if (getenv("TT_MEMCHECK")) return;
    enum { PER_SECOND = 10000, SECONDS = 24 * 3600 };
    tt__pool p = {0};
    p.tag = 7;
    uint32_t *slot = malloc(PER_SECOND * sizeof *slot);
    uint32_t *gen0 = malloc(PER_SECOND * sizeof *gen0);
    ENSURE(slot && gen0);
    bool grew;
    for (uint32_t s = 0; s < SECONDS; s++) {
        for (uint32_t i = 0; i < PER_SECOND; i++) {
            slot[i] = tt__pool_alloc(&p, TT_HANDLE_MAX_SLOTS, &grew);
            if (slot[i] == UINT32_MAX) ENSURE(!"the pool ran out of handles");
        }
        if (s == 0)
            for (uint32_t i = 0; i < PER_SECOND; i++) gen0[i] = p.gen[slot[i]];
        for (uint32_t i = 0; i < PER_SECOND; i++) tt__pool_free(&p, slot[i]);
    }
    /* Each slot served 65 535 lives before retiring: 86 400 s of churn took
     * two sets of 10 000 slots, 0.12 % of the budget. */
    ENSURE(p.count == 2 * PER_SECOND);
    /* No handle of the first second names anything again: its slots are
     * retired, their generation never comes back. */
    for (uint32_t i = 0; i < PER_SECOND; i++) {
        uint32_t g = p.gen[i];
        ENSURE((g & TT_POOL_GEN_MASK) == TT_POOL_GEN_MASK && g != gen0[i]);
    }
    for (uint32_t i = 0; i < p.free_count; i++) ENSURE(p.free_list[i] >= PER_SECOND);
    free(slot);
    free(gen0);
    tt__pool_destroy(&p);
}

/* The worst case for one slot: one particle made and removed over and over,
 * through the world. The slot retires after 65 535 removals, the next one
 * takes over, and no handle from before is ever valid again. */
TEST(a_slot_retires_after_its_reuse_budget_and_its_handles_stay_stale)
{
    tt_world *w = tt_world_create(NULL);
    tt_particle_def d = tt_particle_def_default();
    tt_particle first = tt_particle_create(w, &d), p = first;
    uint32_t lives = 0;
    while (p.index == first.index) {
        ENSURE_OK(tt_particle_destroy(w, p));
        p = tt_particle_create(w, &d);
        ENSURE(p.gen != 0);
        lives++;
    }
    ENSURE(lives == (1u << TT_HANDLE_GEN_BITS) - 1);
    ENSURE(!tt_particle_is_valid(w, first));
    ENSURE(tt_particle_is_valid(w, p) && p.index == first.index + 1);
    /* As integers (what Lua and saved games see) the handles differ too. */
    ENSURE(tt_particle_to_u64(p) != tt_particle_to_u64(first));
    ENSURE(tt_particle_to_u64(p) < (1ull << 53) && tt_handle_kind(tt_particle_to_u64(p)) == TT_KIND_PARTICLE);
    tt_world_destroy(w);
}

/* As one integer a handle carries its kind: an integer of one kind decodes
 * to the null handle as any other kind, so it is refused as stale, never
 * taken for the object in the same slot of another kind. */
TEST(handles_as_integers_carry_their_kind_and_fit_a_double)
{
    tt_world *w = tt_world_create(NULL);
    tt_particle_def d = tt_particle_def_default();
    tt_particle p = tt_particle_create(w, &d);
    d.position.x = 1;
    tt_particle q = tt_particle_create(w, &d);
    tt_spring_def sd = tt_spring_def_default();
    sd.a = p;
    sd.b = q;
    tt_spring s = tt_spring_create(w, &sd);
    uint64_t up = tt_particle_to_u64(p), us = tt_spring_to_u64(s);
    ENSURE(p.index == 0 && s.index == 0 && up != us);
    ENSURE(tt_handle_kind(up) == TT_KIND_PARTICLE && tt_handle_kind(us) == TT_KIND_SPRING);
    ENSURE(up < (1ull << 53) && (uint64_t)(double)up == up);
    ENSURE(tt_particle_is_valid(w, tt_particle_from_u64(up)));
    ENSURE(!tt_particle_is_valid(w, tt_particle_from_u64(us)));
    ENSURE(!tt_spring_is_valid(w, tt_spring_from_u64(up)));
    ENSURE(tt_handle_kind(0) == TT_KIND_NONE && tt_handle_kind(up | (1ull << 53)) == TT_KIND_NONE);
    ENSURE(tt_particle_from_u64(up | (1ull << 53)).gen == 0);
    /* A forged struct past the budget packs to 0, not to another object. */
    tt_particle forged = {p.index + TT_HANDLE_MAX_SLOTS, p.gen};
    ENSURE(tt_particle_to_u64(forged) == 0);
    forged = (tt_particle){p.index, p.gen | (1u << 31)};
    ENSURE(tt_particle_to_u64(forged) == 0);
    ENSURE(tt_particle_to_u64((tt_particle){0, 0}) == 0);
    tt_world_destroy(w);
}
