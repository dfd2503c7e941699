# PhysPix — every entry point: deps, all, check, test, demo, pictures, bench, wheel, install, clean (and godot-api,
# fuzz, bench-instr).
# Build outputs go to build/ (ignored by git).

# Compiler and linker command lines show with V=1 (`make V=1`); otherwise one short line each ("CC lib/core/alloc.c").
Q     := $(if $(V),,@)
quiet  = $(if $(V),,@printf '  %-4s %s\n' '$(1)' '$(2)';)

CC      ?= cc
CXX     ?= c++
NM      ?= nm
OBJCOPY ?= objcopy
PREFIX  ?= /usr/local
BUILD   := build

# The one version source is include/physpix.h (PHYSPIX_VERSION_*); the .pc and the Python package follow it.
version_part = $(shell sed -n 's/^.define PHYSPIX_VERSION_$(1) \([0-9][0-9]*\).*/\1/p' include/physpix.h)
SOMAJOR := $(call version_part,MAJOR)
VERSION := $(SOMAJOR).$(call version_part,MINOR).$(call version_part,PATCH)

# Debian packages the build, the tests and the demo need (see README).
# EGL/GLES headers build the GPU backend; Mesa's EGL and llvmpipe run it on a machine without a GPU.
# clang and its runtime (libFuzzer, TSan) build the fuzz targets; valgrind checks the demo for leaks;
# git clones the repository for the fresh-clone test; python3-venv gives Debian's python3 its venv module.
DEPS := gcc g++ make pkg-config binutils git libode-dev libcriterion-dev libegl-dev libgles-dev libegl-mesa0 \
        libgl1-mesa-dri libpng-dev libcjson-dev libxxhash-dev godot3-server python3 python3-venv clang libclang-rt-14-dev valgrind
# godot3 (Godot 3.2's X11 build), xvfb and xauth render the Godot example's pictures (make godot-pictures) through
# Mesa; no test needs them.
DEPS += godot3 xvfb xauth
# Box2D 2.4 and Chipmunk 7 are the stability benchmark's peers only (tests/bench/stability); no library or test links them.
DEPS += libbox2d-dev libchipmunk-dev
# The interpreter the project's virtual environment (build/venv, see plugin/python/python.mk) is made from.
PYTHON ?= python3

WARN     := -Wall -Wextra -Wshadow -Wstrict-prototypes -Wno-unused-parameter
# lib/ in layers, lowest first: core (allocator, statuses, handles), collide (rasters, broadphase, narrowphase
# and its backends), then dynamics (world, bodies, joints, islands, the solver), edit (pixel edits, splits, timed
# edits), query (rays, region queries, pair collide) and io (scenes, snapshots, images, the camera).
LIB_DIRS  := core collide dynamics edit query io
PP_BASE   := -std=c11 -D_POSIX_C_SOURCE=200809L $(WARN) -Iinclude
PP_CFLAGS := $(PP_BASE) $(LIB_DIRS:%=-Ilib/%)
LIBOPT    := -O2 -g -fPIC -fvisibility=hidden -DPHYSPIX_BUILD
LIBCFLAGS := $(PP_CFLAGS) $(LIBOPT)
# A library object sees the headers of its own layer and the layers below it only, so core and collide
# cannot reach up into the world: $(call layer_inc,DIR).
layer_inc = $(if $(filter core,$(1)),-Ilib/core,$(if $(filter collide,$(1)),-Ilib/core -Ilib/collide,$(LIB_DIRS:%=-Ilib/%)))
LIBS     := -lode -lpng -lcjson -lm -lpthread -ldl
# The user's flags come after ours, so `make CFLAGS=-O0` wins; LDFLAGS go before the libraries.
USER_CFLAGS = $(CPPFLAGS) $(CFLAGS)
# Each library object lists the headers it includes (build/*/*/*.d), so a header change rebuilds only those.
DEPFLAGS := -MMD -MP
SANFLAGS := -fsanitize=address,undefined,float-cast-overflow -fno-omit-frame-pointer -fno-sanitize-recover=undefined,float-cast-overflow
# The sanitizer build also checks the internal invariants (PP_ASSERT, lib/core/check.h).
SANFLAGS += -DPP_CHECKS

LIB_SRC  := $(foreach d,$(LIB_DIRS),$(wildcard lib/$(d)/*.c))
GLSL_SRC := $(wildcard glsl/*.comp)
GLSL_GEN := $(BUILD)/gen/glsl_sources.c
LIB_OBJ  := $(LIB_SRC:lib/%.c=$(BUILD)/obj/%.o) $(BUILD)/obj/glsl_sources.o
SAN_OBJ  := $(LIB_SRC:lib/%.c=$(BUILD)/san/%.o) $(BUILD)/san/glsl_sources.o
# The C tests build the stability benchmark's scenes through its PhysPix side, not its peers.
TEST_SRC := $(wildcard tests/c/*.c) tests/bench/stability/scenes.c tests/bench/stability/scenes_physpix.c
BENCH_SRC := $(wildcard tests/bench/*.c)
PLUGIN_SRC := plugin/plugin.c plugin/classes.c plugin/settings.c

SONAME   := libphyspix.so.$(SOMAJOR)
SHARED   := $(BUILD)/libphyspix.so.$(VERSION)
STATIC   := $(BUILD)/libphyspix.a
PLUGIN   := $(BUILD)/libphyspix_plugin.so

.PHONY: all lib print-version deps test check test-c test-san test-compile test-plugin test-python test-godot test-demo test-pictures test-package check-deep \
        demo bench bench-instr install clean fuzz test-fuzz api check-api
.DEFAULT_GOAL := all

# Installs missing packages as root; otherwise prints the apt-get line and fails.
deps:
	@missing=""; for p in $(DEPS); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" = 0 ]; then \
	    echo "make deps: installing$$missing"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing || exit 1; \
	  else \
	    echo "make deps: missing packages; run as root:"; \
	    echo "  apt-get install -y$$missing"; exit 1; \
	  fi; \
	fi
	@$(MAKE) --no-print-directory venv wheel-tools

# The shared library alone (what the Python package's build asks for).
lib: $(SHARED)

print-version:
	@echo $(VERSION)

$(BUILD)/obj/%.o: lib/%.c
	@mkdir -p $(@D)
	$(call quiet,CC,$<)$(CC) $(PP_BASE) $(call layer_inc,$(*D)) $(LIBOPT) $(DEPFLAGS) $(USER_CFLAGS) -c $< -o $@

$(BUILD)/san/%.o: lib/%.c
	@mkdir -p $(@D)
	$(call quiet,CC,$<)$(CC) $(PP_BASE) $(call layer_inc,$(*D)) -O1 -g -DPHYSPIX_BUILD $(SANFLAGS) $(DEPFLAGS) $(USER_CFLAGS) -c $< -o $@

# Each compute shader is glsl/common.glsl followed by its .comp, embedded as a C string.
$(GLSL_GEN): glsl/common.glsl $(GLSL_SRC) | $(BUILD)/gen
	$(call quiet,GEN,$@){ echo '/* Generated by make from glsl/; edit those files instead. */'; \
	  echo '#include "gpu_context.h"'; \
	  echo 'const gpu_shader_source gpu_shader_sources[] = {'; \
	  for f in $(GLSL_SRC); do \
	    echo "    {\"$$(basename $$f .comp)\","; \
	    cat glsl/common.glsl $$f | sed -e 's/\\/\\\\/g' -e 's/"/\\"/g' -e 's/^/     "/' -e 's/$$/\\n"/'; \
	    echo '    },'; \
	  done; \
	  echo '};'; \
	  echo 'const int gpu_shader_source_count = (int)(sizeof gpu_shader_sources / sizeof gpu_shader_sources[0]);'; \
	} > $@

$(BUILD)/obj/glsl_sources.o: $(GLSL_GEN) lib/collide/gpu_context.h | $(BUILD)/obj
	$(call quiet,CC,$<)$(CC) $(LIBCFLAGS) $(USER_CFLAGS) -c $< -o $@

$(BUILD)/san/glsl_sources.o: $(GLSL_GEN) lib/collide/gpu_context.h | $(BUILD)/san
	$(call quiet,CC,$<)$(CC) $(PP_CFLAGS) -O1 -g -DPHYSPIX_BUILD $(SANFLAGS) $(USER_CFLAGS) -c $< -o $@

$(SHARED): $(LIB_OBJ)
	$(call quiet,LD,$@)$(CC) -shared -Wl,-soname,$(SONAME) -Wl,--no-undefined -o $@ $^ $(LDFLAGS) $(LIBS)
	$(Q)ln -sf libphyspix.so.$(VERSION) $(BUILD)/$(SONAME)
	$(Q)ln -sf $(SONAME) $(BUILD)/libphyspix.so

# The engine plugin: the class table over the C ABI, finding libphyspix.so.0 beside itself.
$(PLUGIN): $(PLUGIN_SRC) plugin/plugin.h plugin/classes_gen.h plugin/api/def_fields.h lib/core/handle.h lib/core/id_pool.h \
  include/physpix_plugin.h $(SHARED)
	$(call quiet,LD,$@)$(CC) $(LIBCFLAGS) -Iplugin $(USER_CFLAGS) -shared -Wl,--no-undefined -o $@ $(PLUGIN_SRC) $(LDFLAGS) \
	  -L$(BUILD) -l:$(SONAME) -Wl,-rpath,'$$ORIGIN' -lcjson -lm -lpthread

# The archive keeps global only what the shared library exports (the pp_* entry points), so a program that
# links it statically may define its own read_int: the objects are merged into one, the rest made local.
STATIC_OBJ := $(BUILD)/static/physpix.o
$(STATIC): $(LIB_OBJ) $(SHARED)
	$(Q)mkdir -p $(BUILD)/static
	$(Q)$(NM) -D --defined-only $(SHARED) | awk '{ print $$3 }' > $(BUILD)/static/exports.txt
	$(call quiet,LD,$(STATIC_OBJ))$(CC) -nostdlib -r -o $(STATIC_OBJ) $(LIB_OBJ)
	$(Q)$(OBJCOPY) --keep-global-symbols=$(BUILD)/static/exports.txt $(STATIC_OBJ)
	$(Q)rm -f $@ && $(AR) rcs $@ $(STATIC_OBJ)

$(BUILD)/physpix.pc: Makefile include/physpix.h | $(BUILD)
	$(call quiet,GEN,$@)printf 'prefix=%s\nlibdir=$${prefix}/lib\nincludedir=$${prefix}/include\n\nName: physpix\nDescription: 2D rigid bodies from bitmaps\nVersion: %s\nLicense: MIT\nRequires.private: ode\nLibs: -L$${libdir} -lphyspix\nLibs.private: -lpng -lcjson -lm -lpthread -ldl\nCflags: -I$${includedir}\n' '$(PREFIX)' '$(VERSION)' > $@

$(BUILD) $(BUILD)/obj $(BUILD)/san $(BUILD)/tests $(BUILD)/gen:
	$(Q)mkdir -p $@

# C tests: Criterion, linked against the sanitized library (ASan + UBSan). It links the objects, so
# PP_TEST_PRIVATE lets tests reach private headers (tests/c/test_tiles.c).
$(BUILD)/tests/test_c_san: $(TEST_SRC) $(SAN_OBJ) tests/c/*.h tests/bench/accuracy/analytic.h tests/bench/stability/stability.h | $(BUILD)/tests
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O1 -g $(SANFLAGS) -DPP_TEST_PRIVATE $(USER_CFLAGS) -o $@ $(TEST_SRC) $(SAN_OBJ) $(LDFLAGS) \
	  -lcriterion $(LIBS)

# The same tests against the optimised shared library, as a user links it.
$(BUILD)/tests/test_c: $(TEST_SRC) $(SHARED) tests/c/*.h tests/bench/accuracy/analytic.h tests/bench/stability/stability.h | $(BUILD)/tests
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O2 -g $(USER_CFLAGS) -o $@ $(TEST_SRC) $(LDFLAGS) -L$(BUILD) -lphyspix -Wl,-rpath,'$$ORIGIN/..' \
	  -lcriterion $(LIBS)

# bench_core reaches the library's private headers: it is built here too, so a change to them that breaks it
# fails make test, not only make bench; bench_instr is built (never run: that needs valgrind) for the same reason.
test-compile: $(BUILD)/bench/bench_core $(BUILD)/bench/bench_instr | $(BUILD)/tests
	$(call quiet,CC,tests/compile/header_c.c)$(CC) -std=c11 -Wall -Wextra -Wpedantic -Werror -Iinclude -c tests/compile/header_c.c -o $(BUILD)/tests/header_c.o
	$(call quiet,CXX,tests/compile/header_cpp.cpp)$(CXX) -std=c++17 -Wall -Wextra -Wpedantic -Werror -Iinclude -c tests/compile/header_cpp.cpp -o $(BUILD)/tests/header_cpp.o
	@echo "public headers compile as C11 and C++17 with -Werror"

# The API's one description, plugin/api/physpix_api.json: `make api` writes the bindings generated from it (the Python
# ctypes mirror, the plugin's and the Godot adapter's method tables, the def fields); check-api checks that they
# are current, that the description matches include/physpix.h and that every call reaches each host or says why not,
# then runs the checker's own tests (tests/api). Standard-library Python only; -B keeps bytecode out of the tree.
api:
	$(PYTHON) -B plugin/api/gen_api.py

check-api:
	$(PYTHON) -B plugin/api/gen_api.py --check
	$(PYTHON) -B -m unittest discover -s tests/api -p 'test_*.py'

# Leaks are checked after each test (tests/c/helpers.h); the runner's own exit check is off because
# Criterion keeps 48 bytes to its exit. Any LeakSanitizer report fails the target.
# $(call run_san,binary,log): run a sanitized Criterion binary; fail on its status or on any LeakSanitizer report.
run_san = @ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=leak_check_at_exit=0 UBSAN_OPTIONS=print_stacktrace=1 \
	  $(1) --jobs 2 > $(2) 2>&1; rc=$$?; cat $(2); \
	  if grep -q "ERROR: LeakSanitizer" $(2); then echo "$@: LeakSanitizer found leaks"; exit 1; fi; \
	  exit $$rc

test-san: $(BUILD)/tests/test_c_san
	$(call run_san,$<,$(BUILD)/tests/san.log)

# The plugin interface through the reference host's loader: manifests, version refusal, every method.
$(BUILD)/tests/test_plugin: tests/plugin/test_plugin.c demo/plugin_host.c $(PLUGIN) demo/plugin_host.h include/physpix_plugin.h | $(BUILD)/tests
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -Idemo -O1 -g $(SANFLAGS) $(USER_CFLAGS) -o $@ tests/plugin/test_plugin.c demo/plugin_host.c \
	  $(LDFLAGS) -lcriterion -ldl -lm

$(BUILD)/demo/host: demo/host.c demo/plugin_host.c demo/plugin_host.h include/physpix_plugin.h
	$(Q)mkdir -p $(BUILD)/demo
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O2 -g $(USER_CFLAGS) -o $@ demo/host.c demo/plugin_host.c $(LDFLAGS) -ldl -lm

test-plugin: all $(BUILD)/tests/test_plugin $(BUILD)/demo/host
	$(call run_san,$(BUILD)/tests/test_plugin,$(BUILD)/tests/plugin.log)
	$(BUILD)/demo/host plugin/physpix.plugin

test-c: $(BUILD)/tests/test_c
	$< --jobs 2

# make test: every suite, each a target below, then a summary (tests/suites.py): per suite its result, its count
# of tests (or inputs, scripts) and its time; each suite's output also lands in build/tests/logs/.
TEST_SUITES := build=all compile=test-compile api=check-api c=test-c san=test-san fuzz=test-fuzz plugin=test-plugin \
  python=test-python godot=test-godot demo=test-demo pictures=test-pictures package=test-package deep=check-deep
# make check: the edit-compile-test loop, under 3 minutes on 2 cores: the build, the C tests against the optimised
# library and the Python tests.
CHECK_SUITES := build=all compile=test-compile c=test-c python=test-python
SUITES = $(PYTHON) -B tests/suites.py --make $(MAKE) --logs $(BUILD)/tests/logs

test: deps
	@$(SUITES) --title "make test" $(TEST_SUITES)

check: venv
	@$(SUITES) --title "make check" $(CHECK_SUITES)

# The hosts: the Python package and the Godot 3.2 adapter keep their rules beside their code.
include plugin/python/python.mk plugin/godot/godot.mk

all: $(SHARED) $(STATIC) $(BUILD)/physpix.pc $(PLUGIN) $(GODOT_ALL)

# What a user meets outside the build tree: a fresh clone, the installed prefix, the wheel, the exports,
# the version, the licence, the README's first program (tests/package).
test-package: all venv $(BUILD)/demo/host
	BUILD=$(BUILD) PYTHON=$(PYTHON) $(VENV_PY) -m pytest -q -p no:cacheprovider tests/package

# The demo: scene, sprites, renderer; its rules live beside it.
include demo/demo.mk

# libFuzzer targets: `make fuzz`, `make test-fuzz`; their rules live beside them.
include tests/fuzz/fuzz.mk

# ThreadSanitizer and valgrind checks: tests/deep/.
include tests/deep/deep.mk

$(BUILD)/bench/bench: $(BENCH_SRC) $(STATIC) $(wildcard tests/bench/*.h)
	$(Q)mkdir -p $(BUILD)/bench
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O2 -g $(USER_CFLAGS) -o $@ $(BENCH_SRC) $(STATIC) $(LDFLAGS) $(LIBS)

# Narrowphase throughput, CPU against GPU, and what AUTO picks.
$(BUILD)/bench/bench_narrow: tests/bench/narrowphase/main.c tests/bench/machine.h $(STATIC)
	$(Q)mkdir -p $(BUILD)/bench
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O2 -g $(USER_CFLAGS) -o $@ $< $(STATIC) $(LDFLAGS) $(LIBS)

# The CPU narrowphase core alone, tiled against dense, on named pairs (private headers: the objects, since the archive keeps only pp_* global).
$(BUILD)/bench/bench_core: tests/bench/narrowphase/core.c tests/bench/machine.h $(LIB_OBJ)
	$(Q)mkdir -p $(BUILD)/bench
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O2 -g $(USER_CFLAGS) -o $@ $< $(LIB_OBJ) $(LDFLAGS) $(LIBS)

# Edit latency: a crater in a large terrain, and the step after it.
$(BUILD)/bench/bench_edit: tests/bench/edit/main.c tests/bench/machine.h $(STATIC)
	$(Q)mkdir -p $(BUILD)/bench
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O2 -g $(USER_CFLAGS) -o $@ $< $(STATIC) $(LDFLAGS) $(LIBS)

# Tunnelling: the largest speed at which a fast body never passes through an 8 px wall.
$(BUILD)/bench/bench_tunnel: tests/bench/tunnel/main.c tests/bench/machine.h $(STATIC)
	$(Q)mkdir -p $(BUILD)/bench
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O2 -g $(USER_CFLAGS) -o $@ $< $(STATIC) $(LDFLAGS) $(LIBS)

# Crowded spawns: n bodies created at one point against a settled pile of n (the contact budget).
$(BUILD)/bench/bench_spawn: tests/bench/spawn/main.c tests/bench/machine.h $(STATIC)
	$(Q)mkdir -p $(BUILD)/bench
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O2 -g $(USER_CFLAGS) -o $@ $< $(STATIC) $(LDFLAGS) $(LIBS)

# What a scene pays for the features it does not use.
$(BUILD)/bench/bench_features: tests/bench/features/main.c tests/bench/machine.h $(STATIC)
	$(Q)mkdir -p $(BUILD)/bench
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O2 -g $(USER_CFLAGS) -o $@ $< $(STATIC) $(LDFLAGS) $(LIBS)

# Raycasts and queries per second against a large terrain with 1,000 crates.
$(BUILD)/bench/bench_raycast: tests/bench/raycast/main.c tests/bench/machine.h $(STATIC)
	$(Q)mkdir -p $(BUILD)/bench
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O2 -g $(USER_CFLAGS) -o $@ $< $(STATIC) $(LDFLAGS) $(LIBS)

# Whole scenes (a 4096×2048 terrain, falling crates, blasts) on the CPU backend, the GPU backend and AUTO.
$(BUILD)/bench/bench_backends: tests/bench/backends/main.c tests/bench/machine.h $(STATIC)
	$(Q)mkdir -p $(BUILD)/bench
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O2 -g $(USER_CFLAGS) -o $@ $< $(STATIC) $(LDFLAGS) $(LIBS)

# What pp_world_debug_draw costs beside a step: a cratered 2048×1024 terrain with 300 crates.
$(BUILD)/bench/bench_debug_draw: tests/bench/debug_draw/main.c tests/bench/machine.h $(STATIC)
	$(Q)mkdir -p $(BUILD)/bench
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O2 -g $(USER_CFLAGS) -o $@ $< $(STATIC) $(LDFLAGS) $(LIBS)

# Loading and scheduling at scale: a 100,000-body scene and snapshot, 100,000 edits in decreasing time order.
$(BUILD)/bench/bench_load: tests/bench/load/main.c tests/bench/machine.h $(STATIC)
	$(Q)mkdir -p $(BUILD)/bench
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O2 -g $(USER_CFLAGS) -o $@ $< $(STATIC) $(LDFLAGS) $(LIBS)

# What sleeping bodies cost, alone and beside a few awake ones.
$(BUILD)/bench/sleep_box2d.o: tests/bench/sleep/peer_box2d.cpp tests/bench/sleep/peer.h
	$(Q)mkdir -p $(BUILD)/bench
	$(call quiet,CXX,$<)$(CXX) -std=c++17 $(filter-out -Wstrict-prototypes,$(WARN)) -O2 -g $(CPPFLAGS) $(CXXFLAGS) -c $< -o $@

$(BUILD)/bench/bench_sleep: tests/bench/sleep/main.c tests/bench/sleep/peer_chipmunk.c tests/bench/sleep/peer.h \
  tests/bench/machine.h $(BUILD)/bench/sleep_box2d.o $(STATIC)
	$(Q)mkdir -p $(BUILD)/bench
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O2 -g $(USER_CFLAGS) -o $@ $< tests/bench/sleep/peer_chipmunk.c $(BUILD)/bench/sleep_box2d.o \
	  $(STATIC) $(LDFLAGS) -lbox2d -lchipmunk -lstdc++ $(LIBS)

# Speed against accuracy of the world's knobs: a table, CSV, and a plot by plot.py.
ACC_SRC := $(wildcard tests/bench/accuracy/*.c) tests/bench/scenes.c
$(BUILD)/bench/bench_accuracy: $(ACC_SRC) $(wildcard tests/bench/accuracy/*.h) tests/bench/bench.h tests/bench/machine.h $(STATIC)
	$(Q)mkdir -p $(BUILD)/bench
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -Itests/bench -O2 -g $(USER_CFLAGS) -o $@ $(ACC_SRC) $(STATIC) $(LDFLAGS) $(LIBS)

# How cost grows with bodies, bitmap sizes, overlap and edits, raster beside analytic: a table, CSV, a plot.
SCALE_SRC := $(wildcard tests/bench/scale/*.c) tests/bench/engine_ode.c tests/bench/engine_physpix.c \
  tests/bench/scenes.c tests/bench/settings.c
$(BUILD)/bench/bench_scale: $(SCALE_SRC) tests/bench/scale/scale.h tests/bench/bench.h tests/bench/machine.h $(STATIC)
	$(Q)mkdir -p $(BUILD)/bench
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -Itests/bench -O2 -g $(USER_CFLAGS) -o $@ $(SCALE_SRC) $(STATIC) $(LDFLAGS) $(LIBS)

# Stacks, rolling, bouncing, friction and wall shots on the presets against Box2D 2.4 and Chipmunk 7 (issue 22).
# The Box2D peer is C++ (its own object); the rest is C11.
STAB_SRC := $(wildcard tests/bench/stability/*.c) tests/bench/settings.c
STAB_HDR := $(wildcard tests/bench/stability/*.h) tests/bench/bench.h tests/bench/machine.h
$(BUILD)/bench/peer_box2d.o: tests/bench/stability/peer_box2d.cpp $(STAB_HDR) include/physpix.h
	$(Q)mkdir -p $(BUILD)/bench
	$(call quiet,CXX,$<)$(CXX) -std=c++17 $(filter-out -Wstrict-prototypes,$(WARN)) -Iinclude -O2 -g $(CPPFLAGS) $(CXXFLAGS) -c $< -o $@

$(BUILD)/bench/bench_stability: $(STAB_SRC) $(STAB_HDR) $(BUILD)/bench/peer_box2d.o $(STATIC)
	$(Q)mkdir -p $(BUILD)/bench
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -Itests/bench -O2 -g $(USER_CFLAGS) -o $@ $(STAB_SRC) $(BUILD)/bench/peer_box2d.o $(STATIC) \
	  $(LDFLAGS) -lbox2d -lchipmunk -lstdc++ $(LIBS)

# Step cost against Box2D 2.4 and Chipmunk 7 on the same scenes (issue 23): the stability scenes and peers, the
# rain and the destruction scene; Box2D's remeshing terrain is C++ (its own object), beside peer_box2d.o.
COST_SRC := $(wildcard tests/bench/cost/*.c) tests/bench/stability/scenes.c tests/bench/stability/scenes_physpix.c \
  tests/bench/stability/peer_chipmunk.c tests/bench/settings.c
COST_HDR := $(wildcard tests/bench/cost/*.h) $(STAB_HDR)
$(BUILD)/bench/cost_remesh.o: tests/bench/cost/peer_remesh.cpp $(COST_HDR) include/physpix.h
	$(Q)mkdir -p $(BUILD)/bench
	$(call quiet,CXX,$<)$(CXX) -std=c++17 $(filter-out -Wstrict-prototypes,$(WARN)) -Iinclude -O2 -g $(CPPFLAGS) $(CXXFLAGS) -c $< -o $@

$(BUILD)/bench/bench_cost: $(COST_SRC) $(COST_HDR) $(BUILD)/bench/peer_box2d.o $(BUILD)/bench/cost_remesh.o $(STATIC)
	$(Q)mkdir -p $(BUILD)/bench
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O2 -g $(USER_CFLAGS) -o $@ $(COST_SRC) $(BUILD)/bench/peer_box2d.o $(BUILD)/bench/cost_remesh.o \
	  $(STATIC) $(LDFLAGS) -lbox2d -lchipmunk -lstdc++ $(LIBS)

# Instructions per step, stage by stage, under callgrind (issue 40): bench_instr runs one scene and counts only its
# measured steps; report.py runs it under valgrind per scene and charges each instruction to a stage of lib/ or
# to ODE. -g lets callgrind name each function's source file. About 1.5 min.
INSTR_SRC := tests/bench/instr/main.c tests/bench/cost/scenes.c tests/bench/stability/scenes.c \
  tests/bench/stability/scenes_physpix.c
$(BUILD)/bench/bench_instr: $(INSTR_SRC) $(COST_HDR) $(STATIC)
	@mkdir -p $(BUILD)/bench
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O2 -g $(USER_CFLAGS) -o $@ $(INSTR_SRC) $(STATIC) $(LDFLAGS) $(LIBS)

# Save and restore of a world's state in memory against a step (issue 44): the rain and the destruction scene.
STATE_SRC := tests/bench/state/main.c tests/bench/cost/scenes.c tests/bench/stability/scenes.c \
  tests/bench/stability/scenes_physpix.c
$(BUILD)/bench/bench_state: $(STATE_SRC) $(COST_HDR) tests/bench/machine.h $(STATIC)
	@mkdir -p $(BUILD)/bench
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O2 -g $(USER_CFLAGS) -o $@ $(STATE_SRC) $(STATIC) $(LDFLAGS) $(LIBS)

bench-instr: deps
	$(MAKE) all $(BUILD)/bench/bench_instr
	$(VENV_PY) tests/bench/instr/report.py --binary $(BUILD)/bench/bench_instr --csv $(BUILD)/bench/instr.csv

bench: deps
	$(MAKE) all $(BUILD)/bench/bench $(BUILD)/bench/bench_narrow $(BUILD)/bench/bench_edit $(BUILD)/bench/bench_tunnel \
	  $(BUILD)/bench/bench_accuracy $(BUILD)/bench/bench_features $(BUILD)/bench/bench_core $(BUILD)/bench/bench_scale \
	  $(BUILD)/bench/bench_raycast $(BUILD)/bench/bench_load $(BUILD)/bench/bench_spawn $(BUILD)/bench/bench_stability \
	  $(BUILD)/bench/bench_sleep $(BUILD)/bench/bench_cost $(BUILD)/bench/bench_instr $(BUILD)/bench/bench_debug_draw \
	  $(BUILD)/bench/bench_state $(BUILD)/bench/bench_backends
	$(BUILD)/bench/bench_edit --csv $(BUILD)/bench/edit.csv
	$(BUILD)/bench/bench_raycast --csv $(BUILD)/bench/raycast.csv
	$(BUILD)/bench/bench_debug_draw --csv $(BUILD)/bench/debug_draw.csv
	$(BUILD)/bench/bench_load --csv $(BUILD)/bench/load.csv
	$(BUILD)/bench/bench_features --csv $(BUILD)/bench/features.csv
	$(BUILD)/bench/bench --csv $(BUILD)/bench/bench.csv
	$(BUILD)/bench/bench_core
	$(BUILD)/bench/bench_narrow --csv $(BUILD)/bench/narrowphase.csv
	$(BUILD)/bench/bench_backends --csv $(BUILD)/bench/backends.csv
	$(BUILD)/bench/bench_tunnel --csv $(BUILD)/bench/tunnel.csv --detail $(BUILD)/bench/tunnel_speeds.csv
	$(BUILD)/bench/bench_accuracy --csv $(BUILD)/bench/accuracy.csv
	$(BUILD)/bench/bench_scale --csv $(BUILD)/bench/scale.csv
	$(BUILD)/bench/bench_spawn --csv $(BUILD)/bench/spawn.csv
	$(BUILD)/bench/bench_stability --csv $(BUILD)/bench/stability.csv
	$(BUILD)/bench/bench_sleep --csv $(BUILD)/bench/sleep.csv
	$(BUILD)/bench/bench_cost --csv $(BUILD)/bench/cost.csv
	$(BUILD)/bench/bench_state --csv $(BUILD)/bench/state.csv
	@# matplotlib only draws the plot: without it the plot is skipped (plot.py says why), never the bench.
	@$(VENV_PY) -c 'import matplotlib' 2>/dev/null || { echo "make bench: installing into $(VENV) from PyPI: matplotlib"; \
	  $(VENV_PY) -m pip install --quiet matplotlib || echo "make bench: pip could not install matplotlib (above)"; }
	$(VENV_PY) tests/bench/accuracy/plot.py $(BUILD)/bench/accuracy.csv $(BUILD)/bench/accuracy.png
	$(VENV_PY) tests/bench/scale/plot.py $(BUILD)/bench/scale.csv $(BUILD)/bench/scale.png
	$(VENV_PY) tests/bench/cost/plot.py $(BUILD)/bench/cost.csv $(BUILD)/bench/cost.png
	$(VENV_PY) tests/bench/instr/report.py --binary $(BUILD)/bench/bench_instr --csv $(BUILD)/bench/instr.csv

# Under PREFIX: lib/ (libraries, the plugin and its manifest, pkgconfig/physpix.pc), include/, and share/physpix/:
# godot/addons/physpix/ (the Godot 3.2 addon with its libraries, copied into a project's addons/) and python/
# (the package's source; `pip install PREFIX/share/physpix/python` builds a wheel that carries PREFIX/lib's library).
INSTALL_LIB    = $(DESTDIR)$(PREFIX)/lib
INSTALL_SHARE  = $(DESTDIR)$(PREFIX)/share/physpix
install: all
	install -d $(INSTALL_LIB)/pkgconfig $(DESTDIR)$(PREFIX)/include $(INSTALL_SHARE)/godot/addons/physpix \
	  $(INSTALL_SHARE)/python/physpix
	install -m 644 include/physpix.h include/physpix_plugin.h $(DESTDIR)$(PREFIX)/include/
	install -m 755 $(SHARED) $(INSTALL_LIB)/
	ln -sf libphyspix.so.$(VERSION) $(INSTALL_LIB)/$(SONAME)
	ln -sf $(SONAME) $(INSTALL_LIB)/libphyspix.so
	install -m 644 $(STATIC) $(INSTALL_LIB)/
	sed 's|^prefix=.*|prefix=$(PREFIX)|' $(BUILD)/physpix.pc > $(INSTALL_LIB)/pkgconfig/physpix.pc
	install -m 755 $(PLUGIN) $(INSTALL_LIB)/
	sed 's|"../build/libphyspix_plugin.so"|"libphyspix_plugin.so"|' plugin/physpix.plugin > $(INSTALL_LIB)/physpix.plugin
	install -m 644 $(GODOT_ADDON_SRC) $(INSTALL_SHARE)/godot/addons/physpix/
	install -m 755 $(GODOT_LIB) $(INSTALL_SHARE)/godot/addons/physpix/
	install -m 755 $(SHARED) $(INSTALL_SHARE)/godot/addons/physpix/$(SONAME)
	install -m 644 plugin/python/pyproject.toml plugin/python/setup.py plugin/python/README.md $(INSTALL_SHARE)/python/
	install -m 644 plugin/python/physpix/*.py plugin/python/physpix/py.typed $(INSTALL_SHARE)/python/physpix/
	install -m 644 LICENSE $(INSTALL_SHARE)/

clean:
	rm -rf $(BUILD) plugin/python/build plugin/python/physpix.egg-info

-include $(wildcard $(BUILD)/obj/*/*.d $(BUILD)/san/*/*.d $(BUILD)/tsan/*/*.d $(FUZZ_DIR)/obj/*/*.d)
