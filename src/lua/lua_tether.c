/* tether — the Lua module: require "tether".
 *
 *   tether.version      "0.1.0"
 *   tether.integrators  {"euler", "symplectic_euler", "leapfrog", "verlet", "rk4"}
 *   tether.world(opts)  a new world (lua_world.c), its methods added below by
 *                       the lua_<concept>.c files
 *   tether.clock(opts)  a fixed-step clock (lua_clock.c)
 *   tether.load_journal(path)  a replay journal from a file (lua_journal.c)
 *
 * Built into build/tether.so for stock lua5.4 and linked into the runner. */
#include "lua_common.h"
#include "lua_render.h"
#include "lua_mask.h"

static const luaL_Reg tether_funcs[] = {
    { "world", tl_world_new },
    { NULL, NULL }
};

TT_API int luaopen_tether(lua_State *L);

TT_API int luaopen_tether(lua_State *L)
{
    luaL_checkversion(L);
    tl_world_register(L);
    tl_particles_register(L);
    tl_springs_register(L);
    tl_stepping_register(L);
    tl_stats_register(L);
    tl_bulk_register(L);
    tl_constraints_register(L);
    tl_composites_register(L);
    tl_collide_register(L);
    tl_terrain_register(L);
    tl_snapshot_register(L);
    lua_createtable(L, 0, 4);
    tl_setfuncs(L, tether_funcs, "tether.");
    lua_pushstring(L, tt_version());
    lua_setfield(L, -2, "version");
    tl_push_integrators(L);
    lua_setfield(L, -2, "integrators");
    tl_clock_register(L);
    tl_rewind_register(L);
    tl_journal_register(L);
    tl_render_register(L);
    tl_mask_register(L);
    tl_mask_ops_register(L);
    tl_mask_draw_register(L);
    return 1;
}
