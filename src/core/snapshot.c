/* tether — snapshots: the one definition of a world's state. A world saves
 * to a versioned byte stream and restores from one, in place or into a new
 * world; the world hash is the hash of the same stream. The stream:
 *
 *   header (32 bytes): "TTSS", format version (u32), 0x01020304 as written
 *     by the saving machine (u32: byte order), header size (u32), body length
 *     (u64), checksum of the body (u64, stream.c's hash);
 *   body: sections, each id (four letters), 0 (u32), payload length (u64),
 *     payload: "WRLD" (settings, counters, particles, springs: this file),
 *     then one per feature group in solver order ("CONS" constraints and
 *     composites, "COLL" shapes and contacts), written by the group's hooks.
 *
 * Numbers are in the saving machine's byte order (the header refuses
 * another) and written field by field, never as structs, so no padding
 * byte reaches the stream or the hash. A restore reads and validates the
 * whole stream into a new world first and only then swaps it in, so a
 * truncated, corrupted or foreign stream leaves the world as it was. */
#include "stream.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { TT__SNAP_VERSION = 1, TT__SNAP_HEADER = 32 };
static const char magic[4] = {'T', 'T', 'S', 'S'};
#define ID_WORLD TT__ID('W', 'R', 'L', 'D')
#define ID_FIXED TT__ID('F', 'X', 'P', 'T') /* inside WRLD, after the attractors: the fixed-point quantum */
#define ID_TRAVEL TT__ID('T', 'R', 'V', 'L') /* inside WRLD, last: substeps by speed */

/* ---- saving ---------------------------------------------------------------- */

/* arr[0..count) of elem bytes, with zeros for removed slots: what a slot
 * held before its particle went is not state. */
static bool any_user(const tt_world *w)
{
    if (!w->user) return false;
    for (uint32_t i = 0; i < w->ppool.count; i++)
        if ((w->flags[i] & TT__PF_ALIVE) && w->user[i]) return true;
    return false;
}

static void put_live(tt__sink *s, const tt_world *w, const void *arr, size_t elem)
{
    static const unsigned char zeros[64];
    const unsigned char *a = arr;
    const uint32_t n = w->ppool.count;
    uint32_t i = 0;
    while (i < n) {
        uint32_t j = i;
        bool alive = w->flags[i] & TT__PF_ALIVE;
        while (j < n && (bool)(w->flags[j] & TT__PF_ALIVE) == alive) j++;
        if (alive) {
            tt__put(s, a + (size_t)i * elem, (size_t)(j - i) * elem);
        } else {
            for (uint32_t k = i; k < j; k++) tt__put(s, zeros, elem);
        }
        i = j;
    }
}

static void save_settings(const tt_world *w, tt__sink *s)
{
    tt__put_f64(s, w->gravity.x);
    tt__put_f64(s, w->gravity.y);
    tt__put_f64(s, w->wind.x);
    tt__put_f64(s, w->wind.y);
    tt__put_f64(s, w->damping);
    tt__put_u32(s, (uint32_t)w->integrator);
    tt__put_f64(s, w->dt_prev);
    tt__put_u32(s, w->max_particles);
    tt__put_u32(s, w->substeps);
    tt__put_u32(s, w->iterations);
    tt__put_f64(s, w->tolerance);
    tt__put_u32(s, (uint32_t)w->order);
    tt__put_u32(s, s->hashing ? 0 : w->tag);
    /* the counters a script reads; the wall-clock times are not state */
    tt__put_u64(s, w->stats.steps);
    tt__put_f64(s, w->stats.time);
    tt__put_u32(s, w->stats.force_evaluations);
    tt__put_u32(s, w->stats.diverged);
    tt__put_u32(s, w->stats.iterations);
    tt__put_f64(s, w->stats.max_error);
}

static void save_particles(const tt_world *w, tt__sink *s)
{
    tt__put_pool(s, &w->ppool);
    put_live(s, w, w->px, sizeof *w->px);
    put_live(s, w, w->py, sizeof *w->py);
    put_live(s, w, w->qx, sizeof *w->qx);
    put_live(s, w, w->qy, sizeof *w->qy);
    put_live(s, w, w->inv_mass, sizeof *w->inv_mass);
    put_live(s, w, w->mass, sizeof *w->mass);
    put_live(s, w, w->radius, sizeof *w->radius);
    put_live(s, w, w->flags, sizeof *w->flags);
    put_live(s, w, w->category, sizeof *w->category);
    put_live(s, w, w->mask, sizeof *w->mask);
    /* forces applied since the last step act in the next one */
    tt__put_u8(s, w->forces_pending);
    if (w->forces_pending) {
        put_live(s, w, w->fx, sizeof *w->fx);
        put_live(s, w, w->fy, sizeof *w->fy);
    }
    /* the values are the state, not whether their array was ever made */
    const bool user = any_user(w);
    tt__put_u8(s, user);
    if (user) put_live(s, w, w->user, sizeof *w->user);
    tt__put_u32(s, w->fresh_count);
    tt__put(s, w->fresh, (size_t)w->fresh_count * sizeof *w->fresh);
}

static void save_springs(const tt_world *w, tt__sink *s)
{
    tt__put_pool(s, &w->spool);
    for (uint32_t i = 0; i < w->spool.count; i++) {
        const tt__spring *sp = &w->springs[i];
        tt__put_u8(s, sp->alive);
        tt__put_u32(s, sp->alive ? sp->a : 0);
        tt__put_u32(s, sp->alive ? sp->b : 0);
        tt__put_f64(s, sp->alive ? sp->rest : 0.0);
        tt__put_f64(s, sp->alive ? sp->k : 0.0);
        tt__put_f64(s, sp->alive ? sp->c : 0.0);
    }
}

/* Written only when some slot is in use, so that a world without
 * attractors saves (and hashes) exactly as before they existed. */
static void save_attractors(const tt_world *w, tt__sink *s)
{
    if (!w->attractors_used) return;
    tt__put_u32(s, TT_MAX_ATTRACTORS);
    for (int k = 0; k < TT_MAX_ATTRACTORS; k++) {
        const tt_attractor *a = &w->attractors[k];
        tt__put_f64(s, a->center.x);
        tt__put_f64(s, a->center.y);
        tt__put_f64(s, a->strength);
        tt__put_f64(s, a->softening);
    }
}

/* Written only when set (after its tag, which no attractor count equals),
 * so that a world of plain doubles saves and hashes as before it existed. */
static void save_fixed_point(const tt_world *w, tt__sink *s)
{
    if (w->fixed_point == 0.0) return;
    tt__put_u32(s, ID_FIXED);
    tt__put_f64(s, w->fixed_point);
}

/* Whether substeps by speed says more than the defaults and the setting do:
 * on, a cap not the default's, or a last step that ran another count than
 * the setting (changed since, or by speed before it was switched off). */
static bool travel_told(const tt_world *w)
{
    return w->max_travel != 0.0 || w->max_substeps != TT__MAX_SUBSTEPS_DEFAULT ||
           (w->stats.substeps != 0 && w->stats.substeps != w->substeps);
}

/* Written only where travel_told: a world without it saves and hashes as
 * before it existed. */
static void save_travel(const tt_world *w, tt__sink *s)
{
    if (!travel_told(w)) return;
    tt__put_u32(s, ID_TRAVEL);
    tt__put_f64(s, w->max_travel);
    tt__put_u32(s, w->max_substeps);
    tt__put_u32(s, w->stats.substeps);
}

/* The body; false when a group cannot be saved (hashing skips it). */
static bool save_body(const tt_world *w, tt__sink *s, const char **unsaveable)
{
    size_t at = tt__section_open(s, ID_WORLD);
    save_settings(w, s);
    save_particles(w, s);
    save_springs(w, s);
    save_attractors(w, s);
    save_fixed_point(w, s);
    save_travel(w, s);
    tt__section_close(s, at);
    for (int g = 0; g < w->group_count; g++) {
        const tt__group_ops *ops = w->groups[g].ops;
        if (ops->idle && ops->idle(w, w->groups[g].self)) continue;
        if (!ops->save) {
            if (unsaveable && !*unsaveable) *unsaveable = ops->name;
            continue;
        }
        at = tt__section_open(s, ops->id);
        ops->save(w, w->groups[g].self, s);
        tt__section_close(s, at);
    }
    return !unsaveable || !*unsaveable;
}

static void put_header(unsigned char *b, size_t body, uint64_t checksum)
{
    uint32_t v[3] = {TT__SNAP_VERSION, 0x01020304u, TT__SNAP_HEADER};
    uint64_t n = body;
    memcpy(b, magic, 4);
    memcpy(b + 4, v, 12);
    memcpy(b + 16, &n, 8);
    memcpy(b + 24, &checksum, 8);
}

tt_result tt_world_save(const tt_world *w, void *buf, size_t cap, size_t *size)
{
    TT_CHECK_WORLD(w, "tt_world_save");
    if (!buf && cap) return tt__fail(w, TT_EINVAL, "tt_world_save: buf is NULL with cap %zu", cap);
    tt__sink s = {.buf = buf, .cap = buf ? cap : 0, .fixed = true};
    static const unsigned char blank[TT__SNAP_HEADER];
    tt__put(&s, blank, sizeof blank);
    const char *bad = NULL;
    save_body(w, &s, &bad);
    if (bad) return tt__fail(w, TT_ESTATE, "tt_world_save: the '%s' group keeps no snapshot state", bad);
    if (size) *size = s.len;
    if (s.overflow)
        return tt__fail(w, TT_ENOMEM, "tt_world_save: the stream takes %zu bytes, the buffer holds %zu", s.len, cap);
    unsigned char *b = buf;
    put_header(b, s.len - TT__SNAP_HEADER, tt__hash_bytes(b + TT__SNAP_HEADER, s.len - TT__SNAP_HEADER));
    return TT_OK;
}

uint64_t tt_world_hash(const tt_world *w)
{
    tt__sink s = {.hashing = true};
    tt__hasher_init(&s.hs);
    if (w) save_body(w, &s, NULL);
    return tt__hasher_end(&s.hs);
}

/* ---- loading: into a new world, every field checked ---------------------------- */

static void load_settings(tt_world *w, tt__source *s)
{
    w->gravity.x = tt__get_num(s, -TT_MAX_VALUE, TT_MAX_VALUE, "gravity");
    w->gravity.y = tt__get_num(s, -TT_MAX_VALUE, TT_MAX_VALUE, "gravity");
    w->wind.x = tt__get_num(s, -TT_MAX_VALUE, TT_MAX_VALUE, "wind");
    w->wind.y = tt__get_num(s, -TT_MAX_VALUE, TT_MAX_VALUE, "wind");
    w->damping = tt__get_num(s, 0.0, TT_MAX_VALUE, "damping");
    uint32_t integrator = tt__get_u32(s);
    w->dt_prev = tt__get_num(s, TT_MIN_DT / TT_MAX_SUBSTEPS, TT_MAX_DT, "the last step's dt");
    w->max_particles = tt__get_u32(s);
    w->substeps = tt__get_u32(s);
    w->iterations = tt__get_u32(s);
    w->tolerance = tt__get_num(s, 0.0, TT_MAX_VALUE, "tolerance");
    uint32_t order = tt__get_u32(s);
    w->tag = tt__get_u32(s);
    w->stats.steps = tt__get_u64(s);
    w->stats.time = tt__get_num(s, 0.0, 1e300, "time");
    w->stats.force_evaluations = tt__get_u32(s);
    w->stats.diverged = tt__get_u32(s);
    w->stats.iterations = tt__get_u32(s);
    w->stats.max_error = tt__get_num(s, 0.0, 1e300, "the last step's error");
    if (s->failed) return;
    if (integrator >= TT_INTEGRATOR_COUNT) tt__src_fail(s, "integrator %u is unknown", integrator);
    if (order != TT_GAUSS_SEIDEL && order != TT_JACOBI) tt__src_fail(s, "solver order %u is unknown", order);
    if (w->max_particles == 0 || w->max_particles > (1u << 30)) tt__src_fail(s, "max_particles %u", w->max_particles);
    if (w->substeps < 1 || w->substeps > TT_MAX_SUBSTEPS) tt__src_fail(s, "substeps %u", w->substeps);
    if (w->iterations < 1 || w->iterations > TT_MAX_ITERATIONS) tt__src_fail(s, "iterations %u", w->iterations);
    if (w->tag == 0 || w->tag > TT_POOL_MAX_TAG) tt__src_fail(s, "world tag %u, outside [1, %u]", w->tag, TT_POOL_MAX_TAG);
    w->integrator = (tt_integrator)integrator;
    w->order = (tt_solver_order)order;
}

static void get_array(tt__source *s, void *dst, size_t bytes)
{
    const void *p = tt__get_span(s, bytes);
    if (p) tt__copy(dst, p, bytes);
}

/* Slot i against the rules every public call keeps. The velocity is held
 * to TT_DIVERGED as tt_particle_get_velocity computes it (Verlet: from
 * x_old and dt_prev, read before the particles), the bound no step leaves:
 * a bound on x_old alone let a crafted stream carry |v| far past it. */
static bool particle_valid(const tt_world *w, uint32_t i)
{
    const double xmax = TT_DIVERGED;
    uint16_t f = w->flags[i];
    if (f & ~(TT__PF_ALIVE | TT__PF_PINNED | TT__PF_FRESH | TT__PF_ASLEEP)) return false;
    if ((f & TT__PF_PINNED) && (f & TT__PF_ASLEEP)) return false; /* sleep.c never puts a pinned particle to sleep */
    if (!(f & TT__PF_ALIVE))
        return f == 0 && w->px[i] == 0 && w->py[i] == 0 && w->qx[i] == 0 && w->qy[i] == 0 && w->inv_mass[i] == 0 &&
               w->mass[i] == 0 && w->radius[i] == 0 && w->category[i] == 0 && w->mask[i] == 0;
    const tt_vec2 v = tt__velocity(w, i);
    if (!(fabs(w->px[i]) <= xmax && fabs(w->py[i]) <= xmax && fabs(v.x) <= xmax && fabs(v.y) <= xmax)) return false;
    if (!(w->mass[i] >= TT_MIN_MASS && w->mass[i] <= TT_MAX_MASS)) return false;
    if (w->inv_mass[i] != ((f & (TT__PF_PINNED | TT__PF_ASLEEP)) ? 0.0 : 1.0 / w->mass[i])) return false;
    return w->radius[i] >= 0.0f && w->radius[i] <= (float)TT_MAX_VALUE;
}

static bool optional_array(tt__source *s, tt_world *w, void **dst, size_t elem)
{
    *dst = calloc(w->pcap, elem);
    if (!*dst) return tt__src_fail(s, "out of memory");
    get_array(s, *dst, (size_t)w->ppool.count * elem);
    return !s->failed;
}

static void load_particles(tt_world *w, tt__source *s)
{
    if (!tt__get_pool(s, &w->ppool, w->max_particles, w->tag, "particles")) return;
    const uint32_t n = w->ppool.count;
    if (tt__particles_reserve(w, n ? n : 1) != TT_OK) { tt__src_fail(s, "out of memory for %u particles", n); return; }
    get_array(s, w->px, (size_t)n * sizeof *w->px);
    get_array(s, w->py, (size_t)n * sizeof *w->py);
    get_array(s, w->qx, (size_t)n * sizeof *w->qx);
    get_array(s, w->qy, (size_t)n * sizeof *w->qy);
    get_array(s, w->inv_mass, (size_t)n * sizeof *w->inv_mass);
    get_array(s, w->mass, (size_t)n * sizeof *w->mass);
    get_array(s, w->radius, (size_t)n * sizeof *w->radius);
    get_array(s, w->flags, (size_t)n * sizeof *w->flags);
    get_array(s, w->category, (size_t)n * sizeof *w->category);
    get_array(s, w->mask, (size_t)n * sizeof *w->mask);
    if (s->failed) return;
    for (uint32_t i = 0; i < n; i++) {
        if (!particle_valid(w, i)) { tt__src_fail(s, "particle %u is not a valid particle", i); return; }
        if (w->flags[i] & TT__PF_ALIVE) w->alive++;
    }
    for (uint32_t k = 0; k < w->ppool.free_count; k++)
        if (w->flags[w->ppool.free_list[k]] & TT__PF_ALIVE) { tt__src_fail(s, "particle %u is alive and free", w->ppool.free_list[k]); return; }
    w->forces_pending = tt__get_bool(s, "forces pending");
    if (w->forces_pending && (!optional_array(s, w, (void **)&w->fx, sizeof *w->fx) || !optional_array(s, w, (void **)&w->fy, sizeof *w->fy))) return;
    for (uint32_t i = 0; w->fx && i < n; i++)
        if (!(fabs(w->fx[i]) <= TT_MAX_VALUE * 1e3 && fabs(w->fy[i]) <= TT_MAX_VALUE * 1e3)) { tt__src_fail(s, "force on particle %u", i); return; }
    if (tt__get_bool(s, "user data") && !optional_array(s, w, (void **)&w->user, sizeof *w->user)) return;
    w->fresh_count = tt__get_count(s, 4, "fresh particles");
    if (s->failed) return;
    w->fresh_cap = w->fresh_count;
    w->fresh = malloc((size_t)(w->fresh_count ? w->fresh_count : 1) * sizeof *w->fresh);
    if (!w->fresh) { tt__src_fail(s, "out of memory"); return; }
    get_array(s, w->fresh, (size_t)w->fresh_count * sizeof *w->fresh);
    for (uint32_t k = 0; k < w->fresh_count && !s->failed; k++)
        if (w->fresh[k] >= n) tt__src_fail(s, "fresh particle %u out of range", w->fresh[k]);
}

static void load_springs(tt_world *w, tt__source *s)
{
    if (!tt__get_pool(s, &w->spool, UINT32_MAX - 1, w->tag, "springs")) return;
    const uint32_t n = w->spool.count;
    if (n > (s->len - s->at) / 33) { tt__src_fail(s, "springs: %u slots are more than the stream holds", n); return; }
    w->scap = n;
    w->springs = calloc(n ? n : 1, sizeof *w->springs);
    if (!w->springs) { tt__src_fail(s, "out of memory for %u springs", n); return; }
    for (uint32_t i = 0; i < n && !s->failed; i++) {
        tt__spring *sp = &w->springs[i];
        sp->alive = tt__get_bool(s, "spring alive");
        sp->a = tt__get_u32(s);
        sp->b = tt__get_u32(s);
        sp->rest = tt__get_num(s, 0.0, 3 * TT_DIVERGED, "spring rest length"); /* made from positions: between any two short of the guard */
        sp->k = tt__get_num(s, 0.0, TT_MAX_VALUE, "spring stiffness");
        sp->c = tt__get_num(s, 0.0, TT_MAX_VALUE, "spring damping");
        if (s->failed || !sp->alive) continue;
        w->springs_alive++;
        if (sp->a >= w->ppool.count || sp->b >= w->ppool.count || sp->a == sp->b ||
            !(w->flags[sp->a] & TT__PF_ALIVE) || !(w->flags[sp->b] & TT__PF_ALIVE))
            tt__src_fail(s, "spring %u joins particles %u and %u", i, sp->a, sp->b);
    }
    for (uint32_t k = 0; k < w->spool.free_count && !s->failed; k++)
        if (w->springs[w->spool.free_list[k]].alive) tt__src_fail(s, "spring %u is alive and free", w->spool.free_list[k]);
}

static void load_attractor_slots(tt_world *w, tt__source *s, uint32_t tag)
{
    if (tag != TT_MAX_ATTRACTORS) { tt__src_fail(s, "attractor slots: not %d", TT_MAX_ATTRACTORS); return; }
    for (int k = 0; k < TT_MAX_ATTRACTORS && !s->failed; k++) {
        tt_attractor *a = &w->attractors[k];
        a->center.x = tt__get_num(s, -TT_MAX_VALUE, TT_MAX_VALUE, "attractor centre");
        a->center.y = tt__get_num(s, -TT_MAX_VALUE, TT_MAX_VALUE, "attractor centre");
        a->strength = tt__get_num(s, -TT_MAX_VALUE, TT_MAX_VALUE, "attractor strength");
        a->softening = tt__get_num(s, 0.0, TT_MAX_VALUE, "attractor softening");
        if (a->strength == 0.0 && (a->center.x != 0.0 || a->center.y != 0.0 || a->softening != 0.0))
            tt__src_fail(s, "attractor %d is unused but not cleared", k);
        w->attractors_used += a->strength != 0.0;
    }
    if (!s->failed && !w->attractors_used) tt__src_fail(s, "attractors saved but none in use");
}

static void load_fixed(tt_world *w, tt__source *s)
{
    w->fixed_point = tt__get_num(s, 0x1p-60, 0x1p-1, "fixed-point quantum");
    if (!s->failed && !tt__fixed_quantum_ok(w->fixed_point)) tt__src_fail(s, "fixed-point quantum %g is not a power of two", w->fixed_point);
    if (!s->failed && !tt__fixed_loaded_ok(w))
        tt__src_fail(s, "a fixed-point world with a position off its lattice or range, or not integrated by 'verlet'");
}

static void load_travel(tt_world *w, tt__source *s)
{
    w->max_travel = tt__get_num(s, 0.0, TT_MAX_VALUE, "max_travel");
    w->max_substeps = tt__get_u32(s);
    w->stats.substeps = tt__get_u32(s);
    if (s->failed) return;
    if (w->max_substeps < 1 || w->max_substeps > TT_MAX_SUBSTEPS) tt__src_fail(s, "max_substeps %u", w->max_substeps);
    else if (w->stats.substeps > TT_MAX_SUBSTEPS || (w->stats.substeps == 0) != (w->stats.steps == 0))
        tt__src_fail(s, "the last step's substeps %u after %llu steps", w->stats.substeps, (unsigned long long)w->stats.steps);
    else if (!travel_told(w))
        tt__src_fail(s, "substeps by speed written out while it says nothing");
}

/* What follows the springs, each only when saved: the attractors, the
 * fixed-point quantum, substeps by speed. */
static void load_extras(tt_world *w, tt__source *s, const tt__section *sec)
{
    w->max_travel = 0.0; /* off, as tt_world_def_default, and the last step's count as the setting, unless saved */
    w->max_substeps = TT__MAX_SUBSTEPS_DEFAULT;
    w->stats.substeps = w->stats.steps ? w->substeps : 0;
    if (s->failed || s->at >= sec->end) return; /* none saved */
    uint32_t tag = tt__get_u32(s);
    if (tag != ID_FIXED && tag != ID_TRAVEL) {
        load_attractor_slots(w, s, tag);
        if (s->failed || s->at >= sec->end) return;
        tag = tt__get_u32(s);
    }
    if (tag == ID_FIXED) {
        load_fixed(w, s);
        if (s->failed || s->at >= sec->end) return;
        tag = tt__get_u32(s);
    }
    if (tag != ID_TRAVEL) { tt__src_fail(s, "unknown field after the springs"); return; }
    load_travel(w, s);
}

static void load_sections(tt_world *w, tt__source *s)
{
    tt__section sec;
    if (!tt__section_begin(s, &sec)) return;
    if (sec.id != ID_WORLD) { tt__src_fail(s, "the first section is not 'WRLD'"); return; }
    load_settings(w, s);
    load_particles(w, s);
    load_springs(w, s);
    load_extras(w, s, &sec);
    if (!tt__section_end(s, &sec)) return;
    while (s->at < s->len && !s->failed) {
        if (!tt__section_begin(s, &sec)) return;
        const tt__group_ops *ops = tt__feature_find(sec.id);
        if (!ops || !ops->load) { tt__src_fail(s, "unknown section '%.4s'", (const char *)&sec.id); return; }
        if (tt__group_find(w, ops)) { tt__src_fail(s, "section '%.4s' appears twice", (const char *)&sec.id); return; }
        void *self = ops->load(w, s);
        if (!self) { tt__src_fail(s, "section '%.4s' is not valid", (const char *)&sec.id); return; }
        if (tt__group_add(w, ops, self) < 0) {
            ops->destroy(w, self);
            tt__src_fail(s, "too many sections");
            return;
        }
        tt__section_end(s, &sec);
    }
    if (!s->failed && !tt__sleep_loaded_ok(w)) tt__src_fail(s, "particles asleep in a world without the sleep section");
}

/* A new world holding the stream's state, or NULL with the reason in why. */
tt_world *tt__world_parse(const void *data, size_t size, uint64_t epoch, char *why, size_t whylen)
{
    const unsigned char *b = data;
    uint32_t v[3];
    uint64_t body, sum;
    if (!data || size < TT__SNAP_HEADER) { snprintf(why, whylen, "%zu bytes is too short for a snapshot", data ? size : 0); return NULL; }
    memcpy(v, b + 4, 12);
    memcpy(&body, b + 16, 8);
    memcpy(&sum, b + 24, 8);
    if (memcmp(b, magic, 4) != 0) { snprintf(why, whylen, "not a tether snapshot (no 'TTSS' at its start)"); return NULL; }
    if (v[1] != 0x01020304u) { snprintf(why, whylen, "saved on a machine of the other byte order"); return NULL; }
    if (v[0] != TT__SNAP_VERSION) { snprintf(why, whylen, "format version %u, this build reads version %d", v[0], TT__SNAP_VERSION); return NULL; }
    if (v[2] != TT__SNAP_HEADER || body != size - TT__SNAP_HEADER) {
        snprintf(why, whylen, "%zu bytes, the header says %llu (truncated or padded)", size, (unsigned long long)(body + v[2]));
        return NULL;
    }
    if (tt__hash_bytes(b + TT__SNAP_HEADER, (size_t)body) != sum) { snprintf(why, whylen, "checksum mismatch (corrupted)"); return NULL; }
    tt_world *w = calloc(1, sizeof *w);
    if (!w) { snprintf(why, whylen, "out of memory"); return NULL; }
    w->epoch = epoch;
    w->springs_detach = tt__springs_detach; /* as tt_world_create sets it */
    tt__source s = {.p = b + TT__SNAP_HEADER, .len = (size_t)body};
    load_sections(w, &s);
    if (!s.failed) return w;
    snprintf(why, whylen, "%s", s.why);
    tt_world_destroy(w);
    return NULL;
}

void tt__world_take(tt_world *w, tt_world *fresh)
{
    /* the world keeps its address (scripts and the binding hold it); what it held goes with the husk */
    tt_world old = *w;
    *w = *fresh;
    w->scr = old.scr; /* scratch, not state: the world keeps its buffers, and the husk takes fresh's */
    old.scr = fresh->scr;
    memcpy(w->error, old.error, sizeof w->error);
    w->journal = old.journal; /* a journal records the change, and goes on */
    w->journal_hooks = old.journal_hooks;
    *fresh = old;
    fresh->journal = NULL;
    tt_world_destroy(fresh);
}

tt_result tt_world_restore(tt_world *w, const void *data, size_t size)
{
    TT_CHECK_WORLD(w, "tt_world_restore");
    char why[200];
    tt_world *fresh = tt__world_parse(data, size, w->epoch + 1, why, sizeof why);
    if (!fresh) return tt__fail(w, TT_EINVAL, "tt_world_restore: %s; the world is unchanged", why);
    /* drawing between steps goes on, from the restored positions (a jump has nothing to draw between) */
    if (w->ox && !tt__interp_start(fresh)) {
        tt_world_destroy(fresh);
        return tt__fail(w, TT_ENOMEM, "tt_world_restore: out of memory; the world is unchanged");
    }
    tt__world_take(w, fresh);
    return TT_OK;
}

tt_world *tt_world_load(const void *data, size_t size)
{
    char why[200];
    tt_world *w = tt__world_parse(data, size, 1, why, sizeof why);
    if (!w) tt__fail(NULL, TT_EINVAL, "tt_world_load: %s", why);
    return w;
}
