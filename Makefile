# tether — plain Makefile. `make demo`, `make test`, `make bench`, `make install PREFIX=...`
# `make test SANITIZE=1` builds everything with ASan+UBSan into build-san/.

PREFIX ?= /usr/local
FUZZ_SECONDS ?= 60
FUZZ_SEED ?=
VERSION := $(shell sed -n 's/^\#define TT_VERSION_STRING "\(.*\)"/\1/p' include/tether/base.h)
# The shared library's ABI version is the major version: programs linked
# against libtether.so.0 keep running across 0.x.y upgrades.
SOVERSION := $(firstword $(subst ., ,$(VERSION)))
SONAME    := libtether.so.$(SOVERSION)
CC     ?= cc
CXX    ?= c++

# Debian packages the project needs (see README "Set-up").
DEB_PKGS := pkg-config lua5.4 liblua5.4-dev luajit libluajit-5.1-dev libbox2d-dev libsdl2-dev libosmesa6-dev libpng-dev xvfb xauth love gnuplot-nox valgrind clang
PC_PKGS  := lua5.4 luajit box2d sdl2 osmesa libpng

ifeq ($(SANITIZE),1)
BUILD    := build-san
# -fsanitize=undefined leaves out float-cast-overflow (a double too big for
# the int it becomes, as the grid's cell counts once were): named on its own.
SANFLAGS := -fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=undefined,float-cast-overflow -fno-omit-frame-pointer -g
OPT      := -O1
else
BUILD    := build
SANFLAGS :=
OPT      := -O2
endif

WARN     := -Wall -Wextra -Wpedantic -Wshadow -Wmissing-prototypes -Wstrict-prototypes
# Determinism: no contraction of a*b+c into FMA, never -ffast-math.
FPFLAGS  := -ffp-contract=off
CFLAGS_ALL := -std=c11 -D_DEFAULT_SOURCE $(OPT) $(FPFLAGS) $(WARN) -fPIC -fvisibility=hidden -Iinclude -Isrc $(SANFLAGS) $(CFLAGS)
LDFLAGS_ALL := $(SANFLAGS) $(LDFLAGS)

# The package flags are read when a recipe first needs them, not when this file
# is parsed: on a fresh machine `make deps` (run first, see the order-only
# prerequisites below) has only just installed the packages. `lazy` asks
# pkg-config once and keeps the answer.
PC_CFLAGS = $(shell pkg-config --cflags $(1) 2>/dev/null)
PC_LIBS   = $(shell pkg-config --libs $(1) 2>/dev/null)
lazy = $(eval $(1) := $(2))$($(1))
LUA_CFLAGS = $(call lazy,LUA_CFLAGS,$(call PC_CFLAGS,lua5.4))
LUA_LIBS   = $(call lazy,LUA_LIBS,$(call PC_LIBS,lua5.4))
LUAJIT_CFLAGS = $(call lazy,LUAJIT_CFLAGS,$(call PC_CFLAGS,luajit))
BOX2D_CFLAGS = $(call lazy,BOX2D_CFLAGS,$(call PC_CFLAGS,box2d))
BOX2D_LIBS   = $(call lazy,BOX2D_LIBS,$(call PC_LIBS,box2d))
PNG_CFLAGS = $(call lazy,PNG_CFLAGS,$(call PC_CFLAGS,libpng))
PNG_LIBS   = $(call lazy,PNG_LIBS,$(call PC_LIBS,libpng))

# Sources by part (one folder each under src/, see README "Layout"). The
# engine is core + constraints + collide + mask (mask needs libpng for its
# PNG files, so the shared library and the Lua module link it); the Lua module adds lua/ and the
# plain-C canvas of render/; the GL back ends need OSMesa, SDL2 and libpng.
ENGINE_SRC := $(wildcard src/core/*.c src/constraints/*.c src/collide/*.c src/mask/*.c)
LUA_SRC    := $(wildcard src/lua/*.c)
CANVAS_SRC := src/render/render_canvas.c src/render/render_font.c src/render/render_debug.c src/render/render_mask.c
RENDER_SRC := $(wildcard src/render/*.c)
RUNNER_SRC := $(wildcard src/runner/*.c)
# Scene descriptions and their tether builder (plain C, public API only):
# linked by the bench, the tests and the Box2D bridge, never by the engine.
SCENES_SRC := $(wildcard src/scenes/*.c)
# The Box2D cross-check: the only C++ file, its C side and its Lua module.
B2_SRC     := $(filter-out src/box2d/lua_%.c,$(wildcard src/box2d/*.c))
B2_LUA_SRC := $(wildcard src/box2d/lua_*.c)
obj_of = $(patsubst src/%.c,$(BUILD)/obj/%.o,$(1))
CORE_OBJ   := $(call obj_of,$(ENGINE_SRC))
LUA_OBJ    := $(call obj_of,$(LUA_SRC))
CANVAS_OBJ := $(call obj_of,$(CANVAS_SRC))
RENDER_OBJ := $(call obj_of,$(RENDER_SRC))
RUNNER_OBJ := $(call obj_of,$(RUNNER_SRC))
SCENES_OBJ := $(call obj_of,$(SCENES_SRC))
B2_OBJ     := $(call obj_of,$(B2_SRC)) $(BUILD)/obj/box2d/box2d_bridge.o
B2_LUA_OBJ := $(call obj_of,$(B2_LUA_SRC))
# The same binding sources compiled a second time against LuaJIT (src/lua/lua_compat.h).
LUAJIT_OBJ := $(patsubst src/lua/%.c,$(BUILD)/obj/luajit/%.o,$(LUA_SRC))
B2_LUAJIT_OBJ := $(patsubst src/box2d/%.c,$(BUILD)/obj/luajit_box2d/%.o,$(B2_LUA_SRC))
RENDER_CFLAGS = $(call lazy,RENDER_CFLAGS,$(call PC_CFLAGS,sdl2 libpng))
# OSMesa exports the gl* functions itself: never add -lGL (SDL loads libGL at run time).
RENDER_LIBS = $(call lazy,RENDER_LIBS,$(call PC_LIBS,osmesa sdl2 libpng))
# tests/fuzz/ holds fuzzers with their own main, built on their own; the
# snapshot stream reader's and the replay journal reader's fuzzers are tests of
# test_c (make test runs 300 streams and 200 journals).
# tests/box2d/ links Box2D: a program of its own.
TEST_SRC := $(filter-out tests/fuzz/% tests/box2d/% tests/crossbuild/%,$(wildcard tests/*.c tests/*/*.c)) tests/fuzz/fuzz_stream.c tests/fuzz/fuzz_bytes.c \
            tests/fuzz/fuzz_journal.c
FUZZ_C_SRC := $(wildcard tests/fuzz/fuzz_c*.c)
FUZZ_C_OBJ := $(FUZZ_C_SRC:tests/%.c=$(BUILD)/obj/tests/%.o)
TEST_OBJ := $(TEST_SRC:tests/%.c=$(BUILD)/obj/tests/%.o)
# The cross-check's tests link Box2D, so they are a program of their own.
TEST_B2_SRC := tests/test_main.c $(wildcard tests/box2d/*.c)
TEST_B2_OBJ := $(TEST_B2_SRC:tests/%.c=$(BUILD)/obj/tests/%.o)
BENCH_SRC := $(wildcard bench/*.c)

LIB_A   := $(BUILD)/libtether.a
LIB_SO  := $(BUILD)/libtether.so
LIB_SO_REAL := $(BUILD)/libtether.so.$(VERSION)
RENDER_A := $(BUILD)/libtether_render.a
LUA_MOD := $(BUILD)/tether.so
LUAJIT_MOD := $(BUILD)/luajit/tether.so
RUNNER  := $(BUILD)/tether
TEST_C  := $(BUILD)/test_c
FUZZ_C  := $(BUILD)/fuzz_c
SCENES_A := $(BUILD)/libtether_scenes.a
B2_A     := $(BUILD)/libtether_box2d.a
B2_MOD   := $(BUILD)/tether_box2d.so
B2_LUAJIT_MOD := $(BUILD)/luajit/tether_box2d.so
TEST_B2  := $(BUILD)/test_box2d
BENCH   := $(BUILD)/bench

.PHONY: all luajit deps demo pictures test test-c test-lua fuzz memcheck bench bench-payonly bench-love crosscheck atlas atlas-cg install uninstall clean
all: deps $(LIB_A) $(LIB_SO) $(RENDER_A) $(LUA_MOD) $(LUAJIT_MOD) $(RUNNER) $(SCENES_A) $(B2_A) $(B2_MOD) $(B2_LUAJIT_MOD)
luajit: deps $(LUAJIT_MOD) $(B2_LUAJIT_MOD)

# --- dependencies -----------------------------------------------------------
# Installs what is missing when run as root on Debian; otherwise prints the
# exact apt-get line and stops.
deps:
	@missing=""; \
	if command -v dpkg-query >/dev/null 2>&1; then \
	  for p in $(DEB_PKGS); do \
	    dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	  done; \
	else \
	  for p in $(PC_PKGS); do pkg-config --exists $$p 2>/dev/null || missing="$$missing $$p"; done; \
	fi; \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
	    echo "tether: installing missing Debian packages:$$missing"; \
	    apt-get update -q >/dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y -q $$missing >/dev/null || exit 1; \
	  else \
	    echo "tether: missing packages:$$missing"; \
	    echo "tether: run as root:  apt-get update && apt-get install -y$$missing"; \
	    exit 1; \
	  fi; \
	fi

# --- build ------------------------------------------------------------------
HEADERS := $(wildcard include/*.h include/tether/*.h src/*/*.h)
$(BUILD)/obj/%.o: src/%.c $(HEADERS) | deps
	@mkdir -p $(@D)
	$(CC) $(CFLAGS_ALL) -MMD -c $< -o $@

$(BUILD)/obj/lua/%.o: src/lua/%.c | deps
	@mkdir -p $(@D)
	$(CC) $(CFLAGS_ALL) $(LUA_CFLAGS) -MMD -c $< -o $@

$(BUILD)/obj/luajit/%.o: src/lua/%.c | deps
	@mkdir -p $(@D)
	$(CC) $(CFLAGS_ALL) $(LUAJIT_CFLAGS) -MMD -c $< -o $@

$(BUILD)/obj/runner/%.o: src/runner/%.c | deps
	@mkdir -p $(@D)
	$(CC) $(CFLAGS_ALL) $(LUA_CFLAGS) $(RENDER_CFLAGS) -MMD -c $< -o $@

$(BUILD)/obj/mask/%.o: src/mask/%.c $(HEADERS) | deps
	@mkdir -p $(@D)
	$(CC) $(CFLAGS_ALL) $(PNG_CFLAGS) -MMD -c $< -o $@

$(BUILD)/obj/render/%.o: src/render/%.c | deps
	@mkdir -p $(@D)
	$(CC) $(CFLAGS_ALL) $(RENDER_CFLAGS) -MMD -c $< -o $@

# The bridge: C++17 with the C files' warnings and floating-point rules.
CXXFLAGS_ALL := -std=c++17 $(OPT) $(FPFLAGS) -Wall -Wextra -Wpedantic -Wshadow -fPIC -fvisibility=hidden -Isrc $(SANFLAGS) $(CXXFLAGS)
$(BUILD)/obj/box2d/%.o: src/box2d/%.cpp src/box2d/box2d_bridge.h | deps
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS_ALL) $(BOX2D_CFLAGS) -MMD -c $< -o $@

$(BUILD)/obj/box2d/lua_%.o: src/box2d/lua_%.c $(HEADERS) | deps
	@mkdir -p $(@D)
	$(CC) $(CFLAGS_ALL) $(LUA_CFLAGS) -MMD -c $< -o $@

$(BUILD)/obj/luajit_box2d/lua_%.o: src/box2d/lua_%.c $(HEADERS) | deps
	@mkdir -p $(@D)
	$(CC) $(CFLAGS_ALL) $(LUAJIT_CFLAGS) -MMD -c $< -o $@

$(BUILD)/obj/tests/%.o: tests/%.c | deps
	@mkdir -p $(@D)
	$(CC) $(CFLAGS_ALL) $(RENDER_CFLAGS) -Itests -MMD -c $< -o $@

$(LIB_A): $(CORE_OBJ)
	rm -f $@; ar rcs $@ $^

$(LIB_SO_REAL): $(CORE_OBJ)
	$(CC) -shared -Wl,-soname,$(SONAME) -o $@ $^ $(LDFLAGS_ALL) $(PNG_LIBS) -lm

$(LIB_SO): $(LIB_SO_REAL)
	ln -sf libtether.so.$(VERSION) $(BUILD)/$(SONAME)
	ln -sf $(SONAME) $@

$(SCENES_A): $(SCENES_OBJ)
	rm -f $@; ar rcs $@ $^

$(B2_A): $(B2_OBJ)
	rm -f $@; ar rcs $@ $^

# The cross-check's Lua module carries its own copy of the engine (like
# tether.so) and is the one product that links Box2D and libstdc++. It reads
# its option tables with the binding's checkers (lua_common.c, lua_options.c),
# linked in as objects: hidden symbols, no clash with tether.so's.
B2_TL_OBJ := $(BUILD)/obj/lua/lua_common.o $(BUILD)/obj/lua/lua_options.o
B2_TL_LUAJIT_OBJ := $(BUILD)/obj/luajit/lua_common.o $(BUILD)/obj/luajit/lua_options.o
$(B2_MOD): $(B2_LUA_OBJ) $(B2_TL_OBJ) $(B2_A) $(SCENES_A) $(LIB_A)
	$(CC) -shared -o $@ $^ $(LDFLAGS_ALL) $(BOX2D_LIBS) -lstdc++ -lm

$(B2_LUAJIT_MOD): $(B2_LUAJIT_OBJ) $(B2_TL_LUAJIT_OBJ) $(B2_A) $(SCENES_A) $(LIB_A)
	@mkdir -p $(@D)
	$(CC) -shared -o $@ $^ $(LDFLAGS_ALL) $(BOX2D_LIBS) -lstdc++ -lm

# The Lua module is not linked against liblua: the host (lua5.4 or our runner)
# provides the Lua API, and a second copy of Lua in one process breaks it.
$(RENDER_A): $(RENDER_OBJ)
	rm -f $@; ar rcs $@ $^

$(LUA_MOD): $(LUA_OBJ) $(CORE_OBJ) $(CANVAS_OBJ)
	$(CC) -shared -o $@ $^ $(LDFLAGS_ALL) $(PNG_LIBS) -lm

# For LuaJIT hosts (luajit, LÖVE): `require "tether"` with build/luajit/?.so on package.cpath.
$(LUAJIT_MOD): $(LUAJIT_OBJ) $(CORE_OBJ) $(CANVAS_OBJ)
	@mkdir -p $(@D)
	$(CC) -shared -o $@ $^ $(LDFLAGS_ALL) $(PNG_LIBS) -lm

$(RUNNER): $(RUNNER_OBJ) $(LUA_OBJ) $(RENDER_A) $(LIB_A)
	$(CC) -o $@ $^ $(LDFLAGS_ALL) -Wl,-E $(LUA_LIBS) $(RENDER_LIBS) -lm

# The C tests route the engine's allocations through tests/alloc_fail.c, so a
# test can make memory run out at any chosen allocation.
TEST_WRAP := -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc
$(TEST_C): $(TEST_OBJ) $(RENDER_A) $(SCENES_A) $(LIB_A)
	$(CC) -o $@ $^ $(LDFLAGS_ALL) $(TEST_WRAP) $(RENDER_LIBS) -lm

# The PNG loader's fuzzer (tests/fuzz/fuzz_png.c), run by `make fuzz`.
FUZZ_PNG := $(BUILD)/fuzz_png
$(FUZZ_PNG): tests/fuzz/fuzz_png.c $(LIB_A) | deps
	$(CC) $(CFLAGS_ALL) $(PNG_CFLAGS) -o $@ $< $(LIB_A) $(LDFLAGS_ALL) $(PNG_LIBS) -lm

# The C API fuzzer (tests/fuzz/fuzz_c*.c): the engine and its masks (libpng), no allocation wrapping.
$(FUZZ_C): $(FUZZ_C_OBJ) $(LIB_A)
	$(CC) -o $@ $^ $(LDFLAGS_ALL) $(PNG_LIBS) -lm

$(TEST_B2): $(TEST_B2_OBJ) $(B2_A) $(SCENES_A) $(LIB_A)
	$(CC) -o $@ $^ $(LDFLAGS_ALL) $(BOX2D_LIBS) -lstdc++ -lm

# The bench compares with Box2D 2.4.1 through the bridge (src/box2d/), on
# the shared scenes (src/scenes/).
$(BENCH): $(BENCH_SRC) $(RENDER_A) $(B2_A) $(SCENES_A) $(LIB_A) | deps
	$(CC) $(CFLAGS_ALL) $(RENDER_CFLAGS) -Ibench -o $@ $(BENCH_SRC) $(RENDER_A) $(B2_A) $(SCENES_A) $(LIB_A) $(LDFLAGS_ALL) \
	  $(RENDER_LIBS) $(BOX2D_LIBS) -lstdc++ -lm

-include $(wildcard $(BUILD)/obj/*/*.d $(BUILD)/obj/luajit_box2d/*.d $(BUILD)/obj/tests/*/*.d $(BUILD)/obj/tests/*.d)

# `make crosscheck [QUICK=1]`: the eight scenes in tether and in Box2D 2.4.1,
# one table on the terminal, CSV and Markdown in $(BUILD)/crosscheck/.
crosscheck: all
	$(RUNNER) crosscheck $(if $(QUICK),--quick) --out $(BUILD)/crosscheck

# `make atlas [QUICK=1]`: the speed/accuracy atlas (lua/tether_atlas.lua):
# ten reference scenes with known answers swept over integrator, dt,
# substeps, iterations and solver order; CSV and log-log PNG plots of error
# against cost, the Pareto front drawn thick, in $(BUILD)/atlas/. QUICK=1 is
# the small sweep (6 CPU-seconds); the full one about 10 CPU-minutes.
atlas: deps $(RUNNER)
	$(RUNNER) atlas $(if $(QUICK),--quick) --out $(BUILD)/atlas

# `make atlas-cg [ONLY=scene]`: the atlas's cost in instructions (callgrind
# counts each point's steps alone; bench/atlas_cg.sh): a figure the machine's
# load does not move. The quick sweep by default (a few minutes); ONLY=NAME
# runs that scene's full sweep (up to an hour under callgrind).
atlas-cg: deps $(RUNNER)
	sh bench/atlas_cg.sh $(RUNNER) $(BUILD)/atlas-cg $(if $(ONLY),--only $(ONLY),--quick)

# --- run --------------------------------------------------------------------
# `make demo` renders DEMO headless to PNG frames in $(BUILD)/demo/ (100 frames,
# one every 6 steps: 10 s of simulated time at 10 frames per second), then an
# MP4 (ffmpeg) or an animated GIF (ImageMagick) when one of them is installed.
DEMO ?= demos/fountain.lua
DEMO_OUT := $(BUILD)/demo
demo: all
	@rm -f $(DEMO_OUT)/frame_*.png
	$(RUNNER) --headless --frames 100 --every 6 --size 800x600 --out $(DEMO_OUT) $(DEMO)
	@name=$$(basename $(DEMO) .lua); \
	if command -v ffmpeg >/dev/null 2>&1; then \
	  ffmpeg -loglevel error -y -framerate 10 -i $(DEMO_OUT)/frame_%05d.png -pix_fmt yuv420p $(DEMO_OUT)/$$name.mp4 && \
	  echo "demo: video $(DEMO_OUT)/$$name.mp4"; \
	elif convert -version 2>/dev/null | grep -q ImageMagick; then \
	  convert -delay 10 -loop 0 -resize 400x300 $(DEMO_OUT)/frame_*.png -layers Optimize $(DEMO_OUT)/$$name.gif && \
	  echo "demo: animated GIF $(DEMO_OUT)/$$name.gif"; \
	else echo "demo: PNG frames in $(DEMO_OUT)/ (install ffmpeg or ImageMagick for a video)"; fi

# `make pictures`: one PNG per demo (640x480, after 5 s of simulated
# time) into docs/img/, the pictures the README and docs/render.md show, and
# docs/img/demo.gif, 6 s of the default demo at the top of the README.
pictures: all
	@mkdir -p docs/img
	@for d in demos/*.lua; do n=$$(basename $$d .lua); \
	  $(RUNNER) --headless --frames 1 --every 300 --size 640x480 --out $(BUILD)/pictures/$$n $$d >/dev/null 2>&1 && \
	  cp $(BUILD)/pictures/$$n/frame_00000.png docs/img/$$n.png && echo "docs/img/$$n.png" || echo "$$d: FAILED"; done
	@rm -rf $(BUILD)/pictures/gif && $(RUNNER) --headless --frames 90 --every 4 --size 480x360 --out $(BUILD)/pictures/gif $(DEMO) >/dev/null 2>&1 && \
	  convert -delay 7 -loop 0 $(BUILD)/pictures/gif/frame_*.png -layers Optimize docs/img/demo.gif && echo "docs/img/demo.gif" || \
	  echo "docs/img/demo.gif: not made (needs ImageMagick's convert)"

test: all $(TEST_C) $(FUZZ_C) $(TEST_B2)
	@BUILD=$(BUILD) SANITIZE=$(SANITIZE) sh tests/run.sh

# `make memcheck`: the C tests under valgrind memcheck; any error or leak
# of ours fails (libOSMesa's own leak is suppressed by library).
memcheck: all $(TEST_C)
	TT_MEMCHECK=1 valgrind --quiet --error-exitcode=3 --leak-check=full --errors-for-leak-kinds=definite,indirect \
	  --suppressions=tests/valgrind.supp $(TEST_C) >$(BUILD)/memcheck.log 2>&1; rc=$$?; \
	  grep -v '^ok ' $(BUILD)/memcheck.log | tail -n 40; exit $$rc

# `make fuzz [FUZZ_SECONDS=60] [FUZZ_SEED=n] [SANITIZE=1]`: every fuzz target
# of tests/fuzz/run.sh (the Lua API fuzzer under the runner and under
# LuaJIT, the C API fuzzer, the PNG loader's, the snapshot stream reader's, the replay journal reader's),
# each for its share of FUZZ_SECONDS; on a failure each prints its seed and replay.
fuzz: all $(FUZZ_C) $(FUZZ_PNG) $(TEST_C)
	@BUILD=$(BUILD) SANITIZE=$(SANITIZE) FUZZ_SECONDS=$(FUZZ_SECONDS) FUZZ_SEED=$(FUZZ_SEED) sh tests/fuzz/run.sh

# The mask section compares with Debian's python3-pygame (pygame.mask): installed
# here when run as root, otherwise the table says it is absent.
bench: deps $(BENCH) $(RUNNER) $(LUA_MOD)
	@mkdir -p $(BUILD)/bench-out
	$(BENCH) $(BUILD)/bench-out
	@sh bench/payonly_cg.sh $(BENCH) $(BUILD)/bench-out/payonly-cg
	@if ! /usr/bin/python3 -c 'import pygame' >/dev/null 2>&1; then \
	  if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
	    echo "bench: installing python3-pygame (pygame.mask, the comparison)"; \
	    { DEBIAN_FRONTEND=noninteractive apt-get install -y -q python3-pygame || \
	      { apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q python3-pygame; }; } >/dev/null 2>&1 || \
	      echo "bench: python3-pygame could not be installed"; \
	  else echo "bench: python3-pygame is absent (as root, make bench installs it)"; fi; \
	fi
	LUA_CPATH='$(BUILD)/?.so' lua5.4 bench/mask_bench.lua $(BUILD)/bench-out
	@if command -v gnuplot >/dev/null 2>&1; then \
	  for g in bench/*.gp; do gnuplot -e "dir='$(BUILD)/bench-out'" $$g; done; \
	  echo "plots: $(BUILD)/bench-out/*.png"; \
	else echo "gnuplot not installed: no plots (CSV in $(BUILD)/bench-out)"; fi
	@$(MAKE) --no-print-directory bench-love

# `make bench-payonly`: the pay-only table alone (unused features against a
# plain world of 100 000 particles), wall clock and callgrind instructions.
bench-payonly: deps $(BENCH)
	@mkdir -p $(BUILD)/bench-out
	$(BENCH) $(BUILD)/bench-out payonly
	@sh bench/payonly_cg.sh $(BENCH) $(BUILD)/bench-out/payonly-cg

# `make bench-love`: love.physics (Box2D) and tether pour 2 000 and 10 000
# circles into one box in one LÖVE process (bench/love/; no display needed):
# ms/step beside max overlap and kinetic energy, CSV in $(BUILD)/bench-out/.
bench-love: deps $(LUAJIT_MOD)
	@mkdir -p $(BUILD)/bench-out
	LUA_CPATH="$(CURDIR)/$(LUAJIT_MOD:tether.so=?.so)" love bench/love --out $(CURDIR)/$(BUILD)/bench-out $(BENCH_LOVE_ARGS)

# Lua finds C modules in <prefix>/lib/lua/<version>: at the default prefix
# that is on the package.cpath of Debian's lua5.4 and luajit (tests/install.sh).
LUA_CMOD_DIR    = $(PREFIX)/lib/lua/5.4
LUAJIT_CMOD_DIR = $(PREFIX)/lib/lua/5.1
PC_SUBST = sed -e 's|@PREFIX@|$(PREFIX)|g' -e 's|@VERSION@|$(VERSION)|g'
install: all
	install -d $(DESTDIR)$(PREFIX)/lib $(DESTDIR)$(PREFIX)/include/tether $(DESTDIR)$(PREFIX)/bin \
	  $(DESTDIR)$(LUA_CMOD_DIR) $(DESTDIR)$(LUAJIT_CMOD_DIR) $(DESTDIR)$(PREFIX)/lib/pkgconfig $(DESTDIR)$(PREFIX)/share/lua/5.4
	install -m 644 $(LIB_A) $(RENDER_A) $(DESTDIR)$(PREFIX)/lib/
	install -m 755 $(LIB_SO_REAL) $(DESTDIR)$(PREFIX)/lib/
	ln -sf libtether.so.$(VERSION) $(DESTDIR)$(PREFIX)/lib/$(SONAME)
	ln -sf $(SONAME) $(DESTDIR)$(PREFIX)/lib/libtether.so
	install -m 644 include/tether.h $(DESTDIR)$(PREFIX)/include/
	install -m 644 include/tether/*.h $(DESTDIR)$(PREFIX)/include/tether/
	install -m 755 $(LUA_MOD) $(DESTDIR)$(LUA_CMOD_DIR)/tether.so
	install -m 755 $(LUAJIT_MOD) $(DESTDIR)$(LUAJIT_CMOD_DIR)/tether.so
	install -m 755 $(B2_MOD) $(DESTDIR)$(LUA_CMOD_DIR)/tether_box2d.so
	install -m 755 $(B2_LUAJIT_MOD) $(DESTDIR)$(LUAJIT_CMOD_DIR)/tether_box2d.so
	install -m 755 $(RUNNER) $(DESTDIR)$(PREFIX)/bin/tether
	install -m 644 lua/tether.d.lua lua/tether_box2d.d.lua $(DESTDIR)$(PREFIX)/share/lua/5.4/
	install -m 644 lua/tether_atlas.lua lua/tether_atlas_scenes.lua $(DESTDIR)$(PREFIX)/share/lua/5.4/
	$(PC_SUBST) pkgconfig/tether.pc.in > $(DESTDIR)$(PREFIX)/lib/pkgconfig/tether.pc
	$(PC_SUBST) pkgconfig/tether-render.pc.in > $(DESTDIR)$(PREFIX)/lib/pkgconfig/tether-render.pc
	@# The loader's cache must learn the new library, or programs fail with
	@# "cannot open shared object file"; other prefixes are not on its path.
	@if [ -z "$(DESTDIR)" ] && [ "$(PREFIX)" = /usr/local ] && command -v ldconfig >/dev/null 2>&1; then \
	  ldconfig && echo "install: ldconfig run: programs find $(SONAME)"; \
	elif [ -z "$(DESTDIR)" ]; then \
	  echo "install: $(PREFIX)/lib is not on the loader's path: link with -Wl,-rpath,$(PREFIX)/lib (see README \"Embedding\")"; \
	fi

uninstall:
	rm -rf $(DESTDIR)$(PREFIX)/include/tether $(DESTDIR)$(PREFIX)/include/tether.h
	rm -f $(DESTDIR)$(PREFIX)/lib/libtether.a $(DESTDIR)$(PREFIX)/lib/libtether.so $(DESTDIR)$(PREFIX)/lib/$(SONAME) \
	  $(DESTDIR)$(PREFIX)/lib/libtether.so.$(VERSION) $(DESTDIR)$(PREFIX)/lib/libtether_render.a \
	  $(DESTDIR)$(LUA_CMOD_DIR)/tether.so $(DESTDIR)$(LUA_CMOD_DIR)/tether_box2d.so $(DESTDIR)$(LUAJIT_CMOD_DIR)/tether.so \
	  $(DESTDIR)$(LUAJIT_CMOD_DIR)/tether_box2d.so $(DESTDIR)$(PREFIX)/bin/tether \
	  $(DESTDIR)$(PREFIX)/lib/pkgconfig/tether.pc $(DESTDIR)$(PREFIX)/lib/pkgconfig/tether-render.pc \
	  $(DESTDIR)$(PREFIX)/share/lua/5.4/tether.d.lua $(DESTDIR)$(PREFIX)/share/lua/5.4/tether_box2d.d.lua \
	  $(DESTDIR)$(PREFIX)/share/lua/5.4/tether_atlas.lua $(DESTDIR)$(PREFIX)/share/lua/5.4/tether_atlas_scenes.lua
	@if [ -z "$(DESTDIR)" ] && [ "$(PREFIX)" = /usr/local ] && command -v ldconfig >/dev/null 2>&1; then ldconfig; fi

clean:
	rm -rf build build-san
