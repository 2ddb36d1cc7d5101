// tether — the Box2D 2.4.1 side of the collision benchmark: n circles of
// radius r settling in a box `width` wide, 8 velocity / 3 position
// iterations, continuous physics off, sleeping allowed (its best setting);
// the final centres into xy (2n doubles) when it is not NULL.
// Linked into the bench binary only; the engine never links Box2D.
#include <box2d/box2d.h>

#include <algorithm>
#include <chrono>
#include <vector>

extern "C" double box2d_settle_ms(int n, double radius, double width, int steps, double *max_step_ms, double *xy)
{
    b2World world(b2Vec2(0.0f, -9.81f));
    world.SetContinuousPhysics(false);
    world.SetAllowSleeping(true);
    b2BodyDef gd;
    b2Body *ground = world.CreateBody(&gd);
    const float hw = (float)(width / 2);
    b2PolygonShape box;
    box.SetAsBox(hw + 1.0f, 0.5f, b2Vec2(0.0f, -0.5f), 0.0f); // floor, top at y = 0
    ground->CreateFixture(&box, 0.0f);
    box.SetAsBox(0.5f, 500.0f, b2Vec2(-hw - 0.5f, 500.0f), 0.0f); // walls, inner faces at ±hw
    ground->CreateFixture(&box, 0.0f);
    box.SetAsBox(0.5f, 500.0f, b2Vec2(hw + 0.5f, 500.0f), 0.0f);
    ground->CreateFixture(&box, 0.0f);

    b2CircleShape circle;
    circle.m_radius = (float)radius;
    b2FixtureDef fd;
    fd.shape = &circle;
    fd.density = 1.0f;
    fd.friction = 0.6f;
    const int cols = (int)(width / (2.4 * radius));
    std::vector<b2Body *> bodies;
    for (int i = 0; i < n; i++) {
        b2BodyDef bd;
        bd.type = b2_dynamicBody;
        double x = -width / 2 + 1.2 * radius + (i % cols) * 2.4 * radius + ((i / cols) % 2) * 0.3 * radius;
        double y = radius * 1.2 + (i / cols) * 2.4 * radius;
        bd.position.Set((float)x, (float)y);
        b2Body *b = world.CreateBody(&bd);
        b->CreateFixture(&fd);
        bodies.push_back(b);
    }
    double total = 0, worst = 0;
    for (int s = 0; s < steps; s++) {
        auto t0 = std::chrono::steady_clock::now();
        world.Step(1.0f / 60.0f, 8, 3);
        double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        total += ms;
        worst = std::max(worst, ms);
    }
    for (int i = 0; xy && i < n; i++) {
        xy[2 * i] = bodies[i]->GetPosition().x;
        xy[2 * i + 1] = bodies[i]->GetPosition().y;
    }
    if (max_step_ms) *max_step_ms = worst;
    return total / steps;
}
