/* tests/fuzz/fuzz_c.h — the seeded fuzzer of tether's C API (build/fuzz_c).
 *
 * One fuzzer call = one wrapper from a table (fuzz_c_*.c) = one public call
 * with generated arguments (a scene entry makes many particles in a loop).
 * Wrappers say what the call was (logged as a C-like line), which world it
 * used, whether it failed, whether it had to fail (a NULL world, a stale,
 * foreign or null handle) and whether it was a read; the driver (fuzz_c.c)
 * holds them to the invariants. Everything is drawn from one xorshift64*
 * stream, so a seed and a call number replay exactly. */
#ifndef TETHER_FUZZ_C_H
#define TETHER_FUZZ_C_H

#include <tether.h>

#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>

enum fz_api_id {
#define FZ_API(name) FZ_##name,
#include "fuzz_c_api.h"
#undef FZ_API
    FZ_API_COUNT
};

#define FZ_WORLDS 3        /* live worlds at once: enough for foreign handles */
#define FZ_KINDS 7         /* tt_kind values, NONE included, indexed directly */
#define FZ_LIST_CAP 2048   /* handles remembered per world and kind */
#define FZ_STALE_CAP 512   /* removed handles remembered per world and kind */
#define FZ_FOREIGN_CAP 256 /* handles of destroyed worlds, per kind */
#define FZ_MASKS 5         /* live masks at once */
#define FZ_MASK_AREA (1 << 17) /* larger masks are checked and freed, not kept */
#define FZ_CLOCKS 2

/* A handle of any kind: every tt_<kind> struct has this layout. */
typedef struct fz_h {
    uint32_t index, gen;
} fz_h;

typedef struct fz_hlist {
    fz_h *h;
    uint32_t n;
} fz_hlist;

typedef struct fz_world {
    tt_world *w;
    int name;                 /* printed as w<name> */
    uint64_t hash;            /* state before the current call */
    uint32_t counts[5];
    bool snap_valid;
    fz_hlist live[FZ_KINDS];  /* handles that were live once (may have gone stale since) */
    fz_hlist stale[FZ_KINDS]; /* handles this fuzzer removed: refused forever */
} fz_world;

typedef struct fz {
    uint64_t rng;
    uint64_t seed;
    uint64_t call;
    fz_world slots[FZ_WORLDS];
    int names;               /* worlds created so far (names and tags) */
    fz_hlist foreign[FZ_KINDS];
    uint64_t hits[FZ_API_COUNT];
    tt_mask *masks[FZ_MASKS]; /* fuzz_c_mask.c: the pool, NULL where empty */
    void *mask_mem[FZ_MASKS]; /* the memory of a tt_mask_init mask, else NULL */
    tt_clock clocks[FZ_CLOCKS]; /* fuzz_c_clock.c; all zero (no clock yet) at first */
    bool trace;
    /* the current call, filled in by the wrapper */
    int cur;                 /* slot used, −1 none (NULL world or no world) */
    bool failed, must_fail, readonly, stepped;
    const char *why_must;    /* what made must_fail */
    fz_h must_h;             /* the handle that did, if one did */
    tt_kind must_k;
} fz;

typedef void (*fz_fn)(fz *f);
typedef struct fz_entry {
    const char *name;
    fz_fn fn;
    unsigned weight;
} fz_entry;

/* fuzz_c_gen.c: draws */
uint64_t fz_rand(fz *f);
uint32_t fz_below(fz *f, uint32_t n);
bool fz_chance(fz *f, unsigned percent);
double fz_unit(fz *f);
double fz_nasty(fz *f);
double fz_real(fz *f, double lo, double hi);
double fz_coord(fz *f);
tt_vec2 fz_vec(fz *f, double lo, double hi);
tt_vec2 fz_point(fz *f);
uint32_t fz_count(fz *f, uint32_t lo, uint32_t hi);
int fz_enum(fz *f, int count);
uint16_t fz_bits16(fz *f);
double fz_stiffness(fz *f);
double fz_compliance(fz *f);
double fz_dt(fz *f);

/* fuzz_c_gen.c: worlds and handles */
void fz_snapshot(fz_world *s);
tt_world *fz_world_pick(fz *f);
tt_world *fz_world_any(fz *f);
fz_h fz_handle(fz *f, tt_kind kind);
fz_h fz_live(fz *f, tt_kind kind);
void fz_remember(fz *f, tt_kind kind, fz_h h);
void fz_forget(fz *f, tt_kind kind, fz_h h);
void fz_list_add(fz_hlist *l, uint32_t cap, fz_h h, fz *f);
void fz_list_free(fz_hlist *l);
tt_particle *fz_particles(fz *f, uint32_t n);
uint32_t fz_polygon(fz *f, tt_vec2 *pts, uint32_t max);

/* fuzz_c_log.c: the log and its names */
void fz_log(fz *f, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void fz_log_more(fz *f, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void fz_log_dump(int fd, unsigned lines);
void fz_log_ids(fz *f, const tt_particle *ids, uint32_t n);
const char *fz_d(double v);
const char *fz_u(unsigned long long v);
const char *fz_v(tt_vec2 v);
const char *fz_wn(fz *f, const tt_world *w);
const char *fz_hn(fz_h h, tt_kind kind);
const char *fz_res_name(tt_result r);

/* fuzz_c.c: outcomes and checks */
void fz_hit(fz *f, enum fz_api_id id);
void fz_res(fz *f, tt_result r);
void fz_hres(fz *f, tt_kind kind, fz_h h);
void fz_fail(fz *f, const char *fmt, ...) __attribute__((format(printf, 2, 3), noreturn));
void fz_finite(fz *f, double v, const char *what);
void fz_finite_vec(fz *f, tt_vec2 v, const char *what);
void fz_check_world(fz *f, tt_world *w);
void fz_world_too_big(fz *f);
tt_world *fz_world_fresh(fz *f, int slot);
void *fz_buffer(fz *f, uint32_t *cap, uint32_t plausible, size_t size);

/* the wrapper tables */
extern const fz_entry fz_world_entries[];
extern const fz_entry fz_particle_entries[];
extern const fz_entry fz_constraint_entries[];
extern const fz_entry fz_composite_entries[];
extern const fz_entry fz_collide_entries[];
extern const fz_entry fz_scene_entries[];
extern const fz_entry fz_stream_entries[]; /* fuzz_c_stream.c */
extern const fz_entry fz_terrain_entries[]; /* fuzz_c_terrain.c */
extern const fz_entry fz_rewind_entries[]; /* fuzz_c_rewind.c */
extern const fz_entry fz_journal_entries[]; /* fuzz_c_journal.c */
extern const fz_entry fz_mask_entries[];   /* fuzz_c_mask.c */
extern const fz_entry fz_mask2_entries[];  /* fuzz_c_mask_px.c */
extern const fz_entry fz_mask3_entries[];  /* fuzz_c_mask_shape.c */
extern const fz_entry fz_clock_entries[];  /* fuzz_c_clock.c */

/* fuzz_c_mask.c: the mask pool */
tt_mask *fz_mask_pick(fz *f, int *slot);
void fz_mask_put(fz *f, tt_mask *m, const char *what);
void fz_mask_free_all(fz *f);
uint64_t fz_mask_sig(const tt_mask *m);
void fz_mres(fz *f, tt_result r);
const char *fz_mn(int slot);
int fz_mask_coord(fz *f, int side);
int fz_mask_offset(fz *f, int side_a, int side_b);
int fz_mask_w(const tt_mask *m);
int fz_mask_h(const tt_mask *m);

/* Handle conversions: all five structs share fz_h's layout. Functions, not
 * macros, so an argument with draws in it is evaluated once. */
static inline tt_particle FZ_P(fz_h h) { return (tt_particle){ h.index, h.gen }; }
static inline tt_spring FZ_S(fz_h h) { return (tt_spring){ h.index, h.gen }; }
static inline tt_constraint FZ_C(fz_h h) { return (tt_constraint){ h.index, h.gen }; }
static inline tt_shape FZ_SH(fz_h h) { return (tt_shape){ h.index, h.gen }; }
static inline tt_composite FZ_CO(fz_h h) { return (tt_composite){ h.index, h.gen }; }
static inline tt_terrain FZ_T(fz_h h) { return (tt_terrain){ h.index, h.gen }; }
/* And back, once per argument: FZ_H(tt_particle_create(...)) makes one particle. */
static inline fz_h fz_h_p(tt_particle x) { return (fz_h){ x.index, x.gen }; }
static inline fz_h fz_h_s(tt_spring x) { return (fz_h){ x.index, x.gen }; }
static inline fz_h fz_h_c(tt_constraint x) { return (fz_h){ x.index, x.gen }; }
static inline fz_h fz_h_sh(tt_shape x) { return (fz_h){ x.index, x.gen }; }
static inline fz_h fz_h_co(tt_composite x) { return (fz_h){ x.index, x.gen }; }
static inline fz_h fz_h_t(tt_terrain x) { return (fz_h){ x.index, x.gen }; }
#define FZ_H(x) _Generic((x), tt_particle: fz_h_p, tt_spring: fz_h_s, tt_constraint: fz_h_c, tt_shape: fz_h_sh, \
                              tt_composite: fz_h_co, tt_terrain: fz_h_t)(x)

/* Marks a call as made (for "N of M functions reached"). */
#define FZ_HIT(f, name) fz_hit((f), FZ_##name)

#endif
