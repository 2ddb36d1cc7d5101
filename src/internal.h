/* tether — private declarations shared by the engine's source files. */
#ifndef TETHER_INTERNAL_H
#define TETHER_INTERNAL_H

#include "tether.h"
#include "pool.h"

#include <math.h>

#if defined(__GNUC__)
#define TT_UNLIKELY(x) __builtin_expect(!!(x), 0)
#define TT_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define TT_UNLIKELY(x) (x)
#define TT_PRINTF(a, b)
#endif

/* Particle flags. */
enum {
    TT_PF_ALIVE = 1u << 0,
    TT_PF_PINNED = 1u << 1,
    TT_PF_FRESH = 1u << 2 /* Verlet: velocity was set exactly; first step starts with a·dt²/2 */
};

typedef struct tt__spring {
    uint32_t a, b;
    double rest, k, c;
    bool alive;
} tt__spring;

/* Scratch arrays, allocated the first time an integrator needs them. */
enum { TT_SCRATCH_AX, TT_SCRATCH_AY, TT_SCRATCH_RK4_FIRST, TT_SCRATCH_COUNT = TT_SCRATCH_RK4_FIRST + 8 };

struct tt_world {
    /* settings */
    tt_vec2 gravity, wind;
    double damping;
    tt_integrator integrator;
    double dt_prev;       /* dt of the last step (dt_hint before the first): Verlet's x_old is x − v·dt_prev */
    uint32_t max_particles;

    /* particles: struct of arrays indexed by slot; a slot keeps its index for life */
    tt_pool ppool;
    uint32_t pcap;        /* slots allocated in each array */
    uint32_t alive;
    double *px, *py;      /* position */
    double *qx, *qy;      /* Verlet: previous position; every other integrator: velocity */
    double *inv_mass;     /* 0 when pinned or removed: the integrator and solvers skip it */
    double *mass;         /* kept while pinned */
    float *radius;
    uint16_t *flags, *category, *mask;
    /* optional arrays: NULL until a feature first needs them */
    double *fx, *fy;      /* force accumulator (apply_force) */
    bool forces_pending;  /* some force was applied since the last step */
    uint64_t *user;
    double *scratch[TT_SCRATCH_COUNT];
    uint32_t scratch_cap[TT_SCRATCH_COUNT];
    uint32_t *fresh;      /* Verlet particles whose velocity was set exactly since the last step */
    uint32_t fresh_count, fresh_cap;

    /* springs */
    tt_pool spool;
    tt__spring *springs;
    uint32_t scap, springs_alive;

    tt_stats stats;
    char error[256];
};

/* Errors: set the message, return the code. */
tt_result tt__fail(const tt_world *w, tt_result code, const char *fmt, ...) TT_PRINTF(3, 4);
#define TT_CHECK_WORLD(w, fn) \
    do { if (!(w)) return tt__fail(NULL, TT_EINVAL, "%s: world is NULL", fn); } while (0)

static inline bool tt__finite(double x) { return x - x == 0.0; }
static inline bool tt__in_range(double x, double lo, double hi) { return x >= lo && x <= hi; }
static inline bool tt__vec_ok(tt_vec2 v) { return fabs(v.x) <= TT_MAX_VALUE && fabs(v.y) <= TT_MAX_VALUE; }
double tt__now_ms(void);

/* Particles. */
tt_result tt__particles_reserve(tt_world *w, uint32_t cap);
void tt__particles_free(tt_world *w);
bool tt__particle_ok(const tt_world *w, tt_particle p);
tt_result tt__particle_check(const tt_world *w, tt_particle p, const char *fn);
void tt__mark_fresh(tt_world *w, uint32_t i);
tt_vec2 tt__velocity(const tt_world *w, uint32_t i);
void tt__set_velocity(tt_world *w, uint32_t i, tt_vec2 v);
double *tt__scratch(tt_world *w, int which);

/* Springs. */
void tt__springs_detach(tt_world *w, uint32_t particle);
double tt__springs_energy(const tt_world *w);
void tt__springs_free(tt_world *w);

/* Forces and integration (integrate.c / forces.c). */
bool tt__has_forces(const tt_world *w);
void tt__eval_accel(tt_world *w, const double *x, const double *y, const double *vx, const double *vy,
                    double *ax, double *ay);
void tt__integrate(tt_world *w, double dt);
void tt__convert_state(tt_world *w, tt_integrator from, tt_integrator to);

#endif
