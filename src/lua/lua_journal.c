/* tether — Lua replay journals (class "tether.journal"), a thin layer over
 * tt_journal (tether/journal.h):
 *
 *   local j = w:journal()             -- records w's steps from now on
 *   ... play: calls and w:step(dt) ...
 *   j:stop(); j:save("run.ttj")
 *
 *   local j = assert(tether.load_journal("run.ttj"))
 *   j:replay(w)                       -- w becomes the recorded start
 *   function tether.update(dt)
 *     local s = j:step()              -- "sync", "desync" or "end"
 *   end
 *
 * Every call that changes the world between two steps is in the journal
 * (found by comparing streams, not by hooking calls); user values are not,
 * and a replay leaves them as they are. The journal holds the world it
 * records or replays as its user value, so the world lives while it does. */
#include "lua_common.h"
#include "tether/journal.h"

#include <inttypes.h>
#include <stdio.h>

#define TL_JOURNAL_CLASS "tether.journal"

typedef struct tl_journal {
    tt_journal *j; /* NULL once destroyed */
} tl_journal;

static tt_journal *check_journal(lua_State *L, int arg)
{
    tl_journal *u = luaL_testudata(L, arg, TL_JOURNAL_CLASS);
    if (u == NULL) tl_typeerror(L, arg, TL_JOURNAL_CLASS);
    if (u->j == NULL) tl_argerror(L, arg, "the journal was destroyed");
    return u->j;
}

/* A new, empty userdata on the stack, owning j (destroyed on failure). */
static void push_journal(lua_State *L, tt_journal *j)
{
    tl_journal *u = lua_newuserdatauv(L, sizeof *u, 1);
    u->j = NULL;
    luaL_setmetatable(L, TL_JOURNAL_CLASS);
    u->j = j;
}

/* The journal's world (the value at idx) kept as its user value, inside a
 * table: LuaJIT's user value (an environment) must be a table. */
static void keep_world(lua_State *L, int journal, int idx)
{
    idx = lua_absindex(L, idx);
    journal = lua_absindex(L, journal);
    lua_createtable(L, 1, 0);
    lua_pushvalue(L, idx);
    lua_rawseti(L, -2, 1);
    lua_setiuservalue(L, journal, 1);
}

static const tl_range R_BYTES = {1024, 1e15, false};
typedef struct journal_opts_def {
    double max_bytes; /* a size_t in tt_journal_def: read as a number */
} journal_opts_def;
static const tl_opt journal_opts[] = {
    TL_OPT_NUM(journal_opts_def, "max_bytes", max_bytes, &R_BYTES),
    TL_OPT_END,
};

/* w:journal([opts]) → journal, recording w: max_bytes (default 256 MB) */
static int w_journal(lua_State *L)
{
    tl_check_world(L, 1);
    tt_journal_def def = tt_journal_def_default();
    journal_opts_def o = {(double)def.max_bytes};
    tl_readopts(L, 2, journal_opts, &o);
    def.max_bytes = (size_t)o.max_bytes;
    push_journal(L, NULL); /* first: an allocation error now leaks nothing */
    tt_world *w = tl_check_world(L, 1);
    tt_journal *j = tt_journal_start(w, &def);
    if (!j) tl_check_result(L, w, TT_EINVAL);
    ((tl_journal *)lua_touserdata(L, -1))->j = j;
    keep_world(L, -1, 1);
    return 1;
}

/* tether.load_journal(path) → journal, or nil and the reason */
static int load_journal(lua_State *L)
{
    const char *path = tl_checkstring(L, 1);
    push_journal(L, NULL);
    tt_journal *j = tt_journal_load_file(path);
    if (!j) {
        lua_pushnil(L);
        lua_pushstring(L, tt_last_error(NULL));
        return 2;
    }
    ((tl_journal *)lua_touserdata(L, -1))->j = j;
    return 1;
}

static tt_journal_info info_of(lua_State *L, int arg)
{
    tt_journal_info info;
    tt_journal_get_info(check_journal(L, arg), &info);
    return info;
}

/* j:stop(): recording stops (nothing when it was not recording) */
static int j_stop(lua_State *L)
{
    tt_journal_stop(check_journal(L, 1));
    return 0;
}

static int j_recording(lua_State *L)
{
    lua_pushboolean(L, info_of(L, 1).recording);
    return 1;
}

static int j_steps(lua_State *L)
{
    lua_pushinteger(L, (lua_Integer)info_of(L, 1).steps);
    return 1;
}

/* j:size() → bytes held (snapshot, record, work space) */
static int j_size(lua_State *L)
{
    lua_pushinteger(L, (lua_Integer)info_of(L, 1).bytes);
    return 1;
}

static void push_hash(lua_State *L, uint64_t h)
{
    char buf[17];
    snprintf(buf, sizeof buf, "%016" PRIx64, h);
    lua_pushstring(L, buf);
}

/* j:info() → {steps, changed, bytes, record_bytes, snapshot_bytes, recording, full, replayed, desync} */
static int j_info(lua_State *L)
{
    tt_journal_info i = info_of(L, 1);
    lua_createtable(L, 0, 9);
    const struct { const char *k; uint64_t v; } ints[] = {
        {"steps", i.steps}, {"changed", i.changed}, {"bytes", i.bytes}, {"record_bytes", i.record_bytes},
        {"snapshot_bytes", i.snapshot_bytes}, {"replayed", i.replayed}, {"desync", i.desync}};
    for (unsigned k = 0; k < sizeof ints / sizeof ints[0]; k++) {
        lua_pushinteger(L, (lua_Integer)ints[k].v);
        lua_setfield(L, -2, ints[k].k);
    }
    lua_pushboolean(L, i.recording);
    lua_setfield(L, -2, "recording");
    lua_pushboolean(L, i.full);
    lua_setfield(L, -2, "full");
    return 1;
}

/* j:desync() → step, expected hash, got hash (hex strings, as w:hash()); nil when none */
static int j_desync(lua_State *L)
{
    tt_journal_info i = info_of(L, 1);
    if (!i.desync) {
        lua_pushnil(L);
        return 1;
    }
    lua_pushinteger(L, (lua_Integer)i.desync);
    push_hash(L, i.desync_expected);
    push_hash(L, i.desync_got);
    return 3;
}

/* j:save(path) → true, or nil and the reason */
static int j_save(lua_State *L)
{
    tt_journal *j = check_journal(L, 1);
    const char *path = tl_checkstring(L, 2);
    if (tt_journal_save_file(j, path) != TT_OK) {
        lua_pushnil(L);
        lua_pushstring(L, tt_last_error(NULL));
        return 2;
    }
    lua_pushboolean(L, 1);
    return 1;
}

/* j:replay(w): w becomes the journal's start, the replay before its first step */
static int j_replay(lua_State *L)
{
    tt_journal *j = check_journal(L, 1);
    tt_world *w = tl_check_world(L, 2);
    tl_check_result(L, w, tt_journal_replay_begin(j, w));
    keep_world(L, 1, 2);
    return 0;
}

/* The world the replay plays into (raises when none or destroyed). */
static tt_world *replay_world(lua_State *L, tt_journal *j)
{
    tt_journal_info i;
    tt_journal_get_info(j, &i);
    if (i.recording) tl_error(L, "the journal is recording (j:stop() it first)");
    tt_world *w = NULL;
    if (lua_getiuservalue(L, 1, 1) == LUA_TTABLE) {
        lua_rawgeti(L, -1, 1);
        w = tl_toworld(L, -1);
        lua_pop(L, 1);
    }
    lua_pop(L, 1);
    if (!w) tl_error(L, "no replay begun (j:replay(w)), or its world was destroyed");
    return w;
}

static const char *const replay_names[] = {"end", "sync", "desync"};

/* j:step() → "sync" (a step played, the recorded hash), "desync" (played,
 * another hash: j:desync() says where) or "end" (nothing left) */
static int j_step(lua_State *L)
{
    tt_journal *j = check_journal(L, 1);
    tt_world *w = replay_world(L, j);
    tt_replay r = TT_REPLAY_END;
    tl_check_result(L, w, tt_journal_replay_step(j, w, &r));
    lua_pushstring(L, replay_names[r]);
    return 1;
}

/* j:run() → "end" or "desync" (where the replay stopped), steps played */
static int j_run(lua_State *L)
{
    tt_journal *j = check_journal(L, 1);
    tt_world *w = replay_world(L, j);
    const uint64_t before = info_of(L, 1).replayed;
    tt_replay r = TT_REPLAY_END;
    tl_check_result(L, w, tt_journal_replay_all(j, w, &r));
    lua_pushstring(L, replay_names[r]);
    lua_pushinteger(L, (lua_Integer)(info_of(L, 1).replayed - before));
    return 2;
}

/* j:destroy(), and the collector: stops recording and frees it; safe to repeat */
static int j_destroy(lua_State *L)
{
    tl_journal *u = luaL_checkudata(L, 1, TL_JOURNAL_CLASS);
    tt_journal_destroy(u->j);
    u->j = NULL;
    return 0;
}

static int j_tostring(lua_State *L)
{
    tl_journal *u = luaL_checkudata(L, 1, TL_JOURNAL_CLASS);
    if (!u->j) {
        lua_pushstring(L, "tether.journal (destroyed)");
        return 1;
    }
    tt_journal_info i;
    tt_journal_get_info(u->j, &i);
    lua_pushfstring(L, "tether.journal (" TL_I " steps, " TL_I " bytes%s)", TL_IARG(i.steps), TL_IARG(i.bytes),
                    i.recording ? ", recording" : "");
    return 1;
}

static const luaL_Reg journal_world_methods[] = {{"journal", w_journal}, {NULL, NULL}};
static const luaL_Reg journal_methods[] = {
    {"stop", j_stop}, {"recording", j_recording}, {"steps", j_steps}, {"size", j_size}, {"info", j_info},
    {"desync", j_desync}, {"save", j_save}, {"replay", j_replay}, {"step", j_step}, {"run", j_run},
    {"destroy", j_destroy}, {NULL, NULL}};
static const luaL_Reg journal_meta[] = {{"__gc", j_destroy}, {"__tostring", j_tostring}, {NULL, NULL}};
static const luaL_Reg journal_funcs[] = {{"load_journal", load_journal}, {NULL, NULL}};

/* Adds tether.load_journal to the module table on top of the stack, and w:journal. */
void tl_journal_register(lua_State *L)
{
    if (luaL_newmetatable(L, TL_JOURNAL_CLASS)) {
        tl_setfuncs(L, journal_meta, "");
        lua_createtable(L, 0, 11);
        tl_setfuncs(L, journal_methods, "");
        lua_setfield(L, -2, "__index");
    }
    lua_pop(L, 1);
    tl_setfuncs(L, journal_funcs, "tether.");
    tl_world_add_methods(L, journal_world_methods);
}
