/* tether — private side of terrains (terrain.c: storage, the public calls,
 * carving; terrain_band.c: the distance band; terrain_contact.c: what the contacts group
 * and the queries ask of them; terrain_tiles.c: the coarse map that spares
 * particles far from every surface their test; terrain_state.c: their part
 * of the snapshot).
 * The contacts group (tt__collide) holds them as c->terr, NULL until the
 * world's first terrain: a world without terrains takes none of these
 * paths. */
#ifndef TETHER_TERRAIN_INTERNAL_H
#define TETHER_TERRAIN_INTERNAL_H

#include "collide_internal.h"
#include "mask/mask_internal.h"
#include "tether/terrain.h"

/* The coarse map (terrain_tiles.c): one value per TT__TILE × TT__TILE pixels. */
#define TT__TILE_SHIFT 4
#define TT__TILE (1 << TT__TILE_SHIFT)

/* A terrain contact's primitive field (tt__scontact.prim, ccd_prim):
 * this bit over the terrain slot. Shapes' primitives stay far below it. */
#define TT__PRIM_TERRAIN (1u << 30)
static inline bool tt__prim_is_terrain(uint32_t prim) { return (prim & TT__PRIM_TERRAIN) != 0; }

typedef struct tt__terrain {
    bool alive;
    tt_mask *m;          /* the terrain's own pixels */
    float *sdf;          /* per pixel (row major): signed distance to the surface in pixels, ±band, negative in solid */
    float *tile;         /* per tile (row major, tw × th): the least sdf of its pixels; derived, like sdf */
    int tw, th;
    tt_terrain_def def;  /* def.solid is NULL */
    double inv;          /* 1 / def.pixel */
    double lox, loy, hix, hiy; /* world rectangle */
} tt__terrain;

/* What the distance update (terrain_band.c) works in and keeps between
 * updates: scratch, neither saved nor hashed (terrain_state.c saves the
 * terrains' state, the rest of tt__terrains). */
typedef struct tt__terrain_scratch {
    unsigned char *buf;
    size_t cap;
    /* raw distances by squared distance for the band it was made for */
    int32_t lut[(TT_TERRAIN_MAX_BAND + 1) * (TT_TERRAIN_MAX_BAND + 1) + 1];
    int lut_band;
    uint64_t spread8[256]; /* byte k: 0xFF where bit k of the index is set */
} tt__terrain_scratch;

typedef struct tt__terrains {
    tt__pool pool;
    tt__terrain *t;
    uint32_t cap, alive;
    tt__terrain_scratch scr;
    bool no_tiles; /* debug (tests): detection tests every particle, as without the map; same results.
                    * Not state: a restore makes the terrains anew, with it off */
} tt__terrains;

bool tt__terrain_ok(const tt__collide *c, tt_terrain t);
/* The distances of pixels [x0, x1] × [y0, y1] (inclusive, clamped to the
 * terrain) and of everything within band of them, after their bits
 * changed; false on no memory (the band is then stale there). */
bool tt__terrain_update(tt__terrains *ts, tt__terrain *T, int x0, int y0, int x1, int y1);
/* The scratch that update needs for the same box, so that a call can fail
 * before it changes a pixel (update then cannot fail). */
bool tt__terrain_reserve(tt__terrains *ts, const tt__terrain *T, int x0, int y0, int x1, int y1);
/* The per-pixel band and the tile map for T's mask (contents unset);
 * false on no memory (nothing kept). */
bool tt__terrain_alloc(tt__terrain *T);
void tt__terrain_free_one(tt__terrain *T);
void tt__terrains_free(tt__terrains *ts);
size_t tt__terrains_bytes(const tt__terrains *ts);
/* Sets the derived fields of T from its def and mask (world rectangle). */
void tt__terrain_place(tt__terrain *T);

/* The one hook carving and filling call with the world rectangle they
 * changed (grown by the band): whatever rests there must notice (sleeping
 * particles wake, issue 22). */
void tt__terrain_changed(tt_world *w, double lox, double loy, double hix, double hiy);

/* The tile map (terrain_tiles.c). The least band value of each tile that
 * meets pixels [x0, x1] × [y0, y1] (inclusive, within the terrain), after
 * their band changed. */
void tt__terrain_tiles_update(tt__terrain *T, int x0, int y0, int x1, int y1);
/* Marks near[c] for each cell c of the particle grid g (just built over
 * the particles, none moved since) where a particle centred in it, inside
 * the grid, with a radius up to g->rmax, may have a contact with some
 * terrain; near[c] = 0 means none can (its pixel's band says so, as the
 * per-particle test would). False when the map cannot tell (every particle
 * is then tested). */
bool tt__terrain_near_cells(const tt__terrains *ts, const tt__grid *g, uint8_t *near, uint32_t cap);

/* Contacts (terrain_contact.c). */
/* Signed distance (m) at world (x, y) and the outward normal (0, 0 when flat). */
double tt__terrain_sample(const tt__terrain *T, double x, double y, double *nx, double *ny);
/* Particle (x, y, r) against terrain code (prim field): depth > 0 is
 * penetration, (x, y) + n·depth the nearest free position found. */
void tt__terrain_hit(const tt__collide *c, uint32_t code, double x, double y, double r, tt__hit *out);
void tt__terrain_material(const tt__collide *c, uint32_t code, double *e, double *fs, double *fk);
tt_terrain tt__terrain_handle(const tt__collide *c, uint32_t code);
/* The substep's particle–terrain contacts, appended to c->scr.sc; false when
 * memory ran out (the rest were skipped). */
bool tt__terrain_detect(tt_world *w, tt__collide *c, uint32_t n, bool grid_built);
/* A bullet's path from (x0, y0) to (x1, y1) marched through the distance
 * band: the terrain code first touched (−1: none) at fraction *t. */
int32_t tt__terrain_sweep(tt_world *w, const tt__collide *c, uint32_t i, double x0, double y0, double x1, double y1,
                          double *t, double *nx, double *ny);
/* The first terrain along a ray (into *out when nearer than out->fraction). */
void tt__terrain_raycast(const tt_world *w, const tt__collide *c, tt_vec2 from, tt_vec2 to, uint16_t mask,
                         tt_ray_hit *out);

/* Snapshot (terrain_state.c): appended to the contacts section when the world has terrains. */
void tt__terrains_save(const tt__collide *c, struct tt__sink *s);
bool tt__terrains_load(tt_world *w, tt__collide *c, struct tt__source *s);

#endif
