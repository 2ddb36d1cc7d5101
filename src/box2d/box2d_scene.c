/* tether — a scene description built in Box2D through the bridge, body for
 * body, so body i of the scene is body i of the Box2D world. */
#include "box2d_scene.h"

#include <math.h>
#include <string.h>

static void to_def(const ts_body *b, tb_body_def *d)
{
    *d = tb_body_def_default();
    d->shape = (tb_shape)b->shape;
    d->dynamic = b->dynamic;
    d->position[0] = b->position.x;
    d->position[1] = b->position.y;
    d->angle = b->angle;
    d->velocity[0] = b->velocity.x;
    d->velocity[1] = b->velocity.y;
    d->spin = b->spin;
    d->radius = b->radius;
    d->half[0] = b->half.x;
    d->half[1] = b->half.y;
    d->a[0] = b->a.x;
    d->a[1] = b->a.y;
    d->b[0] = b->b.x;
    d->b[1] = b->b.y;
    d->count = (int)b->count;
    for (uint32_t i = 0; i < b->count && i < TS_MAX_POLYGON; i++) {
        d->points[2 * i] = b->points[i].x;
        d->points[2 * i + 1] = b->points[i].y;
    }
    d->density = b->density;
    d->friction = b->friction;
    d->restitution = b->restitution;
    d->fixed_rotation = b->fixed_rotation;
}

tb_world *tb_scene_build(const ts_scene *s, const tb_world_def *def, const char **why)
{
    if (!s || !def) {
        if (why) *why = "tb_scene_build: scene and def must not be NULL";
        return NULL;
    }
    tb_world_def d = *def;
    d.gravity[0] = s->gravity.x;
    d.gravity[1] = s->gravity.y;
    tb_world *w = tb_world_create(&d);
    bool good = w != NULL;
    for (uint32_t i = 0; good && i < s->body_count; i++) {
        tb_body_def bd;
        to_def(&s->bodies[i], &bd);
        good = tb_body_create(w, &bd) >= 0;
    }
    for (uint32_t i = 0; good && i < s->joint_count; i++) {
        const ts_joint *j = &s->joints[i];
        const double a[2] = {j->anchor_a.x, j->anchor_a.y}, b[2] = {j->anchor_b.x, j->anchor_b.y};
        good = tb_joint_create(w, (tb_joint)j->kind, j->a, j->b, a, b) >= 0;
    }
    if (!good) {
        if (why) *why = tb_last_error();
        tb_world_destroy(w);
        return NULL;
    }
    return w;
}

bool tb_scene_state(const tb_world *w, uint32_t body, ts_state *out)
{
    tb_body_state st;
    memset(out, 0, sizeof *out);
    if (!tb_body_state_get(w, (int)body, &st)) return false;
    out->position = (tt_vec2){st.position[0], st.position[1]};
    out->angle = st.angle;
    out->velocity = (tt_vec2){st.velocity[0], st.velocity[1]};
    out->spin = st.spin;
    out->momentum = st.inertia * st.spin;
    return true;
}

double tb_scene_kinetic_per_kg(const tb_world *w)
{
    const double m = tb_world_mass(w);
    return m > 0 ? tb_world_kinetic_energy(w) / m : NAN;
}
