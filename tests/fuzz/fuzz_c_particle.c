/* tests/fuzz/fuzz_c_particle.c — wrappers of tether/particle.h and
 * tether/spring.h: defs with garbage fields, every getter and setter with
 * every sort of handle, the bulk reads and moves with zero, plausible and
 * huge counts. */
#include "fuzz_c.h"

#include <stdlib.h>

#define PK TT_KIND_PARTICLE
#define SK TT_KIND_SPRING

static double mass(fz *f)
{
    return fz_chance(f, 50) ? 1.0 : fz_real(f, TT_MIN_MASS, fz_chance(f, 80) ? 10.0 : TT_MAX_MASS);
}

static tt_particle_def particle_def(fz *f)
{
    tt_particle_def d = tt_particle_def_default();
    d.position = fz_point(f);
    if (fz_chance(f, 30)) d.velocity = fz_vec(f, -10, 10);
    d.mass = mass(f);
    d.radius = fz_chance(f, 40) ? 0.0 : fz_real(f, 0.0, fz_chance(f, 95) ? 0.5 : 20.0);
    d.pinned = fz_chance(f, 8);
    if (fz_chance(f, 20)) d.category = fz_bits16(f);
    if (fz_chance(f, 20)) d.mask = fz_bits16(f);
    d.user = fz_rand(f);
    return d;
}

static void c_particle_def_default(fz *f)
{
    fz_log(f, "tt_particle_def_default()");
    FZ_HIT(f, tt_particle_def_default);
    tt_particle_def d = tt_particle_def_default();
    if (d.mass != 1.0 || d.radius != 0.0) fz_fail(f, "tt_particle_def_default is not the documented default");
}

static void c_particle_create(fz *f)
{
    tt_world *w = fz_world_pick(f);
    tt_particle_def d = particle_def(f);
    bool null_def = fz_chance(f, 3);
    fz_log(f, "tt_particle_create(%s, %s) /* position %s, velocity %s, mass %s, radius %s, pinned %d, filter %#x/%#x */",
           fz_wn(f, w), null_def ? "NULL" : "&def", fz_v(d.position), fz_v(d.velocity), fz_d(d.mass), fz_d(d.radius),
           d.pinned, d.category, d.mask);
    FZ_HIT(f, tt_particle_create);
    fz_hres(f, PK, FZ_H(tt_particle_create(w, null_def ? NULL : &d)));
    if (null_def && !f->failed) fz_fail(f, "tt_particle_create accepted a NULL def");
}

static void c_particle_destroy(fz *f)
{
    tt_world *w = fz_world_pick(f);
    fz_h h = fz_handle(f, PK);
    fz_log(f, "tt_particle_destroy(%s, %s)", fz_wn(f, w), fz_hn(h, PK));
    FZ_HIT(f, tt_particle_destroy);
    fz_res(f, tt_particle_destroy(w, FZ_P(h)));
    if (!f->failed) fz_forget(f, PK, h);
}

/* is_valid: "false" is its refusal, and what must be refused must be false. */
#define IS_VALID(fn, K, CONV)                                                                        \
    static void c_##fn(fz *f)                                                                        \
    {                                                                                                \
        tt_world *w = fz_world_any(f);                                                               \
        fz_h h = fz_handle(f, K);                                                                    \
        fz_log(f, #fn "(%s, %s)", fz_wn(f, w), fz_hn(h, K));                                         \
        FZ_HIT(f, fn);                                                                               \
        bool ok = fn(w, CONV(h));                                                                    \
        fz_log_more(f, " -> %s", ok ? "true" : "false");                                             \
        f->failed = !ok;                                                                             \
        if (!w) f->must_fail = false, f->failed = true;                                              \
        if (!w && ok) fz_fail(f, #fn " said true for a NULL world");                                 \
    }
IS_VALID(tt_particle_is_valid, PK, FZ_P)
IS_VALID(tt_spring_is_valid, SK, FZ_S)

/* A getter of one value through an out pointer (NULL now and then). */
#define GET_OUT(fn, K, CONV, T, check)                                                               \
    static void c_##fn(fz *f)                                                                        \
    {                                                                                                \
        tt_world *w = fz_world_pick(f);                                                              \
        f->readonly = true;                                                                          \
        fz_h h = fz_handle(f, K);                                                                    \
        T out;                                                                                       \
        bool null_out = fz_chance(f, 4);                                                             \
        fz_log(f, #fn "(%s, %s, %s)", fz_wn(f, w), fz_hn(h, K), null_out ? "NULL" : "&out");         \
        FZ_HIT(f, fn);                                                                               \
        fz_res(f, fn(w, CONV(h), null_out ? NULL : &out));                                           \
        if (!f->failed && null_out) fz_fail(f, #fn " accepted a NULL out");                          \
        if (!f->failed) check;                                                                       \
    }
/* A setter of one value, drawn by draw and printed by show. */
#define SET_ONE(fn, K, CONV, T, draw, show)                                                          \
    static void c_##fn(fz *f)                                                                        \
    {                                                                                                \
        tt_world *w = fz_world_pick(f);                                                              \
        fz_h h = fz_handle(f, K);                                                                    \
        T v = draw;                                                                                  \
        fz_log(f, #fn "(%s, %s, %s)", fz_wn(f, w), fz_hn(h, K), show);                               \
        FZ_HIT(f, fn);                                                                               \
        fz_res(f, fn(w, CONV(h), v));                                                                \
    }

GET_OUT(tt_particle_get_position, PK, FZ_P, tt_vec2, fz_finite_vec(f, out, "a position"))
GET_OUT(tt_particle_get_previous_position, PK, FZ_P, tt_vec2, fz_finite_vec(f, out, "a previous position"))
GET_OUT(tt_particle_get_velocity, PK, FZ_P, tt_vec2, fz_finite_vec(f, out, "a velocity"))
GET_OUT(tt_particle_get_mass, PK, FZ_P, double, fz_finite(f, out, "a mass"))
GET_OUT(tt_particle_get_pinned, PK, FZ_P, bool, (void)out)
GET_OUT(tt_particle_get_asleep, PK, FZ_P, bool, (void)out)
GET_OUT(tt_particle_get_radius, PK, FZ_P, double, fz_finite(f, out, "a radius"))
GET_OUT(tt_particle_get_angle, PK, FZ_P, double, fz_finite(f, out, "an angle"))
GET_OUT(tt_particle_get_spin, PK, FZ_P, double, fz_finite(f, out, "a spin"))
GET_OUT(tt_particle_get_user, PK, FZ_P, uint64_t, (void)out)
SET_ONE(tt_particle_set_velocity, PK, FZ_P, tt_vec2, fz_vec(f, -20, 20), fz_v(v))
SET_ONE(tt_particle_set_mass, PK, FZ_P, double, mass(f), fz_d(v))
SET_ONE(tt_particle_set_pinned, PK, FZ_P, bool, fz_chance(f, 50), v ? "true" : "false")
SET_ONE(tt_particle_set_radius, PK, FZ_P, double, fz_real(f, 0, 1), fz_d(v))
SET_ONE(tt_particle_set_spin, PK, FZ_P, double, fz_chance(f, 10) ? fz_nasty(f) : fz_real(f, -50, 50), fz_d(v))
SET_ONE(tt_particle_set_user, PK, FZ_P, uint64_t, fz_rand(f), fz_u(v))
SET_ONE(tt_particle_apply_force, PK, FZ_P, tt_vec2, fz_vec(f, -1000, 1000), fz_v(v))
SET_ONE(tt_particle_apply_impulse, PK, FZ_P, tt_vec2, fz_vec(f, -100, 100), fz_v(v))
GET_OUT(tt_spring_get_length, SK, FZ_S, double, fz_finite(f, out, "a spring length"))
SET_ONE(tt_spring_set_stiffness, SK, FZ_S, double, fz_real(f, 0, 1000), fz_d(v))
SET_ONE(tt_spring_set_damping, SK, FZ_S, double, fz_real(f, 0, 10), fz_d(v))
SET_ONE(tt_spring_set_rest_length, SK, FZ_S, double, fz_real(f, 0, 10), fz_d(v))

static void c_particle_set_position(fz *f)
{
    tt_world *w = fz_world_pick(f);
    fz_h h = fz_handle(f, PK);
    tt_vec2 p = fz_point(f);
    tt_move_mode mode = (tt_move_mode)fz_enum(f, 2);
    fz_log(f, "tt_particle_set_position(%s, %s, %s, %d)", fz_wn(f, w), fz_hn(h, PK), fz_v(p), (int)mode);
    FZ_HIT(f, tt_particle_set_position);
    fz_res(f, tt_particle_set_position(w, FZ_P(h), p, mode));
}

static void c_particle_get_filter(fz *f)
{
    tt_world *w = fz_world_pick(f);
    f->readonly = true;
    fz_h h = fz_handle(f, PK);
    uint16_t cat, mask;
    bool null_out = fz_chance(f, 4);
    fz_log(f, "tt_particle_get_filter(%s, %s, %s, &mask)", fz_wn(f, w), fz_hn(h, PK), null_out ? "NULL" : "&category");
    FZ_HIT(f, tt_particle_get_filter);
    fz_res(f, tt_particle_get_filter(w, FZ_P(h), null_out ? NULL : &cat, &mask));
}

static void c_particle_set_filter(fz *f)
{
    tt_world *w = fz_world_pick(f);
    fz_h h = fz_handle(f, PK);
    uint16_t cat = fz_bits16(f), mask = fz_bits16(f);
    fz_log(f, "tt_particle_set_filter(%s, %s, %#x, %#x)", fz_wn(f, w), fz_hn(h, PK), cat, mask);
    FZ_HIT(f, tt_particle_set_filter);
    fz_res(f, tt_particle_set_filter(w, FZ_P(h), cat, mask));
}

#define COUNT(fn)                                                                                    \
    static void c_##fn(fz *f)                                                                        \
    {                                                                                                \
        tt_world *w = fz_world_any(f);                                                               \
        fz_log(f, #fn "(%s)", fz_wn(f, w));                                                          \
        FZ_HIT(f, fn);                                                                               \
        uint32_t n = fn(w);                                                                          \
        fz_log_more(f, " -> %u", n);                                                                 \
        if (!w && n) fz_fail(f, #fn "(NULL) is %u", n);                                              \
    }
COUNT(tt_world_particle_count)
COUNT(tt_world_spring_count)

/* A list call's handles become the ones later calls draw from. */
#define LIST(fn, K, T, count_fn)                                                                     \
    static void c_##fn(fz *f)                                                                        \
    {                                                                                                \
        tt_world *w = fz_world_any(f);                                                               \
        uint32_t cap, live = w ? count_fn(w) : 0;                                                    \
        T *out = fz_buffer(f, &cap, live, sizeof *out);                                              \
        fz_log(f, #fn "(%s, %s, %u)", fz_wn(f, w), out ? "out" : "NULL", cap);                       \
        FZ_HIT(f, fn);                                                                               \
        uint32_t n = fn(w, out, cap);                                                                \
        fz_log_more(f, " -> %u", n);                                                                 \
        if (n != live) fz_fail(f, #fn " says %u, the count says %u", n, live);                       \
        for (uint32_t i = 0; out && i < n && i < cap; i++) fz_remember(f, K, FZ_H(out[i]));          \
        free(out);                                                                                   \
    }
LIST(tt_world_list_particles, PK, tt_particle, tt_world_particle_count)
LIST(tt_world_list_springs, SK, tt_spring, tt_world_spring_count)

static void c_world_read_positions(fz *f)
{
    tt_world *w = fz_world_any(f);
    uint32_t cap, live = w ? tt_world_particle_count(w) : 0;
    double *xy = fz_buffer(f, &cap, live, 2 * sizeof *xy);
    fz_log(f, "tt_world_read_positions(%s, %s, %u)", fz_wn(f, w), xy ? "xy" : "NULL", cap);
    FZ_HIT(f, tt_world_read_positions);
    uint32_t n = tt_world_read_positions(w, xy, cap);
    fz_log_more(f, " -> %u", n);
    for (uint32_t i = 0; xy && i < 2 * n && i < 2 * cap; i++) fz_finite(f, xy[i], "a position");
    free(xy);
}

static void c_world_read_previous_positions(fz *f)
{
    tt_world *w = fz_world_any(f);
    uint32_t cap, live = w ? tt_world_particle_count(w) : 0;
    double *xy = fz_buffer(f, &cap, live, 2 * sizeof *xy);
    fz_log(f, "tt_world_read_previous_positions(%s, %s, %u)", fz_wn(f, w), xy ? "xy" : "NULL", cap);
    FZ_HIT(f, tt_world_read_previous_positions);
    uint32_t n = tt_world_read_previous_positions(w, xy, cap);
    fz_log_more(f, " -> %u", n);
    if (n > cap || n > live) fz_fail(f, "tt_world_read_previous_positions gave %u of %u (cap %u)", n, live, cap);
    for (uint32_t i = 0; xy && i < 2 * n && i < 2 * cap; i++) fz_finite(f, xy[i], "a previous position");
    free(xy);
}

/* n handles and 2n numbers, or a count with NULL arrays (which must fail). */
static uint32_t bulk_n(fz *f, tt_particle **ids, double **xy, bool plausible_xy)
{
    uint32_t n = fz_count(f, 0, 64);
    if (n > (1u << 16) || fz_chance(f, 3)) {
        *ids = NULL;
        *xy = NULL;
        return n;
    }
    *ids = fz_particles(f, n);
    *xy = malloc(2 * (size_t)(n ? n : 1) * sizeof **xy);
    if (!*xy) abort();
    for (uint32_t i = 0; i < 2 * n; i++) (*xy)[i] = plausible_xy ? fz_coord(f) : 0.0;
    return n;
}

static void c_particles_get_positions(fz *f)
{
    tt_world *w = fz_world_pick(f);
    f->readonly = true;
    tt_particle *ids;
    double *xy;
    uint32_t n = bulk_n(f, &ids, &xy, false);
    fz_log(f, "tt_particles_get_positions(%s, %s, %u, %s)", fz_wn(f, w), ids ? "ids" : "NULL", n, xy ? "xy" : "NULL");
    fz_log_ids(f, ids, n);
    FZ_HIT(f, tt_particles_get_positions);
    fz_res(f, tt_particles_get_positions(w, ids, n, xy));
    for (uint32_t i = 0; !f->failed && xy && i < 2 * n; i++) fz_finite(f, xy[i], "a bulk position");
    free(ids);
    free(xy);
}

static void c_particles_set_positions(fz *f)
{
    tt_world *w = fz_world_pick(f);
    tt_particle *ids;
    double *xy;
    uint32_t n = bulk_n(f, &ids, &xy, true);
    tt_move_mode mode = (tt_move_mode)fz_enum(f, 2);
    fz_log(f, "tt_particles_set_positions(%s, %s, %u, %s, %d) /* xy[0..1] %s %s */", fz_wn(f, w), ids ? "ids" : "NULL",
           n, xy ? "xy" : "NULL", (int)mode, xy && n ? fz_d(xy[0]) : "-", xy && n ? fz_d(xy[1]) : "-");
    fz_log_ids(f, ids, n);
    FZ_HIT(f, tt_particles_set_positions);
    fz_res(f, tt_particles_set_positions(w, ids, n, xy, mode));
    free(ids);
    free(xy);
}

static void c_spring_def_default(fz *f)
{
    fz_log(f, "tt_spring_def_default()");
    FZ_HIT(f, tt_spring_def_default);
    tt_spring_def d = tt_spring_def_default();
    if (d.stiffness != 100.0 || d.rest_length != -1.0) fz_fail(f, "tt_spring_def_default is not the documented default");
}

static void c_spring_create(fz *f)
{
    tt_world *w = fz_world_pick(f);
    tt_spring_def d = tt_spring_def_default();
    fz_h a = fz_handle(f, PK), b = fz_chance(f, 3) ? a : fz_handle(f, PK);
    d.a = FZ_P(a);
    d.b = FZ_P(b);
    d.stiffness = fz_real(f, 0, 1000);
    d.damping = fz_chance(f, 50) ? 0.0 : fz_real(f, 0, 10);
    d.rest_length = fz_chance(f, 50) ? -1.0 : fz_real(f, 0, 10);
    fz_log(f, "tt_spring_create(%s, &(tt_spring_def){%s, %s, %s, %s, %s})", fz_wn(f, w), fz_hn(a, PK), fz_hn(b, PK),
           fz_d(d.stiffness), fz_d(d.damping), fz_d(d.rest_length));
    FZ_HIT(f, tt_spring_create);
    fz_hres(f, SK, FZ_H(tt_spring_create(w, fz_chance(f, 2) ? NULL : &d)));
}

static void c_spring_destroy(fz *f)
{
    tt_world *w = fz_world_pick(f);
    fz_h h = fz_handle(f, SK);
    fz_log(f, "tt_spring_destroy(%s, %s)", fz_wn(f, w), fz_hn(h, SK));
    FZ_HIT(f, tt_spring_destroy);
    fz_res(f, tt_spring_destroy(w, FZ_S(h)));
    if (!f->failed) fz_forget(f, SK, h);
}

static void c_spring_get_def(fz *f)
{
    tt_world *w = fz_world_pick(f);
    f->readonly = true;
    fz_h h = fz_handle(f, SK);
    tt_spring_def d;
    bool null_out = fz_chance(f, 4);
    fz_log(f, "tt_spring_get_def(%s, %s, %s)", fz_wn(f, w), fz_hn(h, SK), null_out ? "NULL" : "&def");
    FZ_HIT(f, tt_spring_get_def);
    fz_res(f, tt_spring_get_def(w, FZ_S(h), null_out ? NULL : &d));
    if (!f->failed && null_out) fz_fail(f, "tt_spring_get_def accepted a NULL out");
    if (!f->failed) fz_finite(f, d.stiffness + d.damping + d.rest_length, "a spring def's numbers");
}

const fz_entry fz_particle_entries[] = {
    { "tt_particle_def_default", c_particle_def_default, 1 },
    { "tt_particle_create", c_particle_create, 30 },
    { "tt_particle_destroy", c_particle_destroy, 4 },
    { "tt_particle_is_valid", c_tt_particle_is_valid, 2 },
    { "tt_particle_get_position", c_tt_particle_get_position, 2 },
    { "tt_particle_set_position", c_particle_set_position, 4 },
    { "tt_particle_get_previous_position", c_tt_particle_get_previous_position, 1 },
    { "tt_particle_get_velocity", c_tt_particle_get_velocity, 2 },
    { "tt_particle_set_velocity", c_tt_particle_set_velocity, 3 },
    { "tt_particle_get_mass", c_tt_particle_get_mass, 1 },
    { "tt_particle_set_mass", c_tt_particle_set_mass, 2 },
    { "tt_particle_get_pinned", c_tt_particle_get_pinned, 1 },
    { "tt_particle_get_asleep", c_tt_particle_get_asleep, 1 },
    { "tt_particle_set_pinned", c_tt_particle_set_pinned, 2 },
    { "tt_particle_get_radius", c_tt_particle_get_radius, 1 },
    { "tt_particle_set_radius", c_tt_particle_set_radius, 2 },
    { "tt_particle_get_angle", c_tt_particle_get_angle, 1 },
    { "tt_particle_get_spin", c_tt_particle_get_spin, 1 },
    { "tt_particle_set_spin", c_tt_particle_set_spin, 2 },
    { "tt_particle_get_filter", c_particle_get_filter, 1 },
    { "tt_particle_set_filter", c_particle_set_filter, 2 },
    { "tt_particle_get_user", c_tt_particle_get_user, 1 },
    { "tt_particle_set_user", c_tt_particle_set_user, 1 },
    { "tt_particle_apply_force", c_tt_particle_apply_force, 3 },
    { "tt_particle_apply_impulse", c_tt_particle_apply_impulse, 3 },
    { "tt_world_particle_count", c_tt_world_particle_count, 1 },
    { "tt_world_list_particles", c_tt_world_list_particles, 3 },
    { "tt_world_read_positions", c_world_read_positions, 2 },
    { "tt_world_read_previous_positions", c_world_read_previous_positions, 1 },
    { "tt_particles_get_positions", c_particles_get_positions, 2 },
    { "tt_particles_set_positions", c_particles_set_positions, 2 },
    { "tt_spring_def_default", c_spring_def_default, 1 },
    { "tt_spring_create", c_spring_create, 6 },
    { "tt_spring_destroy", c_spring_destroy, 2 },
    { "tt_spring_is_valid", c_tt_spring_is_valid, 1 },
    { "tt_spring_get_def", c_spring_get_def, 1 },
    { "tt_spring_set_stiffness", c_tt_spring_set_stiffness, 2 },
    { "tt_spring_set_damping", c_tt_spring_set_damping, 2 },
    { "tt_spring_set_rest_length", c_tt_spring_set_rest_length, 2 },
    { "tt_spring_get_length", c_tt_spring_get_length, 1 },
    { "tt_world_spring_count", c_tt_world_spring_count, 1 },
    { "tt_world_list_springs", c_tt_world_list_springs, 2 },
    { NULL, NULL, 0 },
};
