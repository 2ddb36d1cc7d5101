/* tether — reference scenes shared by the golden test and the snapshot
 * tests: built from the public API only, deterministic (their own LCG, no
 * clock), each driven step by step by what a game script would do. */
#ifndef TETHER_TEST_SCENES_H
#define TETHER_TEST_SCENES_H

#include <tether.h>

typedef enum {
    SCENE_POUR,        /* circles poured into a box of AABBs: contacts, friction, events, a bullet */
    SCENE_CLOTH,       /* cloth with tearing under wind, 4 substeps, against a circle and a capsule */
    SCENE_ZOO,         /* every constraint kind, every composite and shape kind, moved targets, removals */
    SCENE_INTEGRATORS, /* springs under every integrator in turn, forces, damping, Jacobi */
    SCENE_SETTLE,      /* two bins of circles fall asleep (sleeping at its defaults); a ball dropped in one wakes it */
    SCENE_ROLL,        /* discs that turn (spin) roll down a slope into a pile; the driver spins and kicks some */
    SCENE_PYRAMID,     /* a pyramid of circles held by anchored friction; one is removed, a ball lands on it */
    SCENE_COUNT
} scene_kind;

/* What the per-step driver needs: handles, valid in any world restored from
 * this one's stream. */
typedef struct scene {
    scene_kind kind;
    tt_world *w;
    tt_particle p[8];
    tt_constraint c[4];
    tt_shape s[2];
    tt_spring sp;
} scene;

const char *scene_name(scene_kind k);
/* Builds scene k into sc->w (a new world); false when a call failed. */
bool scene_build(scene *sc, scene_kind k);
/* What the script does before step number w.stats.steps, then the step. */
void scene_step(scene *sc);
/* A small world with one of nearly everything, stepped twice: a short
 * stream for the byte-by-byte tests and the stream fuzzer. */
tt_world *scene_small_world(void);
/* Adds to w a cols × rows network 0.5 m apart from (0, 0) down, undamped
 * springs (k = 200) to the right and below, the top row pinned: the
 * reversal tests' scene. */
void scene_spring_network(tt_world *w, int cols, int rows);
/* w's snapshot stream in a new buffer of *size bytes (free it); NULL on failure. */
unsigned char *scene_save(const tt_world *w, size_t *size);
/* A new world loaded from w's own stream; NULL, with the reason printed,
 * when it does not save or load. */
tt_world *scene_reload(const tt_world *w);
/* FNV-1a over every live particle's position bits in slot order, from
 * tt_world_read_positions: a digest independent of tt_world_hash. */
uint64_t scene_positions_digest(const tt_world *w);

#endif
