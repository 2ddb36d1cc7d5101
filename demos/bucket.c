/* demos/bucket.c — a small complete game on the installed libtether: sand
 * pours from a spout that wanders; move the bucket (arrow keys, A/D or the
 * mouse) to catch it. Pegs scatter the stream; what you catch is the bar at
 * the top, what you spill the bar below it. Space restarts, Esc quits.
 *
 * It uses only the public headers and its own drawing (SDL_Renderer), and
 * builds against an installed copy:
 *
 *     cc -std=c11 bucket.c $(pkg-config --cflags --libs tether sdl2) -lm -o bucket
 *
 * `--frames N` plays N frames on its own (the bucket chases the stream) and
 * prints the world's hash, so a test can run it headless
 * (SDL_VIDEODRIVER=dummy) and compare; `--screenshot F.bmp` saves the last
 * frame. Every frame is one fixed step of 1/60 s: the same input gives the
 * same world, bit for bit, on every machine. */
#include <SDL.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <tether.h>

enum { W = 800, H = 600, MAX_GRAINS = 1500, FRAMES_PER_GRAIN = 2 };
static const double SCALE = 50.0;                  /* pixels per metre */
static const double BUCKET_HALF = 1.0, BUCKET_DEPTH = 1.4, BUCKET_Y = 1.0;
static const double PEGS[][2] = { { -4, 7 }, { -1.5, 6.2 }, { 1.5, 6.2 }, { 4, 7 }, { 0, 8 } };

typedef struct game {
    tt_world *world;
    tt_shape bucket;
    double bucket_x;
    tt_particle grains[MAX_GRAINS];
    int ngrains, caught, spilled;
    long frame;
} game;

/* World coordinates (metres, y up, origin at the bottom centre) to pixels. */
static SDL_FPoint to_screen(tt_vec2 p)
{
    return (SDL_FPoint){ (float)(W / 2 + p.x * SCALE), (float)(H - p.y * SCALE) };
}

static double spout_x(long frame)
{
    return 5.0 * SDL_sin((double)frame * 0.011) * SDL_cos((double)frame * 0.0041);
}

static void game_start(game *g)
{
    tt_world_def wd = tt_world_def_default();
    wd.substeps = 2;
    g->world = tt_world_create(&wd);
    if (g->world == NULL) {
        fprintf(stderr, "bucket: %s\n", tt_last_error(NULL));
        exit(1);
    }
    tt_collision_settings cs = tt_collision_settings_default();
    cs.restitution = 0.1;
    tt_world_set_collision(g->world, &cs);

    tt_shape_def floor = tt_shape_def_default();       /* a segment across the bottom */
    floor.a = (tt_vec2){ -8, 0.1 };
    floor.b = (tt_vec2){ 8, 0.1 };
    tt_shape_create(g->world, &floor);
    for (size_t i = 0; i < sizeof PEGS / sizeof PEGS[0]; i++) {
        tt_shape_def peg = tt_shape_def_default();
        peg.type = TT_SHAPE_CIRCLE;
        peg.position = (tt_vec2){ PEGS[i][0], PEGS[i][1] };
        peg.radius = 0.35;
        peg.restitution = 0.3;
        tt_shape_create(g->world, &peg);
    }
    /* The bucket: a U-shaped chain in its own frame, moved kinematically,
     * so it carries the sand inside it. */
    const tt_vec2 u[] = { { -BUCKET_HALF, BUCKET_DEPTH }, { -BUCKET_HALF * 0.8, 0 },
                          { BUCKET_HALF * 0.8, 0 }, { BUCKET_HALF, BUCKET_DEPTH } };
    tt_shape_def b = tt_shape_def_default();
    b.type = TT_SHAPE_CHAIN;
    b.points = u;
    b.count = 4;
    b.position = (tt_vec2){ 0, BUCKET_Y };
    g->bucket = tt_shape_create(g->world, &b);
    g->bucket_x = 0;
    g->ngrains = g->caught = g->spilled = 0;
    g->frame = 0;
}

/* One frame: a new grain from the spout, the bucket moved towards
 * target_x (at most 8 m/s), one step, then the grains that left the play
 * field are counted, caught or spilled, and removed. */
static void game_update(game *g, double target_x)
{
    const double dt = 1.0 / 60;
    if (g->frame % FRAMES_PER_GRAIN == 0 && g->ngrains < MAX_GRAINS) {
        tt_particle_def pd = tt_particle_def_default();
        pd.position = (tt_vec2){ spout_x(g->frame) + 0.02 * (double)(g->frame % 7), 11.5 };
        pd.velocity = (tt_vec2){ 0, -1 };
        pd.radius = 0.09;
        pd.mass = 0.01;
        tt_particle p = tt_particle_create(g->world, &pd);
        if (tt_particle_is_valid(g->world, p))
            g->grains[g->ngrains++] = p;
    }
    double dx = target_x - g->bucket_x, max_dx = 8.0 * dt;
    g->bucket_x += dx > max_dx ? max_dx : dx < -max_dx ? -max_dx : dx;
    if (g->bucket_x < -7) g->bucket_x = -7;
    if (g->bucket_x > 7) g->bucket_x = 7;
    tt_shape_set_transform(g->world, g->bucket, (tt_vec2){ g->bucket_x, BUCKET_Y }, 0);
    tt_world_step(g->world, dt);

    for (int i = 0; i < g->ngrains;) {
        tt_vec2 x;
        tt_particle_get_position(g->world, g->grains[i], &x);
        bool in_bucket = x.y > BUCKET_Y && x.y < BUCKET_Y + BUCKET_DEPTH && x.x > g->bucket_x - BUCKET_HALF &&
                         x.x < g->bucket_x + BUCKET_HALF;
        bool settled = in_bucket && x.y < BUCKET_Y + 0.6;
        if (settled || x.y < 0.4 || x.x < -8.5 || x.x > 8.5) {
            if (settled) g->caught++; else g->spilled++;
            tt_particle_destroy(g->world, g->grains[i]);
            g->grains[i] = g->grains[--g->ngrains];
        } else {
            i++;
        }
    }
    g->frame++;
}

/* Where the autopilot steers: under the lowest grain still above the bucket's rim. */
static double autopilot(const game *g)
{
    double best_y = 1e9, x_at = g->bucket_x;
    for (int i = 0; i < g->ngrains; i++) {
        tt_vec2 x;
        tt_particle_get_position(g->world, g->grains[i], &x);
        if (x.y > BUCKET_Y + BUCKET_DEPTH && x.y < best_y) {
            best_y = x.y;
            x_at = x.x;
        }
    }
    return x_at;
}

static void fill_circle(SDL_Renderer *r, SDL_FPoint c, float rad, SDL_Color col)
{
    enum { N = 16 };
    SDL_Vertex v[N + 1];
    int idx[3 * N];
    v[0] = (SDL_Vertex){ c, col, { 0, 0 } };
    for (int i = 0; i < N; i++) {
        double a = 6.283185307179586 * i / N;
        v[i + 1] = (SDL_Vertex){ { c.x + rad * (float)SDL_cos(a), c.y + rad * (float)SDL_sin(a) }, col, { 0, 0 } };
        idx[3 * i] = 0;
        idx[3 * i + 1] = i + 1;
        idx[3 * i + 2] = (i + 1) % N + 1;
    }
    SDL_RenderGeometry(r, NULL, v, N + 1, idx, 3 * N);
}

static void game_draw(const game *g, SDL_Renderer *r)
{
    SDL_SetRenderDrawColor(r, 24, 26, 34, 255);
    SDL_RenderClear(r);
    tt_shape shapes[16];
    uint32_t ns = tt_world_list_shapes(g->world, shapes, 16);
    for (uint32_t i = 0; i < ns; i++) {
        tt_shape_type type;
        tt_shape_get_type(g->world, shapes[i], &type);
        if (type == TT_SHAPE_CIRCLE) {
            tt_vec2 pos;
            double angle;
            tt_shape_get_transform(g->world, shapes[i], &pos, &angle);
            fill_circle(r, to_screen(pos), (float)(0.35 * SCALE), (SDL_Color){ 120, 130, 150, 255 });
            continue;
        }
        tt_vec2 pts[8];
        uint32_t n = 0;
        bool closed = false;
        tt_shape_get_outline(g->world, shapes[i], pts, 8, &n, &closed);
        SDL_FPoint sp[9];
        for (uint32_t k = 0; k < n && k < 8; k++) sp[k] = to_screen(pts[k]);
        if (closed && n < 8) sp[n++] = sp[0];
        bool bucket = shapes[i].index == g->bucket.index && shapes[i].gen == g->bucket.gen;
        SDL_SetRenderDrawColor(r, bucket ? 240 : 160, bucket ? 180 : 160, bucket ? 60 : 170, 255);
        for (int t = 0; t < 9; t++) { /* three pixels thick */
            float ox = (float)(t % 3 - 1), oy = (float)(t / 3 - 1);
            for (uint32_t k = 0; k + 1 < n; k++)
                SDL_RenderDrawLineF(r, sp[k].x + ox, sp[k].y + oy, sp[k + 1].x + ox, sp[k + 1].y + oy);
        }
    }
    SDL_SetRenderDrawColor(r, 230, 200, 120, 255);
    for (int i = 0; i < g->ngrains; i++) {
        tt_vec2 x;
        tt_particle_get_position(g->world, g->grains[i], &x);
        SDL_FPoint s = to_screen(x);
        SDL_RenderFillRectF(r, &(SDL_FRect){ s.x - 4, s.y - 4, 8, 8 });
    }
    SDL_FPoint spout = to_screen((tt_vec2){ spout_x(g->frame), 11.7 });
    SDL_SetRenderDrawColor(r, 200, 90, 70, 255);
    SDL_RenderFillRectF(r, &(SDL_FRect){ spout.x - 10, spout.y - 6, 20, 12 });
    SDL_SetRenderDrawColor(r, 90, 200, 110, 255); /* caught */
    SDL_RenderFillRectF(r, &(SDL_FRect){ 10, 10, (float)(g->caught % 780), 8 });
    SDL_SetRenderDrawColor(r, 200, 80, 80, 255);  /* spilled */
    SDL_RenderFillRectF(r, &(SDL_FRect){ 10, 22, (float)(g->spilled % 780), 8 });
}

static void save_screenshot(SDL_Renderer *r, const char *path)
{
    SDL_Surface *s = SDL_CreateRGBSurfaceWithFormat(0, W, H, 32, SDL_PIXELFORMAT_ARGB8888);
    if (s == NULL) return;
    if (SDL_RenderReadPixels(r, NULL, SDL_PIXELFORMAT_ARGB8888, s->pixels, s->pitch) == 0 && SDL_SaveBMP(s, path) == 0)
        printf("bucket: screenshot %s\n", path);
    SDL_FreeSurface(s);
}

int main(int argc, char **argv)
{
    long frames = -1; /* -1: play until the window closes */
    const char *shot = NULL;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (strcmp(argv[i], "--frames") == 0) frames = strtol(argv[i + 1], NULL, 10);
        else if (strcmp(argv[i], "--screenshot") == 0) shot = argv[i + 1];
    }
    if (SDL_Init(SDL_INIT_VIDEO) != 0) {
        fprintf(stderr, "bucket: %s\n", SDL_GetError());
        return 1;
    }
    SDL_Window *win = SDL_CreateWindow("tether: bucket", SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, W, H, 0);
    SDL_Renderer *r = win ? SDL_CreateRenderer(win, -1, frames >= 0 ? SDL_RENDERER_SOFTWARE : 0) : NULL;
    if (r == NULL) {
        fprintf(stderr, "bucket: %s\n", SDL_GetError());
        return 1;
    }
    game g;
    game_start(&g);
    double target = 0;
    bool running = true;
    while (running && (frames < 0 || g.frame < frames)) {
        SDL_Event e;
        while (SDL_PollEvent(&e)) {
            if (e.type == SDL_QUIT || (e.type == SDL_KEYDOWN && e.key.keysym.sym == SDLK_ESCAPE)) running = false;
            if (e.type == SDL_MOUSEMOTION) target = (e.motion.x - W / 2) / SCALE;
            if (e.type == SDL_KEYDOWN && e.key.keysym.sym == SDLK_SPACE) {
                tt_world_destroy(g.world);
                game_start(&g);
            }
        }
        const Uint8 *keys = SDL_GetKeyboardState(NULL);
        if (keys[SDL_SCANCODE_LEFT] || keys[SDL_SCANCODE_A]) target = g.bucket_x - 1;
        if (keys[SDL_SCANCODE_RIGHT] || keys[SDL_SCANCODE_D]) target = g.bucket_x + 1;
        game_update(&g, frames >= 0 ? autopilot(&g) : target);
        game_draw(&g, r);
        if (shot != NULL && g.frame == frames) save_screenshot(r, shot); /* read back before it is shown */
        SDL_RenderPresent(r);
        if (frames < 0) SDL_Delay(16); /* about 60 frames a second; the step stays fixed */
    }
    printf("bucket: %ld frames, caught %d, spilled %d, hash %016llx\n", g.frame, g.caught, g.spilled,
           (unsigned long long)tt_world_hash(g.world));
    tt_world_destroy(g.world);
    SDL_DestroyRenderer(r);
    SDL_DestroyWindow(win);
    SDL_Quit();
    return 0;
}
