/* tests/fuzz/fuzz_c_gen.c — what the C fuzzer passes: numbers that are
 * plausible most of the time (so calls get past validation and scenes get
 * deep) and hostile the rest, worlds, and handles of every sort. */
#include "fuzz_c.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

uint64_t fz_rand(fz *f)
{
    f->rng ^= f->rng >> 12;
    f->rng ^= f->rng << 25;
    f->rng ^= f->rng >> 27;
    return f->rng * 0x2545F4914F6CDD1Dull;
}

uint32_t fz_below(fz *f, uint32_t n) { return n ? (uint32_t)((fz_rand(f) >> 32) % n) : 0; }
bool fz_chance(fz *f, unsigned percent) { return fz_below(f, 100) < percent; }
double fz_unit(fz *f) { return (double)(fz_rand(f) >> 11) * (1.0 / 9007199254740992.0); }

/* Values every number check must survive: NaN, infinities, magnitudes past
 * every limit, denormals, −0, the limits themselves and their neighbours. */
double fz_nasty(fz *f)
{
    static const double table[] = {
        NAN, -NAN, INFINITY, -INFINITY, 1e300, -1e300, DBL_MAX, -DBL_MAX, 4.9e-324, -4.9e-324,
        DBL_MIN / 3, -0.0, 0.0, 1e12, -1e12, 1.0000000001e12, -1.0000000001e12, 1e15, -1e15,
        1e-9, 9.999999e-10, 1e-300, 1e-320, 1e-12, 9.99e-13, 9007199254740993.0, 1e9, 1e9 + 1,
        -1.0, 1e-100, 4294967296.0, 2147483648.0,
    };
    if (fz_chance(f, 12)) {
        uint64_t bits = fz_rand(f);
        double d;
        memcpy(&d, &bits, sizeof d);
        return d;
    }
    return table[fz_below(f, sizeof table / sizeof table[0])];
}

double fz_real(fz *f, double lo, double hi)
{
    unsigned r = fz_below(f, 100);
    if (r < 7) return fz_nasty(f);
    if (r < 9) return lo;
    if (r < 11) return hi;
    return lo + (hi - lo) * fz_unit(f);
}

/* Coordinates: mostly a room-sized scene, sometimes far away or at the
 * limit, and often one of a few shared values, so rows and piles of
 * particles share x or y exactly (the grid's finding 1 was such a row). */
double fz_coord(fz *f)
{
    static const double shared[] = { 0.0, 0.05, 0.3, -7.7, 1.0, 10.0, 0.1, 1e-3, -0.0, 123.456 };
    unsigned r = fz_below(f, 100);
    if (r < 70) return -30.0 + 60.0 * fz_unit(f);
    if (r < 82) return shared[fz_below(f, sizeof shared / sizeof shared[0])];
    if (r < 88) return (fz_unit(f) - 0.5) * 2e6;
    if (r < 92) return (fz_chance(f, 50) ? 1.0 : -1.0) * (1e12 - fz_unit(f) * 1e3);
    if (r < 95) return (fz_unit(f) - 0.5) * 1e-6;
    return fz_nasty(f);
}

tt_vec2 fz_vec(fz *f, double lo, double hi) { return (tt_vec2){ fz_real(f, lo, hi), fz_real(f, lo, hi) }; }
tt_vec2 fz_point(fz *f) { return (tt_vec2){ fz_coord(f), fz_coord(f) }; }

/* Counts: small most of the time (skewed towards the low end), the
 * documented ends, one past them, and counts no array could hold. */
uint32_t fz_count(fz *f, uint32_t lo, uint32_t hi)
{
    static const uint32_t bad[] = { 0, 1, 2, 3, UINT32_MAX, UINT32_MAX - 1, 1u << 31, 1u << 24, (1u << 24) + 1,
                                    65536, 65537, 1000001 };
    unsigned r = fz_below(f, 100);
    if (r < 6) return bad[fz_below(f, sizeof bad / sizeof bad[0])];
    if (r < 8) return hi;
    if (r < 9) return hi + 1;
    if (r < 10) return lo ? lo - 1 : 0;
    uint32_t span = hi - lo + 1, scale = 1u << fz_below(f, 8); /* 1 … 128 */
    return lo + fz_below(f, span < scale ? span : scale);
}

int fz_enum(fz *f, int count)
{
    static const int bad[] = { -1, 1000, 2147483647, -2147483647 - 1, 7, 16 };
    if (fz_chance(f, 92)) return (int)fz_below(f, (uint32_t)count);
    if (fz_chance(f, 40)) return count;
    return bad[fz_below(f, sizeof bad / sizeof bad[0])];
}

uint16_t fz_bits16(fz *f)
{
    if (fz_chance(f, 60)) return fz_chance(f, 50) ? 0xFFFF : 0x0001;
    return (uint16_t)fz_rand(f);
}

double fz_stiffness(fz *f) { return fz_chance(f, 30) ? 1.0 : fz_real(f, 0.0, 1.0); }

double fz_compliance(fz *f)
{
    static const double edge[] = { 1e-12, 9.99e-13, 1e12, 1.0000001e12, 1e-320, 4.9e-324 };
    unsigned r = fz_below(f, 100);
    if (r < 50) return 0.0;
    if (r < 88) return pow(10.0, -12.0 + 10.0 * fz_unit(f));
    if (r < 95) return edge[fz_below(f, sizeof edge / sizeof edge[0])];
    return fz_nasty(f);
}

/* Steps: the usual frame times, the documented ends (1e-9 and 10) and the
 * values either side of them, denormals (finding 5 was dt = 1e-320). */
double fz_dt(fz *f)
{
    static const double usual[] = { 1.0 / 60, 1.0 / 120, 1.0 / 30, 1.0 / 240 };
    static const double edge[] = { 1e-9, 1.0000001e-9, 9.999999e-10, 1e-320, 4.9e-324, 1e-12, 1e-7,
                                   0.1, 1.0, 10.0, 10.000001, 0.0, -0.0, -1.0 / 60 };
    unsigned r = fz_below(f, 100);
    if (r < 60) return usual[fz_below(f, 4)];
    if (r < 78) return 1e-4 + 0.05 * fz_unit(f);
    if (r < 94) return edge[fz_below(f, sizeof edge / sizeof edge[0])];
    return fz_nasty(f);
}

/* --- worlds ---------------------------------------------------------------- */

void fz_snapshot(fz_world *s)
{
    if (s->snap_valid) return;
    s->hash = tt_world_hash(s->w);
    s->counts[0] = tt_world_particle_count(s->w);
    s->counts[1] = tt_world_spring_count(s->w);
    s->counts[2] = tt_world_constraint_count(s->w);
    s->counts[3] = tt_world_shape_count(s->w);
    s->counts[4] = tt_world_composite_count(s->w);
    s->snap_valid = true;
}

static int live_slot(fz *f)
{
    int live[FZ_WORLDS], n = 0;
    for (int i = 0; i < FZ_WORLDS; i++)
        if (f->slots[i].w) live[n++] = i;
    return n ? live[fz_below(f, (uint32_t)n)] : -1;
}

/* The world of a call that reports failure: NULL now and then, which it
 * must refuse. The world's state is taken first, to compare after. */
tt_world *fz_world_pick(fz *f)
{
    f->cur = fz_chance(f, 2) ? -1 : live_slot(f);
    if (f->cur < 0) {
        f->must_fail = true;
        f->why_must = "a NULL world";
        return NULL;
    }
    fz_snapshot(&f->slots[f->cur]);
    return f->slots[f->cur].w;
}

/* The world of a read with no failure channel (a count, a getter). */
tt_world *fz_world_any(fz *f)
{
    f->readonly = true;
    f->cur = fz_chance(f, 2) ? -1 : live_slot(f);
    if (f->cur < 0) return NULL;
    fz_snapshot(&f->slots[f->cur]);
    return f->slots[f->cur].w;
}

/* --- handles ---------------------------------------------------------------- */

void fz_list_add(fz_hlist *l, uint32_t cap, fz_h h, fz *f)
{
    if (h.index == 0 && h.gen == 0) return;
    if (!l->h) l->h = calloc(cap, sizeof *l->h);
    if (!l->h) abort();
    if (l->n < cap) l->h[l->n++] = h;
    else l->h[fz_below(f, cap)] = h; /* full: forget one at random */
}

void fz_list_free(fz_hlist *l)
{
    free(l->h);
    l->h = NULL;
    l->n = 0;
}

void fz_remember(fz *f, tt_kind kind, fz_h h)
{
    if (f->cur >= 0) fz_list_add(&f->slots[f->cur].live[kind], FZ_LIST_CAP, h, f);
}

/* A handle this fuzzer removed goes to the stale list: every later call
 * with it must be refused. */
void fz_forget(fz *f, tt_kind kind, fz_h h)
{
    if (f->cur >= 0) fz_list_add(&f->slots[f->cur].stale[kind], FZ_STALE_CAP, h, f);
}

static fz_h from_list(fz *f, const fz_hlist *l)
{
    return l->n ? l->h[fz_below(f, l->n)] : (fz_h){ 0, 0 };
}

/* A handle that was live in the current world (or a forged one if none). */
fz_h fz_live(fz *f, tt_kind kind)
{
    if (f->cur >= 0 && f->slots[f->cur].live[kind].n) return from_list(f, &f->slots[f->cur].live[kind]);
    return (fz_h){ fz_below(f, 8), fz_below(f, 4) };
}

static uint64_t to_u64(fz *f, tt_kind kind, fz_h h)
{
    switch (kind) {
    case TT_KIND_PARTICLE: FZ_HIT(f, tt_particle_to_u64); return tt_particle_to_u64(FZ_P(h));
    case TT_KIND_SPRING: FZ_HIT(f, tt_spring_to_u64); return tt_spring_to_u64(FZ_S(h));
    case TT_KIND_CONSTRAINT: FZ_HIT(f, tt_constraint_to_u64); return tt_constraint_to_u64(FZ_C(h));
    case TT_KIND_SHAPE: FZ_HIT(f, tt_shape_to_u64); return tt_shape_to_u64(FZ_SH(h));
    case TT_KIND_TERRAIN: FZ_HIT(f, tt_terrain_to_u64); return tt_terrain_to_u64(FZ_T(h));
    default: FZ_HIT(f, tt_composite_to_u64); return tt_composite_to_u64(FZ_CO(h));
    }
}

static fz_h from_u64(fz *f, tt_kind kind, uint64_t u)
{
    switch (kind) {
    case TT_KIND_PARTICLE: FZ_HIT(f, tt_particle_from_u64); return FZ_H(tt_particle_from_u64(u));
    case TT_KIND_SPRING: FZ_HIT(f, tt_spring_from_u64); return FZ_H(tt_spring_from_u64(u));
    case TT_KIND_CONSTRAINT: FZ_HIT(f, tt_constraint_from_u64); return FZ_H(tt_constraint_from_u64(u));
    case TT_KIND_SHAPE: FZ_HIT(f, tt_shape_from_u64); return FZ_H(tt_shape_from_u64(u));
    case TT_KIND_TERRAIN: FZ_HIT(f, tt_terrain_from_u64); return FZ_H(tt_terrain_from_u64(u));
    default: FZ_HIT(f, tt_composite_from_u64); return FZ_H(tt_composite_from_u64(u));
    }
}

static void must(fz *f, const char *why, tt_kind kind, fz_h h)
{
    if (!f->must_fail) {
        f->why_must = why;
        f->must_h = h;
        f->must_k = kind;
    }
    f->must_fail = true;
}

/* A handle of another kind turned into this one through its integer: the
 * null handle, always refused. The same kind must come back unchanged. */
static fz_h turned(fz *f, tt_kind kind)
{
    tt_kind other = (tt_kind)(1 + fz_below(f, FZ_KINDS - 1));
    fz_h h = fz_live(f, other);
    uint64_t u = to_u64(f, other, h);
    FZ_HIT(f, tt_handle_kind);
    if (u && tt_handle_kind(u) != other) fz_fail(f, "tt_handle_kind(%llu) is %d, not %d", (unsigned long long)u, (int)tt_handle_kind(u), (int)other);
    fz_h back = from_u64(f, other, u);
    if (u && (back.index != h.index || back.gen != h.gen)) fz_fail(f, "a handle does not survive tt_*_to_u64/from_u64");
    if (fz_chance(f, 10)) return from_u64(f, kind, fz_rand(f) >> fz_below(f, 12)); /* any integer: no promise */
    fz_h r = from_u64(f, kind, u);
    if (other != kind || !u) {
        if (r.index || r.gen) fz_fail(f, "an integer of kind %d decoded as a handle of kind %d", (int)other, (int)kind);
        must(f, "a handle of another kind (through tt_*_from_u64)", kind, r);
    }
    return r;
}

static fz_h foreign(fz *f, tt_kind kind)
{
    int other = -1;
    for (int i = 0; i < FZ_WORLDS; i++)
        if (i != f->cur && f->slots[i].w && f->slots[i].live[kind].n && (other < 0 || fz_chance(f, 50))) other = i;
    fz_h h = other >= 0 && fz_chance(f, 70) ? from_list(f, &f->slots[other].live[kind]) : from_list(f, &f->foreign[kind]);
    /* Tags are reused after 1023 worlds: only before that is refusal promised. */
    if ((h.index || h.gen) && f->names < 1000) must(f, "a handle of another world", kind, h);
    return h;
}

fz_h fz_handle(fz *f, tt_kind kind)
{
    unsigned r = fz_below(f, 100);
    if (r < 72) return fz_live(f, kind);
    if (r < 80 && f->cur >= 0 && f->slots[f->cur].stale[kind].n) {
        fz_h h = from_list(f, &f->slots[f->cur].stale[kind]);
        must(f, "a stale handle (of an object removed by this fuzzer)", kind, h);
        return h;
    }
    if (r < 86) return foreign(f, kind);
    if (r < 91) return turned(f, kind);
    if (r < 97) { /* forged: may name a live object by chance, so nothing is promised */
        if (fz_chance(f, 50)) return (fz_h){ fz_below(f, 64), fz_below(f, 1u << 20) };
        return (fz_h){ (uint32_t)fz_rand(f), (uint32_t)fz_rand(f) };
    }
    must(f, "the null handle", kind, (fz_h){ 0, 0 });
    return (fz_h){ 0, 0 };
}

/* n particle handles for a bulk call or a def, mostly live ones (freed by
 * the caller). */
tt_particle *fz_particles(fz *f, uint32_t n)
{
    tt_particle *a = malloc((n ? n : 1) * sizeof *a);
    if (!a) abort();
    for (uint32_t i = 0; i < n; i++) a[i] = FZ_P(fz_chance(f, 97) ? fz_live(f, TT_KIND_PARTICLE) : fz_handle(f, TT_KIND_PARTICLE));
    return a;
}

/* An output buffer for a call taking (out, cap): cap is drawn (often past
 * what is needed, sometimes 0 or huge); a cap no buffer could hold comes
 * with NULL, which "may be NULL to count" allows. Freed by the caller. */
void *fz_buffer(fz *f, uint32_t *cap, uint32_t plausible, size_t size)
{
    *cap = fz_count(f, 0, plausible + 8);
    if (*cap > (1u << 20) || fz_chance(f, 5)) return NULL;
    void *p = calloc(*cap ? *cap : 1, size);
    if (!p) abort();
    return p;
}
