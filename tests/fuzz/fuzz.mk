# libFuzzer targets (tests/fuzz/): the library built with clang, ASan, UBSan and its PP_ASSERT checks, and one
# binary per target. `make fuzz` fuzzes every target for FUZZ_SECONDS on a working copy of its corpus (`make -j2
# fuzz` runs two at a time); `make test-fuzz` replays the committed corpus and regressions, then fuzzes each target
# briefly with a fixed seed. Both fail on any crash, leak, timeout or sanitizer report. CPU backend only.
FUZZ_CC           ?= clang
FUZZ_SECONDS      ?= 600
FUZZ_TEST_SECONDS ?= 15
FUZZ_SEED         ?= 1
FUZZ_DIR          := $(BUILD)/fuzz
FUZZ_TARGETS      := fuzz_png fuzz_scene fuzz_snapshot fuzz_api fuzz_state
FUZZ_BINS         := $(FUZZ_TARGETS:%=$(FUZZ_DIR)/%)
FUZZ_OBJ          := $(LIB_SRC:lib/%.c=$(FUZZ_DIR)/obj/%.o) $(FUZZ_DIR)/obj/glsl_sources.o
FUZZ_SAN          := -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer
FUZZ_CFLAGS       := $(PP_CFLAGS) -O1 -g $(FUZZ_SAN) -DPP_CHECKS
FUZZ_HDR          := tests/fuzz/fuzz_common.h tests/fuzz/fuzz_archive.h include/physpix.h lib/core/hash.h
# Per target: the longest input, and the dictionary of the JSON targets. Every target: 10 s and 256 MB in one
# malloc at most (no legitimate input of the harnesses comes near either).
FUZZ_OPTS_fuzz_png      := -max_len=16384
FUZZ_OPTS_fuzz_scene    := -max_len=4096 -dict=tests/fuzz/json.dict
FUZZ_OPTS_fuzz_snapshot := -max_len=16384 -dict=tests/fuzz/json.dict
FUZZ_OPTS_fuzz_api      := -max_len=1024
FUZZ_OPTS_fuzz_state    := -max_len=1024
FUZZ_ENV := ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# Any of these in a log fails the run even when the exit status did not.
FUZZ_BAD := ERROR: AddressSanitizer|ERROR: LeakSanitizer|runtime error:|ERROR: libFuzzer|SUMMARY: UndefinedBehaviorSanitizer

# The objects and binaries are kept: pattern rules would delete them as intermediates.
.PRECIOUS: $(FUZZ_DIR)/obj/%.o $(FUZZ_DIR)/fuzz_%
# (fuzz-run-% and test-fuzz-run-% are pattern rules, which make skips for .PHONY targets: no such files exist.)
.PHONY: fuzz test-fuzz fuzz-seeds

$(FUZZ_DIR)/obj/%.o: lib/%.c
	@mkdir -p $(@D)
	$(call quiet,CC,$<)$(FUZZ_CC) $(FUZZ_CFLAGS) -DPHYSPIX_BUILD -fsanitize=fuzzer-no-link $(DEPFLAGS) -c $< -o $@

$(FUZZ_DIR)/obj/glsl_sources.o: $(GLSL_GEN) lib/collide/gpu_context.h
	@mkdir -p $(@D)
	$(call quiet,CC,$<)$(FUZZ_CC) $(FUZZ_CFLAGS) -DPHYSPIX_BUILD -fsanitize=fuzzer-no-link -c $< -o $@

$(FUZZ_DIR)/fuzz_%: tests/fuzz/fuzz_%.c $(FUZZ_HDR) $(FUZZ_OBJ)
	$(call quiet,LD,$@)$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer -o $@ $< $(FUZZ_OBJ) $(LIBS)

# The seed generator (real snapshots, PNG variants): `make fuzz-seeds` rewrites tests/fuzz/corpus/.
$(FUZZ_DIR)/make_seeds: tests/fuzz/make_seeds.c tests/fuzz/fuzz_archive.h $(STATIC)
	@mkdir -p $(@D)
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O1 -g $(USER_CFLAGS) -o $@ $< $(STATIC) $(LDFLAGS) $(LIBS)

fuzz-seeds: $(FUZZ_DIR)/make_seeds
	$(FUZZ_DIR)/make_seeds tests/fuzz/corpus

# $(call fuzz_run,target,corpus dirs,options,log): run one binary, keep its log, fail on any report.
fuzz_run = mkdir -p $(FUZZ_DIR)/artifacts/$(1) && \
	$(FUZZ_ENV) $(FUZZ_DIR)/$(1) $(FUZZ_OPTS_$(1)) -timeout=10 -malloc_limit_mb=256 -artifact_prefix=$(FUZZ_DIR)/artifacts/$(1)/ \
	  $(3) $(2) > $(4) 2>&1; rc=$$?; \
	if [ $$rc -ne 0 ] || grep -Eq '$(FUZZ_BAD)' $(4); then \
	  tail -n 60 $(4); echo "$(1): FAILED (exit $$rc; log $(4), reproducer in $(FUZZ_DIR)/artifacts/$(1)/)"; exit 1; \
	fi

fuzz-run-%: $(FUZZ_DIR)/%
	rm -rf $(FUZZ_DIR)/corpus-run/$* && mkdir -p $(FUZZ_DIR)/corpus-run/$* && cp tests/fuzz/corpus/$*/* $(FUZZ_DIR)/corpus-run/$*/
	@echo "$*: fuzzing for $(FUZZ_SECONDS) s (log $(FUZZ_DIR)/$*.log)"
	@$(call fuzz_run,$*,$(FUZZ_DIR)/corpus-run/$*,-max_total_time=$(FUZZ_SECONDS) -print_final_stats=1,$(FUZZ_DIR)/$*.log)
	@echo "$*: corpus $$(ls $(FUZZ_DIR)/corpus-run/$* | wc -l) inputs"; grep -E '^(#[0-9]+.*DONE|stat::)' $(FUZZ_DIR)/$*.log

fuzz: $(FUZZ_BINS)
	$(MAKE) $(FUZZ_TARGETS:%=fuzz-run-%)
	@for t in $(FUZZ_TARGETS); do echo "$$t: $$(grep -E '^#[0-9]+.*DONE' $(FUZZ_DIR)/$$t.log | tail -n 1)"; done

# Replay every committed input once (corpus and regressions), then fuzz briefly with a fixed seed on a copy.
test-fuzz-run-%: $(FUZZ_DIR)/%
	@rm -rf $(FUZZ_DIR)/corpus-test/$* && mkdir -p $(FUZZ_DIR)/corpus-test/$* && cp tests/fuzz/corpus/$*/* $(FUZZ_DIR)/corpus-test/$*/
	@$(call fuzz_run,$*,tests/fuzz/corpus/$* $(wildcard tests/fuzz/regressions/$*),-runs=0,$(FUZZ_DIR)/$*.replay.log)
	@echo "$*: replayed $$(find tests/fuzz/corpus/$* $(wildcard tests/fuzz/regressions/$*) -type f | wc -l) inputs"
	@$(call fuzz_run,$*,$(FUZZ_DIR)/corpus-test/$*,-seed=$(FUZZ_SEED) -max_total_time=$(FUZZ_TEST_SECONDS) -print_final_stats=1,$(FUZZ_DIR)/$*.test.log)
	@echo "$*: $$(grep -E '^stat::number_of_executed_units' $(FUZZ_DIR)/$*.test.log | sed 's/.*: *//') runs in $(FUZZ_TEST_SECONDS) s, no reports"

test-fuzz: $(FUZZ_BINS)
	$(MAKE) -j2 $(FUZZ_TARGETS:%=test-fuzz-run-%)
