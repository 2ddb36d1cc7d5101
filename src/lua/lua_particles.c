/* tether — Lua world methods on one particle: w:particle (create), w:remove,
 * the getters and setters of its state (position, velocity, mass, pinned,
 * radius, collision filter), its Lua user value, forces and impulses, and
 * w:explode. The world's user value 1 is a table handle → Lua value (w:user). */
#include "lua_common.h"

const char *const tl_move_modes[] = { "keep", "reset", NULL };

/* Pushes the world's handle → user value table. */
static void push_users(lua_State *L)
{
    lua_getiuservalue(L, 1, 1);
}

/* Forgets the user value of handle h. */
static void clear_user(lua_State *L, uint64_t h)
{
    push_users(L);
    if (lua_istable(L, -1)) {
        lua_pushnil(L);
        lua_rawseti(L, -2, (lua_Integer)h);
    }
    lua_pop(L, 1);
}

static const tl_opt particle_opts[] = {
    TL_OPT_NUM(tt_particle_def, "vx", velocity.x, &TL_R_COORD),
    TL_OPT_NUM(tt_particle_def, "vy", velocity.y, &TL_R_COORD),
    TL_OPT_NUM(tt_particle_def, "mass", mass, &TL_R_MASS),
    TL_OPT_NUM(tt_particle_def, "radius", radius, &TL_R_NONNEG),
    TL_OPT_FLAG(tt_particle_def, "pinned", pinned),
    TL_OPT_UINT16(tt_particle_def, "category", category, 0, 0xFFFF),
    TL_OPT_UINT16(tt_particle_def, "mask", mask, 0, 0xFFFF),
    TL_OPT_BYHAND("user"),
    TL_OPT_END,
};

/* w:particle(x, y [, opts]) → handle */
static int w_particle(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle_def def = tt_particle_def_default();
    tt_particle p;

    lua_settop(L, 4);
    def.position.x = tl_checknumber(L, 2, &TL_R_COORD);
    def.position.y = tl_checknumber(L, 3, &TL_R_COORD);
    tl_readopts(L, 4, particle_opts, &def);
    /* read before the particle is made: a read that raises must leave no particle behind */
    bool has_user = tl_getopt(L, 4, "user");

    p = tt_particle_create(w, &def);
    if (p.gen == 0)
        tl_check_result(L, w, TT_ENOMEM);
    if (has_user) {
        push_users(L);
        lua_insert(L, -2);
        lua_rawseti(L, -2, (lua_Integer)tt_particle_to_u64(p));
        lua_pop(L, 1);
    }
    tl_push_particle(L, p);
    return 1;
}

/* w:remove(p) */
static int w_remove(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    tl_check_result(L, w, tt_particle_destroy(w, p));
    clear_user(L, tt_particle_to_u64(p));
    return 0;
}

/* w:is_valid(p) → boolean */
static int w_is_valid(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    lua_pushboolean(L, tl_handle_is_live(L, w, 2, TT_KIND_PARTICLE));
    return 1;
}

static int w_position(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    tt_vec2 v;
    tl_check_result(L, w, tt_particle_get_position(w, p, &v));
    lua_pushnumber(L, v.x);
    lua_pushnumber(L, v.y);
    return 2;
}

/* w:set_position(p, x, y [, mode]) */
static int w_set_position(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    tt_vec2 v;
    int mode;
    v.x = tl_checknumber(L, 3, &TL_R_COORD);
    v.y = tl_checknumber(L, 4, &TL_R_COORD);
    mode = tl_checkoption(L, 5, "mode", "keep", tl_move_modes);
    tl_check_result(L, w, tt_particle_set_position(w, p, v, mode == 0 ? TT_MOVE_KEEP_VELOCITY : TT_MOVE_RESET_VELOCITY));
    return 0;
}

static int w_velocity(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    tt_vec2 v;
    tl_check_result(L, w, tt_particle_get_velocity(w, p, &v));
    lua_pushnumber(L, v.x);
    lua_pushnumber(L, v.y);
    return 2;
}

static int w_set_velocity(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    tt_vec2 v;
    v.x = tl_checknumber(L, 3, &TL_R_COORD);
    v.y = tl_checknumber(L, 4, &TL_R_COORD);
    tl_check_result(L, w, tt_particle_set_velocity(w, p, v));
    return 0;
}

/* w:rotation(p), w:spin(p): rad and rad/s, counter-clockwise (worlds made with spin = true);
 * w:angle(a, b, c) is the angle constraint's. One number of particle p, read by get. */
static int particle_number(lua_State *L, tt_result (*get)(const tt_world *w, tt_particle p, double *out))
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    double v;
    tl_check_result(L, w, get(w, p, &v));
    lua_pushnumber(L, v);
    return 1;
}

static int w_angle(lua_State *L) { return particle_number(L, tt_particle_get_angle); }
static int w_spin(lua_State *L) { return particle_number(L, tt_particle_get_spin); }

static int w_set_spin(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    tl_check_result(L, w, tt_particle_set_spin(w, p, tl_checknumber(L, 3, &TL_R_COORD)));
    return 0;
}

static int w_mass(lua_State *L) { return particle_number(L, tt_particle_get_mass); }

static int w_set_mass(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    double m = tl_checknumber(L, 3, &TL_R_MASS);
    tl_check_result(L, w, tt_particle_set_mass(w, p, m));
    return 0;
}

static int w_pinned(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    bool b;
    tl_check_result(L, w, tt_particle_get_pinned(w, p, &b));
    lua_pushboolean(L, b);
    return 1;
}

static int w_asleep(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    bool b;
    tl_check_result(L, w, tt_particle_get_asleep(w, p, &b));
    lua_pushboolean(L, b);
    return 1;
}

static int w_set_pinned(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    bool b = tl_checkboolean(L, 3);
    tl_check_result(L, w, tt_particle_set_pinned(w, p, b));
    return 0;
}

static int w_radius(lua_State *L) { return particle_number(L, tt_particle_get_radius); }

static int w_set_radius(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    double r = tl_checknumber(L, 3, &TL_R_NONNEG);
    tl_check_result(L, w, tt_particle_set_radius(w, p, r));
    return 0;
}

static int w_filter(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    uint16_t category, mask;
    tl_check_result(L, w, tt_particle_get_filter(w, p, &category, &mask));
    lua_pushinteger(L, category);
    lua_pushinteger(L, mask);
    return 2;
}

static int w_set_filter(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    uint16_t category = (uint16_t)tl_checkinteger(L, 3, 0, 0xFFFF);
    uint16_t mask = (uint16_t)tl_checkinteger(L, 4, 0, 0xFFFF);
    tl_check_result(L, w, tt_particle_set_filter(w, p, category, mask));
    return 0;
}

/* w:user(p) → the Lua value stored with p (nil if none) */
static int w_user(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    push_users(L);
    lua_rawgeti(L, -1, (lua_Integer)tt_particle_to_u64(p));
    return 1;
}

/* w:set_user(p, value) — any Lua value; nil forgets it */
static int w_set_user(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    lua_settop(L, 3);
    push_users(L);
    lua_pushvalue(L, 3);
    lua_rawseti(L, -2, (lua_Integer)tt_particle_to_u64(p));
    return 0;
}

static int w_apply_force(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    tt_vec2 f;
    f.x = tl_checknumber(L, 3, &TL_R_COORD);
    f.y = tl_checknumber(L, 4, &TL_R_COORD);
    tl_check_result(L, w, tt_particle_apply_force(w, p, f));
    return 0;
}

static int w_apply_impulse(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_particle p = tl_check_particle(L, w, 2);
    tt_vec2 j;
    j.x = tl_checknumber(L, 3, &TL_R_COORD);
    j.y = tl_checknumber(L, 4, &TL_R_COORD);
    tl_check_result(L, w, tt_particle_apply_impulse(w, p, j));
    return 0;
}

/* w:explode(x, y, radius, impulse) */
static int w_explode(lua_State *L)
{
    tt_world *w = tl_check_world(L, 1);
    tt_vec2 c;
    double radius, impulse;
    c.x = tl_checknumber(L, 2, &TL_R_COORD);
    c.y = tl_checknumber(L, 3, &TL_R_COORD);
    radius = tl_checknumber(L, 4, &TL_R_NONNEG);
    impulse = tl_checknumber(L, 5, &TL_R_COORD);
    tl_check_result(L, w, tt_world_explode(w, c, radius, impulse));
    return 0;
}

/* --- registration ----------------------------------------------------------- */

static const luaL_Reg particle_methods[] = {
    { "particle", w_particle },
    { "remove", w_remove },
    { "is_valid", w_is_valid },
    { "position", w_position },
    { "set_position", w_set_position },
    { "velocity", w_velocity },
    { "set_velocity", w_set_velocity },
    { "rotation", w_angle },
    { "spin", w_spin },
    { "set_spin", w_set_spin },
    { "mass", w_mass },
    { "set_mass", w_set_mass },
    { "pinned", w_pinned },
    { "asleep", w_asleep },
    { "set_pinned", w_set_pinned },
    { "radius", w_radius },
    { "set_radius", w_set_radius },
    { "filter", w_filter },
    { "set_filter", w_set_filter },
    { "user", w_user },
    { "set_user", w_set_user },
    { "apply_force", w_apply_force },
    { "apply_impulse", w_apply_impulse },
    { "explode", w_explode },
    { NULL, NULL }
};

void tl_particles_register(lua_State *L)
{
    tl_world_add_methods(L, particle_methods);
}
