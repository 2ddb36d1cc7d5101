/* tether — Lua binding helpers shared by every lua_*.c file.
 *
 * Every binding function is registered as a C closure whose upvalue 1 is its
 * own name ("position", "tether.world"), so every checker here can write a
 * message that names the function and the argument, however the function
 * was called (w:position(p), pcall(w.position, w, p), a local alias):
 *
 *     bad argument #3 to 'set_position' (finite number expected, got nan)
 *
 * Argument numbers count every argument the function receives, the world of
 * a method call included (self is #1). Nothing here lets a non-finite number
 * or an out-of-range value through: the C core never sees Lua garbage. */
#ifndef TETHER_LUA_COMMON_H
#define TETHER_LUA_COMMON_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <lua.h>
#include <lauxlib.h>

#include "lua_compat.h"

#include "tether.h"

/* Limits enforced by the binding: the core's documented limits (base.h),
 * checked here first so that the error names the Lua function and argument. */
#define TL_MAX_ABS    TT_MAX_VALUE /* positions, velocities, forces, impulses, gravity, wind */
#define TL_MAX_POS    TT_MAX_VALUE /* radius, stiffness, damping, rest length, explosion radius */
#define TL_MIN_MASS   TT_MIN_MASS  /* kg */
#define TL_MAX_MASS   TT_MAX_MASS  /* kg */
#define TL_MAX_DT     TT_MAX_DT    /* s */
#define TL_MAX_STEPS  10000000     /* w:step(dt, n): n <= 1e7 */
#define TL_MAX_CAPACITY 16777216   /* world option capacity <= the core's default max_particles */

/* A closed or half-open interval of accepted numbers. */
typedef struct tl_range {
    double lo, hi;
    bool lo_open; /* true: lo itself is refused, written "(lo, hi]" */
} tl_range;

/* Ready-made ranges. */
extern const tl_range TL_R_COORD;  /* [-1e12, 1e12]: positions, velocities, forces, impulses, gravity, wind */
extern const tl_range TL_R_NONNEG; /* [0, 1e12]: radius, stiffness, damping, rest length */
extern const tl_range TL_R_UNIT;   /* [0, 1]: stiffness, restitution, colour channels */
extern const tl_range TL_R_MASS;   /* [1e-9, 1e9] */
extern const tl_range TL_R_DT;     /* [1e-9, 10] */

/* --- registration ---------------------------------------------------------- */

/* Like luaL_setfuncs(L, l, 0) into the table on the top of the stack, but
 * each function becomes a closure with upvalue 1 = prefix .. name. */
void tl_setfuncs(lua_State *L, const luaL_Reg *l, const char *prefix);
/* Name of the running binding function (upvalue 1), or "?". */
const char *tl_fname(lua_State *L);

/* --- errors ---------------------------------------------------------------- */

/* Raises "bad argument #arg to 'fname' (<formatted message>)". Never returns. */
int tl_argerror(lua_State *L, int arg, const char *fmt, ...);
/* Raises "bad argument #arg to 'fname' (<expected> expected, got <type>)". */
int tl_typeerror(lua_State *L, int arg, const char *expected);
/* Raises "fname: <formatted message>". Never returns. */
int tl_error(lua_State *L, const char *fmt, ...);
/* Pushes the type name of the value at idx as luaL_typeerror writes it
 * (the __name of a userdata class, "light userdata", or the basic type). */
const char *tl_pushtypename(lua_State *L, int idx);

/* --- positional arguments -------------------------------------------------- */

/* A number (not a numeric string), finite, inside r. */
double tl_checknumber(lua_State *L, int arg, const tl_range *r);
/* As tl_checknumber, or def when the argument is none or nil. */
double tl_optnumber(lua_State *L, int arg, const tl_range *r, double def);
/* An integer-valued number (3 or 3.0, not "3") inside [lo, hi]. */
lua_Integer tl_checkinteger(lua_State *L, int arg, lua_Integer lo, lua_Integer hi);
lua_Integer tl_optinteger(lua_State *L, int arg, lua_Integer lo, lua_Integer hi, lua_Integer def);
/* A boolean (true or false; no truthiness). */
bool tl_checkboolean(lua_State *L, int arg);
/* A string, or a number turned into one (text to show, a path): what
 * luaL_checkstring accepts, with a message that names the function. */
const char *tl_checkstring(lua_State *L, int arg);
/* As tl_checkstring, or def when the argument is none or nil. */
const char *tl_optstring(lua_State *L, int arg, const char *def);
/* A string from list (NULL-terminated); def (may be NULL) when none or nil.
 * what names the thing in the error:
 * "invalid mode 'x', expected one of: 'keep', 'reset'". Returns the index. */
int tl_checkoption(lua_State *L, int arg, const char *what, const char *def, const char *const list[]);
/* Nothing, nil or a table: returns true for a table. */
bool tl_opttable(lua_State *L, int arg);

/* --- option tables (lua_options.c) -------------------------------------------
 * Each option table a binding accepts is one tl_opt array, ended by
 * TL_OPT_END: key, kind, range, and where the value goes in the C
 * definition struct that the binding filled with its defaults first
 * (tt_*_def_default()). The TL_OPT_* makers check at compile time that the
 * field has the kind's size. An option the struct has no field for is
 * TL_OPT_BYHAND: checked as a known key, read by the caller (tl_getopt or a
 * tl_optfield_* reader). */
typedef enum tl_opt_kind { TL_OPT_NUMBER, TL_OPT_NUMBER2, TL_OPT_U32, TL_OPT_U16, TL_OPT_I32, TL_OPT_BOOL, TL_OPT_VEC2, TL_OPT_ENUM, TL_OPT_OWN } tl_opt_kind;
typedef struct tl_opt {
    const char *key;
    tl_opt_kind kind;
    size_t at;                 /* offsetof the field */
    size_t at2;                /* NUMBER2: the second field it sets */
    const tl_range *range;     /* NUMBER, VEC2 */
    lua_Integer lo, hi;        /* U32, U16, I32 */
    const char *what;          /* ENUM: what its error calls the value */
    const char *const *names;  /* ENUM: the names, in the enum's order */
} tl_opt;
#define TL__AT(T, f, size) (offsetof(T, f) + 0 * sizeof(char[sizeof(((T *)0)->f) == (size) ? 1 : -1]))
#define TL_OPT_NUM(T, key, f, range) {key, TL_OPT_NUMBER, TL__AT(T, f, sizeof(double)), 0, range, 0, 0, NULL, NULL}
/* One number that sets two fields (friction: static and kinetic); listed before the fields' own keys, which then win. */
#define TL_OPT_NUM_BOTH(T, key, f, g, range) {key, TL_OPT_NUMBER2, TL__AT(T, f, sizeof(double)), TL__AT(T, g, sizeof(double)), range, 0, 0, NULL, NULL}
#define TL_OPT_UINT(T, key, f, lo, hi) {key, TL_OPT_U32, TL__AT(T, f, sizeof(uint32_t)), 0, NULL, lo, hi, NULL, NULL}
#define TL_OPT_INT(T, key, f, lo, hi) {key, TL_OPT_I32, TL__AT(T, f, sizeof(int)), 0, NULL, lo, hi, NULL, NULL}
#define TL_OPT_UINT16(T, key, f, lo, hi) {key, TL_OPT_U16, TL__AT(T, f, sizeof(uint16_t)), 0, NULL, lo, hi, NULL, NULL}
#define TL_OPT_FLAG(T, key, f) {key, TL_OPT_BOOL, TL__AT(T, f, sizeof(bool)), 0, NULL, 0, 0, NULL, NULL}
#define TL_OPT_XY(T, key, f, range) {key, TL_OPT_VEC2, TL__AT(T, f, sizeof(tt_vec2)), 0, range, 0, 0, NULL, NULL}
#define TL_OPT_CHOICE(T, key, f, what, names) {key, TL_OPT_ENUM, TL__AT(T, f, sizeof(int)), 0, NULL, 0, 0, what, names}
#define TL_OPT_BYHAND(key) {key, TL_OPT_OWN, 0, 0, NULL, 0, 0, NULL, NULL}
#define TL_OPT_END {NULL, TL_OPT_OWN, 0, 0, NULL, 0, 0, NULL, NULL}
/* The surface and filter options of everything particles touch (shapes,
 * terrains, mask chains, the world's collision settings): fields of these
 * names at P (the struct itself, or a member path ending in '.'). */
#define TL_SURFACE_OPTS(T, P)                                                                       \
    TL_OPT_NUM(T, "restitution", P restitution, &TL_R_UNIT),                                        \
    TL_OPT_NUM_BOTH(T, "friction", P friction_static, P friction_kinetic, &TL_R_NONNEG),            \
    TL_OPT_NUM(T, "friction_static", P friction_static, &TL_R_NONNEG),                              \
    TL_OPT_NUM(T, "friction_kinetic", P friction_kinetic, &TL_R_NONNEG)
#define TL_FILTER_OPTS(T, P)                                                                        \
    TL_OPT_UINT16(T, "category", P category, 0, 0xFFFF), TL_OPT_UINT16(T, "mask", P mask, 0, 0xFFFF)

/* The argument is none, nil or a table whose keys are all keys of spec;
 * raises "fname: unknown option 'gravty' (expected one of: 'gravity', ...)"
 * otherwise. Then reads every option of spec present in it into dst, in
 * spec's order, raising "fname: bad option 'key' (<why>)" at the first bad
 * one. Returns true if it is a table. Nothing is read from the world, so a
 * binding reads its options before it touches the world. */
bool tl_readopts(lua_State *L, int arg, const tl_opt spec[], void *dst);
/* The key check alone. */
bool tl_checkopts(lua_State *L, int arg, const tl_opt spec[]);
/* Pushes field key of the option table at arg (which may be absent).
 * Returns false (and pushes nothing) when the field is nil or the table absent. */
bool tl_getopt(lua_State *L, int arg, const char *key);
/* Readers of one option: def when the field is nil; otherwise the value
 * must be valid or "fname: bad option 'key' (<why>)" is raised. */
double tl_optfield_number(lua_State *L, int arg, const char *key, const tl_range *r, double def);
lua_Integer tl_optfield_integer(lua_State *L, int arg, const char *key, lua_Integer lo, lua_Integer hi, lua_Integer def);
bool tl_optfield_boolean(lua_State *L, int arg, const char *key, bool def);
/* An option whose value is {x, y}: two numbers inside r. */
tt_vec2 tl_optfield_vec2(lua_State *L, int arg, const char *key, const tl_range *r, tt_vec2 def);
/* An option whose value is one string of list: the index, or def_index when
 * nil. Raises "fname: invalid <what> 'x', expected one of: 'a', 'b'". */
int tl_optfield_option(lua_State *L, int arg, const char *key, const char *what, const char *const list[], int def_index);

/* --- validators that report instead of raising ------------------------------
 * Each checks the value at idx; on failure pushes a message ("finite number
 * expected, got nan") and returns false. Used by the raising checkers above
 * and by the bulk functions that add "at index 7" to the message. */
bool tl_tonumber_in(lua_State *L, int idx, const tl_range *r, double *out);
/* An integer-valued number inside [lo, hi]. */
bool tl_tointeger_in(lua_State *L, int idx, lua_Integer lo, lua_Integer hi, lua_Integer *out);
/* Pushes "'a', 'b', 'c'". */
void tl_push_choices(lua_State *L, const char *const list[]);
/* Pushes "<what> expected, got <type>" for the value at idx, or with
 * by_value "got <the number>" when it is a number. */
void tl_push_expected(lua_State *L, int idx, const char *what, bool by_value);

/* --- handles (lua_handle.c): the one place they are pushed and checked ------
 * A handle is an integer carrying its kind (tether/base.h). The checkers
 * refuse a non-integer, an integer that is no handle, a handle of another
 * kind ("particle expected, got shape") and, when w is not NULL, a stale
 * one ("stale particle handle"). */
bool tl_tohandle(lua_State *L, int idx, const tt_world *w, tt_kind kind, uint64_t *out);
uint64_t tl_checkhandle(lua_State *L, const tt_world *w, int arg, tt_kind kind);
void tl_push_particle(lua_State *L, tt_particle p);
void tl_push_spring(lua_State *L, tt_spring s);
void tl_push_constraint(lua_State *L, tt_constraint c);
void tl_push_shape(lua_State *L, tt_shape s);
void tl_push_composite(lua_State *L, tt_composite c);
void tl_push_terrain(lua_State *L, tt_terrain t);
/* What w:is_valid(h) and its kin answer: false for a stale handle and for
 * an integer that is no handle (0 included); raises for a non-integer or a
 * handle of another kind. */
bool tl_handle_is_live(lua_State *L, const tt_world *w, int arg, tt_kind kind);
const char *tl_kind_name(tt_kind k);

/* --- classes (lua_world.c) -------------------------------------------------- */

#define TL_WORLD_CLASS "tether.world"

/* A reusable buffer of the bulk accessors, so that reading positions every
 * frame allocates nothing. */
typedef struct tl_buffer {
    void *p;
    size_t cap;
} tl_buffer;

/* The userdata. Made with w = NULL (harmless) before the world exists;
 * w = NULL again once freed. scratch[d] belongs to the call at depth d + 1
 * (a call nested in another on the same world must not clobber the outer
 * one's buffer while it is still reading it). Here, not in lua_world.c,
 * because the w:each() iterator (lua_bulk.c) holds the userdata itself, not
 * a call's argument 1, and must see it die. */
typedef struct tl_world_ud {
    tt_world *w;
    bool dead;         /* destroyed: no new call may use it; freed when pins is 0 */
    unsigned pins;     /* calls running on this world, nested ones included */
    tl_buffer *scratch;
    unsigned nscratch;
} tl_world_ud;

/* Option names read by more than one file, NULL-terminated, in the order of
 * tt_integrator, tt_solver_order (lua_world.c) and tt_move_mode
 * (lua_particles.c), so that a name's index is the enum value. */
extern const char *const tl_integrator_names[];
extern const char *const tl_solver_names[];
extern const char *const tl_move_modes[];

/* Creates the world metatable (once per state); leaves nothing on the stack. */
void tl_world_register(lua_State *L);
/* tether.world([opts]) */
int tl_world_new(lua_State *L);
/* Pushes the list of integrator names, {"euler", ...}. */
void tl_push_integrators(lua_State *L);
/* Adds methods to the world class (a feature's binding calls this from
 * luaopen_tether through its own tl_<feature>_register). They are pinned,
 * as by tl_setfuncs_pinned. */
void tl_world_add_methods(lua_State *L, const luaL_Reg *methods);
/* As tl_setfuncs, for functions whose argument 1 is a world (every method,
 * and any other function taking a world first): each runs with that world
 * pinned. Lua code that runs in the middle of the call (an __index of an
 * option table, a __close, a finalizer run by one of the call's own
 * allocations) may destroy the world: it is then marked destroyed at once
 * and freed when the outermost call on it returns, so the world pointer a
 * function holds stays valid until it returns. Such Lua code may also step
 * or grow the world: a function copies what it reads from the world (into
 * tl_scratch) before it makes any Lua value. */
void tl_setfuncs_pinned(lua_State *L, const luaL_Reg *l, const char *prefix);
/* A buffer of at least `bytes` bytes for the running pinned call on the
 * world at argument 1, reused from call to call: never a Lua allocation
 * (no collector, no finalizer), and a call nested in it gets another one.
 * Valid until the call returns or asks for scratch again. */
void *tl_scratch(lua_State *L, size_t bytes);
/* The world at arg (raises "attempt to use a destroyed world", or a type error). */
tt_world *tl_check_world(lua_State *L, int arg);
/* A live particle of w at arg (raises "stale particle handle"). */
tt_particle tl_check_particle(lua_State *L, tt_world *w, int arg);
/* Raises "fname: <tt_last_error(w)>" unless r is TT_OK. */
void tl_check_result(lua_State *L, const tt_world *w, tt_result r);
/* The live world of the world userdata at idx, or NULL (not a world, or destroyed): never raises. */
tt_world *tl_toworld(lua_State *L, int idx);

/* --- method files and feature bindings: each adds its methods to the world class */
void tl_particles_register(lua_State *L);   /* lua_particles.c */
void tl_clock_register(lua_State *L);       /* lua_clock.c: tether.clock into the module table on top */
void tl_rewind_register(lua_State *L);      /* lua_rewind.c: tether.rewind into the module table on top */
void tl_journal_register(lua_State *L);     /* lua_journal.c: tether.load_journal into the module table on top, w:journal */
void tl_springs_register(lua_State *L);     /* lua_springs.c */
void tl_stepping_register(lua_State *L);    /* lua_stepping.c */
void tl_stats_register(lua_State *L);       /* lua_stats.c */
void tl_bulk_register(lua_State *L);        /* lua_bulk.c */
void tl_constraints_register(lua_State *L); /* lua_constraints.c */
void tl_composites_register(lua_State *L);  /* lua_composites.c */
void tl_collide_register(lua_State *L);     /* lua_collide.c */
void tl_terrain_register(lua_State *L);     /* lua_terrain.c */
void tl_snapshot_register(lua_State *L);    /* lua_snapshot.c */
/* Registry key of the function (world userdata, snapshot or string, is_file)
 * that loads the saved world (from the file at that path when is_file) into
 * the userdata, its user values the snapshot's; raises when the stream is
 * refused. tether.world{snapshot = s} and tether.world{file = path} call it. */
#define TL_SNAPSHOT_LOADER "tether.snapshot_loader"

#endif
