/* tether — the project's named scenes: the eight rigid-body cases the Box2D
 * cross-check compares, and the reference pours every comparison of piles
 * uses (issue 12). Each is data only; the engines build it their own way. */
#include "scene.h"

#include <math.h>
#include <string.h>

const char *const ts_scene_names[] = {"fall", "pendulum", "bounce", "slope", "spin", "pyramid", "discs", "pour", "pour100k", NULL};

static void add(ts_scene *s, const ts_body *b) { (void)ts_scene_add_body(s, b, NULL); }

/* Floor top at y = 0, `half_w` either side of x = 0, as a static box so both
 * engines meet a solid rather than a one-sided line. */
static void ground(ts_scene *s, double half_w, double friction, double restitution)
{
    ts_body g = ts_box(false, (tt_vec2){0, -0.5}, half_w, 0.5, 0);
    g.friction = friction;
    g.restitution = restitution;
    add(s, &g);
}

void ts_scene_pour(ts_scene *s, uint32_t n, double width)
{
    ts_scene_init(s, n == 100000 && width == 316 ? "pour100k" : "pour");
    s->steps = 1200;
    const double h = width / 2;
    ground(s, h + 1, 0.3, 0);
    ts_body wall = ts_box(false, (tt_vec2){-h - 0.5, 200}, 0.5, 200, 0);
    add(s, &wall);
    wall.position.x = h + 0.5;
    add(s, &wall);
    /* 89 for the 100-wide box, 286 for 316; at least one, however narrow the box */
    const uint32_t cols = width >= 3.3 && width <= 1e6 ? (uint32_t)floor(width / 1.1) - 1 : 1;
    ts_body c = ts_circle(true, (tt_vec2){0, 0}, 0.5);
    for (uint32_t i = 0; i < n; i++) {
        const uint32_t row = i / cols, col = i % cols;
        c.position = (tt_vec2){-((double)cols - 1) * 1.1 / 2 + col * 1.1 + (row % 2) * 0.05, 0.55 + row * 1.1};
        add(s, &c);
    }
}

bool ts_scene_pour_lifted(ts_scene *s, uint32_t n, double width, double lift, const char *name, double *top,
                          const char **why)
{
    ts_scene pour;
    ts_scene_pour(&pour, n, width);
    ts_scene_init(s, name);
    s->gravity = pour.gravity;
    s->dt = pour.dt;
    s->steps = pour.steps;
    *top = 0;
    bool ok = true;
    for (uint32_t i = 0; i < pour.body_count && ok; i++) {
        ts_body c = pour.bodies[i];
        if (!c.dynamic) continue; /* the box: the caller's container stands for it */
        c.position.y += lift;
        *top = fmax(*top, c.position.y + 5);
        ok = ts_scene_add_body(s, &c, why) >= 0;
    }
    ts_scene_free(&pour);
    if (!ok) ts_scene_free(s);
    return ok;
}

void ts_scene_slope(ts_scene *s, double degrees, double mu)
{
    ts_scene_init(s, "slope");
    s->steps = 120;
    const double a = degrees * M_PI / 180, ca = cos(a), sa = sin(a);
    /* the slope's top face passes through the origin; the box sits on it there */
    ts_body slope = ts_box(false, (tt_vec2){0.5 * sa, -0.5 * ca}, 20, 0.5, a);
    slope.friction = mu;
    add(s, &slope);
    ts_body box = ts_box(true, (tt_vec2){-0.5 * sa, 0.5 * ca}, 0.5, 0.5, a);
    box.friction = mu;
    add(s, &box);
}

/* 1. a box dropped from rest and one thrown, with no ground: 1 s. */
static void fall(ts_scene *s)
{
    ts_scene_init(s, "fall");
    ts_body b = ts_box(true, (tt_vec2){-5, 10}, 0.5, 0.5, 0);
    add(s, &b);
    b.position = (tt_vec2){5, 10};
    b.velocity = (tt_vec2){3, 8};
    add(s, &b);
}

/* 2. a bob of radius 0.1 on a 1 m arm from a fixed pivot, let go at 30°: 60 s. */
static void pendulum(ts_scene *s)
{
    ts_scene_init(s, "pendulum");
    s->steps = 3600;
    const double a = 30 * M_PI / 180;
    ts_body bob = ts_circle(true, (tt_vec2){sin(a), 2 - cos(a)}, 0.1);
    add(s, &bob);
    ts_joint j = {TS_REVOLUTE, TS_GROUND, 0, {0, 2}, {0, 2}};
    (void)ts_scene_add_joint(s, &j, NULL);
}

/* 3. a 1 × 1 box dropped from 2 m onto the ground, restitution 0.5 on both: 3 s. */
static void bounce(ts_scene *s)
{
    ts_scene_init(s, "bounce");
    s->steps = 180;
    ground(s, 20, 0.3, 0.5);
    ts_body b = ts_box(true, (tt_vec2){0, 2.5}, 0.5, 0.5, 0);
    b.restitution = 0.5;
    add(s, &b);
}

/* 5. a 2 × 1 box thrown up with spin 3 rad/s, no ground: 2 s. */
static void spin(ts_scene *s)
{
    ts_scene_init(s, "spin");
    s->steps = 120;
    ts_body b = ts_box(true, (tt_vec2){0, 0}, 1, 0.5, 0);
    b.velocity = (tt_vec2){2, 8};
    b.spin = 3;
    add(s, &b);
}

/* 6. ten rows of 1 × 1 boxes, 1.1 apart in a row, stacked touching: 10 s. */
static void pyramid(ts_scene *s, int rows)
{
    ts_scene_init(s, "pyramid");
    s->steps = 600;
    ground(s, 20, 0.6, 0);
    for (int r = 0; r < rows; r++)
        for (int i = 0; i < rows - r; i++) {
            ts_body b = ts_box(true, (tt_vec2){(i - (rows - r - 1) / 2.0) * 1.1, 0.5 + r}, 0.5, 0.5, 0);
            b.friction = 0.6;
            add(s, &b);
        }
}

/* 7. the pyramid in discs that do not turn, tether's particles: radius 0.5,
 * friction 0.3 (the pours'), the bottom row 1.02 apart, each row resting in
 * the one below: 10 s. Without friction between the discs the bottom row is
 * wedged apart and the pyramid falls; Box2D's stands. */
static void discs(ts_scene *s, int rows)
{
    ts_scene_init(s, "discs");
    s->steps = 600;
    ground(s, 20, 0.3, 0);
    const double gap = 1.02, up = sqrt(1.0 - 0.25 * gap * gap);
    for (int r = 0; r < rows; r++)
        for (int i = 0; i < rows - r; i++) {
            ts_body b = ts_circle(true, (tt_vec2){(i - (rows - r - 1) / 2.0) * gap, 0.5 + r * up}, 0.5);
            b.friction = 0.3;
            b.fixed_rotation = true;
            add(s, &b);
        }
}

bool ts_scene_named(ts_scene *s, const char *name, bool quick)
{
    if (!name) return false;
    if (!strcmp(name, "fall")) fall(s);
    else if (!strcmp(name, "pendulum")) pendulum(s);
    else if (!strcmp(name, "bounce")) bounce(s);
    else if (!strcmp(name, "slope")) ts_scene_slope(s, 20, 0.5);
    else if (!strcmp(name, "spin")) spin(s);
    else if (!strcmp(name, "pyramid")) pyramid(s, 10);
    else if (!strcmp(name, "discs")) discs(s, 10);
    /* quick pour: 1 000 circles in a box √10 times narrower, the rule that makes the 100 k box 316 wide */
    else if (!strcmp(name, "pour")) quick ? ts_scene_pour(s, 1000, 31.6) : ts_scene_pour(s, 10000, 100);
    else if (!strcmp(name, "pour100k")) ts_scene_pour(s, 100000, 316);
    else return false;
    if (quick && strcmp(name, "pour") && s->steps > 600) s->steps = 600;
    return true;
}
