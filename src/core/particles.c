/* tether — particles: storage (struct of arrays), handles, reads and writes. */
#include "internal.h"
#include "spin.h"

#include <stdlib.h>
#include <string.h>

static bool grow(void **arr, size_t elem, uint32_t cap)
{
    void *p = realloc(*arr, elem * cap);
    if (!p) return false;
    *arr = p;
    return true;
}

/* Grows every core array to cap slots. On failure nothing is lost: arrays
 * already grown are merely larger, and pcap keeps the old value. */
tt_result tt__particles_reserve(tt_world *w, uint32_t cap)
{
    if (cap <= w->pcap) return TT_OK;
    if (cap > w->max_particles)
        return tt__fail(w, TT_ENOMEM, "tt_particle_create: the world is full (max_particles %u)", w->max_particles);
    uint32_t n = w->pcap ? w->pcap : 256;
    while (n < cap) n = n > UINT32_MAX / 2 ? cap : n * 2;
    if (n > w->max_particles) n = w->max_particles > cap ? w->max_particles : cap;
    bool ok = grow((void **)&w->px, sizeof(double), n) && grow((void **)&w->py, sizeof(double), n) &&
              grow((void **)&w->qx, sizeof(double), n) && grow((void **)&w->qy, sizeof(double), n) &&
              grow((void **)&w->inv_mass, sizeof(double), n) && grow((void **)&w->mass, sizeof(double), n) &&
              grow((void **)&w->radius, sizeof(float), n) && grow((void **)&w->flags, sizeof(uint16_t), n) &&
              grow((void **)&w->category, sizeof(uint16_t), n) && grow((void **)&w->mask, sizeof(uint16_t), n);
    if (ok && w->fx) ok = grow((void **)&w->fx, sizeof(double), n) && grow((void **)&w->fy, sizeof(double), n);
    if (ok && w->user) ok = grow((void **)&w->user, sizeof(uint64_t), n);
    if (ok && w->ox) ok = grow((void **)&w->ox, sizeof(double), n) && grow((void **)&w->oy, sizeof(double), n);
    if (!ok) return tt__fail(w, TT_ENOMEM, "out of memory growing to %u particles", n);
    if (w->fx) {
        memset(w->fx + w->pcap, 0, (size_t)(n - w->pcap) * sizeof(double));
        memset(w->fy + w->pcap, 0, (size_t)(n - w->pcap) * sizeof(double));
    }
    if (w->user) memset(w->user + w->pcap, 0, (size_t)(n - w->pcap) * sizeof(uint64_t));
    w->pcap = n;
    return TT_OK;
}

void tt__particles_free(tt_world *w)
{
    free(w->px); free(w->py); free(w->qx); free(w->qy);
    free(w->inv_mass); free(w->mass); free(w->radius);
    free(w->flags); free(w->category); free(w->mask);
    free(w->fx); free(w->fy); free(w->user); free(w->fresh);
    free(w->ox); free(w->oy);
    tt__pool_destroy(&w->ppool);
}

/* Optional arrays appear on first use, so worlds that never need them never pay. */
static tt_result need_forces(tt_world *w)
{
    if (w->fx) return TT_OK;
    w->fx = calloc(w->pcap ? w->pcap : 1, sizeof(double));
    w->fy = calloc(w->pcap ? w->pcap : 1, sizeof(double));
    if (!w->fx || !w->fy) {
        free(w->fx); free(w->fy);
        w->fx = w->fy = NULL;
        return tt__fail(w, TT_ENOMEM, "out of memory for the force accumulator");
    }
    return TT_OK;
}

static tt_result need_user(tt_world *w)
{
    if (w->user) return TT_OK;
    w->user = calloc(w->pcap ? w->pcap : 1, sizeof(uint64_t));
    return w->user ? TT_OK : tt__fail(w, TT_ENOMEM, "out of memory for user data");
}

double *tt__scratch(tt_world *w, int which)
{
    uint32_t n = w->ppool.count;
    if (w->scr.buf_cap[which] < n) {
        double *p = realloc(w->scr.buf[which], (size_t)w->pcap * sizeof(double));
        if (!p) return NULL;
        w->scr.buf[which] = p;
        w->scr.buf_cap[which] = w->pcap;
    }
    return w->scr.buf[which];
}

uint32_t tt__particle_room(const tt_world *w)
{
    /* a free slot is reused before the pool grows; the pool grows to max_particles */
    return w->ppool.free_count + (w->max_particles - w->ppool.count);
}

bool tt__particle_ok(const tt_world *w, tt_particle p)
{
    return w && p.index < w->ppool.count && p.gen != 0 && w->ppool.gen[p.index] == p.gen &&
           (w->flags[p.index] & TT__PF_ALIVE);
}

tt_result tt__particle_check(const tt_world *w, tt_particle p, const char *fn)
{
    if (!w) return tt__fail(NULL, TT_EINVAL, "%s: world is NULL", fn);
    if (!tt__particle_ok(w, p))
        return tt__fail(w, TT_ESTALE, "%s: stale particle handle (index %u, generation %u)", fn, p.index, p.gen);
    return TT_OK;
}

void tt__mark_fresh(tt_world *w, uint32_t i)
{
    if (w->integrator != TT_VERLET || (w->flags[i] & TT__PF_FRESH)) return;
    if (w->fresh_count == w->fresh_cap) {
        uint32_t cap = w->fresh_cap ? w->fresh_cap * 2 : 64;
        uint32_t *f = realloc(w->fresh, (size_t)cap * sizeof *f);
        if (!f) return; /* the particle starts with a·dt² instead of a·dt²/2: less exact, still valid */
        w->fresh = f;
        w->fresh_cap = cap;
    }
    w->fresh[w->fresh_count++] = i;
    w->flags[i] |= TT__PF_FRESH;
}

void tt__set_velocity(tt_world *w, uint32_t i, tt_vec2 v)
{
    if (w->integrator == TT_VERLET) {
        w->qx[i] = w->px[i] - v.x * w->dt_prev;
        w->qy[i] = w->py[i] - v.y * w->dt_prev;
        tt__mark_fresh(w, i);
    } else {
        w->qx[i] = v.x;
        w->qy[i] = v.y;
    }
}

tt_particle_def tt_particle_def_default(void)
{
    tt_particle_def d;
    memset(&d, 0, sizeof d);
    d.mass = 1.0;
    d.category = 0x0001;
    d.mask = 0xFFFF;
    return d;
}

static tt_result check_def(const tt_world *w, const tt_particle_def *d)
{
    const char *fn = "tt_particle_create";
    if (!d) return tt__fail(w, TT_EINVAL, "%s: def is NULL", fn);
    if (!tt__vec_ok(d->position)) return tt__fail(w, TT_EINVAL, "%s: position must be finite, |x| <= %g", fn, TT_MAX_VALUE);
    if (tt__fixed_check(w, d->position, fn) != TT_OK) return TT_EINVAL;
    if (!tt__vec_ok(d->velocity)) return tt__fail(w, TT_EINVAL, "%s: velocity must be finite, |v| <= %g", fn, TT_MAX_VALUE);
    if (!tt__in_range(d->mass, TT_MIN_MASS, TT_MAX_MASS))
        return tt__fail(w, TT_EINVAL, "%s: mass must be in [%g, %g], got %g", fn, TT_MIN_MASS, TT_MAX_MASS, d->mass);
    if (!tt__in_range(d->radius, 0.0, TT_MAX_VALUE))
        return tt__fail(w, TT_EINVAL, "%s: radius must be in [0, %g], got %g", fn, TT_MAX_VALUE, d->radius);
    return TT_OK;
}

tt_particle tt_particle_create(tt_world *w, const tt_particle_def *d)
{
    tt_particle none = {0, 0};
    if (!w) { tt__fail(NULL, TT_EINVAL, "tt_particle_create: world is NULL"); return none; }
    if (check_def(w, d) != TT_OK) return none;
    if (w->ppool.count == w->pcap && w->ppool.free_count == 0 &&
        tt__particles_reserve(w, w->pcap + 1) != TT_OK)
        return none; /* reserve said why */
    if (d->user && need_user(w) != TT_OK) return none;
    bool grew;
    uint32_t i = tt__pool_alloc(&w->ppool, w->pcap, &grew);
    if (i == UINT32_MAX) {
        tt__fail(w, TT_ENOMEM, "tt_particle_create: the world is full (max_particles %u)", w->max_particles);
        return none;
    }
    const tt_vec2 at = tt__fixed_snap_vec(w, d->position);
    w->px[i] = at.x;
    w->py[i] = at.y;
    tt__interp_moved(w, i);
    w->mass[i] = d->mass;
    w->inv_mass[i] = d->pinned ? 0.0 : 1.0 / d->mass;
    w->radius[i] = (float)d->radius;
    w->flags[i] = TT__PF_ALIVE | (d->pinned ? TT__PF_PINNED : 0);
    w->category[i] = d->category;
    w->mask[i] = d->mask;
    if (w->fx) w->fx[i] = w->fy[i] = 0.0;
    if (w->user) w->user[i] = d->user;
    tt__set_velocity(w, i, d->pinned ? (tt_vec2){0, 0} : d->velocity);
    w->alive++;
    w->epoch++;
    return (tt_particle){i, w->ppool.gen[i]};
}

tt_result tt_particle_destroy(tt_world *w, tt_particle p)
{
    tt_result r = tt__particle_check(w, p, "tt_particle_destroy");
    if (r != TT_OK) return r;
    uint32_t i = p.index;
    if (w->springs_alive) w->springs_detach(w, i);
    tt__solver_particle_removed(w, i);
    /* the slot as a loaded world has it (the stream holds zeros for a dead
     * slot): whatever still reads a dead slot reads the same in both */
    w->flags[i] = 0;
    w->px[i] = w->py[i] = w->qx[i] = w->qy[i] = 0.0;
    w->inv_mass[i] = w->mass[i] = 0.0;
    w->radius[i] = 0.0f;
    w->category[i] = w->mask[i] = 0;
    if (w->fx) w->fx[i] = w->fy[i] = 0.0;
    if (w->user) w->user[i] = 0;
    tt__pool_free(&w->ppool, i);
    w->alive--;
    return TT_OK;
}

bool tt_particle_is_valid(const tt_world *w, tt_particle p) { return tt__particle_ok(w, p); }

#define CHECK(fn)                                     \
    tt_result r_ = tt__particle_check(w, p, fn);      \
    if (r_ != TT_OK) return r_;                       \
    uint32_t i = p.index
#define CHECK_OUT(fn)                                                       \
    CHECK(fn);                                                              \
    if (!out) return tt__fail(w, TT_EINVAL, "%s: out is NULL", fn)

tt_result tt_particle_get_position(const tt_world *w, tt_particle p, tt_vec2 *out)
{
    CHECK_OUT("tt_particle_get_position");
    *out = (tt_vec2){w->px[i], w->py[i]};
    return TT_OK;
}

tt_result tt_particle_set_position(tt_world *w, tt_particle p, tt_vec2 pos, tt_move_mode mode)
{
    CHECK("tt_particle_set_position");
    if (!tt__vec_ok(pos)) return tt__fail(w, TT_EINVAL, "tt_particle_set_position: position must be finite, |x| <= %g", TT_MAX_VALUE);
    if (mode != TT_MOVE_KEEP_VELOCITY && mode != TT_MOVE_RESET_VELOCITY)
        return tt__fail(w, TT_EINVAL, "tt_particle_set_position: unknown move mode %d", (int)mode);
    if (tt__fixed_check(w, pos, "tt_particle_set_position") != TT_OK) return TT_EINVAL;
    pos = tt__fixed_snap_vec(w, pos);
    tt__sleep_touch(w, i);
    if (w->integrator == TT_VERLET && mode == TT_MOVE_KEEP_VELOCITY) {
        w->qx[i] += pos.x - w->px[i]; /* x_old travels with x: the implied velocity is unchanged */
        w->qy[i] += pos.y - w->py[i];
    }
    w->px[i] = pos.x;
    w->py[i] = pos.y;
    tt__interp_moved(w, i);
    w->epoch++;
    if (mode == TT_MOVE_RESET_VELOCITY) tt__set_velocity(w, i, (tt_vec2){0, 0});
    return TT_OK;
}

tt_result tt_particle_get_velocity(const tt_world *w, tt_particle p, tt_vec2 *out)
{
    CHECK_OUT("tt_particle_get_velocity");
    *out = tt__velocity(w, i);
    return TT_OK;
}

tt_result tt_particle_set_velocity(tt_world *w, tt_particle p, tt_vec2 v)
{
    CHECK("tt_particle_set_velocity");
    if (!tt__vec_ok(v)) return tt__fail(w, TT_EINVAL, "tt_particle_set_velocity: velocity must be finite, |v| <= %g", TT_MAX_VALUE);
    if (w->flags[i] & TT__PF_PINNED) return tt__fail(w, TT_ESTATE, "tt_particle_set_velocity: the particle is pinned");
    tt__sleep_touch(w, i);
    tt__set_velocity(w, i, v);
    return TT_OK;
}

tt_result tt_particle_get_mass(const tt_world *w, tt_particle p, double *out)
{
    CHECK_OUT("tt_particle_get_mass");
    *out = w->mass[i];
    return TT_OK;
}

tt_result tt_particle_set_mass(tt_world *w, tt_particle p, double mass)
{
    CHECK("tt_particle_set_mass");
    if (!tt__in_range(mass, TT_MIN_MASS, TT_MAX_MASS))
        return tt__fail(w, TT_EINVAL, "tt_particle_set_mass: mass must be in [%g, %g], got %g", TT_MIN_MASS, TT_MAX_MASS, mass);
    tt__sleep_touch(w, i);
    w->mass[i] = mass;
    if (!(w->flags[i] & TT__PF_PINNED)) w->inv_mass[i] = 1.0 / mass;
    return TT_OK;
}

tt_result tt_particle_get_pinned(const tt_world *w, tt_particle p, bool *out)
{
    CHECK_OUT("tt_particle_get_pinned");
    *out = (w->flags[i] & TT__PF_PINNED) != 0;
    return TT_OK;
}

tt_result tt_particle_set_pinned(tt_world *w, tt_particle p, bool pinned)
{
    CHECK("tt_particle_set_pinned");
    if (pinned == ((w->flags[i] & TT__PF_PINNED) != 0)) return TT_OK;
    tt__sleep_touch(w, i);
    tt__set_velocity(w, i, (tt_vec2){0, 0});
    if (pinned) {
        w->flags[i] |= TT__PF_PINNED;
        w->inv_mass[i] = 0.0;
        tt__spin_stop(w, i);
    } else {
        w->flags[i] &= (uint16_t)~TT__PF_PINNED;
        w->inv_mass[i] = 1.0 / w->mass[i];
    }
    return TT_OK;
}

tt_result tt_particle_get_asleep(const tt_world *w, tt_particle p, bool *out)
{
    CHECK_OUT("tt_particle_get_asleep");
    *out = (w->flags[i] & TT__PF_ASLEEP) != 0;
    return TT_OK;
}

tt_result tt_particle_get_radius(const tt_world *w, tt_particle p, double *out)
{
    CHECK_OUT("tt_particle_get_radius");
    *out = w->radius[i];
    return TT_OK;
}

tt_result tt_particle_set_radius(tt_world *w, tt_particle p, double radius)
{
    CHECK("tt_particle_set_radius");
    if (!tt__in_range(radius, 0.0, TT_MAX_VALUE))
        return tt__fail(w, TT_EINVAL, "tt_particle_set_radius: radius must be in [0, %g], got %g", TT_MAX_VALUE, radius);
    tt__sleep_touch(w, i);
    w->radius[i] = (float)radius;
    if (w->radius[i] == 0.0f) tt__spin_stop(w, i);
    w->epoch++;
    return TT_OK;
}

tt_result tt_particle_get_filter(const tt_world *w, tt_particle p, uint16_t *category, uint16_t *mask)
{
    CHECK("tt_particle_get_filter");
    if (!category || !mask) return tt__fail(w, TT_EINVAL, "tt_particle_get_filter: out is NULL");
    *category = w->category[i];
    *mask = w->mask[i];
    return TT_OK;
}

tt_result tt_particle_set_filter(tt_world *w, tt_particle p, uint16_t category, uint16_t mask)
{
    CHECK("tt_particle_set_filter");
    tt__sleep_touch(w, i);
    w->category[i] = category;
    w->mask[i] = mask;
    return TT_OK;
}

tt_result tt_particle_get_user(const tt_world *w, tt_particle p, uint64_t *out)
{
    CHECK_OUT("tt_particle_get_user");
    *out = w->user ? w->user[i] : 0;
    return TT_OK;
}

tt_result tt_particle_set_user(tt_world *w, tt_particle p, uint64_t user)
{
    CHECK("tt_particle_set_user");
    if (!w->user && user == 0) return TT_OK;
    tt_result r = need_user(w);
    if (r != TT_OK) return r;
    w->user[i] = user;
    return TT_OK;
}

tt_result tt_particle_apply_force(tt_world *w, tt_particle p, tt_vec2 f)
{
    CHECK("tt_particle_apply_force");
    if (!tt__vec_ok(f)) return tt__fail(w, TT_EINVAL, "tt_particle_apply_force: force must be finite, |f| <= %g", TT_MAX_VALUE);
    tt_result r = need_forces(w);
    if (r != TT_OK) return r;
    tt__sleep_touch(w, i);
    w->fx[i] += f.x;
    w->fy[i] += f.y;
    w->forces_pending = true;
    return TT_OK;
}

/* Whether a kick of (dvx, dvy) on particle i is one to make: no larger than
 * a velocity tt_particle_set_velocity accepts, and not leaving the particle
 * past TT_DIVERGED between steps (an impulse on a very light particle did;
 * the step's guard would only stop it then). A particle that integration
 * made faster than TT_MAX_VALUE, as Euler can, still takes small kicks. */
static bool kick_ok(const tt_world *w, uint32_t i, double dvx, double dvy)
{
    const tt_vec2 v = tt__velocity(w, i);
    return tt__vec_ok((tt_vec2){dvx, dvy}) && fabs(v.x + dvx) <= TT_DIVERGED && fabs(v.y + dvy) <= TT_DIVERGED;
}

tt_result tt_particle_apply_impulse(tt_world *w, tt_particle p, tt_vec2 j)
{
    CHECK("tt_particle_apply_impulse");
    if (!tt__vec_ok(j)) return tt__fail(w, TT_EINVAL, "tt_particle_apply_impulse: impulse must be finite, |j| <= %g", TT_MAX_VALUE);
    if (!kick_ok(w, i, j.x * w->inv_mass[i], j.y * w->inv_mass[i]))
        return tt__fail(w, TT_EINVAL, "tt_particle_apply_impulse: the velocity change j/m must be <= %g m/s and leave |v| <= %g (mass %g kg)",
                        TT_MAX_VALUE, TT_DIVERGED, w->inv_mass[i] > 0.0 ? 1.0 / w->inv_mass[i] : 0.0);
    tt__sleep_touch(w, i);
    tt__add_velocity(w, i, j.x * w->inv_mass[i], j.y * w->inv_mass[i]);
    return TT_OK;
}

tt_result tt_world_explode(tt_world *w, tt_vec2 c, double radius, double impulse)
{
    TT_CHECK_WORLD(w, "tt_world_explode");
    if (!tt__vec_ok(c)) return tt__fail(w, TT_EINVAL, "tt_world_explode: centre must be finite, |c| <= %g", TT_MAX_VALUE);
    if (!tt__in_range(radius, 0.0, TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "tt_world_explode: radius must be in [0, %g], got %g", TT_MAX_VALUE, radius);
    if (!tt__in_range(impulse, -TT_MAX_VALUE, TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "tt_world_explode: impulse must be finite, |j| <= %g", TT_MAX_VALUE);
    for (int pass = 0; pass < 2; pass++) { /* check every kick first: a refused explosion changes nothing */
        if (pass) tt__sleep_wake_aabb(w, c.x - radius, c.y - radius, c.x + radius, c.y + radius);
        for (uint32_t i = 0; i < w->ppool.count; i++) {
            if (w->inv_mass[i] == 0.0) continue;
            double dx = w->px[i] - c.x, dy = w->py[i] - c.y;
            double d = sqrt(dx * dx + dy * dy);
            if (!(d > 0.0 && d < radius)) continue;
            double s = impulse * (1.0 - d / radius) * w->inv_mass[i] / d;
            if (pass) tt__add_velocity(w, i, s * dx, s * dy);
            else if (!kick_ok(w, i, s * dx, s * dy))
                return tt__fail(w, TT_EINVAL, "tt_world_explode: the velocity change of particle %u must be <= %g m/s and leave |v| <= %g", i, TT_MAX_VALUE, TT_DIVERGED);
        }
    }
    return TT_OK;
}

uint32_t tt_world_particle_count(const tt_world *w) { return w ? w->alive : 0; }

uint32_t tt_world_list_particles(const tt_world *w, tt_particle *out, uint32_t cap)
{
    if (!w) return 0;
    if (out) {
        uint32_t n = 0;
        for (uint32_t i = 0; i < w->ppool.count && n < cap; i++)
            if (w->flags[i] & TT__PF_ALIVE) out[n++] = (tt_particle){i, w->ppool.gen[i]};
    }
    return w->alive;
}

uint32_t tt_world_read_positions(const tt_world *w, double *xy, uint32_t cap)
{
    if (!w || !xy) return 0;
    uint32_t n = 0;
    for (uint32_t i = 0; i < w->ppool.count && n < cap; i++)
        if (w->flags[i] & TT__PF_ALIVE) {
            xy[2 * n] = w->px[i];
            xy[2 * n + 1] = w->py[i];
            n++;
        }
    return n;
}

tt_result tt_particles_get_positions(const tt_world *w, const tt_particle *ids, uint32_t n, double *xy)
{
    TT_CHECK_WORLD(w, "tt_particles_get_positions");
    if (n && (!ids || !xy)) return tt__fail(w, TT_EINVAL, "tt_particles_get_positions: NULL array");
    for (uint32_t k = 0; k < n; k++) {
        tt_result r = tt__particle_check(w, ids[k], "tt_particles_get_positions");
        if (r != TT_OK) return r;
        xy[2 * k] = w->px[ids[k].index];
        xy[2 * k + 1] = w->py[ids[k].index];
    }
    return TT_OK;
}

tt_result tt_particles_set_positions(tt_world *w, const tt_particle *ids, uint32_t n, const double *xy, tt_move_mode mode)
{
    TT_CHECK_WORLD(w, "tt_particles_set_positions");
    if (n && (!ids || !xy)) return tt__fail(w, TT_EINVAL, "tt_particles_set_positions: NULL array");
    if (mode != TT_MOVE_KEEP_VELOCITY && mode != TT_MOVE_RESET_VELOCITY)
        return tt__fail(w, TT_EINVAL, "tt_particles_set_positions: unknown move mode %d", (int)mode);
    for (uint32_t k = 0; k < n; k++) { /* all or nothing */
        tt_result r = tt__particle_check(w, ids[k], "tt_particles_set_positions");
        if (r != TT_OK) return r;
        if (!tt__vec_ok((tt_vec2){xy[2 * k], xy[2 * k + 1]}))
            return tt__fail(w, TT_EINVAL, "tt_particles_set_positions: position %u must be finite, |x| <= %g", k, TT_MAX_VALUE);
        if (tt__fixed_check(w, (tt_vec2){xy[2 * k], xy[2 * k + 1]}, "tt_particles_set_positions") != TT_OK) return TT_EINVAL;
    }
    for (uint32_t k = 0; k < n; k++)
        tt_particle_set_position(w, ids[k], (tt_vec2){xy[2 * k], xy[2 * k + 1]}, mode);
    return TT_OK;
}
