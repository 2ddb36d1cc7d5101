/* tests/fuzz/fuzz_c_world.c — wrappers of tether/base.h and tether/world.h:
 * names and strings, worlds made from garbage defs, settings, steps with
 * random dt, explosions and the world's reads. */
#include "fuzz_c.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* A pointer the library returns must point at a string (NULL never). */
static void string_ok(fz *f, const char *s, const char *what)
{
    if (!s) fz_fail(f, "%s returned NULL", what);
    fz_log_more(f, " -> \"%.40s\"", s);
}

static void c_integrator_name(fz *f)
{
    tt_integrator i = (tt_integrator)fz_enum(f, TT_INTEGRATOR_COUNT);
    fz_log(f, "tt_integrator_name(%d)", (int)i);
    FZ_HIT(f, tt_integrator_name);
    string_ok(f, tt_integrator_name(i), "tt_integrator_name");
}

static void c_integrator_from_name(fz *f)
{
    static const char *names[] = { "euler", "symplectic_euler", "leapfrog", "verlet", "rk4", "", "RK4", "verlet ",
                                   "eulerx", "\xff\xfe", NULL };
    const char *name = names[fz_below(f, sizeof names / sizeof names[0])];
    tt_integrator out = TT_INTEGRATOR_COUNT;
    bool null_out = fz_chance(f, 5);
    fz_log(f, "tt_integrator_from_name(\"%s\", %s)", name ? name : "(NULL)", null_out ? "NULL" : "&out");
    FZ_HIT(f, tt_integrator_from_name);
    tt_result r = tt_integrator_from_name(name, null_out ? NULL : &out);
    fz_res(f, r);
    if (r == TT_OK && (unsigned)out >= TT_INTEGRATOR_COUNT) fz_fail(f, "tt_integrator_from_name gave %d", (int)out);
    if (r == TT_OK && (null_out || !name)) fz_fail(f, "tt_integrator_from_name accepted a NULL pointer");
}

static void c_result_string(fz *f)
{
    tt_result r = (tt_result)fz_enum(f, TT_ESTATE + 1);
    fz_log(f, "tt_result_string(%d)", (int)r);
    FZ_HIT(f, tt_result_string);
    string_ok(f, tt_result_string(r), "tt_result_string");
}

static void c_version(fz *f)
{
    fz_log(f, "tt_version()");
    FZ_HIT(f, tt_version);
    string_ok(f, tt_version(), "tt_version");
}

static void c_last_error(fz *f)
{
    tt_world *w = fz_world_any(f);
    fz_log(f, "tt_last_error(%s)", fz_wn(f, w));
    FZ_HIT(f, tt_last_error);
    string_ok(f, tt_last_error(w), "tt_last_error");
}

static void c_world_def_default(fz *f)
{
    fz_log(f, "tt_world_def_default()");
    FZ_HIT(f, tt_world_def_default);
    f->names++; /* it takes a world tag */
    tt_world_def d = tt_world_def_default();
    tt_world *w = tt_world_create(&d);
    if (!w) fz_fail(f, "the default world def is refused: %s", tt_last_error(NULL));
    tt_world_destroy(w);
}

/* A def with a few fields changed, each plausible or hostile. */
static tt_world_def world_def(fz *f)
{
    tt_world_def d = tt_world_def_default();
    for (unsigned k = fz_below(f, 4); k > 0; k--) {
        switch (fz_below(f, 13)) {
        case 0: d.gravity = fz_vec(f, -20, 20); break;
        case 1: d.integrator = (tt_integrator)fz_enum(f, TT_INTEGRATOR_COUNT); break;
        case 2: d.damping = fz_real(f, 0, 2); break;
        case 3: d.wind = fz_vec(f, -5, 5); break;
        case 4: d.dt_hint = fz_dt(f); break;
        case 5: d.capacity = fz_count(f, 0, 5000); break;
        case 6: d.max_particles = fz_count(f, 1, 20000); break;
        case 7: d.substeps = fz_count(f, 1, 8); break;
        case 8: d.iterations = fz_count(f, 1, 30); break;
        case 9: d.tolerance = fz_real(f, 0, 1e-3); break;
        case 10: { /* fixed-point positions: a good quantum, a tiny range, a coarse one, one refused */
            static const double q[] = { TT_FIXED_POINT_QUANTUM, 0x1p-50, 0x1p-4, 0.3 };
            d.fixed_point = q[fz_below(f, 4)];
            break;
        }
        case 11: d.spin = fz_chance(f, 50); break;
        default: d.order = (tt_solver_order)fz_enum(f, 2); break;
        }
    }
    return d;
}

static void c_world_create(fz *f)
{
    tt_world_def d = world_def(f);
    bool null_def = fz_chance(f, 5);
    int slot = -1;
    for (int i = 1; i < FZ_WORLDS && slot < 0; i++)
        if (!f->slots[i].w) slot = i;
    fz_log(f, "w%d = tt_world_create(%s) /* gravity %s, integrator %d, damping %s, wind %s, dt_hint %s, capacity %u, "
              "max_particles %u, substeps %u, iterations %u, tolerance %s, order %d, fixed_point %s, spin %d */",
           f->names, null_def ? "NULL" : "&def", fz_v(d.gravity), (int)d.integrator, fz_d(d.damping), fz_v(d.wind),
           fz_d(d.dt_hint), d.capacity, d.max_particles, d.substeps, d.iterations, fz_d(d.tolerance), (int)d.order,
           fz_d(d.fixed_point), (int)d.spin);
    FZ_HIT(f, tt_world_create);
    tt_world *w = tt_world_create(null_def ? NULL : &d);
    fz_log_more(f, " -> %s", w ? "world" : "NULL");
    if (!w) {
        if (null_def) fz_fail(f, "tt_world_create(NULL) failed: %s", tt_last_error(NULL));
        return;
    }
    f->names++;
    if (slot < 0) { /* every slot taken: made and unmade at once */
        tt_world_destroy(w);
        return;
    }
    memset(&f->slots[slot], 0, sizeof f->slots[slot]);
    f->slots[slot].w = w;
    f->slots[slot].name = f->names - 1;
}

/* A destroyed world's handles live on as foreign handles. */
static void retire(fz *f, int slot)
{
    fz_world *s = &f->slots[slot];
    tt_world_destroy(s->w);
    for (int k = 1; k < FZ_KINDS; k++) {
        for (uint32_t i = 0; i < s->live[k].n && i < 64; i++) fz_list_add(&f->foreign[k], FZ_FOREIGN_CAP, s->live[k].h[i], f);
        fz_list_free(&s->live[k]);
        fz_list_free(&s->stale[k]);
    }
    memset(s, 0, sizeof *s);
}

/* The world in slot made afresh (default def): scenes start from one now
 * and then, so a world can hold nothing but a scene's pattern (a row whose
 * particles all share one y, as finding 1 needed). */
tt_world *fz_world_fresh(fz *f, int slot)
{
    fz_log(f, "tt_world_destroy(w%d); w%d = tt_world_create(NULL)", f->slots[slot].name, f->names);
    FZ_HIT(f, tt_world_destroy);
    FZ_HIT(f, tt_world_create);
    retire(f, slot);
    f->slots[slot].w = tt_world_create(NULL);
    f->slots[slot].name = f->names++;
    if (!f->slots[slot].w) fz_fail(f, "tt_world_create(NULL) failed: %s", tt_last_error(NULL));
    return f->slots[slot].w;
}

static void c_world_destroy(fz *f)
{
    int slot = (int)fz_below(f, FZ_WORLDS + 1);
    if (slot == FZ_WORLDS || !f->slots[slot].w) {
        fz_log(f, "tt_world_destroy(NULL)");
        FZ_HIT(f, tt_world_destroy);
        tt_world_destroy(NULL);
        return;
    }
    fz_log(f, "tt_world_destroy(w%d)", f->slots[slot].name);
    FZ_HIT(f, tt_world_destroy);
    retire(f, slot);
}

void fz_world_too_big(fz *f)
{
    for (int i = 0; i < FZ_WORLDS; i++) {
        /* shapes too: masks turned into chains pile them up, and every call hashes them */
        if (!f->slots[i].w || (tt_world_particle_count(f->slots[i].w) <= 2500 && tt_world_shape_count(f->slots[i].w) <= 1000))
            continue;
        fz_log(f, "tt_world_destroy(w%d) /* over 2500 particles or 1000 shapes: a fresh start */", f->slots[i].name);
        FZ_HIT(f, tt_world_destroy);
        retire(f, i);
    }
}

/* A step that would take too long (10 000 sweeps of thousands of
 * particles and contacts) becomes a call that brings substeps or iterations
 * down: the fuzzer's time goes to many calls, not to a few long steps. */
static bool too_costly(fz *f, tt_world *w)
{
    tt_collision_stats cs = { 0 };
    tt_world_get_collision_stats(w, &cs);
    double n = tt_world_particle_count(w) + 2.0 * tt_world_constraint_count(w) + tt_world_spring_count(w) + 16.0 +
               4.0 * (cs.pair_contacts + cs.shape_contacts);
    uint32_t most = 0, sub_n = tt_world_get_substeps(w);
    if (tt_world_get_travel(w, &most) != 0.0 && most > sub_n) sub_n = most; /* what substeps by speed may ask */
    double cost = n * sub_n * tt_world_get_iterations(w);
    if (cost < 4e5) return false;
    uint32_t v = 1 + fz_below(f, 12);
    bool sub = tt_world_get_substeps(w) > 8 && fz_chance(f, 50);
    fz_log(f, "%s(%s, %u) /* the step would cost %.3g */", sub ? "tt_world_set_substeps" : "tt_world_set_iterations",
           fz_wn(f, w), v, cost);
    if (sub) FZ_HIT(f, tt_world_set_substeps);
    else FZ_HIT(f, tt_world_set_iterations);
    fz_res(f, sub ? tt_world_set_substeps(w, v) : tt_world_set_iterations(w, v));
    return true;
}

static void c_world_step(fz *f)
{
    tt_world *w = fz_world_pick(f);
    if (w && too_costly(f, w)) return;
    double dt = fz_dt(f);
    fz_log(f, "tt_world_step(%s, %s)", fz_wn(f, w), fz_d(dt));
    FZ_HIT(f, tt_world_step);
    fz_res(f, tt_world_step(w, dt));
    f->stepped = true;
}

#define SET_VEC(fn, lo, hi)                                                                         \
    static void c_##fn(fz *f)                                                                       \
    {                                                                                               \
        tt_world *w = fz_world_pick(f);                                                             \
        tt_vec2 v = fz_vec(f, lo, hi);                                                              \
        fz_log(f, #fn "(%s, %s)", fz_wn(f, w), fz_v(v));                                            \
        FZ_HIT(f, fn);                                                                              \
        fz_res(f, fn(w, v));                                                                        \
    }
#define SET_NUM(fn, type, draw, fmt)                                                                \
    static void c_##fn(fz *f)                                                                       \
    {                                                                                               \
        tt_world *w = fz_world_pick(f);                                                             \
        type v = (type)(draw);                                                                      \
        fz_log(f, #fn "(%s, " fmt ")", fz_wn(f, w), v);                                             \
        FZ_HIT(f, fn);                                                                              \
        fz_res(f, fn(w, v));                                                                        \
    }
#define GET_VAL(fn, check)                                                                          \
    static void c_##fn(fz *f)                                                                       \
    {                                                                                               \
        tt_world *w = fz_world_any(f);                                                              \
        fz_log(f, #fn "(%s)", fz_wn(f, w));                                                         \
        FZ_HIT(f, fn);                                                                              \
        check;                                                                                      \
    }

SET_VEC(tt_world_set_gravity, -20, 20)
SET_VEC(tt_world_set_wind, -5, 5)
SET_NUM(tt_world_set_integrator, tt_integrator, fz_enum(f, TT_INTEGRATOR_COUNT), "%d")
SET_NUM(tt_world_set_substeps, uint32_t, fz_count(f, 1, 8), "%u")
SET_NUM(tt_world_set_iterations, uint32_t, fz_count(f, 1, 40), "%u")
SET_NUM(tt_world_set_solver_order, tt_solver_order, fz_enum(f, 2), "%d")
GET_VAL(tt_world_get_gravity, fz_finite_vec(f, tt_world_get_gravity(w), "gravity"))
GET_VAL(tt_world_get_wind, fz_finite_vec(f, tt_world_get_wind(w), "wind"))
GET_VAL(tt_world_get_damping, fz_finite(f, tt_world_get_damping(w), "damping"))
GET_VAL(tt_world_get_tolerance, fz_finite(f, tt_world_get_tolerance(w), "tolerance"))
GET_VAL(tt_world_get_integrator, if (w && (unsigned)tt_world_get_integrator(w) >= TT_INTEGRATOR_COUNT) fz_fail(f, "bad integrator"))
GET_VAL(tt_world_get_substeps, if (w && (tt_world_get_substeps(w) - 1u) >= TT_MAX_SUBSTEPS) fz_fail(f, "bad substeps"))
GET_VAL(tt_world_get_iterations, if (w && (tt_world_get_iterations(w) - 1u) >= TT_MAX_ITERATIONS) fz_fail(f, "bad iterations"))
GET_VAL(tt_world_get_solver_order, if (w && (unsigned)tt_world_get_solver_order(w) > TT_JACOBI) fz_fail(f, "bad order"))
GET_VAL(tt_world_get_fixed_point, if (w && tt_world_get_fixed_point(w) != 0.0 && (tt_world_get_fixed_point(w) < 0x1p-60 || tt_world_get_fixed_point(w) > 0.5)) fz_fail(f, "bad fixed-point quantum"))
GET_VAL(tt_world_get_interpolation, if (!w && tt_world_get_interpolation(w)) fz_fail(f, "a NULL world keeps positions"))
GET_VAL(tt_world_hash, if (tt_world_hash(w) != tt_world_hash(w)) fz_fail(f, "two hashes of one state differ"))

/* Keeping the previous positions is not state: the hash must not move. */
static void c_world_set_interpolation(fz *f)
{
    tt_world *w = fz_world_pick(f);
    bool on = fz_chance(f, 2);
    fz_log(f, "tt_world_set_interpolation(%s, %s)", fz_wn(f, w), on ? "true" : "false");
    FZ_HIT(f, tt_world_set_interpolation);
    uint64_t h = w ? tt_world_hash(w) : 0;
    tt_result r = tt_world_set_interpolation(w, on);
    fz_res(f, r);
    if (w && tt_world_hash(w) != h) fz_fail(f, "tt_world_set_interpolation changed the hash");
    if (w && r == TT_OK && tt_world_get_interpolation(w) != on) fz_fail(f, "tt_world_get_interpolation disagrees");
}

static void c_world_set_damping(fz *f)
{
    tt_world *w = fz_world_pick(f);
    double v = fz_real(f, 0, 2);
    fz_log(f, "tt_world_set_damping(%s, %s)", fz_wn(f, w), fz_d(v));
    FZ_HIT(f, tt_world_set_damping);
    fz_res(f, tt_world_set_damping(w, v));
}

static void c_world_set_attractor(fz *f)
{
    tt_world *w = fz_world_pick(f);
    uint32_t slot = fz_chance(f, 5) ? fz_count(f, TT_MAX_ATTRACTORS, 100) : fz_below(f, TT_MAX_ATTRACTORS);
    tt_attractor a = {fz_vec(f, -20, 20), fz_chance(f, 30) ? 0.0 : fz_real(f, -50, 50),
                      fz_chance(f, 20) ? 0.0 : fz_real(f, 0, 2)};
    if (fz_chance(f, 5)) a.strength = fz_nasty(f);
    if (fz_chance(f, 5)) a.softening = fz_nasty(f);
    fz_log(f, "tt_world_set_attractor(%s, %u, {%s, %s, %s})", fz_wn(f, w), slot, fz_v(a.center), fz_d(a.strength), fz_d(a.softening));
    FZ_HIT(f, tt_world_set_attractor);
    fz_res(f, tt_world_set_attractor(w, slot, a));
}

static void c_world_get_attractor(fz *f)
{
    tt_world *w = fz_world_any(f);
    uint32_t slot = fz_below(f, TT_MAX_ATTRACTORS + 1);
    tt_attractor a;
    fz_log(f, "tt_world_get_attractor(%s, %u)", fz_wn(f, w), slot);
    FZ_HIT(f, tt_world_get_attractor);
    tt_result r = tt_world_get_attractor(w, slot, &a);
    fz_res(f, r);
    if (r == TT_OK) {
        fz_finite_vec(f, a.center, "attractor centre");
        fz_finite(f, a.strength, "attractor strength");
        if (!(a.softening >= 0.0)) fz_fail(f, "attractor softening %g", a.softening);
    }
}

static void c_world_set_tolerance(fz *f)
{
    tt_world *w = fz_world_pick(f);
    double v = fz_chance(f, 30) ? 0.0 : fz_real(f, 0, 1e-3);
    fz_log(f, "tt_world_set_tolerance(%s, %s)", fz_wn(f, w), fz_d(v));
    FZ_HIT(f, tt_world_set_tolerance);
    fz_res(f, tt_world_set_tolerance(w, v));
}

static void c_world_set_sleep(fz *f)
{
    tt_world *w = fz_world_pick(f);
    bool on = fz_chance(f, 70);
    double speed = fz_chance(f, 10) ? -1.0 : fz_real(f, 0, 1), time = fz_chance(f, 10) ? NAN : fz_real(f, 0, 2);
    fz_log(f, "tt_world_set_sleep(%s, %s, %s, %s)", fz_wn(f, w), on ? "true" : "false", fz_d(speed), fz_d(time));
    FZ_HIT(f, tt_world_set_sleep);
    fz_res(f, tt_world_set_sleep(w, on, speed, time));
}

static void c_world_set_travel(fz *f)
{
    tt_world *w = fz_world_pick(f);
    double travel = fz_chance(f, 30) ? 0.0 : fz_chance(f, 10) ? fz_nasty(f) : fz_real(f, 0, 2);
    uint32_t most = fz_chance(f, 5) ? 0 : fz_count(f, 1, 8);
    fz_log(f, "tt_world_set_travel(%s, %s, %u)", fz_wn(f, w), fz_d(travel), most);
    FZ_HIT(f, tt_world_set_travel);
    fz_res(f, tt_world_set_travel(w, travel, most));
}

static void c_world_get_travel(fz *f)
{
    tt_world *w = fz_world_any(f); /* a getter: no failure channel (0 for NULL) */
    uint32_t most = 0;
    fz_log(f, "tt_world_get_travel(%s)", fz_wn(f, w));
    FZ_HIT(f, tt_world_get_travel);
    double travel = tt_world_get_travel(w, &most);
    if (!(travel >= 0.0 && travel <= TT_MAX_VALUE) || most < 1 || most > TT_MAX_SUBSTEPS) fz_fail(f, "bad travel setting");
}

static void c_world_get_sleep(fz *f)
{
    tt_world *w = fz_world_any(f); /* a getter: no failure channel (false for NULL) */
    double speed, time;
    fz_log(f, "tt_world_get_sleep(%s)", fz_wn(f, w));
    FZ_HIT(f, tt_world_get_sleep);
    if (tt_world_get_sleep(w, &speed, &time)) {
        fz_finite(f, speed, "a sleep speed");
        fz_finite(f, time, "a sleep time");
    }
}

static void c_world_explode(fz *f)
{
    tt_world *w = fz_world_pick(f);
    tt_vec2 c = fz_point(f);
    double r = fz_real(f, 0, 50), imp = fz_real(f, -100, 100);
    fz_log(f, "tt_world_explode(%s, %s, %s, %s)", fz_wn(f, w), fz_v(c), fz_d(r), fz_d(imp));
    FZ_HIT(f, tt_world_explode);
    fz_res(f, tt_world_explode(w, c, r, imp));
}

static void c_world_get_stats(fz *f)
{
    tt_world *w = fz_world_pick(f);
    f->readonly = true;
    tt_stats st;
    bool null_out = fz_chance(f, 4);
    fz_log(f, "tt_world_get_stats(%s, %s)", fz_wn(f, w), null_out ? "NULL" : "&stats");
    FZ_HIT(f, tt_world_get_stats);
    tt_result r = tt_world_get_stats(w, null_out ? NULL : &st);
    fz_res(f, r);
    if (r == TT_OK && null_out) fz_fail(f, "tt_world_get_stats accepted a NULL out");
    if (r == TT_OK) {
        fz_finite(f, st.time, "stats.time");
        fz_finite(f, st.max_error, "stats.max_error");
    }
}

static void c_world_get_energy(fz *f)
{
    tt_world *w = fz_world_pick(f);
    f->readonly = true;
    tt_energy e;
    bool null_out = fz_chance(f, 4);
    fz_log(f, "tt_world_get_energy(%s, %s)", fz_wn(f, w), null_out ? "NULL" : "&energy");
    FZ_HIT(f, tt_world_get_energy);
    tt_result r = tt_world_get_energy(w, null_out ? NULL : &e);
    fz_res(f, r);
    if (r == TT_OK && null_out) fz_fail(f, "tt_world_get_energy accepted a NULL out");
    if (r == TT_OK) fz_finite(f, e.total, "energy.total");
}

static void c_world_get_memory(fz *f)
{
    tt_world *w = fz_world_pick(f);
    f->readonly = true;
    tt_memory m;
    bool null_out = fz_chance(f, 4);
    fz_log(f, "tt_world_get_memory(%s, %s)", fz_wn(f, w), null_out ? "NULL" : "&memory");
    FZ_HIT(f, tt_world_get_memory);
    tt_result r = tt_world_get_memory(w, null_out ? NULL : &m);
    fz_res(f, r);
    if (r == TT_OK && null_out) fz_fail(f, "tt_world_get_memory accepted a NULL out");
    if (r == TT_OK) fz_finite(f, m.bytes_per_particle, "memory.bytes_per_particle");
}

const fz_entry fz_world_entries[] = {
    { "tt_integrator_name", c_integrator_name, 1 },
    { "tt_integrator_from_name", c_integrator_from_name, 1 },
    { "tt_result_string", c_result_string, 1 },
    { "tt_version", c_version, 1 },
    { "tt_last_error", c_last_error, 1 },
    { "tt_world_def_default", c_world_def_default, 1 },
    { "tt_world_create", c_world_create, 3 },
    { "tt_world_destroy", c_world_destroy, 1 },
    { "tt_world_step", c_world_step, 60 },
    { "tt_world_set_gravity", c_tt_world_set_gravity, 3 },
    { "tt_world_get_gravity", c_tt_world_get_gravity, 1 },
    { "tt_world_set_wind", c_tt_world_set_wind, 3 },
    { "tt_world_get_wind", c_tt_world_get_wind, 1 },
    { "tt_world_set_damping", c_world_set_damping, 3 },
    { "tt_world_get_damping", c_tt_world_get_damping, 1 },
    { "tt_world_set_integrator", c_tt_world_set_integrator, 5 },
    { "tt_world_get_integrator", c_tt_world_get_integrator, 1 },
    { "tt_world_get_fixed_point", c_tt_world_get_fixed_point, 1 },
    { "tt_world_set_interpolation", c_world_set_interpolation, 2 },
    { "tt_world_get_interpolation", c_tt_world_get_interpolation, 1 },
    { "tt_world_set_substeps", c_tt_world_set_substeps, 4 },
    { "tt_world_get_substeps", c_tt_world_get_substeps, 1 },
    { "tt_world_set_travel", c_world_set_travel, 2 },
    { "tt_world_get_travel", c_world_get_travel, 1 },
    { "tt_world_set_iterations", c_tt_world_set_iterations, 4 },
    { "tt_world_get_iterations", c_tt_world_get_iterations, 1 },
    { "tt_world_set_tolerance", c_world_set_tolerance, 2 },
    { "tt_world_set_sleep", c_world_set_sleep, 2 },
    { "tt_world_get_sleep", c_world_get_sleep, 1 },
    { "tt_world_get_tolerance", c_tt_world_get_tolerance, 1 },
    { "tt_world_set_solver_order", c_tt_world_set_solver_order, 3 },
    { "tt_world_get_solver_order", c_tt_world_get_solver_order, 1 },
    { "tt_world_explode", c_world_explode, 3 },
    { "tt_world_set_attractor", c_world_set_attractor, 2 },
    { "tt_world_get_attractor", c_world_get_attractor, 1 },
    { "tt_world_get_stats", c_world_get_stats, 2 },
    { "tt_world_get_energy", c_world_get_energy, 2 },
    { "tt_world_get_memory", c_world_get_memory, 1 },
    { "tt_world_hash", c_tt_world_hash, 1 },
    { NULL, NULL, 0 },
};
