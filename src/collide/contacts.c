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
#include "core/stream.h"
#include "terrain_internal.h"

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
    tt__pair_set_drop(&c->excl, i);
    tt__anchors_drop(&c->anc, i);
    uint32_t k = 0;
    for (uint32_t j = 0; j < c->nprev; j++) {
        uint64_t key = c->prev[j].key;
        bool hit = (uint32_t)key == i || (!(key >> 63) && (uint32_t)(key >> 32) == i);
        if (!hit) c->prev[k++] = c->prev[j];
    }
    c->nprev = k;
}

/* The collision state as tt__collide_get makes it, nothing set since: what
 * a query of a world that never used collisions leaves behind. */
static bool idle(const tt_world *w, const void *self)
{
    (void)w;
    const tt__collide *c = self;
    const tt_collision_settings *s = &c->set, d = tt_collision_settings_default();
    return !s->particles && s->broadphase == d.broadphase && s->cell_size == d.cell_size &&
           s->restitution == d.restitution && s->friction_static == d.friction_static &&
           s->friction_kinetic == d.friction_kinetic && s->restitution_threshold == d.restitution_threshold &&
           s->events == d.events && s->stacking == d.stacking && s->anchored_friction == d.anchored_friction && s->warm_start == d.warm_start && c->spool.count == 0 && c->excl.used == 0 && !c->mat && !c->bullet && c->nprev == 0 &&
           c->nevents == 0 && !c->terr;
}

/* This substep's detection found no contact: relax, sweeps_done and end
 * have nothing to act on (events of sensors were recorded in begin). */
static bool quiet(const tt_world *w, const void *self)
{
    (void)w;
    const tt__collide *c = self;
    return c->scr.npairs == 0 && c->scr.nsc == 0;
}

size_t tt__contacts_memory(const tt_world *w, const void *self)
{
    (void)w;
    const tt__collide *c = self;
    size_t b = sizeof *c + tt__shapes_bytes(c) + tt__grid_bytes(&c->scr.grid);
    b += ((size_t)c->scr.vcap + c->scap + c->scr.gcap + c->scr.pcap) * 2 * sizeof(double);
    b += (size_t)c->scr.lift_cap * (sizeof(tt__lift) + 2 * sizeof(uint32_t)) + (size_t)c->scr.roll_cap * sizeof *c->scr.roll;
    b += (size_t)c->scr.touch_cap * sizeof *c->scr.touch;
    b += (size_t)c->matcap * 3 * sizeof(float) + (size_t)c->bulletcap * (1 + sizeof(int32_t));
    b += tt__pair_set_bytes(&c->excl);
    b += (size_t)c->scr.paircap * sizeof(tt__pair) + (size_t)c->scr.sccap * sizeof(tt__scontact) + tt__batches_bytes(&c->scr.bat);
    b += (size_t)c->scr.runs_cap * sizeof *c->scr.runs + c->scr.near_cap;
    b += ((size_t)c->scr.reccap + c->prevcap) * sizeof(tt__record) + (size_t)c->evcap * sizeof(tt_contact_event);
    b += (size_t)c->scr.undo.cap * 2 * sizeof(double);
    b += tt__anchors_bytes(&c->anc) + tt__anchors_bytes(&c->scr.undo.anc) + (size_t)c->scr.anc.cap * (9 * sizeof(double) + 1 + sizeof(uint32_t)) +
         (size_t)c->scr.anc.bcap * sizeof(uint32_t);
    return b + tt__terrains_bytes(c->terr);
}

void tt__contacts_scratch_free(tt_world *w, void *self)
{
    (void)w;
    tt__collide *c = self;
    tt__collide_scratch *s = &c->scr;
    const uint8_t simd = s->bat.simd; /* the pair sweep's mode is a setting (tests force it), not scratch */
    tt__grid_free(&s->grid);
    free(s->vx0); free(s->vy0); free(s->gx0); free(s->gy0); free(s->px0); free(s->py0);
    free(s->lift); free(s->lift_start); free(s->lift_order); free(s->touch); free(s->roll);
    free(s->pairs); free(s->sc); free(s->runs); free(s->near);
    tt__batches_free(&s->bat);
    free(s->rec);
    free(s->undo.sx0); free(s->undo.sy0);
    tt__anchors_free(&s->undo.anc);
    free(s->anc.rxy); free(s->anc.lt); free(s->anc.mu); free(s->anc.kept); free(s->anc.wl); free(s->anc.resting); free(s->anc.slow); free(s->anc.bucket);
    *s = (tt__collide_scratch){0};
    s->bat.simd = simd;
    s->grid.epoch = UINT64_MAX; /* no grid: a query builds its own */
    if (c->terr) { /* the distance update's buffer; the next carving reserves it again */
        free(c->terr->scr.buf);
        c->terr->scr.buf = NULL;
        c->terr->scr.cap = 0;
    }
}

void tt__contacts_destroy(tt_world *w, void *self)
{
    tt__collide *c = self;
    tt__contacts_scratch_free(w, c);
    tt__shapes_free(c);
    free(c->sx0); free(c->sy0);
    free(c->mat); free(c->bullet); free(c->ccd_prim);
    tt__pair_set_free(&c->excl);
    free(c->prev); free(c->events);
    tt__terrains_free(c->terr);
    tt__anchors_free(&c->anc);
    free(c);
}

const tt__group_ops tt__contacts_ops = {
    .name = "contacts", .rank = TT__RANK_CONTACTS,
    .begin_stage = TT_STAGE_COLLIDE,
    .reserve = tt__contacts_reserve,
    .begin = tt__contacts_begin,
    .relax = tt__contacts_relax,
    .units = tt__contacts_units,
    .rows = tt__contacts_rows,
    .sweeps_done = tt__contacts_sweeps_done,
    .end = tt__contacts_end,
    .stopped = tt__contacts_stopped,
    .after_step = tt__contacts_after_step,
    .fallible = tt__contacts_fallible,
    .undo_reserve = tt__contacts_undo_reserve,
    .undo_mark = tt__contacts_undo_mark,
    .undo = tt__contacts_undo,
    .after_reserve = tt__contacts_after_reserve,
    .particle_removed = particle_removed,
    .memory = tt__contacts_memory,
    .scratch_free = tt__contacts_scratch_free,
    .destroy = tt__contacts_destroy,
    .id = TT__COLL_ID,
    .save = tt__contacts_save,
    .idle = idle,
    .quiet = quiet,
    .load = tt__contacts_load,
};

/* Known to the snapshot reader before any world collides (a saved game
 * with shapes loads in a program that has made none yet). */
__attribute__((constructor)) static void register_feature(void) { tt__feature_register(&tt__contacts_ops); }

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
    c->scr.grid.epoch = UINT64_MAX;
    c->spool.tag = w->tag; /* shape handles carry the world's tag, like particles */
    tt__pair_set_init(&c->excl, true);
    if (tt__group_add(w, &tt__contacts_ops, c) < 0) {
        free(c);
        tt__fail(w, TT_ENOMEM, "%s: no room for another relaxation group (%d)", fn, TT_MAX_GROUPS);
        return NULL;
    }
    return c;
}

/* --- the snapshot section ("COLL") ------------------------------------------
 * Settings, shapes with their points (a shape the script moved since the
 * last step with where that step left it), per-particle materials and bullets,
 * switched-off pairs, the contact records of the last step (what the next
 * step's begin/persist/end events compare with), the events published, and
 * for integrators that keep velocities, the last substep's end positions
 * while they are still valid (the next substep starts from them). The
 * static index, the grid, pairs, batches and every per-substep array are
 * rebuilt. */

static void put_event(tt__sink *s, const tt_contact_event *e)
{
    tt__put_u32(s, e->kind);
    tt__put_u8(s, e->sensor);
    tt__put_u32(s, e->a.index);
    tt__put_gen(s, e->a.gen);
    tt__put_u32(s, e->b.index);
    tt__put_gen(s, e->b.gen);
    tt__put_u32(s, e->shape.index);
    tt__put_gen(s, e->shape.gen);
    tt__put(s, &e->point, sizeof e->point);
    tt__put(s, &e->normal, sizeof e->normal);
    tt__put_f64(s, e->impulse);
}

static void save_shape(tt__sink *s, const tt__shape *sh)
{
    const tt_shape_def *d = &sh->def;
    tt__put_u8(s, sh->alive);
    if (!sh->alive) return;
    tt__put_u8(s, sh->moved);
    if (sh->moved) { /* the next step carries it from where the last one left it */
        tt__put(s, &sh->from, sizeof sh->from);
        tt__put_f64(s, sh->from_angle);
    }
    tt__put_u32(s, (uint32_t)d->type);
    tt__put(s, &d->position, sizeof d->position);
    tt__put_f64(s, d->angle);
    tt__put(s, &d->a, sizeof d->a);
    tt__put(s, &d->b, sizeof d->b);
    tt__put(s, &d->half_extents, sizeof d->half_extents);
    tt__put_f64(s, d->radius);
    tt__put_u32(s, d->count);
    tt__put(s, sh->pts, (size_t)d->count * sizeof *sh->pts);
    tt__put_u8(s, d->loop);
    tt__put_f64(s, d->restitution);
    tt__put_f64(s, d->friction_static);
    tt__put_f64(s, d->friction_kinetic);
    tt__put_u16(s, d->category);
    tt__put_u16(s, d->mask);
    tt__put_u8(s, d->sensor);
    tt__put_u64(s, d->user);
}

static void save_particle_data(const tt_world *w, const tt__collide *c, tt__sink *s)
{
    const uint32_t n = w->ppool.count;
    static const float none[3] = {-1.0f, -1.0f, -1.0f};
    tt__put_u8(s, c->mat != NULL);
    if (c->mat) {
        uint32_t have = n < c->matcap ? n : c->matcap;
        tt__put(s, c->mat, (size_t)have * 3 * sizeof *c->mat);
        for (uint32_t i = have; i < n; i++) tt__put(s, none, sizeof none);
    }
    tt__put_u8(s, c->bullet != NULL);
    if (c->bullet) {
        uint32_t have = n < c->bulletcap ? n : c->bulletcap;
        tt__put(s, c->bullet, have);
        for (uint32_t i = have; i < n; i++) tt__put_u8(s, 0);
    }
    uint32_t nexcl;
    const uint64_t *excl = tt__pair_set_sorted(&c->excl, &nexcl);
    tt__put_u32(s, nexcl);
    tt__put(s, excl, (size_t)nexcl * sizeof *excl);
    /* valid as contact_detect.c's substep_start reads them: the next substep starts from them */
    bool ends = w->integrator != TT_VERLET && c->sx0 && c->s_epoch == w->epoch && c->s_count == n;
    tt__put_u8(s, ends);
    if (ends) {
        tt__put(s, c->sx0, (size_t)n * sizeof *c->sx0);
        tt__put(s, c->sy0, (size_t)n * sizeof *c->sy0);
    }
}

void tt__contacts_save(const tt_world *w, const void *self, tt__sink *s)
{
    const tt__collide *c = self;
    const tt_collision_settings *set = &c->set;
    tt__put_u8(s, set->particles);
    tt__put_u32(s, (uint32_t)set->broadphase);
    tt__put_f64(s, set->cell_size);
    tt__put_f64(s, set->restitution);
    tt__put_f64(s, set->friction_static);
    tt__put_f64(s, set->friction_kinetic);
    tt__put_f64(s, set->restitution_threshold);
    tt__put_u32(s, set->events);
    tt__put_pool(s, &c->spool);
    for (uint32_t i = 0; i < c->spool.count; i++) save_shape(s, &c->shapes[i]);
    save_particle_data(w, c, s);
    tt__put_u32(s, c->nprev);
    for (uint32_t k = 0; k < c->nprev; k++) {
        tt__put_u64(s, c->prev[k].key);
        put_event(s, &c->prev[k].ev);
    }
    tt__put_u32(s, c->nevents);
    for (uint32_t k = 0; k < c->nevents; k++) put_event(s, &c->events[k]);
    if (c->terr) tt__terrains_save(c, s); /* last, only when there are terrains: other worlds' streams are unchanged */
    if (set->stacking != 0.0) { /* after them, only when on: likewise */
        tt__put_u32(s, TT__ID('S', 'T', 'A', 'K'));
        tt__put_f64(s, set->stacking);
    }
    if (set->anchored_friction) tt__anchors_save(&c->anc, s); /* only when on: likewise */
    if (set->warm_start != 0.0) tt__anchors_save_warm(&c->anc, set->warm_start, s); /* last, only when on: likewise */
}

/* A record (record: its kind is not set yet, 0) or a published event. */
static bool get_event(tt__source *s, tt_contact_event *e, bool record)
{
    e->kind = tt__get_u32(s);
    e->sensor = tt__get_bool(s, "event sensor");
    e->a.index = tt__get_u32(s);
    e->a.gen = tt__get_u32(s);
    e->b.index = tt__get_u32(s);
    e->b.gen = tt__get_u32(s);
    e->shape.index = tt__get_u32(s);
    e->shape.gen = tt__get_u32(s);
    e->point.x = tt__get_num(s, -1e300, 1e300, "event point");
    e->point.y = tt__get_num(s, -1e300, 1e300, "event point");
    e->normal.x = tt__get_num(s, -2, 2, "event normal");
    e->normal.y = tt__get_num(s, -2, 2, "event normal");
    e->impulse = tt__get_num(s, -1e300, 1e300, "event impulse");
    if (!s->failed && !(record && e->kind == 0) && e->kind != TT_EVENT_BEGIN && e->kind != TT_EVENT_PERSIST && e->kind != TT_EVENT_END)
        tt__src_fail(s, "contact event kind %u", e->kind);
    return !s->failed;
}

static bool load_shape(tt_world *w, tt__shape *sh, tt__source *s)
{
    tt_shape_def *d = &sh->def;
    *d = tt_shape_def_default();
    sh->alive = tt__get_bool(s, "shape alive");
    if (!sh->alive) return !s->failed;
    sh->moved = tt__get_bool(s, "shape moved");
    if (sh->moved) {
        sh->from.x = tt__get_num(s, -TT_MAX_VALUE, TT_MAX_VALUE, "shape start");
        sh->from.y = tt__get_num(s, -TT_MAX_VALUE, TT_MAX_VALUE, "shape start");
        sh->from_angle = tt__get_num(s, -TT_MAX_VALUE, TT_MAX_VALUE, "shape start angle");
    }
    d->type = (tt_shape_type)tt__get_u32(s);
    tt__get(s, &d->position, sizeof d->position);
    d->angle = tt__get_num(s, -1e300, 1e300, "shape angle");
    tt__get(s, &d->a, sizeof d->a);
    tt__get(s, &d->b, sizeof d->b);
    d->half_extents.x = tt__get_num(s, -1e300, 1e300, "box half extent");
    d->half_extents.y = tt__get_num(s, -1e300, 1e300, "box half extent");
    d->radius = tt__get_num(s, -1e300, 1e300, "shape radius");
    d->count = tt__get_count(s, sizeof(tt_vec2), "shape points");
    if (s->failed) return false;
    if (d->count && !(sh->pts = malloc((size_t)d->count * sizeof *sh->pts))) return tt__src_fail(s, "out of memory");
    tt__get(s, sh->pts, (size_t)d->count * sizeof *sh->pts);
    d->loop = tt__get_bool(s, "chain loop");
    d->restitution = tt__get_num(s, -1e300, 1e300, "shape restitution");
    d->friction_static = tt__get_num(s, -1e300, 1e300, "shape friction");
    d->friction_kinetic = tt__get_num(s, -1e300, 1e300, "shape friction");
    d->category = tt__get_u16(s);
    d->mask = tt__get_u16(s);
    d->sensor = tt__get_bool(s, "shape sensor");
    d->user = tt__get_u64(s);
    if (s->failed) return false;
    if (!sh->moved) {
        sh->from = d->position;
        sh->from_angle = d->angle;
    }
    d->points = sh->pts;
    bool ok = tt__shape_check_def(w, d, "snapshot") == TT_OK;
    bool with_points = d->type == TT_SHAPE_CHAIN || d->type == TT_SHAPE_POLYGON;
    d->points = NULL;
    if (!ok || (!with_points && d->count)) return tt__src_fail(s, "shape: %s", tt_last_error(w));
    return true;
}

static bool load_shapes(tt_world *w, tt__collide *c, tt__source *s)
{
    if (!tt__get_pool(s, &c->spool, TT_MAX_SHAPES, w->tag, "shapes")) return false;
    const uint32_t n = c->spool.count;
    if (n > s->len - s->at) return tt__src_fail(s, "shapes: %u slots are more than the stream holds", n);
    if (!(c->shapes = calloc(n ? n : 1, sizeof *c->shapes))) return tt__src_fail(s, "out of memory");
    c->shcap = n;
    for (uint32_t i = 0; i < n; i++) {
        if (!load_shape(w, &c->shapes[i], s)) return false;
        c->shapes_alive += c->shapes[i].alive;
        c->any_moved |= c->shapes[i].moved;
    }
    for (uint32_t k = 0; k < c->spool.free_count; k++)
        if (c->shapes[c->spool.free_list[k]].alive) return tt__src_fail(s, "shape %u is alive and free", c->spool.free_list[k]);
    c->dirty = true;
    return true;
}

static bool load_particle_data(tt_world *w, tt__collide *c, tt__source *s)
{
    const uint32_t n = w->ppool.count, cap = w->pcap;
    if (tt__get_bool(s, "materials")) {
        if (!(c->mat = malloc((size_t)cap * 3 * sizeof *c->mat))) return tt__src_fail(s, "out of memory");
        c->matcap = cap;
        for (uint32_t i = 0; i < 3 * cap; i++) c->mat[i] = -1.0f;
        tt__get(s, c->mat, (size_t)n * 3 * sizeof *c->mat);
        for (uint32_t i = 0; i < 3 * n && !s->failed; i++)
            if (!(c->mat[i] == -1.0f || (c->mat[i] >= 0.0f && c->mat[i] <= (float)TT__PARTICLE_MAX_FRICTION)) ||
                (c->mat[i] != -1.0f && i % 3 == 0 && c->mat[i] > 1.0f))
                tt__src_fail(s, "particle %u: material %g", i / 3, c->mat[i]);
    }
    if (tt__get_bool(s, "bullets")) {
        c->bullet = calloc(cap, 1);
        c->ccd_prim = malloc((size_t)cap * sizeof *c->ccd_prim);
        if (!c->bullet || !c->ccd_prim) return tt__src_fail(s, "out of memory");
        c->bulletcap = cap;
        tt__get(s, c->bullet, n);
        for (uint32_t i = 0; i < cap; i++) {
            c->ccd_prim[i] = -1;
            if (c->bullet[i] > 1 || (c->bullet[i] && !(w->flags[i] & TT__PF_ALIVE))) return tt__src_fail(s, "bullet %u", i);
            c->nbullets += c->bullet[i];
        }
    }
    const uint32_t nexcl = tt__get_count(s, 8, "switched-off pairs");
    if (s->failed || !tt__pair_set_reserve(&c->excl, nexcl)) return tt__src_fail(s, "out of memory");
    for (uint64_t k = 0, key, last = 0; k < nexcl && !s->failed; k++, last = key) {
        key = tt__get_u64(s);
        uint32_t a = (uint32_t)(key >> 32), b = (uint32_t)key;
        if (s->failed) break;
        if (a >= b || b >= n || (k && last >= key)) tt__src_fail(s, "switched-off pair %u", (uint32_t)k);
        else tt__pair_set_add(&c->excl, a, b); /* room reserved: cannot fail */
    }
    if (tt__get_bool(s, "end positions")) {
        if (w->integrator == TT_VERLET) return tt__src_fail(s, "end positions in a Verlet world");
        if (!(c->sx0 = malloc((size_t)cap * sizeof *c->sx0)) || !(c->sy0 = malloc((size_t)cap * sizeof *c->sy0)))
            return tt__src_fail(s, "out of memory");
        c->scap = cap;
        tt__get(s, c->sx0, (size_t)n * sizeof *c->sx0);
        tt__get(s, c->sy0, (size_t)n * sizeof *c->sy0);
        for (uint32_t i = 0; i < n && !s->failed; i++)
            if (!(fabs(c->sx0[i]) <= 1e3 * TT_DIVERGED && fabs(c->sy0[i]) <= 1e3 * TT_DIVERGED)) tt__src_fail(s, "end position %u: (%g, %g)", i, c->sx0[i], c->sy0[i]);
        c->s_count = n;
        c->s_epoch = w->epoch;
    } else {
        c->s_epoch = w->epoch - 1;
    }
    return !s->failed;
}

/* The last step's contact records, sorted by key as the events' merge needs. */
static bool load_records(tt_world *w, tt__collide *c, tt__source *s)
{
    c->nprev = c->prevcap = tt__get_count(s, 77, "contact records");
    if (s->failed || !(c->prev = malloc((size_t)(c->nprev ? c->nprev : 1) * sizeof *c->prev))) return tt__src_fail(s, "out of memory");
    for (uint32_t k = 0; k < c->nprev; k++) {
        uint64_t key = c->prev[k].key = tt__get_u64(s);
        if (!get_event(s, &c->prev[k].ev, true)) return false;
        uint32_t hi = (uint32_t)(key >> 32) & 0x7FFFFFFFu, lo = (uint32_t)key;
        /* a terrain's key (bits 63 and 62): its slot is checked with the terrains, loaded after */
        bool ok = (key >> 62) == 3 ? lo < w->ppool.count
                  : (key >> 63)    ? hi < c->spool.count && lo < w->ppool.count
                                   : hi < lo && lo < w->ppool.count;
        if (!ok || (k && c->prev[k - 1].key >= key)) return tt__src_fail(s, "contact record %u", k);
    }
    c->nevents = c->evcap = tt__get_count(s, 69, "contact events");
    if (s->failed || !(c->events = malloc((size_t)(c->nevents ? c->nevents : 1) * sizeof *c->events))) return tt__src_fail(s, "out of memory");
    for (uint32_t k = 0; k < c->nevents; k++)
        if (!get_event(s, &c->events[k], false)) return false;
    return true;
}

/* A stream without terrains has no record of a terrain contact. */
static bool no_terrain_records(const tt__collide *c, tt__source *s)
{
    for (uint32_t k = 0; k < c->nprev; k++)
        if ((c->prev[k].key >> 62) == 3) return tt__src_fail(s, "contact record %u: no terrains", k);
    return true;
}

/* What may follow the records, each only when there is one: the terrains,
 * then the stacking setting, then anchored friction's anchors, then the
 * warm start (a stream of a world without any is the same as before they
 * existed). */
static bool load_tail(tt_world *w, tt__collide *c, tt__source *s)
{
    bool terrains = false;
    if (s->at < s->len && s->len - s->at >= 4) {
        const size_t at = s->at;
        const bool terr = tt__get_u32(s) == TT__ID('T', 'E', 'R', 'R');
        s->at = at;
        if (terr && !(terrains = tt__terrains_load(w, c, s))) return false;
    }
    if (!terrains && !no_terrain_records(c, s)) return false;
    uint32_t id = s->at < s->len ? tt__get_u32(s) : 0;
    if (id == TT__ID('S', 'T', 'A', 'K')) {
        c->set.stacking = tt__get_num(s, 0.0, TT_MAX_VALUE, "stacking");
        if (!s->failed && c->set.stacking == 0.0) return tt__src_fail(s, "stacking 0 written out");
        id = !s->failed && s->at < s->len ? tt__get_u32(s) : 0;
    }
    if (id == TT__ID('A', 'N', 'C', 'H')) {
        c->set.anchored_friction = true;
        if (!tt__anchors_load(&c->anc, s, w->ppool.count)) return false;
        id = s->at < s->len ? tt__get_u32(s) : 0;
    }
    if (id == TT__ID('W', 'A', 'R', 'M')) {
        if (!tt__anchors_load_warm(&c->anc, s, &c->set.warm_start)) return false;
        id = 0;
    }
    if (id) return tt__src_fail(s, "collisions: unknown section");
    return !s->failed && s->at == s->len;
}

void *tt__contacts_load(tt_world *w, tt__source *s)
{
    tt__collide *c = calloc(1, sizeof *c);
    if (!c) { tt__src_fail(s, "out of memory"); return NULL; }
    c->scr.grid.epoch = UINT64_MAX;
    c->spool.tag = w->tag;
    tt__pair_set_init(&c->excl, true);
    tt_collision_settings *set = &c->set;
    set->particles = tt__get_bool(s, "particle collisions");
    set->broadphase = (tt_broadphase)tt__get_u32(s);
    set->cell_size = tt__get_num(s, 0.0, TT_MAX_VALUE, "cell size");
    set->restitution = tt__get_num(s, 0.0, 1.0, "restitution");
    set->friction_static = tt__get_num(s, 0.0, TT_MAX_VALUE, "static friction");
    set->friction_kinetic = tt__get_num(s, 0.0, TT_MAX_VALUE, "kinetic friction");
    set->restitution_threshold = tt__get_num(s, -1.0, TT_MAX_VALUE, "restitution threshold");
    set->events = tt__get_u32(s);
    if (!s->failed && ((unsigned)set->broadphase > TT_BROADPHASE_BRUTE || set->events > 7 ||
                       (set->restitution_threshold < 0 && set->restitution_threshold != -1.0)))
        tt__src_fail(s, "collision settings");
    if (!s->failed && load_shapes(w, c, s) && load_particle_data(w, c, s) && load_records(w, c, s) && load_tail(w, c, s))
        return c;
    tt__src_fail(s, "collisions");
    tt__contacts_destroy(w, c);
    return NULL;
}
