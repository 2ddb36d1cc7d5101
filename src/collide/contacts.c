/* tether — contacts: the collision group of the relaxation loop.
 *   begin  (per substep)  detection: bullets' sweeps, the particle grid and
 *                          its pairs, particles against the static index
 *                          (contact_detect.c);
 *   relax  (per sweep)     projection to the nearest valid position, mass
 *                          weighted between particles, through tt__correct
 *                          (contact_response.c);
 *   end    (per substep)   restitution and Coulomb friction on velocities
 *                          (Verlet: by moving x_old; others: v)
 *                          (contact_response.c);
 *   after_step             contact events, gathered as arrays
 *                          (contact_events.c).
 * Registered the first time a world gets a shape or collision settings, so
 * a world without collisions pays nothing. This file holds the group's
 * registration and bookkeeping; the public settings are in collide.c. */
#include "collide_internal.h"

#include <stdlib.h>
#include <string.h>

/* --- bookkeeping ----------------------------------------------------------- */

static void particle_removed(tt_world *w, void *self, uint32_t i)
{
    (void)w;
    tt__collide *c = self;
    if (c->mat && i < c->matcap) c->mat[3 * (size_t)i] = c->mat[3 * (size_t)i + 1] = c->mat[3 * (size_t)i + 2] = -1.0f;
    if (c->bullet && i < c->bulletcap && c->bullet[i]) {
        c->bullet[i] = 0;
        c->nbullets--;
    }
    if (c->ccd_prim && i < c->bulletcap) c->ccd_prim[i] = -1;
    uint32_t k = 0;
    for (uint32_t j = 0; j < c->nexcl; j++)
        if ((uint32_t)(c->excl[j] >> 32) != i && (uint32_t)c->excl[j] != i) c->excl[k++] = c->excl[j];
    c->nexcl = k;
    k = 0;
    for (uint32_t j = 0; j < c->nprev; j++) {
        uint64_t key = c->prev[j].key;
        bool hit = (uint32_t)key == i || (!(key >> 63) && (uint32_t)(key >> 32) == i);
        if (!hit) c->prev[k++] = c->prev[j];
    }
    c->nprev = k;
}

/* A query of a world that never used collisions makes the collision state
 * for its grid; left as made, that state is the world without collisions
 * and hashes as nothing, so reading a world never changes its hash. */
static bool pristine(const tt__collide *c)
{
    const tt_collision_settings *s = &c->set, d = tt_collision_settings_default();
    return !s->particles && s->broadphase == d.broadphase && s->cell_size == d.cell_size &&
           s->restitution == d.restitution && s->friction_static == d.friction_static &&
           s->friction_kinetic == d.friction_kinetic && s->restitution_threshold == d.restitution_threshold &&
           s->events == d.events && c->shapes_alive == 0 && c->nexcl == 0 && !c->mat && !c->bullet;
}

static uint64_t hash(const tt_world *w, const void *self, uint64_t h)
{
    const tt__collide *c = self;
    if (pristine(c)) return h;
    const tt_collision_settings *s = &c->set;
    uint32_t flags = (uint32_t)s->particles | ((uint32_t)s->broadphase << 1) | (s->events << 8);
    h = tt__fnv(h, &flags, sizeof flags);
    h = tt__fnv(h, &s->cell_size, sizeof s->cell_size);
    h = tt__fnv(h, &s->restitution, sizeof s->restitution);
    h = tt__fnv(h, &s->friction_static, sizeof s->friction_static);
    h = tt__fnv(h, &s->friction_kinetic, sizeof s->friction_kinetic);
    h = tt__fnv(h, &s->restitution_threshold, sizeof s->restitution_threshold);
    for (uint32_t i = 0; i < c->spool.count; i++) {
        const tt__shape *sh = &c->shapes[i];
        if (!sh->alive) continue;
        const tt_shape_def *d = &sh->def;
        uint32_t f = (uint32_t)d->type | ((uint32_t)d->sensor << 8) | ((uint32_t)d->category << 16);
        h = tt__fnv(h, &i, sizeof i);
        h = tt__fnv(h, &f, sizeof f);
        h = tt__fnv(h, &d->mask, sizeof d->mask);
        h = tt__fnv(h, &d->position, sizeof d->position);
        h = tt__fnv(h, &d->angle, sizeof d->angle);
        h = tt__fnv(h, &d->restitution, sizeof d->restitution);
        h = tt__fnv(h, &d->friction_static, sizeof d->friction_static);
        h = tt__fnv(h, &d->friction_kinetic, sizeof d->friction_kinetic);
    }
    if (c->nexcl) h = tt__fnv(h, c->excl, (size_t)c->nexcl * sizeof *c->excl);
    uint32_t n = w->ppool.count;
    if (c->mat) h = tt__fnv(h, c->mat, (size_t)(n < c->matcap ? n : c->matcap) * 3 * sizeof *c->mat);
    if (c->bullet) h = tt__fnv(h, c->bullet, (size_t)(n < c->bulletcap ? n : c->bulletcap));
    return h;
}

size_t tt__contacts_memory(const tt_world *w, const void *self)
{
    (void)w;
    const tt__collide *c = self;
    size_t b = sizeof *c + tt__shapes_bytes(c) + tt__grid_bytes(&c->grid);
    b += ((size_t)c->vcap + c->scap + c->gcap) * 2 * sizeof(double);
    b += (size_t)c->matcap * 3 * sizeof(float) + (size_t)c->bulletcap * (1 + sizeof(int32_t));
    b += (size_t)c->exclcap * sizeof(uint64_t);
    b += (size_t)c->paircap * sizeof(tt__pair) + (size_t)c->sccap * sizeof(tt__scontact) + tt__batches_bytes(&c->bat);
    b += (size_t)c->runs_cap * sizeof *c->runs + c->near_cap;
    b += ((size_t)c->reccap + c->prevcap) * sizeof(tt__record) + (size_t)c->evcap * sizeof(tt_contact_event);
    return b;
}

static void destroy(tt_world *w, void *self)
{
    (void)w;
    tt__collide *c = self;
    tt__shapes_free(c);
    tt__grid_free(&c->grid);
    free(c->vx0); free(c->vy0); free(c->sx0); free(c->sy0); free(c->gx0); free(c->gy0);
    free(c->mat); free(c->bullet); free(c->ccd_prim);
    free(c->excl);
    free(c->pairs); free(c->sc); free(c->runs); free(c->near);
    tt__batches_free(&c->bat);
    free(c->rec); free(c->prev); free(c->events);
    free(c);
}

const tt__group_ops tt__contacts_ops = {
    .name = "contacts", .rank = TT__RANK_CONTACTS,
    .begin_stage = TT_STAGE_COLLIDE,
    .begin = tt__contacts_begin,
    .relax = tt__contacts_relax,
    .sweeps_done = tt__contacts_sweeps_done,
    .end = tt__contacts_end,
    .after_step = tt__contacts_after_step,
    .particle_removed = particle_removed,
    .hash = hash,
    .memory = tt__contacts_memory,
    .destroy = destroy,
};

tt__collide *tt__collide_get(tt_world *w, bool create, const char *fn)
{
    tt__collide *c = tt__collide_peek(w);
    if (c || !create) return c;
    c = calloc(1, sizeof *c);
    if (!c) {
        tt__fail(w, TT_ENOMEM, "%s: out of memory for collisions", fn);
        return NULL;
    }
    c->set = tt_collision_settings_default();
    c->set.particles = false; /* until tt_world_set_collision says otherwise */
    c->grid.epoch = UINT64_MAX;
    c->spool.tag = w->tag; /* shape handles carry the world's tag, like particles */
    if (tt__group_add(w, &tt__contacts_ops, c) < 0) {
        free(c);
        tt__fail(w, TT_ENOMEM, "%s: no room for another relaxation group (%d)", fn, TT_MAX_GROUPS);
        return NULL;
    }
    return c;
}
