/* tether — linear springs: force based, so integrators can be compared on them. */
#ifndef TETHER_SPRING_H
#define TETHER_SPRING_H

#include "world.h"

#ifdef __cplusplus
extern "C" {
#endif

/// How a spring is made. Start from tt_spring_def_default().
/// Force on a: −k·(|xa − xb| − rest)·n − c·((va − vb)·n)·n, with n the unit
/// vector from b to a; b gets the opposite force.
typedef struct tt_spring_def {
    tt_particle a, b;   ///< two distinct live particles
    double stiffness;   ///< k, N/m, ≥ 0; default 100
    double damping;     ///< c, N·s/m, ≥ 0; default 0
    double rest_length; ///< m, ≥ 0; default −1 = the distance between a and b when made
} tt_spring_def;

TT_API tt_spring_def tt_spring_def_default(void);
/// Adds a spring; the null handle on bad input (tt_last_error says why).
TT_API tt_spring tt_spring_create(tt_world *w, const tt_spring_def *def);
TT_API tt_result tt_spring_destroy(tt_world *w, tt_spring s);
TT_API bool tt_spring_is_valid(const tt_world *w, tt_spring s);
/// The current def (ends, stiffness, damping, rest length).
TT_API tt_result tt_spring_get_def(const tt_world *w, tt_spring s, tt_spring_def *out);
TT_API tt_result tt_spring_set_stiffness(tt_world *w, tt_spring s, double k);    ///< N/m, ≥ 0
TT_API tt_result tt_spring_set_damping(tt_world *w, tt_spring s, double c);      ///< N·s/m, ≥ 0
TT_API tt_result tt_spring_set_rest_length(tt_world *w, tt_spring s, double l);  ///< m, ≥ 0
/// Current length |xa − xb|, m.
TT_API tt_result tt_spring_get_length(const tt_world *w, tt_spring s, double *out);
/// Live springs in the world.
TT_API uint32_t tt_world_spring_count(const tt_world *w);
/// Bulk: writes up to `cap` live spring handles in slot order into out (may
/// be NULL to count); returns the number of live springs.
TT_API uint32_t tt_world_list_springs(const tt_world *w, tt_spring *out, uint32_t cap);

#ifdef __cplusplus
}
#endif

#endif
