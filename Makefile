# PhysPix — every entry point: deps, all, test, demo, bench, install, clean.
# Build outputs go to build/ (ignored by git).

CC      ?= cc
CXX     ?= c++
PREFIX  ?= /usr/local
BUILD   := build
VERSION := 0.1.0
SOMAJOR := 0

# Debian packages the build, the tests and the demo need (see README).
DEPS := gcc g++ make pkg-config libode-dev libcriterion-dev

WARN     := -Wall -Wextra -Wshadow -Wstrict-prototypes -Wno-unused-parameter
CFLAGS_  := -std=c11 -D_POSIX_C_SOURCE=200809L $(WARN) -Iinclude -Ilib
LIBCFLAGS := $(CFLAGS_) -O2 -g -fPIC -fvisibility=hidden -DPHYSPIX_BUILD
LIBS     := -lode -lm -lpthread
SANFLAGS := -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined

LIB_SRC  := $(wildcard lib/*.c)
LIB_OBJ  := $(LIB_SRC:lib/%.c=$(BUILD)/obj/%.o)
SAN_OBJ  := $(LIB_SRC:lib/%.c=$(BUILD)/san/%.o)
LIB_HDR  := include/physpix.h $(wildcard lib/*.h)
TEST_SRC := $(wildcard tests/c/*.c)
BENCH_SRC := $(wildcard tests/bench/*.c)
DEMO_SRC := $(wildcard demo/*.c)

SONAME   := libphyspix.so.$(SOMAJOR)
SHARED   := $(BUILD)/libphyspix.so.$(VERSION)
STATIC   := $(BUILD)/libphyspix.a

.PHONY: all deps test test-c test-san test-compile demo bench install clean
.DEFAULT_GOAL := all

# Installs missing packages as root; otherwise prints the apt-get line and fails.
deps:
	@missing=""; for p in $(DEPS); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -z "$$missing" ]; then exit 0; fi; \
	if [ "$$(id -u)" = 0 ]; then \
	  echo "make deps: installing$$missing"; \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing; \
	else \
	  echo "make deps: missing packages; run as root:"; \
	  echo "  apt-get install -y$$missing"; exit 1; \
	fi

all: $(SHARED) $(STATIC) $(BUILD)/physpix.pc

$(BUILD)/obj/%.o: lib/%.c $(LIB_HDR) | $(BUILD)/obj
	$(CC) $(LIBCFLAGS) -c $< -o $@

$(BUILD)/san/%.o: lib/%.c $(LIB_HDR) | $(BUILD)/san
	$(CC) $(CFLAGS_) -O1 -g -DPHYSPIX_BUILD $(SANFLAGS) -c $< -o $@

$(SHARED): $(LIB_OBJ)
	$(CC) -shared -Wl,-soname,$(SONAME) -Wl,--no-undefined -o $@ $^ $(LIBS)
	ln -sf libphyspix.so.$(VERSION) $(BUILD)/$(SONAME)
	ln -sf $(SONAME) $(BUILD)/libphyspix.so

$(STATIC): $(LIB_OBJ)
	rm -f $@ && ar rcs $@ $^

$(BUILD)/physpix.pc: Makefile | $(BUILD)
	printf 'prefix=%s\nlibdir=$${prefix}/lib\nincludedir=$${prefix}/include\n\nName: physpix\nDescription: 2D rigid bodies from bitmaps\nVersion: %s\nRequires.private: ode\nLibs: -L$${libdir} -lphyspix\nLibs.private: -lm -lpthread\nCflags: -I$${includedir}\n' '$(PREFIX)' '$(VERSION)' > $@

$(BUILD) $(BUILD)/obj $(BUILD)/san $(BUILD)/tests:
	mkdir -p $@

# C tests: Criterion, linked against the sanitized library (ASan + UBSan).
$(BUILD)/tests/test_c_san: $(TEST_SRC) $(SAN_OBJ) tests/c/*.h | $(BUILD)/tests
	$(CC) $(CFLAGS_) -O1 -g $(SANFLAGS) -o $@ $(TEST_SRC) $(SAN_OBJ) -lcriterion $(LIBS)

# The same tests against the optimised shared library, as a user links it.
$(BUILD)/tests/test_c: $(TEST_SRC) $(SHARED) tests/c/*.h | $(BUILD)/tests
	$(CC) $(CFLAGS_) -O2 -g -o $@ $(TEST_SRC) -L$(BUILD) -lphyspix -Wl,-rpath,'$$ORIGIN/..' -lcriterion $(LIBS)

test-compile: | $(BUILD)/tests
	$(CC) -std=c11 -Wall -Wextra -Wpedantic -Werror -Iinclude -c tests/compile/header_c.c -o $(BUILD)/tests/header_c.o
	$(CXX) -std=c++17 -Wall -Wextra -Wpedantic -Werror -Iinclude -c tests/compile/header_cpp.cpp -o $(BUILD)/tests/header_cpp.o
	@echo "public header compiles as C11 and C++17 with -Werror"

# Leaks are checked after each test (tests/c/helpers.h); the runner's own exit check is off because
# Criterion keeps 48 bytes to its exit. Any LeakSanitizer report fails the target.
test-san: $(BUILD)/tests/test_c_san
	@ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=leak_check_at_exit=0 UBSAN_OPTIONS=print_stacktrace=1 \
	  $< --jobs 2 > $(BUILD)/tests/san.log 2>&1; rc=$$?; cat $(BUILD)/tests/san.log; \
	  if grep -q "ERROR: LeakSanitizer" $(BUILD)/tests/san.log; then echo "test-san: LeakSanitizer found leaks"; exit 1; fi; \
	  exit $$rc

test-c: $(BUILD)/tests/test_c
	$< --jobs 2

test: deps
	$(MAKE) all
	$(MAKE) test-compile
	$(MAKE) test-c
	$(MAKE) test-san

$(BUILD)/bench/bench: $(BENCH_SRC) $(STATIC) $(wildcard tests/bench/*.h)
	mkdir -p $(BUILD)/bench
	$(CC) $(CFLAGS_) -O2 -g -o $@ $(BENCH_SRC) $(STATIC) $(LIBS)

bench: deps
	$(MAKE) all $(BUILD)/bench/bench
	$(BUILD)/bench/bench --csv $(BUILD)/bench/bench.csv

$(BUILD)/demo/demo: $(DEMO_SRC) $(SHARED)
	mkdir -p $(BUILD)/demo
	$(CC) $(CFLAGS_) -O2 -g -o $@ $(DEMO_SRC) -L$(BUILD) -lphyspix -Wl,-rpath,'$$ORIGIN/..' $(LIBS)

demo: deps
	$(MAKE) all $(BUILD)/demo/demo
	$(BUILD)/demo/demo

install: all
	install -d $(DESTDIR)$(PREFIX)/lib $(DESTDIR)$(PREFIX)/include $(DESTDIR)$(PREFIX)/lib/pkgconfig
	install -m 644 include/physpix.h $(DESTDIR)$(PREFIX)/include/
	install -m 755 $(SHARED) $(DESTDIR)$(PREFIX)/lib/
	ln -sf libphyspix.so.$(VERSION) $(DESTDIR)$(PREFIX)/lib/$(SONAME)
	ln -sf $(SONAME) $(DESTDIR)$(PREFIX)/lib/libphyspix.so
	install -m 644 $(STATIC) $(DESTDIR)$(PREFIX)/lib/
	sed 's|^prefix=.*|prefix=$(PREFIX)|' $(BUILD)/physpix.pc > $(DESTDIR)$(PREFIX)/lib/pkgconfig/physpix.pc

clean:
	rm -rf $(BUILD)
