// tether — the Box2D 2.4.1 side of the collision benchmark: n circles of
// radius r settling in a box `width` wide, 8 velocity / 3 position
// iterations, continuous physics off, sleeping allowed (its best setting).
// Linked into the bench binary only; the engine never links Box2D.
#include <box2d/box2d.h>

#include <chrono>
#include <vector>

// The scene as an opaque handle, so the bench can step it in turn with
// tether's and both see the same machine load.
struct box2d_scene {
    b2World world{b2Vec2(0.0f, -9.81f)};
    std::vector<b2Body *> bodies;
};

extern "C" box2d_scene *box2d_scene_create(int n, double radius, double width)
{
    box2d_scene *sc = new box2d_scene;
    b2World &world = sc->world;
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
    for (int i = 0; i < n; i++) {
        b2BodyDef bd;
        bd.type = b2_dynamicBody;
        double x = -width / 2 + 1.2 * radius + (i % cols) * 2.4 * radius + ((i / cols) % 2) * 0.3 * radius;
        double y = radius * 1.2 + (i / cols) * 2.4 * radius;
        bd.position.Set((float)x, (float)y);
        b2Body *b = world.CreateBody(&bd);
        b->CreateFixture(&fd);
        sc->bodies.push_back(b);
    }
    return sc;
}

// One step of 1/60 s; returns its wall time, ms.
extern "C" double box2d_scene_step(box2d_scene *sc)
{
    auto t0 = std::chrono::steady_clock::now();
    sc->world.Step(1.0f / 60.0f, 8, 3);
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// The centres into xy (2n doubles).
extern "C" void box2d_scene_positions(const box2d_scene *sc, double *xy)
{
    for (size_t i = 0; i < sc->bodies.size(); i++) {
        xy[2 * i] = sc->bodies[i]->GetPosition().x;
        xy[2 * i + 1] = sc->bodies[i]->GetPosition().y;
    }
}

extern "C" void box2d_scene_destroy(box2d_scene *sc) { delete sc; }
