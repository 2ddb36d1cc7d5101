// tether — the Box2D 2.4.1 bridge (see box2d_bridge.h). The project's only
// C++: everything else talks to Box2D through the C functions below. Each
// checks its input first, because a bad value would reach a b2Assert (an
// abort) or a NaN inside Box2D, and no C++ exception crosses into C.
#include "box2d_bridge.h"

#include <box2d/box2d.h>

#include <cmath>
#include <cstdio>
#include <new>
#include <vector>

struct tb_world {
    b2World world{b2Vec2(0.0f, -10.0f)};
    std::vector<b2Body *> bodies;
    tb_world_def def;
};

static thread_local char g_error[256];

static bool fail(const char *fn, const char *why)
{
    std::snprintf(g_error, sizeof g_error, "%s: %s", fn, why);
    return false;
}

// Box2D stores floats: beyond 1e9 m the sums inside it lose every digit.
static bool ok(double v, double lim = 1e9) { return std::isfinite(v) && std::fabs(v) <= lim; }
static bool ok2(const double *v, double lim = 1e9) { return ok(v[0], lim) && ok(v[1], lim); }
static b2Vec2 vec(const double *v) { return b2Vec2((float)v[0], (float)v[1]); }

extern "C" const char *tb_last_error(void) { return g_error; }

extern "C" tb_world_def tb_world_def_default(void)
{
    tb_world_def d;
    d.gravity[0] = 0;
    d.gravity[1] = -10;
    d.velocity_iterations = 8;
    d.position_iterations = 3;
    d.sleep = true;
    d.continuous = true;
    return d;
}

extern "C" tb_body_def tb_body_def_default(void)
{
    tb_body_def d = {};
    d.radius = 0.5;
    d.half[0] = d.half[1] = 0.5;
    d.density = 1;
    d.friction = 0.3;
    return d;
}

static bool check_world_def(const char *fn, const tb_world_def *d)
{
    if (!d) return fail(fn, "def is NULL");
    if (!ok2(d->gravity, 1e6)) return fail(fn, "gravity must be finite, |g| <= 1e6");
    if (d->velocity_iterations < 1 || d->velocity_iterations > 1000 || d->position_iterations < 1 || d->position_iterations > 1000)
        return fail(fn, "iterations must be in [1, 1000]");
    return true;
}

extern "C" bool tb_world_set(tb_world *w, const tb_world_def *d)
{
    if (!w) return fail("tb_world_set", "world is NULL");
    if (!check_world_def("tb_world_set", d)) return false;
    w->def = *d;
    w->world.SetGravity(vec(d->gravity));
    w->world.SetAllowSleeping(d->sleep);
    w->world.SetContinuousPhysics(d->continuous);
    g_error[0] = 0;
    return true;
}

extern "C" tb_world *tb_world_create(const tb_world_def *d)
{
    if (!check_world_def("tb_world_create", d)) return nullptr;
    tb_world *w = new (std::nothrow) tb_world;
    if (!w) {
        fail("tb_world_create", "out of memory");
        return nullptr;
    }
    tb_world_set(w, d);
    return w;
}

extern "C" void tb_world_destroy(tb_world *w) { delete w; }

// Convex and counter-clockwise with no edge shorter than Box2D's weld
// distance: what b2PolygonShape::Set keeps as given.
static bool good_polygon(const double *p, int n)
{
    for (int i = 0; i < n; i++) {
        const double *a = p + 2 * i, *b = p + 2 * ((i + 1) % n), *c = p + 2 * ((i + 2) % n);
        if (!ok2(a, 1e6)) return false;
        if (std::hypot(b[0] - a[0], b[1] - a[1]) < 0.01) return false;
        if ((b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]) <= 1e-9) return false;
    }
    return true;
}

static const char *check_body(const tb_body_def *d)
{
    if (!ok2(d->position) || !ok(d->angle, 1e6) || !ok2(d->velocity, 1e6) || !ok(d->spin, 1e6))
        return "position, angle, velocity and spin must be finite (|x| <= 1e9, the rest <= 1e6)";
    if (!(d->friction >= 0 && d->friction <= 1e3) || !(d->restitution >= 0 && d->restitution <= 1))
        return "friction must be in [0, 1000] and restitution in [0, 1]";
    if (d->dynamic && !(d->density > 0 && d->density <= 1e9)) return "a dynamic body's density must be in (0, 1e9]";
    switch (d->shape) {
    case TB_CIRCLE: return d->radius >= 0.005 && d->radius <= 1e6 ? nullptr : "radius must be in [0.005, 1e6]";
    case TB_BOX:
        return d->half[0] >= 0.005 && d->half[1] >= 0.005 && ok2(d->half, 1e6) ? nullptr : "half extents must be in [0.005, 1e6]";
    case TB_POLYGON:
        if (d->count < 3 || d->count > TB_MAX_POLYGON) return "a polygon needs 3 to 8 points";
        return good_polygon(d->points, d->count) ? nullptr : "polygon points must be convex, counter-clockwise, edges >= 0.01";
    case TB_EDGE:
        if (d->dynamic) return "an edge can only be static";
        if (!ok2(d->a) || !ok2(d->b) || std::hypot(d->b[0] - d->a[0], d->b[1] - d->a[1]) < 0.01) return "edge ends must be finite, >= 0.01 apart";
        return nullptr;
    }
    return "unknown shape";
}

static void add_fixture(b2Body *body, const tb_body_def *d)
{
    b2CircleShape circle;
    b2PolygonShape poly;
    b2EdgeShape edge;
    b2FixtureDef fd;
    switch (d->shape) {
    case TB_CIRCLE: circle.m_radius = (float)d->radius; fd.shape = &circle; break;
    case TB_BOX: poly.SetAsBox((float)d->half[0], (float)d->half[1]); fd.shape = &poly; break;
    case TB_POLYGON: {
        b2Vec2 p[TB_MAX_POLYGON];
        for (int i = 0; i < d->count; i++) p[i] = vec(d->points + 2 * i);
        poly.Set(p, d->count);
        fd.shape = &poly;
        break;
    }
    case TB_EDGE: edge.SetTwoSided(vec(d->a), vec(d->b)); fd.shape = &edge; break;
    }
    fd.density = (float)d->density;
    fd.friction = (float)d->friction;
    fd.restitution = (float)d->restitution;
    body->CreateFixture(&fd);
}

extern "C" int tb_body_create(tb_world *w, const tb_body_def *d)
{
    const char *fn = "tb_body_create";
    if (!w || !d) return fail(fn, "world and def must not be NULL"), -1;
    if (const char *why = check_body(d)) return fail(fn, why), -1;
    if (w->bodies.size() >= 10000000) return fail(fn, "too many bodies"), -1;
    if (w->world.IsLocked()) return fail(fn, "the world is stepping"), -1;
    b2BodyDef bd;
    bd.type = d->dynamic ? b2_dynamicBody : b2_staticBody;
    bd.position = vec(d->position);
    bd.angle = (float)d->angle;
    bd.linearVelocity = vec(d->velocity);
    bd.angularVelocity = (float)d->spin;
    bd.fixedRotation = d->fixed_rotation;
    try {
        w->bodies.reserve(w->bodies.size() + 1);
    } catch (const std::bad_alloc &) {
        return fail(fn, "out of memory"), -1;
    }
    b2Body *body = w->world.CreateBody(&bd);
    add_fixture(body, d);
    w->bodies.push_back(body);
    g_error[0] = 0;
    return (int)w->bodies.size() - 1;
}

extern "C" int tb_joint_create(tb_world *w, tb_joint kind, int a, int b, const double anchor_a[2], const double anchor_b[2])
{
    const char *fn = "tb_joint_create";
    const int n = w ? (int)w->bodies.size() : 0;
    if (!w || !anchor_a || (kind == TB_DISTANCE && !anchor_b)) return fail(fn, "world and anchors must not be NULL"), -1;
    if (kind < TB_REVOLUTE || kind > TB_WELD) return fail(fn, "kind must be revolute, distance or weld"), -1;
    if (a < TB_GROUND || a >= n || b < 0 || b >= n || a == b) return fail(fn, "bodies must be two different existing bodies (a may be -1, the ground)"), -1;
    if (w->bodies[b]->GetType() != b2_dynamicBody) return fail(fn, "body b must be dynamic"), -1;
    if (!ok2(anchor_a) || (anchor_b && !ok2(anchor_b))) return fail(fn, "anchors must be finite"), -1;
    if (w->world.IsLocked()) return fail(fn, "the world is stepping"), -1;
    b2Body *ba = a == TB_GROUND ? nullptr : w->bodies[a];
    if (!ba) { // the ground: one static body without fixtures, made on first use
        b2BodyDef gd;
        ba = w->world.CreateBody(&gd);
    }
    b2Body *bb = w->bodies[b];
    if (kind == TB_REVOLUTE) {
        b2RevoluteJointDef jd;
        jd.Initialize(ba, bb, vec(anchor_a));
        w->world.CreateJoint(&jd);
    } else if (kind == TB_DISTANCE) {
        b2DistanceJointDef jd;
        jd.Initialize(ba, bb, vec(anchor_a), vec(anchor_b));
        w->world.CreateJoint(&jd);
    } else {
        b2WeldJointDef jd;
        jd.Initialize(ba, bb, vec(anchor_a));
        w->world.CreateJoint(&jd);
    }
    g_error[0] = 0;
    return w->world.GetJointCount() - 1;
}

extern "C" bool tb_world_step(tb_world *w, double dt)
{
    if (!w) return fail("tb_world_step", "world is NULL");
    if (!(dt > 0 && dt <= 10)) return fail("tb_world_step", "dt must be in (0, 10]");
    w->world.Step((float)dt, w->def.velocity_iterations, w->def.position_iterations);
    return true;
}

extern "C" bool tb_body_state_get(const tb_world *w, int i, tb_body_state *out)
{
    if (!w || !out) return fail("tb_body_state_get", "world and out must not be NULL");
    if (i < 0 || i >= (int)w->bodies.size()) return fail("tb_body_state_get", "no such body");
    const b2Body *b = w->bodies[i];
    const b2Vec2 c = b->GetWorldCenter(), v = b->GetLinearVelocity(), lc = b->GetLocalCenter();
    out->position[0] = c.x;
    out->position[1] = c.y;
    out->angle = b->GetAngle();
    out->velocity[0] = v.x;
    out->velocity[1] = v.y;
    out->spin = b->GetAngularVelocity();
    out->mass = b->GetMass();
    // GetInertia is about the body's origin: move it to the centre of mass
    out->inertia = b->GetInertia() - b->GetMass() * b2Dot(lc, lc);
    out->awake = b->IsAwake();
    return true;
}

extern "C" bool tb_positions(const tb_world *w, int first, int n, double *xy)
{
    if (!w || (!xy && n > 0)) return fail("tb_positions", "world and xy must not be NULL");
    if (first < 0 || n < 0 || first > (int)w->bodies.size() - n) return fail("tb_positions", "range past the last body");
    for (int i = 0; i < n; i++) {
        const b2Vec2 c = w->bodies[first + i]->GetWorldCenter();
        xy[2 * i] = c.x;
        xy[2 * i + 1] = c.y;
    }
    return true;
}

extern "C" int tb_world_body_count(const tb_world *w) { return w ? (int)w->bodies.size() : 0; }

extern "C" double tb_world_kinetic_energy(const tb_world *w)
{
    double e = 0;
    if (!w) return 0;
    for (const b2Body *b : w->bodies) {
        if (b->GetType() != b2_dynamicBody) continue;
        const b2Vec2 v = b->GetLinearVelocity(), lc = b->GetLocalCenter();
        const double I = b->GetInertia() - b->GetMass() * b2Dot(lc, lc), om = b->GetAngularVelocity();
        e += 0.5 * b->GetMass() * ((double)v.x * v.x + (double)v.y * v.y) + 0.5 * I * om * om;
    }
    return e;
}

extern "C" double tb_world_mass(const tb_world *w)
{
    double m = 0;
    if (w)
        for (const b2Body *b : w->bodies) m += b->GetMass();
    return m;
}
