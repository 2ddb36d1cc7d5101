/* tether — a scene description built from tether's parts: static bodies
 * become shapes, dynamic circles particles, dynamic boxes and polygons
 * lattice composites (particles braced by rigid links), joints pins and
 * distance links between the particles nearest their anchors. Where that
 * differs from a rigid body is said in README "Box2D cross-check". */
#include "scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

ts_tether_settings ts_tether_settings_default(void)
{
    ts_tether_settings s = {1, 8, 4, false, false};
    return s;
}

static tt_shape static_body(tt_world *w, const ts_body *b)
{
    tt_shape_def d = tt_shape_def_default();
    d.position = b->position;
    d.angle = b->angle;
    d.restitution = b->restitution;
    d.friction_static = d.friction_kinetic = b->friction;
    switch (b->shape) {
    case TS_CIRCLE: d.type = TT_SHAPE_CIRCLE; d.radius = b->radius; break;
    case TS_BOX: d.type = TT_SHAPE_BOX; d.half_extents = b->half; break;
    case TS_POLYGON: d.type = TT_SHAPE_POLYGON; d.points = b->points; d.count = b->count; break;
    case TS_EDGE: d.type = TT_SHAPE_SEGMENT; d.a = b->a; d.b = b->b; break;
    }
    return tt_shape_create(w, &d);
}

/* Every particle of a lattice moves with the body: v + ω × (p − c). */
static tt_result set_rigid_velocity(tt_world *w, tt_composite c, const ts_body *b)
{
    tt_particle ps[64 * 64 + 64];
    uint32_t n = 0;
    tt_result r = tt_composite_get_particles(w, c, ps, sizeof ps / sizeof ps[0], &n);
    for (uint32_t i = 0; r == TT_OK && i < n; i++) {
        tt_vec2 p;
        r = tt_particle_get_position(w, ps[i], &p);
        const double dx = p.x - b->position.x, dy = p.y - b->position.y;
        if (r == TT_OK) r = tt_particle_set_velocity(w, ps[i], (tt_vec2){b->velocity.x - b->spin * dy, b->velocity.y + b->spin * dx});
        if (r == TT_OK) r = tt_particle_set_material(w, ps[i], b->restitution, b->friction, b->friction);
    }
    return r;
}

/* A box as cols × rows particles whose discs fill its outline: centres
 * one spacing in from each other and half a spacing in from the edges. */
static tt_composite lattice_box(tt_world *w, const ts_body *b, uint32_t per_side)
{
    const double W = 2 * b->half.x, H = 2 * b->half.y, s = fmin(W, H) / per_side;
    tt_lattice_def d = tt_lattice_def_default();
    d.columns = (uint32_t)fmax(2, fmin(64, floor(W / s + 0.5)));
    d.rows = (uint32_t)fmax(2, fmin(64, floor(H / s + 0.5)));
    const double sx = W / d.columns, sy = H / d.rows;
    d.width = W - sx;
    d.height = H - sy;
    d.center = b->position;
    d.angle = b->angle;
    d.common.radius = 0.5 * fmin(sx, sy);
    d.common.mass = ts_body_mass(b) / (d.columns * d.rows);
    return tt_lattice_create(w, &d);
}

/* A polygon as a particle at each corner, pulled in by its radius (a
 * quarter of the shortest edge) so the discs stay inside the outline. */
static tt_composite lattice_polygon(tt_world *w, const ts_body *b)
{
    tt_vec2 p[TS_MAX_POLYGON];
    double shortest = INFINITY, cx = 0, cy = 0;
    for (uint32_t i = 0; i < b->count; i++) {
        const tt_vec2 u = b->points[i], v = b->points[(i + 1) % b->count];
        shortest = fmin(shortest, hypot(v.x - u.x, v.y - u.y));
        cx += u.x / b->count;
        cy += u.y / b->count;
    }
    const double r = shortest / 4, ca = cos(b->angle), sa = sin(b->angle);
    for (uint32_t i = 0; i < b->count; i++) {
        const double dx = b->points[i].x - cx, dy = b->points[i].y - cy, k = 1 - r / hypot(dx, dy);
        const double lx = cx + dx * k, ly = cy + dy * k;
        p[i] = (tt_vec2){b->position.x + ca * lx - sa * ly, b->position.y + sa * lx + ca * ly};
    }
    tt_lattice_def d = tt_lattice_def_default();
    d.points = p;
    d.point_count = b->count;
    d.common.radius = r;
    d.common.mass = ts_body_mass(b) / b->count;
    return tt_lattice_create(w, &d);
}

static tt_result dynamic_body(ts_tether *t, const ts_body *b, uint32_t per_side, ts_tether_body *out)
{
    tt_world *w = t->world;
    if (b->shape == TS_CIRCLE) {
        tt_particle_def d = tt_particle_def_default();
        d.position = b->position;
        d.velocity = b->velocity;
        d.radius = b->radius;
        d.mass = ts_body_mass(b);
        out->particle = tt_particle_create(w, &d);
        if (out->particle.gen == 0) return TT_EINVAL;
        t->circles[t->circle_count++] = out->particle;
        return tt_particle_set_material(w, out->particle, b->restitution, b->friction, b->friction);
    }
    out->composite = b->shape == TS_BOX ? lattice_box(w, b, per_side) : lattice_polygon(w, b);
    if (out->composite.gen == 0) return TT_EINVAL;
    return set_rigid_velocity(w, out->composite, b);
}

/* The particles of body i nearest `at` (up to k ≤ 2 of them, nearest first). */
static uint32_t nearest(const ts_tether *t, int32_t i, tt_vec2 at, tt_particle *out, uint32_t k)
{
    const ts_tether_body *tb = &t->body[i];
    if (tb->particle.gen) {
        out[0] = tb->particle;
        return 1;
    }
    tt_particle ps[64 * 64 + 64];
    uint32_t n = 0;
    if (tt_composite_get_particles(t->world, tb->composite, ps, sizeof ps / sizeof ps[0], &n) != TT_OK) return 0;
    double d0 = INFINITY, d1 = INFINITY;
    for (uint32_t j = 0; j < n; j++) {
        tt_vec2 p;
        tt_particle_get_position(t->world, ps[j], &p);
        const double d = hypot(p.x - at.x, p.y - at.y);
        if (d < d0) {
            d1 = d0;
            out[1] = out[0];
            d0 = d;
            out[0] = ps[j];
        } else if (d < d1) {
            d1 = d;
            out[1] = ps[j];
        }
    }
    return n == 0 ? 0 : (k < 2 || n < 2) ? 1 : 2;
}

/* A pinned point that collides with nothing: the ground end of a joint. */
static tt_particle ground_point(tt_world *w, tt_vec2 at)
{
    tt_particle_def d = tt_particle_def_default();
    d.position = at;
    d.pinned = true;
    d.category = 0;
    d.mask = 0;
    return tt_particle_create(w, &d);
}

static tt_result link(tt_world *w, tt_particle a, tt_particle b)
{
    tt_distance_def d = tt_distance_def_default();
    d.a = a;
    d.b = b;
    return tt_distance_create(w, &d).gen ? TT_OK : TT_EINVAL;
}

/* revolute: a pivot particle at the anchor (pinned on the ground side,
 * else light), linked to the nearest one or two particles of each body; distance: one
 * link between the particles nearest the anchors; weld: the nearest two
 * of each body linked pairwise (pinned where they are on the ground side). */
static tt_result joint(ts_tether *t, const ts_joint *j)
{
    tt_world *w = t->world;
    tt_particle pa[2], pb[2];
    const bool ground = j->a == TS_GROUND;
    tt_result r = TT_OK;
    if (j->kind == TS_DISTANCE) {
        if (ground) pa[0] = ground_point(w, j->anchor_a);
        else if (!nearest(t, j->a, j->anchor_a, pa, 1)) return TT_EINVAL;
        if (!nearest(t, j->b, j->anchor_b, pb, 1)) return TT_EINVAL;
        return link(w, pa[0], pb[0]);
    }
    const uint32_t nb = nearest(t, j->b, j->anchor_a, pb, 2);
    if (nb == 0) return TT_EINVAL;
    if (j->kind == TS_REVOLUTE) {
        tt_particle pivot = ground_point(w, j->anchor_a);
        if (!ground) {
            /* a pivot between two bodies carries a hundredth of a particle's mass: enough to stay finite */
            const uint32_t na = nearest(t, j->a, j->anchor_a, pa, 2);
            double m = 1;
            r = tt_particle_get_mass(w, pb[0], &m);
            if (r == TT_OK) r = tt_particle_set_pinned(w, pivot, false);
            if (r == TT_OK) r = tt_particle_set_mass(w, pivot, 0.01 * m);
            for (uint32_t i = 0; r == TT_OK && i < na; i++) r = link(w, pivot, pa[i]);
        }
        for (uint32_t i = 0; r == TT_OK && i < nb; i++) r = link(w, pivot, pb[i]);
        return r;
    }
    if (ground) {
        tt_pin_def d = tt_pin_def_default();
        for (uint32_t i = 0; r == TT_OK && i < nb; i++) {
            d.particle = pb[i];
            r = tt_pin_create(w, &d).gen ? TT_OK : TT_EINVAL;
        }
        return r;
    }
    const uint32_t na = nearest(t, j->a, j->anchor_a, pa, 2);
    for (uint32_t i = 0; r == TT_OK && i < na; i++)
        for (uint32_t k = 0; r == TT_OK && k < nb; k++) r = link(w, pa[i], pb[k]);
    return r;
}

static tt_world *make_world(const ts_scene *s, const ts_tether_settings *set)
{
    tt_world_def wd = tt_world_def_default();
    wd.gravity = s->gravity;
    wd.dt_hint = s->dt;
    wd.substeps = set->substeps;
    wd.iterations = set->iterations;
    wd.spin = set->spin;
    wd.capacity = s->body_count;
    wd.sleep = false; /* the cross-check and the bench compare motion with Box2D's, run with its sleeping off */
    tt_world *w = tt_world_create(&wd);
    tt_collision_settings cs = tt_collision_settings_default();
    cs.friction_static = cs.friction_kinetic = 0.3;
    cs.anchored_friction = set->anchored;
    if (w && tt_world_set_collision(w, &cs) != TT_OK) {
        tt_world_destroy(w);
        return NULL;
    }
    return w;
}

tt_result ts_tether_build(const ts_scene *s, const ts_tether_settings *set, ts_tether *t, const char **why)
{
    memset(t, 0, sizeof *t);
    const char *bad = NULL;
    if (!s || !set) bad = "scene and settings must not be NULL";
    else if (set->lattice < 2 || set->lattice > 64) bad = "lattice must be in [2, 64] particles per side";
    else if (set->substeps < 1 || set->substeps > TT_MAX_SUBSTEPS || set->iterations < 1 || set->iterations > TT_MAX_ITERATIONS)
        bad = "substeps must be in [1, 1000] and iterations in [1, 10000]";
    else if (!(t->world = make_world(s, set))) bad = tt_last_error(NULL);
    else if (!(t->body = calloc(s->body_count + 1, sizeof *t->body)) || !(t->circles = calloc(s->body_count + 1, sizeof *t->circles)))
        bad = "out of memory";
    tt_result r = bad ? TT_EINVAL : TT_OK;
    for (uint32_t i = 0; r == TT_OK && i < s->body_count; i++) {
        const ts_body *b = &s->bodies[i];
        if (b->dynamic) {
            r = dynamic_body(t, b, set->lattice, &t->body[i]);
            t->mass += ts_body_mass(b);
        } else if (!(t->body[i].shape = static_body(t->world, b)).gen)
            r = TT_EINVAL;
        t->body[i].angle0 = b->angle;
        t->count = i + 1;
    }
    for (uint32_t i = 0; r == TT_OK && i < s->joint_count; i++) r = joint(t, &s->joints[i]);
    if (r != TT_OK) {
        /* the world's message dies with it: keep a copy */
        static _Thread_local char msg[256];
        snprintf(msg, sizeof msg, "%s", bad ? bad : tt_last_error(t->world));
        if (why) *why = msg;
        ts_tether_free(t);
    }
    return r;
}

void ts_tether_free(ts_tether *t)
{
    tt_world_destroy(t->world);
    free(t->body);
    free(t->circles);
    memset(t, 0, sizeof *t);
}

tt_result ts_tether_state(const ts_tether *t, uint32_t body, ts_state *out)
{
    memset(out, 0, sizeof *out);
    if (!t || !t->world || body >= t->count) return TT_EINVAL;
    const ts_tether_body *tb = &t->body[body];
    if (tb->particle.gen) {
        tt_result r = tt_particle_get_position(t->world, tb->particle, &out->position);
        return r == TT_OK ? tt_particle_get_velocity(t->world, tb->particle, &out->velocity) : r;
    }
    if (!tb->composite.gen) return TT_OK; /* static: never moves */
    tt_result r = tt_composite_get_center(t->world, tb->composite, &out->position);
    if (r == TT_OK) r = tt_composite_get_angle(t->world, tb->composite, &out->angle);
    out->angle += tb->angle0;
    /* the centre's velocity and the spin that best fits the particles' (least squares, mass weighted) */
    tt_particle ps[64 * 64 + 64];
    uint32_t n = 0;
    if (r == TT_OK) r = tt_composite_get_particles(t->world, tb->composite, ps, sizeof ps / sizeof ps[0], &n);
    double m = 0, vx = 0, vy = 0, L = 0, I = 0;
    for (uint32_t i = 0; r == TT_OK && i < n; i++) {
        tt_vec2 p, v;
        double mi;
        r = tt_particle_get_position(t->world, ps[i], &p);
        if (r == TT_OK) r = tt_particle_get_velocity(t->world, ps[i], &v);
        if (r == TT_OK) r = tt_particle_get_mass(t->world, ps[i], &mi);
        if (r != TT_OK) break;
        const double dx = p.x - out->position.x, dy = p.y - out->position.y;
        m += mi;
        vx += mi * v.x;
        vy += mi * v.y;
        L += mi * (dx * v.y - dy * v.x);
        I += mi * (dx * dx + dy * dy);
    }
    if (r == TT_OK && m > 0) {
        out->velocity = (tt_vec2){vx / m, vy / m};
        out->spin = I > 0 ? L / I : 0; /* the centre's own motion adds nothing to L: Σ m r = 0 */
        out->momentum = L;
    }
    return r;
}

double ts_tether_kinetic_per_kg(const ts_tether *t)
{
    tt_energy e;
    if (!t || !t->world || t->mass <= 0 || tt_world_get_energy(t->world, &e) != TT_OK) return NAN;
    return e.kinetic / t->mass;
}

tt_result ts_tether_jitter(ts_tether *t, uint64_t seed, double amount)
{
    uint64_t st = seed * 2654435761u + 1;
    for (uint32_t i = 0; seed && i < t->circle_count; i++) {
        tt_vec2 p;
        tt_result r = tt_particle_get_position(t->world, t->circles[i], &p);
        for (int k = 0; k < 2; k++) {
            st = st * 6364136223846793005ull + 1442695040888963407ull;
            const double u = 2.0 * ((double)(st >> 11) / 9007199254740992.0) - 1.0;
            if (k == 0) p.x += u * amount;
            else p.y += u * amount;
        }
        if (r == TT_OK) r = tt_particle_set_position(t->world, t->circles[i], p, TT_MOVE_RESET_VELOCITY);
        if (r != TT_OK) return r;
    }
    return TT_OK;
}

tt_result ts_tether_pour_circles(uint32_t n, double width, double lift, const char *name, ts_tether *t, double *top,
                                 uint32_t *steps, const char **why)
{
    memset(t, 0, sizeof *t);
    ts_scene s;
    if (!ts_scene_pour_lifted(&s, n, width, lift, name, top, why)) return TT_ENOMEM;
    *steps = s.steps;
    ts_tether_settings set = ts_tether_settings_default();
    tt_result r = ts_tether_build(&s, &set, t, why);
    ts_scene_free(&s);
    return r;
}
