/* tether — Lua binding of collisions (include/tether/collide.h): shapes,
 * collision settings, per-particle material and bullets, queries and
 * contact events. Methods join the world class through tl_world_add_methods;
 * every argument is checked (lua_common.h) before the core is called. */
#include "lua_common.h"

#include <string.h>

static const tl_range tl_r_pos = {0.0, TT_MAX_VALUE, true};

static tt_shape check_shape(lua_State *L, tt_world *w, int arg)
{
    return tt_shape_from_u64(tl_checkhandle(L, w, arg, TT_KIND_SHAPE));
}


/* --- shapes ----------------------------------------------------------------- */

static const tl_opt shape_opts[] = {
    TL_SURFACE_OPTS(tt_shape_def, ),
    TL_FILTER_OPTS(tt_shape_def, ),
    TL_OPT_FLAG(tt_shape_def, "sensor", sensor),
    TL_OPT_BYHAND("angle"), /* only some shapes take these two */
    TL_OPT_BYHAND("loop"),
    TL_OPT_END,
};

/* Common options of every shape constructor; opts at arg. */
static void shape_options(lua_State *L, int arg, tt_shape_def *d, bool angle, bool loop)
{
    tl_readopts(L, arg, shape_opts, d);
    if (tl_getopt(L, arg, "angle")) {
        lua_pop(L, 1);
        if (!angle) tl_error(L, "option 'angle' is not valid for this shape (only box and polygon turn)");
        d->angle = tl_optfield_number(L, arg, "angle", &TL_R_COORD, 0.0);
    }
    if (tl_getopt(L, arg, "loop")) {
        lua_pop(L, 1);
        if (!loop) tl_error(L, "option 'loop' is only valid for chains");
        d->loop = tl_optfield_boolean(L, arg, "loop", false);
    }
}

static int make_shape(lua_State *L, tt_world *w, const tt_shape_def *d)
{
    tt_shape s = tt_shape_create(w, d);
    if (s.gen == 0) tl_check_result(L, w, TT_EINVAL);
    tl_push_shape(L, s);
    return 1;
}

/* w:segment(x1, y1, x2, y2 [, opts]) */
static int w_segment(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_shape_def d = tt_shape_def_default();
    lua_settop(L, 6);
    d.a = (tt_vec2){tl_checknumber(L, 2, &TL_R_COORD), tl_checknumber(L, 3, &TL_R_COORD)};
    d.b = (tt_vec2){tl_checknumber(L, 4, &TL_R_COORD), tl_checknumber(L, 5, &TL_R_COORD)};
    shape_options(L, 6, &d, false, false);
    return make_shape(L, w, &d);
}

/* w:capsule(x1, y1, x2, y2, r [, opts]) */
static int w_capsule(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_shape_def d = tt_shape_def_default();
    lua_settop(L, 7);
    d.type = TT_SHAPE_CAPSULE;
    d.a = (tt_vec2){tl_checknumber(L, 2, &TL_R_COORD), tl_checknumber(L, 3, &TL_R_COORD)};
    d.b = (tt_vec2){tl_checknumber(L, 4, &TL_R_COORD), tl_checknumber(L, 5, &TL_R_COORD)};
    d.radius = tl_checknumber(L, 6, &TL_R_NONNEG);
    shape_options(L, 7, &d, false, false);
    return make_shape(L, w, &d);
}

/* w:aabb(x1, y1, x2, y2 [, opts]): min and max corners */
static int w_aabb(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_shape_def d = tt_shape_def_default();
    lua_settop(L, 6);
    d.type = TT_SHAPE_AABB;
    d.a = (tt_vec2){tl_checknumber(L, 2, &TL_R_COORD), tl_checknumber(L, 3, &TL_R_COORD)};
    d.b = (tt_vec2){tl_checknumber(L, 4, &TL_R_COORD), tl_checknumber(L, 5, &TL_R_COORD)};
    if (d.b.x < d.a.x) tl_argerror(L, 4, "x2 must be >= x1 (min and max corners)");
    if (d.b.y < d.a.y) tl_argerror(L, 5, "y2 must be >= y1 (min and max corners)");
    shape_options(L, 6, &d, false, false);
    return make_shape(L, w, &d);
}

/* w:box(cx, cy, half_w, half_h [, opts]) — opts.angle turns it */
static int w_box(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_shape_def d = tt_shape_def_default();
    lua_settop(L, 6);
    d.type = TT_SHAPE_BOX;
    d.position = (tt_vec2){tl_checknumber(L, 2, &TL_R_COORD), tl_checknumber(L, 3, &TL_R_COORD)};
    d.half_extents = (tt_vec2){tl_checknumber(L, 4, &tl_r_pos), tl_checknumber(L, 5, &tl_r_pos)};
    shape_options(L, 6, &d, true, false);
    return make_shape(L, w, &d);
}

/* w:circle(x, y, r [, opts]) */
static int w_circle(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_shape_def d = tt_shape_def_default();
    lua_settop(L, 5);
    d.type = TT_SHAPE_CIRCLE;
    d.position = (tt_vec2){tl_checknumber(L, 2, &TL_R_COORD), tl_checknumber(L, 3, &TL_R_COORD)};
    d.radius = tl_checknumber(L, 4, &tl_r_pos);
    shape_options(L, 5, &d, false, false);
    return make_shape(L, w, &d);
}

/* Reads {x1, y1, x2, y2, …} at arg into a userdata buffer left on the stack.
 * Raw, like every list the binding reads (no __len, no __index). */
static tt_vec2 *check_points(lua_State *L, int arg, uint32_t lo, uint32_t hi, uint32_t *count)
{
    if (lua_type(L, arg) != LUA_TTABLE) tl_typeerror(L, arg, "table of coordinates {x1, y1, x2, y2, ...}");
    lua_Integer n = (lua_Integer)lua_rawlen(L, arg);
    if (n % 2 != 0) tl_argerror(L, arg, "an even number of coordinates expected, got %d", (int)n);
    if (n / 2 < lo || n / 2 > hi) tl_argerror(L, arg, "between %d and %d points expected, got %d", (int)lo, (int)hi, (int)(n / 2));
    tt_vec2 *p = lua_newuserdatauv(L, (size_t)(n / 2) * sizeof *p + 1, 0);
    for (lua_Integer k = 1; k <= n; k++) {
        lua_rawgeti(L, arg, k);
        double v;
        if (!tl_tonumber_in(L, -1, &TL_R_COORD, &v))
            tl_argerror(L, arg, "%s at index %d", lua_tostring(L, -1), (int)k);
        lua_pop(L, 1);
        if (k % 2) p[(k - 1) / 2].x = v;
        else p[(k - 1) / 2].y = v;
    }
    *count = (uint32_t)(n / 2);
    return p;
}

/* w:chain({x1, y1, …} [, opts]) — opts.loop closes it */
static int w_chain(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_shape_def d = tt_shape_def_default();
    lua_settop(L, 3);
    d.type = TT_SHAPE_CHAIN;
    shape_options(L, 3, &d, false, true);
    d.points = check_points(L, 2, 2, TT_MAX_CHAIN_POINTS, &d.count);
    return make_shape(L, w, &d);
}

/* w:polygon({x1, y1, …} [, opts]) — convex */
static int w_polygon(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_shape_def d = tt_shape_def_default();
    lua_settop(L, 3);
    d.type = TT_SHAPE_POLYGON;
    shape_options(L, 3, &d, true, false);
    d.points = check_points(L, 2, 3, TT_MAX_POLYGON_POINTS, &d.count);
    return make_shape(L, w, &d);
}

static int w_remove_shape(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tl_check_result(L, w, tt_shape_destroy(w, check_shape(L, w, 2)));
    return 0;
}

static int w_shape_is_valid(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_pushboolean(L, tl_handle_is_live(L, w, 2, TT_KIND_SHAPE));
    return 1;
}

static int w_shape_count(lua_State *L)
{
    lua_pushinteger(L, (lua_Integer)tt_world_shape_count(tl_check_world(L, 1)));
    return 1;
}

static int w_shape_type(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_shape_type t;
    tl_check_result(L, w, tt_shape_get_type(w, check_shape(L, w, 2), &t));
    lua_pushstring(L, tt_shape_type_name(t));
    return 1;
}

/* w:shape_transform(s) → x, y, angle */
static int w_shape_transform(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_vec2 p;
    double a;
    tl_check_result(L, w, tt_shape_get_transform(w, check_shape(L, w, 2), &p, &a));
    lua_pushnumber(L, p.x);
    lua_pushnumber(L, p.y);
    lua_pushnumber(L, a);
    return 3;
}

/* w:set_shape_transform(s, x, y [, angle]) */
static int w_set_shape_transform(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_shape s = check_shape(L, w, 2);
    tt_vec2 p = {tl_checknumber(L, 3, &TL_R_COORD), tl_checknumber(L, 4, &TL_R_COORD)};
    double a = tl_optnumber(L, 5, &TL_R_COORD, 0.0);
    tl_check_result(L, w, tt_shape_set_transform(w, s, p, a));
    return 0;
}

/* w:set_shape_material(s, restitution, friction_static [, friction_kinetic]) */
static int w_set_shape_material(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_shape s = check_shape(L, w, 2);
    double e = tl_checknumber(L, 3, &TL_R_UNIT), fs = tl_checknumber(L, 4, &TL_R_NONNEG);
    double fk = tl_optnumber(L, 5, &TL_R_NONNEG, fs);
    tl_check_result(L, w, tt_shape_set_material(w, s, e, fs, fk));
    return 0;
}

static int w_set_shape_filter(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_shape s = check_shape(L, w, 2);
    uint16_t c = (uint16_t)tl_checkinteger(L, 3, 0, 0xFFFF), m = (uint16_t)tl_checkinteger(L, 4, 0, 0xFFFF);
    tl_check_result(L, w, tt_shape_set_filter(w, s, c, m));
    return 0;
}

static int w_set_shape_sensor(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_shape s = check_shape(L, w, 2);
    tl_check_result(L, w, tt_shape_set_sensor(w, s, tl_checkboolean(L, 3)));
    return 0;
}

/* w:shape_aabb(s) → x1, y1, x2, y2 */
static int w_shape_aabb(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_vec2 lo, hi;
    tl_check_result(L, w, tt_shape_get_aabb(w, check_shape(L, w, 2), &lo, &hi));
    lua_pushnumber(L, lo.x);
    lua_pushnumber(L, lo.y);
    lua_pushnumber(L, hi.x);
    lua_pushnumber(L, hi.y);
    return 4;
}

/* --- settings ----------------------------------------------------------------- */

static const char *const broadphases[] = {"grid", "brute", NULL};
static const char *const event_names[] = {"begin", "persist", "end", NULL};
static const tl_opt collision_opts[] = {
    TL_OPT_FLAG(tt_collision_settings, "particles", particles),
    TL_OPT_CHOICE(tt_collision_settings, "broadphase", broadphase, "broadphase", broadphases),
    TL_OPT_NUM(tt_collision_settings, "cell_size", cell_size, &TL_R_NONNEG),
    TL_SURFACE_OPTS(tt_collision_settings, ),
    TL_OPT_NUM(tt_collision_settings, "restitution_threshold", restitution_threshold, &TL_R_NONNEG),
    TL_OPT_NUM(tt_collision_settings, "stacking", stacking, &TL_R_NONNEG),
    TL_OPT_FLAG(tt_collision_settings, "anchored_friction", anchored_friction),
    TL_OPT_NUM(tt_collision_settings, "warm_start", warm_start, &TL_R_UNIT),
    TL_OPT_BYHAND("events"),
    TL_OPT_END,
};

/* w:set_collision([opts]) — switches collisions on; unset options keep their current value */
static int w_set_collision(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_settop(L, 2);
    tt_collision_settings s;
    tt_world_get_collision(w, &s);
    s.particles = true; /* unlike the others, not kept: set_collision{} switches particle pairs on */
    tl_readopts(L, 2, collision_opts, &s);
    if (tl_getopt(L, 2, "events")) {
        if (lua_type(L, -1) != LUA_TTABLE)
            tl_error(L, "bad option 'events' (array of 'begin', 'persist', 'end' expected, got %s)", luaL_typename(L, -1));
        uint32_t bits = 0;
        lua_Integer n = (lua_Integer)lua_rawlen(L, -1);
        for (lua_Integer k = 1; k <= n; k++) {
            lua_rawgeti(L, -1, k);
            const char *name = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : NULL;
            int found = -1;
            for (int j = 0; name && event_names[j]; j++)
                if (strcmp(name, event_names[j]) == 0) found = j;
            if (found < 0)
                tl_error(L, "bad option 'events' (invalid event '%s' at index %d, expected one of: 'begin', 'persist', 'end')",
                         name ? name : luaL_typename(L, -1), (int)k);
            bits |= 1u << found;
            lua_pop(L, 1);
        }
        lua_pop(L, 1);
        s.events = bits;
    }
    tl_check_result(L, w, tt_world_set_collision(w, &s));
    return 0;
}

/* w:collision() → settings table */
static int w_collision(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_collision_settings s;
    tl_check_result(L, w, tt_world_get_collision(w, &s));
    lua_createtable(L, 0, 12);
    lua_pushboolean(L, s.particles); lua_setfield(L, -2, "particles");
    lua_pushstring(L, broadphases[s.broadphase == TT_BROADPHASE_BRUTE]); lua_setfield(L, -2, "broadphase");
    lua_pushnumber(L, s.cell_size); lua_setfield(L, -2, "cell_size");
    lua_pushnumber(L, s.restitution); lua_setfield(L, -2, "restitution");
    lua_pushnumber(L, s.friction_static); lua_setfield(L, -2, "friction_static");
    lua_pushnumber(L, s.friction_kinetic); lua_setfield(L, -2, "friction_kinetic");
    lua_pushnumber(L, s.restitution_threshold); lua_setfield(L, -2, "restitution_threshold");
    lua_pushnumber(L, s.stacking); lua_setfield(L, -2, "stacking");
    lua_pushboolean(L, s.anchored_friction); lua_setfield(L, -2, "anchored_friction");
    lua_pushnumber(L, s.warm_start); lua_setfield(L, -2, "warm_start");
    lua_createtable(L, 3, 0);
    int k = 0;
    for (int j = 0; j < 3; j++)
        if (s.events & (1u << j)) {
            lua_pushstring(L, event_names[j]);
            lua_rawseti(L, -2, ++k);
        }
    lua_setfield(L, -2, "events");
    return 1;
}

/* w:collision_stats() → table */
static int w_collision_stats(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_collision_stats s;
    tl_check_result(L, w, tt_world_get_collision_stats(w, &s));
    lua_createtable(L, 0, 9);
    lua_pushinteger(L, s.shapes); lua_setfield(L, -2, "shapes");
    lua_pushinteger(L, s.pair_contacts); lua_setfield(L, -2, "pair_contacts");
    lua_pushinteger(L, s.shape_contacts); lua_setfield(L, -2, "shape_contacts");
    lua_pushinteger(L, s.cells); lua_setfield(L, -2, "cells");
    lua_pushinteger(L, s.static_rebuilds); lua_setfield(L, -2, "static_rebuilds");
    lua_pushinteger(L, (lua_Integer)s.broadphase_bytes); lua_setfield(L, -2, "broadphase_bytes");
    lua_pushnumber(L, s.broadphase_bytes_per_particle); lua_setfield(L, -2, "broadphase_bytes_per_particle");
    lua_pushinteger(L, (lua_Integer)s.total_bytes); lua_setfield(L, -2, "total_bytes");
    lua_pushnumber(L, s.broadphase_ms); lua_setfield(L, -2, "broadphase_ms");
    return 1;
}

/* --- per particle ------------------------------------------------------------- */

/* w:set_material(p, restitution, friction_static [, friction_kinetic]) */
static int w_set_material(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    double e = tl_checknumber(L, 3, &TL_R_UNIT), fs = tl_checknumber(L, 4, &TL_R_NONNEG);
    double fk = tl_optnumber(L, 5, &TL_R_NONNEG, fs);
    tl_check_result(L, w, tt_particle_set_material(w, p, e, fs, fk));
    return 0;
}

static int w_material(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    double e, fs, fk;
    tl_check_result(L, w, tt_particle_get_material(w, tl_check_particle(L, w, 2), &e, &fs, &fk));
    lua_pushnumber(L, e);
    lua_pushnumber(L, fs);
    lua_pushnumber(L, fk);
    return 3;
}

static int w_set_bullet(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    tl_check_result(L, w, tt_particle_set_bullet(w, p, tl_checkboolean(L, 3)));
    return 0;
}

static int w_bullet(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    bool b;
    tl_check_result(L, w, tt_particle_get_bullet(w, tl_check_particle(L, w, 2), &b));
    lua_pushboolean(L, b);
    return 1;
}

/* w:set_pair_collision(a, b, enabled) */
static int w_set_pair_collision(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle a = tl_check_particle(L, w, 2), b = tl_check_particle(L, w, 3);
    bool on = tl_checkboolean(L, 4);
    if (a.index == b.index) tl_argerror(L, 3, "the same particle as argument #2");
    tl_check_result(L, w, tt_world_set_pair_collision(w, a, b, on));
    return 0;
}

/* --- queries ------------------------------------------------------------------- */

/* w:raycast(x1, y1, x2, y2 [, mask]) → nil, or {particle | shape | terrain, x, y, nx, ny, fraction} */
static int w_raycast(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_vec2 a = {tl_checknumber(L, 2, &TL_R_COORD), tl_checknumber(L, 3, &TL_R_COORD)};
    tt_vec2 b = {tl_checknumber(L, 4, &TL_R_COORD), tl_checknumber(L, 5, &TL_R_COORD)};
    uint16_t mask = (uint16_t)tl_optinteger(L, 6, 0, 0xFFFF, 0xFFFF);
    tt_ray_hit h;
    tl_check_result(L, w, tt_world_raycast(w, a, b, mask, &h));
    if (!h.hit) {
        lua_pushnil(L);
        return 1;
    }
    lua_createtable(L, 0, 6);
    if (h.particle.gen) {
        tl_push_particle(L, h.particle);
        lua_setfield(L, -2, "particle");
    } else if (h.terrain.gen) {
        tl_push_terrain(L, h.terrain);
        lua_setfield(L, -2, "terrain");
    } else {
        tl_push_shape(L, h.shape);
        lua_setfield(L, -2, "shape");
    }
    lua_pushnumber(L, h.point.x); lua_setfield(L, -2, "x");
    lua_pushnumber(L, h.point.y); lua_setfield(L, -2, "y");
    lua_pushnumber(L, h.normal.x); lua_setfield(L, -2, "nx");
    lua_pushnumber(L, h.normal.y); lua_setfield(L, -2, "ny");
    lua_pushnumber(L, h.fraction); lua_setfield(L, -2, "fraction");
    return 1;
}

/* Runs a point/box query twice when the buffers were too small (all of it,
 * into one scratch buffer, before any Lua value is made); pushes
 * {particles}, {shapes}, {terrains}. */
static int area(lua_State *L, tt_world *w, bool point, tt_vec2 lo, tt_vec2 hi, uint16_t mask)
{
    uint32_t np = 0, ns = 0, nt = 0, pcap = 64, scap = 16, tcap = 4;
    for (int round = 0; round < 2; round++) {
        /* one buffer: particles, then shapes, then terrains, each at a multiple of 16 bytes */
        const size_t at = ((size_t)pcap * sizeof(tt_particle) + 15) & ~(size_t)15;
        const size_t at2 = at + (((size_t)scap * sizeof(tt_shape) + 15) & ~(size_t)15);
        char *buf = tl_scratch(L, at2 + (size_t)tcap * sizeof(tt_terrain) + 1);
        tt_particle *ps = (tt_particle *)buf;
        tt_shape *ss = (tt_shape *)(buf + at);
        tt_terrain *ts = (tt_terrain *)(buf + at2);
        tt_result r = point ? tt_world_query_point(w, lo, mask, ps, pcap, &np, ss, scap, &ns)
                            : tt_world_query_aabb(w, lo, hi, mask, ps, pcap, &np, ss, scap, &ns);
        tl_check_result(L, w, r);
        tl_check_result(L, w, tt_world_query_terrains(w, lo, hi, mask, ts, tcap, &nt));
        if (np <= pcap && ns <= scap && nt <= tcap) {
            lua_createtable(L, (int)np, 0);
            for (uint32_t k = 0; k < np; k++) {
                tl_push_particle(L, ps[k]);
                lua_rawseti(L, -2, k + 1);
            }
            lua_createtable(L, (int)ns, 0);
            for (uint32_t k = 0; k < ns; k++) {
                tl_push_shape(L, ss[k]);
                lua_rawseti(L, -2, k + 1);
            }
            lua_createtable(L, (int)nt, 0);
            for (uint32_t k = 0; k < nt; k++) {
                tl_push_terrain(L, ts[k]);
                lua_rawseti(L, -2, k + 1);
            }
            return 3;
        }
        pcap = np > pcap ? np : pcap;
        scap = ns > scap ? ns : scap;
        tcap = nt > tcap ? nt : tcap;
    }
    return tl_error(L, "the world changed during the query");
}

/* w:query_point(x, y [, mask]) → {particles}, {shapes}, {terrains} */
static int w_query_point(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_vec2 p = {tl_checknumber(L, 2, &TL_R_COORD), tl_checknumber(L, 3, &TL_R_COORD)};
    uint16_t mask = (uint16_t)tl_optinteger(L, 4, 0, 0xFFFF, 0xFFFF);
    return area(L, w, true, p, p, mask);
}

/* w:query_aabb(x1, y1, x2, y2 [, mask]) → {particles}, {shapes}, {terrains} */
static int w_query_aabb(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_vec2 lo = {tl_checknumber(L, 2, &TL_R_COORD), tl_checknumber(L, 3, &TL_R_COORD)};
    tt_vec2 hi = {tl_checknumber(L, 4, &TL_R_COORD), tl_checknumber(L, 5, &TL_R_COORD)};
    uint16_t mask = (uint16_t)tl_optinteger(L, 6, 0, 0xFFFF, 0xFFFF);
    if (hi.x < lo.x) tl_argerror(L, 4, "x2 must be >= x1");
    if (hi.y < lo.y) tl_argerror(L, 5, "y2 must be >= y1");
    return area(L, w, false, lo, hi, mask);
}

/* --- events ---------------------------------------------------------------------- */

/* w:contacts() → array of {kind, a, b | shape | terrain, x, y, nx, ny, impulse, sensor} of the last step */
static int w_contacts(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    uint32_t n;
    const tt_contact_event *live = tt_world_get_contact_events(w, &n);
    /* the world's own array changes if Lua code steps the world while the tables are made */
    tt_contact_event *ev = tl_scratch(L, (size_t)n * sizeof *ev + 1);
    if (n > 0) memcpy(ev, live, (size_t)n * sizeof *ev);
    lua_createtable(L, (int)n, 0);
    for (uint32_t k = 0; k < n; k++) {
        const tt_contact_event *e = &ev[k];
        lua_createtable(L, 0, 9);
        lua_pushstring(L, e->kind == TT_EVENT_BEGIN ? "begin" : e->kind == TT_EVENT_PERSIST ? "persist" : "end");
        lua_setfield(L, -2, "kind");
        tl_push_particle(L, e->a);
        lua_setfield(L, -2, "a");
        if (e->b.gen) {
            tl_push_particle(L, e->b);
            lua_setfield(L, -2, "b");
        } else if (e->terrain.gen) {
            tl_push_terrain(L, e->terrain);
            lua_setfield(L, -2, "terrain");
        } else {
            tl_push_shape(L, e->shape);
            lua_setfield(L, -2, "shape");
        }
        lua_pushnumber(L, e->point.x); lua_setfield(L, -2, "x");
        lua_pushnumber(L, e->point.y); lua_setfield(L, -2, "y");
        lua_pushnumber(L, e->normal.x); lua_setfield(L, -2, "nx");
        lua_pushnumber(L, e->normal.y); lua_setfield(L, -2, "ny");
        lua_pushnumber(L, e->impulse); lua_setfield(L, -2, "impulse");
        lua_pushboolean(L, e->sensor); lua_setfield(L, -2, "sensor");
        lua_rawseti(L, -2, (lua_Integer)k + 1);
    }
    return 1;
}

static const luaL_Reg collide_methods[] = {
    {"segment", w_segment},
    {"capsule", w_capsule},
    {"aabb", w_aabb},
    {"box", w_box},
    {"circle", w_circle},
    {"chain", w_chain},
    {"polygon", w_polygon},
    {"remove_shape", w_remove_shape},
    {"shape_is_valid", w_shape_is_valid},
    {"shape_count", w_shape_count},
    {"shape_type", w_shape_type},
    {"shape_transform", w_shape_transform},
    {"set_shape_transform", w_set_shape_transform},
    {"set_shape_material", w_set_shape_material},
    {"set_shape_filter", w_set_shape_filter},
    {"set_shape_sensor", w_set_shape_sensor},
    {"shape_aabb", w_shape_aabb},
    {"set_collision", w_set_collision},
    {"collision", w_collision},
    {"collision_stats", w_collision_stats},
    {"set_material", w_set_material},
    {"material", w_material},
    {"set_bullet", w_set_bullet},
    {"bullet", w_bullet},
    {"set_pair_collision", w_set_pair_collision},
    {"raycast", w_raycast},
    {"query_point", w_query_point},
    {"query_aabb", w_query_aabb},
    {"contacts", w_contacts},
    {NULL, NULL},
};

void tl_collide_register(lua_State *L)
{
    tl_world_add_methods(L, collide_methods);
}
