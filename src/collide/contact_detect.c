/* tether — contact detection, the group's begin (per substep): the
 * velocities and positions the substep starts from, bullets' sweeps, the
 * particle grid and its pairs (planned into batches), and particles against
 * the static index. */
#include "collide_internal.h"
#include "terrain_internal.h"

#include <stdlib.h>
#include <string.h>

typedef struct detect_ctx {
    tt_world *w;
    tt__collide *c;
    uint32_t i;
    double x, y, r, margin;
    bool ok;
} detect_ctx;

static void detect_visit(void *ctx, uint32_t k)
{
    detect_ctx *d = ctx;
    tt__collide *c = d->c;
    const tt__prim *p = &c->prims[k];
    const tt_shape_def *sd = &c->shapes[p->shape].def;
    if (!tt__shape_filter(d->w, sd, d->i)) return;
    if (c->ccd_prim && d->i < c->bulletcap && c->ccd_prim[d->i] == (int32_t)k) return; /* the sweep has it */
    tt__hit hit;
    tt__circle_vs_prim(c, p, d->x, d->y, d->r, &hit);
    if (sd->sensor) {
        if (hit.depth > 0.0 && c->set.events)
            tt__record_contact(d->w, c, tt__shape_key(p->shape, d->i), d->i, UINT32_MAX, p->shape, true, hit.nx, hit.ny, 0.0);
        return;
    }
    if (hit.depth <= -d->margin) return;
    if (c->scr.nsc == c->scr.sccap && !tt__grow((void **)&c->scr.sc, &c->scr.sccap, c->scr.nsc + 1, sizeof *c->scr.sc)) {
        d->ok = false;
        return;
    }
    double cx, cy; /* the shape's motion where it meets the particle */
    tt__shape_carry(&c->shapes[p->shape], d->x - hit.nx * d->r, d->y - hit.ny * d->r, &cx, &cy);
    c->scr.sc[c->scr.nsc++] = (tt__scontact){d->i, k, hit.nx, hit.ny, 0.0, 0.0, 0.0, cx, cy, 0};
}

/* Marks the cells of the particle grid, just built, (c->scr.near) a particle
 * centred in could touch a static primitive: each primitive's box grown by
 * the largest radius and the margin, clamped into the grid as particles are
 * (clamping is monotone, so a particle outside still lands in a marked cell).
 * One byte load then spares most particles the static test. False on no
 * memory. */
static bool grid_near_shapes(tt__collide *c)
{
    const tt__grid *g = &c->scr.grid;
    if (g->ncell == 0) return false;
    if (g->ncell > c->scr.near_cap) return false; /* contacts_reserve sized it for any grid */
    memset(c->scr.near, 0, g->ncell);
    const double grow = g->rmax * (1.0 + TT__CONTACT_MARGIN);
    for (uint32_t k = 0; k < c->nprim; k++) {
        const tt__prim *p = &c->prims[k];
        int32_t x0 = tt__cell_coord(p->lox - grow, g->ox, g->inv), x1 = tt__cell_coord(p->hix + grow, g->ox, g->inv);
        int32_t y0 = tt__cell_coord(p->loy - grow, g->oy, g->inv), y1 = tt__cell_coord(p->hiy + grow, g->oy, g->inv);
        x0 = x0 < 0 ? 0 : x0 >= g->nx ? g->nx - 1 : x0;
        x1 = x1 < 0 ? 0 : x1 >= g->nx ? g->nx - 1 : x1;
        y0 = y0 < 0 ? 0 : y0 >= g->ny ? g->ny - 1 : y0;
        y1 = y1 < 0 ? 0 : y1 >= g->ny ? g->ny - 1 : y1;
        for (int32_t y = y0; y <= y1; y++)
            memset(c->scr.near + (size_t)y * (size_t)g->nx + (size_t)x0, 1, (size_t)(x1 - x0 + 1));
    }
    return true;
}

/* A pair of per-particle arrays grown to hold n (to the world's capacity
 * at once); false, the old ones kept, on no memory. */
static bool grow_xy(const tt_world *w, double **x, double **y, uint32_t *cap, uint32_t n)
{
    if (*cap >= n) return true;
    const uint32_t want = w->pcap > n ? w->pcap : n;
    double *a = realloc(*x, (size_t)want * sizeof *a);
    if (!a) return false;
    *x = a;
    double *b = realloc(*y, (size_t)want * sizeof *b);
    if (!b) return false;
    *y = b;
    *cap = want;
    return true;
}

/* What the substeps need from the counts of particles and shapes, before
 * the step changes anything: the static index, the arrays begin fills per
 * particle, the grid for any spread of the particles. */
bool tt__contacts_reserve(tt_world *w, void *self)
{
    tt__collide *c = self;
    c->step_clear = false; /* until tt__pairs_plan_step says otherwise for this step */
    if (c->dirty && tt__shapes_rebuild(w, c) != TT_OK) return false;
    const bool pairs = c->set.particles;
    if (!tt__contacts_detect_any(c)) return true;
    const uint32_t n = w->ppool.count;
    /* Contacts and events: room for half as many again as the most seen, so a step whose contacts grow
     * less than that allocates nothing for them (a step that outgrows it grows them inside, and reports
     * it if it cannot) */
#define ROOM(k) ((k) + (k) / 2 + 16)
    if (!tt__grow((void **)&c->scr.sc, &c->scr.sccap, ROOM(c->sc_peak), sizeof *c->scr.sc) ||
        (pairs && !tt__grow((void **)&c->scr.pairs, &c->scr.paircap, ROOM(c->pair_peak), sizeof *c->scr.pairs)))
        return false;
    if (c->set.events && (!tt__grow((void **)&c->scr.rec, &c->scr.reccap, ROOM(c->rec_peak), sizeof *c->scr.rec) ||
                          !tt__grow((void **)&c->events, &c->evcap, ROOM(c->ev_peak), sizeof *c->events)))
        return false;
#undef ROOM
    if (!grow_xy(w, &c->scr.vx0, &c->scr.vy0, &c->scr.vcap, n)) return false;
    if (w->integrator != TT_VERLET && !grow_xy(w, &c->sx0, &c->sy0, &c->scap, n)) return false;
    if (c->nprim && !grow_xy(w, &c->scr.gx0, &c->scr.gy0, &c->scr.gcap, n)) return false;
    if (pairs && !grow_xy(w, &c->scr.px0, &c->scr.py0, &c->scr.pcap, n)) return false;
    if (pairs && c->set.broadphase == TT_BROADPHASE_GRID) {
        if (!tt__grid_reserve(&c->scr.grid, n)) return false;
        const uint32_t cells = tt__grid_max_cells(n);
        if ((c->nprim || c->terr) && cells > c->scr.near_cap) { /* the shapes' near cells, then the terrains' */
            uint8_t *p = realloc(c->scr.near, cells);
            if (!p) return false;
            c->scr.near = p;
            c->scr.near_cap = cells;
        }
    }
    if (pairs) tt__pairs_plan_step(w, c, n);
    return (!pairs || tt__batches_reserve(&c->scr.bat, n)) && tt__contacts_bound(w, c, n);
}

/* The velocities and positions the substep starts from (contacts_reserve
 * sized their arrays). */
static void substep_start(tt_world *w, tt__collide *c, double h, uint32_t n)
{
    /* pre-solve velocities: what restitution and friction measure against */
    if (w->integrator == TT_VERLET) {
        const double inv_h = 1.0 / h;
        for (uint32_t i = 0; i < n; i++) {
            c->scr.vx0[i] = (w->px[i] - w->qx[i]) * inv_h;
            c->scr.vy0[i] = (w->py[i] - w->qy[i]) * inv_h;
        }
    } else {
        tt__copy(c->scr.vx0, w->qx, (size_t)n * sizeof *c->scr.vx0);
        tt__copy(c->scr.vy0, w->qy, (size_t)n * sizeof *c->scr.vy0);
    }
    if (w->integrator != TT_VERLET) {
        /* the last substep's end positions, unless something moved or appeared since: then x − v·h */
        if (!(c->s_epoch == w->epoch && c->s_count == n)) {
            /* where each integrator started the substep, exact under gravity alone */
            double k = w->integrator == TT_SYMPLECTIC_EULER ? 0.0 : w->integrator == TT_EULER ? 1.0 : 0.5;
            double gx = k * w->gravity.x * h * h, gy = k * w->gravity.y * h * h;
            for (uint32_t i = 0; i < n; i++) {
                c->sx0[i] = w->px[i] - w->qx[i] * h + gx;
                c->sy0[i] = w->py[i] - w->qy[i] * h + gy;
            }
        }
    }
}

/* Whether this substep provably has no pair (contact_skip.c): the bound
 * holds, or a probe with cells twice as wide finds no two particles
 * (filters aside) within reach plus the ordinary cell. */
static bool no_pair_near(tt_world *w, tt__collide *c, uint32_t n)
{
    const tt__pair_plan plan = tt__pairs_skip(w, c, n);
    if (plan != TT__PAIRS_PROBE) return plan == TT__PAIRS_NONE;
    tt__grid *g = &c->scr.grid;
    if (!tt__grid_build_wide(w, g, c->set.cell_size, 2.0)) return false;
    g->epoch = UINT64_MAX; /* a grid for no query */
    const double gap = g->cs0;
    const bool clear = g->ncell == 0 || (g->rmax > 0.0 && gap > 0.0 && g->cs >= 2.0 * gap && !tt__grid_any_near(g, gap));
    tt__pairs_probed(w, c, clear, clear && g->ncell != 0, gap, g->extent);
    return clear;
}

/* The broadphase: the substep's particle pairs, planned into batches when
 * they are solved from them. True when the particle grid was built. */
static bool detect_pairs(tt_world *w, tt__collide *c, uint32_t n)
{
    bool grid_built = false; /* this substep: its cells can filter the static test */
    bool ok;
    c->scr.nrows = 0;
    const double t0 = tt__now_ms();
    if (c->bp_step != w->stats.steps) { /* the step's first substep */
        c->bp_step = w->stats.steps;
        c->bp_ms = 0.0;
    }
    if (tt__contacts_points_only(w, c, n)) { /* no pair, whatever the broadphase */
        ok = true;
        c->scr.grid.epoch = UINT64_MAX; /* not built: a query builds its own */
    } else if (no_pair_near(w, c, n)) { /* no two particles near enough: no pair, as the build would find */
        ok = true;
        c->scr.grid.epoch = UINT64_MAX;
    } else if (c->set.broadphase == TT_BROADPHASE_BRUTE) {
        ok = tt__brute_pairs(w, c);
        c->scr.grid.epoch = UINT64_MAX;
    } else {
        ok = tt__grid_detect(w, c);
        c->cells_used = c->scr.grid.ncell; /* the stat: a probe's grid (no_pair_near) is not the pairs' */
        grid_built = ok;
    }
    c->bp_ms += tt__now_ms() - t0;
    if (!ok) tt__step_oom(w, "contact pairs");
    /* batches pay for their planning from the second sweep on */
    c->scr.batched = false;
    if (w->order == TT_GAUSS_SEIDEL && w->iterations > 1) {
        c->scr.batched = tt__batches_plan(&c->scr.bat, c->scr.pairs, c->scr.npairs, c->scr.runs, c->scr.nrows, w->inv_mass, n);
        if (!c->scr.batched) tt__step_oom(w, "contact batches");
    }
    return grid_built;
}

/* Particles against the static index: the substep's shape contacts, and
 * where the sweeps start from. */
static void detect_shapes(tt_world *w, tt__collide *c, uint32_t n, bool grid_built)
{
    detect_ctx d = {w, c, 0, 0, 0, 0, 0, true};
    const uint8_t *near = grid_built && grid_near_shapes(c) ? c->scr.near : NULL;
    for (uint32_t i = 0; i < n; i++) {
        if (w->inv_mass[i] == 0.0) continue; /* pinned or removed: shapes never push them */
        if (near && !near[c->scr.grid.cell[i] & 0x7FFFFFFFu]) continue; /* its cell is far from every shape */
        double r = w->radius[i], m = r * TT__CONTACT_MARGIN;
        d.i = i;
        d.x = w->px[i];
        d.y = w->py[i];
        d.r = r;
        d.margin = m;
        /* fast path: no primitive's box near the particle (most particles, most steps) */
        if (!tt__sgrid_near(c, d.x - r - m, d.y - r - m, d.x + r + m, d.y + r + m)) continue;
        tt__sgrid_query(c, d.x - r - m, d.y - r - m, d.x + r + m, d.y + r + m, detect_visit, &d);
        if (!d.ok) {
            tt__step_oom(w, "shape contacts");
            break;
        }
    }
    /* where the sweeps start from, for the guard in sweeps_done */
    if (n && c->scr.gcap >= n) {
        memcpy(c->scr.gx0, w->px, (size_t)n * sizeof *c->scr.gx0);
        memcpy(c->scr.gy0, w->py, (size_t)n * sizeof *c->scr.gy0);
        c->scr.guard = true;
    }
}

/* Whether some particle can move: one that can makes every pair and shape
 * contact; a world all pinned or asleep (a settled pile) makes none, and
 * finds its first movable particle at once when it has any. */
static bool any_movable(const tt_world *w, uint32_t n)
{
    for (uint32_t i = 0; i < n; i++)
        if (w->inv_mass[i] != 0.0) return true;
    return false;
}

void tt__contacts_begin(tt_world *w, void *self, double h)
{
    tt__collide *c = self;
    c->scr.npairs = 0;
    c->scr.nsc = 0;
    c->cells_used = 0;
    c->scr.batched = false;
    c->scr.anc.on = false; /* until this substep's detection: a substep that returns before has no pairs */
    c->scr.guard = false; /* until this substep's start positions are copied */
    if (c->dirty && tt__shapes_rebuild(w, c) != TT_OK) c->nprim = 0;
    tt__shapes_place_moved(w, c);
    bool pairs = c->set.particles;
    c->clear_ok &= pairs; /* contact_skip.c: a substep without the scan ends the bound */
    if (!tt__contacts_detect_any(c)) return;
    const uint32_t n = w->ppool.count;
    if (!c->nbullets && !any_movable(w, n)) { /* nothing to detect: not even a grid to build */
        c->clear_ok = false;
        return;
    }
    /* Shapes alone, far from every particle: no contact, and no other group
     * to carry a particle into a shape during the sweeps (the guard's job),
     * so nothing to prepare. (Verlet: the others keep the substep's start
     * positions for the next, whether in contact or not.) */
    if (!pairs && !c->nbullets && !c->terr && tt__groups_relaxing(w) == 1 && w->integrator == TT_VERLET &&
        tt__shapes_out_of_reach(w, c, n))
        return;
    /* The velocities the substep starts from are read only where there are
     * contacts: Verlet takes them after detection (which moves nothing) and
     * only then; bullets' sweeps move particles, and the other integrators
     * keep the start positions for the next substep, so those take them first. */
    const bool start_first = w->integrator != TT_VERLET || c->nbullets;
    if (start_first) substep_start(w, c, h, n);
    if (c->nbullets && (c->nprim || c->terr)) tt__ccd(w, c, h);
    bool grid_built = pairs && detect_pairs(w, c, n);
    if (c->nprim) detect_shapes(w, c, n, grid_built);
    if (c->terr && !tt__terrain_detect(w, c, n, grid_built)) tt__step_oom(w, "terrain contacts");
    if (!start_first && (c->scr.npairs || c->scr.nsc)) substep_start(w, c, h, n);
    if (c->set.anchored_friction) tt__anchors_begin(w, c, n, h); /* before pre-stabilisation moves the starts */
    /* stacking weighs pre-stabilisation's pairs too: unweighted, it left a
     * collapsed pile's old overlap to the weighted sweeps, whose push is
     * speed (a column of 2 000 circles thrown from 274 m to 538 m) */
    if (c->scr.batched) tt__contacts_stack(w, c);
    if (c->scr.npairs) tt__contacts_prestab(w, c, n);
    c->quiet_last = c->scr.npairs == 0 && c->scr.nsc == 0;
    if (!c->quiet_last) c->clear_ok = false; /* the sweeps will push: moves the displacements do not see */
    if (c->scr.npairs > c->pair_peak) c->pair_peak = c->scr.npairs;
    if (c->scr.nsc > c->sc_peak) c->sc_peak = c->scr.nsc;
}
