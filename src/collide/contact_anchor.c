/* tether — anchored friction between particles
 * (tt_collision_settings.anchored_friction).
 *
 * Friction between two particles is otherwise bounded in the velocity pass
 * by μ·Δvn, and each substep measures the slide it undoes from where the
 * pair began that substep. What a substep's sweeps leave of a slide is
 * never undone, so a pile creeps: a pyramid of ten rows of circles at
 * μ = 0.3 spreads 8.45 m at its base in 10 s (Box2D 2.4.1: 1.4 cm), and
 * three of eleven jittered pours into the mask bowl still moved at 20 s
 * (kinetic energy up to 5.9e-3 J/kg).
 *
 * With the setting on, a pair's friction is a position constraint solved
 * in the sweeps beside its normal push (as a shape's is, contact_response.c
 * rub), and the slide is measured from an anchor: the pair's relative
 * position where it stuck, kept here from substep to substep. The anchor
 * moves to where the pair is only when the pair slipped (its friction
 * ended the sweeps at the static bound μs·λ) or moved faster than the
 * restitution threshold (an impact is the velocity pass's to handle: with
 * every pair held from its first touch, a landing pour builds a loose pile
 * 10 % taller). A pair that stops touching loses its anchor. After the
 * sweeps come two passes of friction alone and one pass that only pushes
 * particles out of shapes (the friction may have moved them in): those,
 * and the friction itself, are contact_response.c's.
 *
 * The measures that chose this (each part left out, and what it did) are
 * in docs/collisions.md "Anchored friction".
 *
 * The anchors are state: saved and hashed (contacts.c), put back with a
 * step that fails (contact_undo.c), dropped with a removed particle. A
 * substep looks every pair up (begin) and keeps the touching ones (end);
 * the table is sorted by key, so the same pairs make the same stream
 * whatever order the broadphase found them in. */
#include "collide_internal.h"
#include "core/spin.h"

#include <stdlib.h>
#include <string.h>

enum { PAD = 4 }; /* find's fixed scan, and the sentinels past the last entry (seal) */

bool tt__anchors_on(const tt_world *w, const tt__collide *c)
{
    return c->set.anchored_friction && c->set.particles && w->order == TT_GAUSS_SEIDEL &&
           (w->integrator == TT_VERLET || w->integrator == TT_SYMPLECTIC_EULER) && !tt__spin_peek(w);
}

/* Entry of key, or UINT32_MAX: among the few whose lower slot is key's.
 * An index by lower slot, not a hash: begin looks pairs up in the batches'
 * order, and a hash sent each lookup to a slot and an entry of its own, two
 * cache misses a pair (11 % of an anchored step in the bowl). */
static uint32_t find(const tt__anchors *t, uint64_t key)
{
    const uint32_t lo = (uint32_t)(key >> 32);
    if (t->nfirst == 0 || lo >= t->nfirst - 1) return UINT32_MAX;
    const uint32_t e0 = t->first[lo], e1 = t->first[lo + 1];
    uint32_t at = UINT32_MAX;
    /* a slot's few entries scanned a fixed PAD at a time, picking without a branch: how many a
     * slot has goes either way pair after pair. Past the slot the next slots' entries (another
     * lower slot) and the table's sentinels (seal) never match */
    if (e1 - e0 <= PAD) {
        for (uint32_t e = e0; e < e0 + PAD; e++) at = t->e[e].key == key ? e : at;
        return at;
    }
    for (uint32_t e = e0; e < e1; e++) at = t->e[e].key == key ? e : at;
    return at;
}

/* The PAD entries past the last: keys no pair has (its two slots would be
 * equal), for find's fixed scan. False, and no index, where there is no
 * room for them (room keeps it: never, but then nothing is found). */
static bool seal(tt__anchors *t)
{
    if (t->cap < t->n || t->cap - t->n < PAD) return false;
    for (uint32_t e = t->n; e < t->n + PAD; e++) t->e[e] = (tt__anchor){UINT64_MAX, 0.0, 0.0, 0.0};
    return true;
}

/* The index of the sorted entries. Room keeps fcap above every lower slot
 * (below the particle count), so it always fits; were it not to, nothing
 * would be found, never a wrong entry. */
static void index_all(tt__anchors *t)
{
    t->nfirst = 0;
    if (t->n == 0 || !seal(t)) return;
    const uint64_t nf = (t->e[t->n - 1].key >> 32) + 2;
    if (nf > t->fcap) return;
    uint32_t e = 0;
    for (uint32_t p = 0; p + 1 < nf; p++) {
        t->first[p] = e;
        while (e < t->n && (t->e[e].key >> 32) == p) e++;
    }
    t->first[nf - 1] = t->n;
    t->nfirst = (uint32_t)nf;
}

/* Room for cap entries and the index of np particles; the entries are kept. */
static bool table_room(tt__anchors *t, uint32_t cap, uint32_t np)
{
    if (!tt__anchors_room(t, cap < 16 ? 16 : cap)) return false;
    if (np > UINT32_MAX - 1) return false;
    return tt__grow((void **)&t->first, &t->fcap, np + 1, sizeof *t->first);
}

void tt__anchors_free(tt__anchors *t)
{
    free(t->e); free(t->first);
    *t = (tt__anchors){0};
}

size_t tt__anchors_bytes(const tt__anchors *t)
{
    return (size_t)t->cap * sizeof *t->e + (size_t)t->fcap * sizeof *t->first;
}

void tt__anchors_clear(tt__anchors *t)
{
    t->n = 0;
    t->nfirst = 0;
}

/* Begin, after detection and the pre-solve velocities: each pair's anchor
 * (where it began the substep when it has none), friction so far (none)
 * and whether it is slow. The table is then spent
 * until end rebuilds it: a substep that ends with no contact (end does not
 * run) leaves none. */
void tt__anchors_begin(tt_world *w, tt__collide *c, uint32_t n, double h)
{
    tt__collide_scratch *s = &c->scr;
    const double g = sqrt(w->gravity.x * w->gravity.x + w->gravity.y * w->gravity.y);
    s->anc.on = tt__anchors_on(w, c);
    s->anc.thr = c->set.restitution_threshold >= 0.0 ? c->set.restitution_threshold : 2.0 * g * h; /* as end's */
    s->anc.h = h;
    if (!s->anc.on) {
        tt__anchors_clear(&c->anc);
        return;
    }
    const uint32_t nu = tt__anc_units(c);
    uint32_t c1 = s->anc.cap, c2 = s->anc.cap, c3 = s->anc.cap, c4 = s->anc.cap, c5 = s->anc.cap, c6 = s->anc.cap, c7 = s->anc.cap;
    if (!tt__grow((void **)&s->anc.rxy, &c1, nu + 1, 2 * sizeof *s->anc.rxy) || !tt__grow((void **)&s->anc.lt, &c2, nu + 1, sizeof *s->anc.lt) ||
        !tt__grow((void **)&s->anc.mu, &c3, nu + 1, sizeof *s->anc.mu) || !tt__grow((void **)&s->anc.kept, &c4, nu + 1, sizeof *s->anc.kept) ||
        !tt__grow((void **)&s->anc.slow, &c5, nu + 1, sizeof *s->anc.slow) || !tt__grow((void **)&s->anc.wl, &c6, nu + 1, sizeof *s->anc.wl) ||
        !tt__grow((void **)&s->anc.resting, &c7, nu + 1, sizeof *s->anc.resting) ||
        !tt__grow((void **)&s->anc.bucket, &s->anc.bcap, n + 2, sizeof *s->anc.bucket)) {
        s->anc.cap = 0; /* some grew: the next substep grows all again */
        tt__step_oom(w, "anchored friction");
        s->anc.on = false; /* this substep without it; the step is undone */
        return;
    }
    s->anc.cap = c1;
    const double *sx = w->integrator == TT_VERLET ? w->qx : c->sx0, *sy = w->integrator == TT_VERLET ? w->qy : c->sy0;
    const double thr2 = s->anc.thr * s->anc.thr;
    uint32_t nr = 0;
    for (uint32_t k = 0; k < nu; k++) {
        uint32_t a, b;
        double lam, *r = s->anc.rxy + 2 * (size_t)k;
        s->anc.lt[k] = s->anc.wl[k] = 0.0;
        if (!tt__anc_unit(c, k, &a, &b, &lam)) { /* a batch's padding */
            s->anc.slow[k] = 0;
            s->anc.mu[k] = r[0] = r[1] = 0.0;
            continue;
        }
        const uint32_t e = find(&c->anc, tt__pair_key(a, b));
        const double vx = s->vx0[a] - s->vx0[b], vy = s->vy0[a] - s->vy0[b];
        s->anc.slow[k] = !(vx * vx + vy * vy > thr2);
        s->anc.mu[k] = s->anc.slow[k] ? tt__pair_mu(c, a, b, 1) : 0.0;
        if (e == UINT32_MAX) {
            r[0] = sx[a] - sx[b];
            r[1] = sy[a] - sy[b];
        } else { /* stored lower minus higher */
            const tt__anchor *en = &c->anc.e[e];
            r[0] = a < b ? en->rx : -en->rx;
            r[1] = a < b ? en->ry : -en->ry;
            s->anc.wl[k] = en->lm;
        }
        s->anc.resting[nr] = k;
        nr += s->anc.slow[k] & (s->anc.wl[k] > 0.0); /* &, not &&: no branch */
    }
    s->anc.nresting = nr;
    if (s->batched) tt__batches_anchor(&s->bat, s->anc.rxy, s->anc.lt, s->anc.mu);
    tt__anchors_clear(&c->anc);
    if (!table_room(&c->anc, nu, n)) {
        tt__step_oom(w, "anchored friction");
        s->anc.on = false;
    }
}

/* Sorts the n entries of from into t by key: counting sort by the lower
 * slot (below nb), then insertion within each slot's few. The counts'
 * starts are the index (as index_all makes it, without walking the table
 * again). */
static void sort_entries(tt__anchors *t, uint32_t *bucket, uint32_t nb, const tt__anchor *from)
{
    memset(bucket, 0, (size_t)(nb + 1) * sizeof *bucket);
    uint32_t top = 0; /* the highest lower slot */
    for (uint32_t e = 0; e < t->n; e++) {
        const uint32_t lo = (uint32_t)(from[e].key >> 32);
        bucket[lo + 1]++;
        top = lo > top ? lo : top;
    }
    for (uint32_t i = 0; i < nb; i++) bucket[i + 1] += bucket[i];
    const uint64_t nf = (uint64_t)top + 2;
    t->nfirst = 0;
    if (t->n && nf <= t->fcap && nf <= (uint64_t)nb + 1 && seal(t)) {
        memcpy(t->first, bucket, nf * sizeof *t->first);
        t->nfirst = (uint32_t)nf;
    }
    for (uint32_t e = 0; e < t->n; e++) t->e[bucket[from[e].key >> 32]++] = from[e];
    for (uint32_t e = 1; e < t->n; e++) {
        const tt__anchor x = t->e[e];
        uint32_t j = e;
        for (; j > 0 && t->e[j - 1].key > x.key; j--) t->e[j] = t->e[j - 1];
        t->e[j] = x;
    }
}

/* End, before the velocity pass: the touching pairs' anchors, kept where
 * the pair held (slow, and its friction within the static bound), else
 * where the pair is now. Written pair by pair into the scratch, then
 * sorted into the table. Not over the substep's anchors (rxy): the
 * velocity pass reads them after this (anchored_unrub), and read there a
 * later pair's anchor wherever a pair before it had not touched. */
void tt__anchors_keep(tt_world *w, tt__collide *c)
{
    tt__collide_scratch *s = &c->scr;
    tt__anchors *t = &c->anc;
    const uint32_t n = w->ppool.count, nu = tt__anc_units(c);
    if (!s->anc.on || t->cap < nu || s->anc.bcap < n + 2 || s->anc.cap <= nu) return;
    const double *rxy = s->anc.rxy;
    tt__anchor *kept = s->anc.kept;
    const bool warm = c->set.warm_start > 0.0;
    uint32_t m = 0;
    for (uint32_t i = 0; i < s->ntouch; i++) {
        const uint32_t k = s->touch[i];
        uint32_t a, b;
        double lam;
        (void)tt__anc_unit(c, k, &a, &b, &lam);
        double x = rxy[2 * (size_t)k], y = rxy[2 * (size_t)k + 1];
        if (!s->anc.slow[k] || fabs(s->anc.lt[k]) >= 0.999 * s->anc.mu[k] * lam) {
            x = w->px[a] - w->px[b];
            y = w->py[a] - w->py[b];
        }
        kept[m++] = (tt__anchor){tt__pair_key(a, b), tt__pick(a < b, x, -x), tt__pick(a < b, y, -y), warm ? lam : 0.0};
    }
    t->n = m;
    sort_entries(t, s->anc.bucket, n, kept);
}

/* A removed particle's anchors go (its slot may be reused). */
void tt__anchors_drop(tt__anchors *t, uint32_t i)
{
    uint32_t m = 0;
    for (uint32_t e = 0; e < t->n; e++) {
        if ((uint32_t)(t->e[e].key >> 32) == i || (uint32_t)t->e[e].key == i) continue;
        t->e[m++] = t->e[e];
    }
    if (m == t->n) return;
    t->n = m;
    index_all(t);
}

/* Room for n entries and the sentinels past them (not their index); false on no memory. */
bool tt__anchors_room(tt__anchors *t, uint32_t n)
{
    if (n > UINT32_MAX - PAD) return false;
    n += PAD; /* and the sentinels */
    if (t->cap >= n) return true;
    return tt__grow((void **)&t->e, &t->cap, n, sizeof *t->e);
}

/* Copies the entries of from into to (whose index is not kept up); false on no memory. */
bool tt__anchors_copy(tt__anchors *to, const tt__anchors *from)
{
    if (!tt__anchors_room(to, from->n)) return false;
    to->n = from->n;
    if (from->n) memcpy(to->e, from->e, (size_t)from->n * sizeof *to->e);
    return true;
}

void tt__anchors_restore(tt__anchors *t, const tt__anchors *from)
{
    tt__anchors_clear(t);
    if (from->n == 0 || t->cap < from->n) return; /* the second cannot be: the table only grows */
    (void)tt__anchors_copy(t, from); /* room: allocates nothing */
    index_all(t);
}

void tt__anchors_save(const tt__anchors *t, tt__sink *s)
{
    tt__put_u32(s, TT__ID('A', 'N', 'C', 'H'));
    tt__put_u32(s, t->n);
    for (uint32_t e = 0; e < t->n; e++) {
        tt__put_u64(s, t->e[e].key);
        tt__put_f64(s, t->e[e].rx);
        tt__put_f64(s, t->e[e].ry);
    }
}

/* After the section's id: the entries, each a pair of live slots below n,
 * in ascending order. */
bool tt__anchors_load(tt__anchors *t, tt__source *s, uint32_t n)
{
    const uint32_t m = tt__get_count(s, 24, "anchors");
    if (s->failed) return false;
    if (!table_room(t, m, n)) return tt__src_fail(s, "out of memory");
    for (uint32_t e = 0; e < m; e++) {
        const uint64_t key = tt__get_u64(s);
        const double x = tt__get_num(s, -1e300, 1e300, "anchor"), y = tt__get_num(s, -1e300, 1e300, "anchor");
        const uint32_t lo = (uint32_t)(key >> 32), hi = (uint32_t)key;
        if (s->failed || !(lo < hi && hi < n) || (e && t->e[e - 1].key >= key)) return tt__src_fail(s, "anchor %u", e);
        t->e[e] = (tt__anchor){key, x, y, 0.0}; /* warm_start's section, when there is one, follows */
    }
    t->n = m;
    index_all(t);
    return true;
}

void tt__anchors_save_warm(const tt__anchors *t, double warm, tt__sink *s)
{
    tt__put_u32(s, TT__ID('W', 'A', 'R', 'M'));
    tt__put_f64(s, warm);
    tt__put_u32(s, t->n);
    for (uint32_t e = 0; e < t->n; e++) tt__put_f64(s, t->e[e].lm);
}

bool tt__anchors_load_warm(tt__anchors *t, tt__source *s, double *warm)
{
    *warm = tt__get_num(s, 0.0, 1.0, "warm start");
    const uint32_t m = tt__get_count(s, 8, "warm start's corrections");
    if (s->failed) return false;
    if (*warm == 0.0) return tt__src_fail(s, "warm start 0 written out");
    if (m != t->n) return tt__src_fail(s, "warm start: %u corrections for %u anchors", m, t->n);
    for (uint32_t e = 0; e < m; e++) t->e[e].lm = tt__get_num(s, 0.0, TT_MAX_VALUE, "warm start's correction");
    return !s->failed;
}

void tt__anchors_cool(tt__anchors *t)
{
    for (uint32_t e = 0; e < t->n; e++) t->e[e].lm = 0.0;
}
