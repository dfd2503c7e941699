# Deeper checks, run by `make test` and alone by `make check-deep`:
# - check-tsan: tests/deep/tsan_worlds.c, eight worlds on eight threads, against the library built with
#   ThreadSanitizer into build/tsan/; any race report fails it (halt_on_error, exit code 66).
# - check-valgrind: the demo's destruction scene for 2.5 s on the CPU backend under valgrind's memcheck;
#   any invalid access or definite/indirect leak fails it.
TSAN_CC    ?= clang
TSAN_FLAGS := -fsanitize=thread -fno-omit-frame-pointer
TSAN_OBJ   := $(LIB_SRC:lib/%.c=$(BUILD)/tsan/%.o) $(BUILD)/tsan/glsl_sources.o
TSAN_BIN   := $(BUILD)/tsan/tsan_worlds
TSAN_RUN   := TSAN_OPTIONS="halt_on_error=1 exitcode=66 second_deadlock_stack=1 suppressions=tests/deep/tsan.supp"

DEEP_OUT       := $(BUILD)/deep
DEEP_SCENE     := $(DEEP_OUT)/scene_cpu.json
DEEP_SECONDS   := 2.5
VALGRIND_LOG   := $(DEEP_OUT)/valgrind.log
VALGRIND_FLAGS := --tool=memcheck --leak-check=full --show-leak-kinds=definite,indirect \
  --errors-for-leak-kinds=definite,indirect --error-exitcode=1 --suppressions=tests/deep/valgrind.supp

.PHONY: check-deep check-tsan check-valgrind

$(BUILD)/tsan:
	$(Q)mkdir -p $@

$(BUILD)/tsan/%.o: lib/%.c
	@mkdir -p $(@D)
	$(call quiet,CC,$<)$(TSAN_CC) $(PP_CFLAGS) -O1 -g -DPHYSPIX_BUILD $(TSAN_FLAGS) $(DEPFLAGS) -c $< -o $@

$(BUILD)/tsan/glsl_sources.o: $(GLSL_GEN) lib/collide/gpu_context.h | $(BUILD)/tsan
	$(call quiet,CC,$<)$(TSAN_CC) $(PP_CFLAGS) -O1 -g -DPHYSPIX_BUILD $(TSAN_FLAGS) -c $< -o $@

$(TSAN_BIN): tests/deep/tsan_worlds.c $(TSAN_OBJ) include/physpix.h
	$(call quiet,LD,$@)$(TSAN_CC) $(PP_CFLAGS) -O1 -g $(TSAN_FLAGS) -o $@ $< $(TSAN_OBJ) $(LIBS)

check-tsan: $(TSAN_BIN)
	$(TSAN_RUN) $(TSAN_BIN)

# The demo's scene with the CPU backend named (AUTO could open EGL for a big batch), beside copies of its PNGs:
# a scene reads files only from inside its own folder.
$(DEEP_SCENE): demo/scene.json $(wildcard demo/*.png) tests/deep/deep.mk | $(DEEP_OUT)
	cp demo/*.png $(DEEP_OUT)/
	sed -e 's|"allow_sleep": true|"allow_sleep": true, "backend": "cpu"|' $< > $@
	grep -q '"backend": "cpu"' $@

$(DEEP_OUT):
	$(Q)mkdir -p $@

# valgrind's exit status is the check; the log's summary lines are a second one.
check-valgrind: all $(DEMO_BIN) $(DEEP_SCENE)
	valgrind $(VALGRIND_FLAGS) --log-file=$(VALGRIND_LOG) \
	  $(DEMO_BIN) --seconds $(DEEP_SECONDS) --every 30 --out $(DEEP_OUT)/demo --scene $(DEEP_SCENE) --quiet \
	  || { cat $(VALGRIND_LOG); exit 1; }
	@grep -q "ERROR SUMMARY: 0 errors" $(VALGRIND_LOG) && \
	  grep -Eq "definitely lost: 0 bytes|no leaks are possible" $(VALGRIND_LOG) && \
	  ! grep -Eq "indirectly lost: [1-9]" $(VALGRIND_LOG) || { cat $(VALGRIND_LOG); echo "$@: valgrind found errors or leaks"; exit 1; }
	@grep -E "in use at exit|definitely lost|indirectly lost|still reachable|no leaks are possible|ERROR SUMMARY" $(VALGRIND_LOG)

check-deep: check-tsan check-valgrind
