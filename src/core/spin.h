/* tether — particles that turn (tt_world_def.spin): each particle's angle
 * and angular velocity, a solid disc's (I = m r²/2). The state lives here
 * (spin.c: the group that keeps, saves and integrates it); the contacts
 * read and change the angular velocity where friction acts at the contact
 * point (collide/contact_roll.c). A world without the option has no spin
 * group and pays nothing. */
#ifndef TT_SPIN_H
#define TT_SPIN_H

#include "internal.h"
#include "stream.h"

#define TT__SPIN_ID TT__ID('S', 'P', 'I', 'N') /* its snapshot section, and how the contacts find it */

typedef struct tt__spin {
    double *angle;  /* per slot: rad, kept in [−π, π] */
    double *omega;  /* per slot: rad/s, counter-clockwise */
    uint32_t cap;   /* slots in each array; slots past it are 0 */
    double *undo_omega; /* the step's undo: omega as the step began (scratch) */
    uint32_t undo_cap;
} tt__spin;

static inline tt__spin *tt__spin_peek(const tt_world *w) { return (tt__spin *)tt__group_find_id(w, TT__SPIN_ID); }
/* Particle slot i stops turning (pinned, or made a point); nothing in a
 * world whose particles do not turn. Inline: particles.c calls it, and
 * spin.c uses particles.c (no circle between the two). */
static inline void tt__spin_stop(tt_world *w, uint32_t i)
{
    tt__spin *s = tt__spin_peek(w);
    if (s && i < s->cap) s->omega[i] = 0.0;
}
/* Gives the world a spin group (false on no memory); nothing if it has one. */
bool tt__spin_enable(tt_world *w);

#endif
