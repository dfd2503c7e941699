# The demo: the default destruction scene through the reference plugin host, rendered to PNG.
# `make demo` runs it and the reference host, writing only under build/; `make test-demo` runs it briefly and
# checks its images; `make demo-sprites` redraws the sprites in demo/ (they are committed, so `make demo` never
# needs it). The README's picture, demo/contact_sheet.png, is the contact sheet of the default run: `make pictures`
# renders it again (commit it when the physics or the renderer changed it) and `make test-pictures` checks that the
# committed one matches a fresh render (tests/demo/test_pictures.c says how closely).
DEMO_BIN     := $(BUILD)/demo/demo
DEMO_SPRITES := $(BUILD)/demo/make_sprites
DEMO_SRC     := demo/demo.c demo/render.c demo/debug_view.c demo/plugin_host.c
DEMO_HDR     := demo/render.h demo/debug_view.h demo/plugin_host.h include/physpix.h include/physpix_plugin.h
# The short run test-demo makes; tests/demo/test_demo.c reads the same figures from the environment.
TEST_DEMO_SECONDS := 1
TEST_DEMO_EVERY   := 10
TEST_DEMO_OUT     := $(BUILD)/tests/demo

PICTURES_OUT      := $(BUILD)/pictures
TEST_PICTURES_OUT := $(BUILD)/tests/pictures

.PHONY: demo-sprites pictures test-pictures

# $(call render_pictures,folder): the default demo run, the one the README shows, into a new folder.
render_pictures = rm -rf $(1) && $(DEMO_BIN) --quiet --out $(1) > $(1).log 2>&1 || { cat $(1).log; exit 1; }

# The simulation goes through the plugin (dlopen); libphyspix is linked for PNG in and out only.
$(DEMO_BIN): $(DEMO_SRC) $(DEMO_HDR) $(SHARED)
	$(Q)mkdir -p $(BUILD)/demo
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -Idemo -O2 -g $(USER_CFLAGS) -o $@ $(DEMO_SRC) $(LDFLAGS) -L$(BUILD) -lphyspix -Wl,-rpath,'$$ORIGIN/..' -ldl -lm

$(DEMO_SPRITES): demo/make_sprites.c include/physpix.h $(SHARED)
	$(Q)mkdir -p $(BUILD)/demo
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O2 -g $(USER_CFLAGS) -o $@ $< $(LDFLAGS) -L$(BUILD) -lphyspix -Wl,-rpath,'$$ORIGIN/..' -lm

demo-sprites: $(DEMO_SPRITES)
	$(DEMO_SPRITES) demo

demo: deps
	$(MAKE) all $(DEMO_BIN) $(BUILD)/demo/host
	$(DEMO_BIN) --out $(BUILD)/demo
	$(BUILD)/demo/host plugin/physpix.plugin

pictures: all $(DEMO_BIN)
	$(call render_pictures,$(PICTURES_OUT))
	cp $(PICTURES_OUT)/contact_sheet.png demo/contact_sheet.png
	@echo "make pictures: wrote demo/contact_sheet.png; commit it"

# Criterion, with ASan+UBSan; the renderer gives the test the sky and the debug view's cell colours.
$(BUILD)/tests/test_demo: tests/demo/test_demo.c demo/render.c demo/render.h demo/debug_view.c demo/debug_view.h \
  $(SHARED) | $(BUILD)/tests
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -Idemo -O1 -g $(SANFLAGS) $(USER_CFLAGS) -o $@ tests/demo/test_demo.c demo/render.c \
	  demo/debug_view.c $(LDFLAGS) -L$(BUILD) -lphyspix \
	  -Wl,-rpath,'$$ORIGIN/..' -lcriterion -lm

test-demo: export PP_DEMO_OUT := $(TEST_DEMO_OUT)
test-demo: export PP_DEMO_SECONDS := $(TEST_DEMO_SECONDS)
test-demo: export PP_DEMO_EVERY := $(TEST_DEMO_EVERY)
test-demo: all $(DEMO_BIN) $(BUILD)/tests/test_demo
	rm -rf $(TEST_DEMO_OUT)
	$(DEMO_BIN) --seconds $(TEST_DEMO_SECONDS) --every $(TEST_DEMO_EVERY) --out $(TEST_DEMO_OUT) --quiet
	$(call run_san,$(BUILD)/tests/test_demo,$(BUILD)/tests/demo.log)

$(BUILD)/tests/test_pictures: tests/demo/test_pictures.c include/physpix.h $(SHARED) | $(BUILD)/tests
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O1 -g $(SANFLAGS) $(USER_CFLAGS) -o $@ $< $(LDFLAGS) -L$(BUILD) -lphyspix \
	  -Wl,-rpath,'$$ORIGIN/..' -lcriterion -lm

test-pictures: export PP_PICTURE_COMMITTED := demo/contact_sheet.png
test-pictures: export PP_PICTURE_FRESH := $(TEST_PICTURES_OUT)/contact_sheet.png
test-pictures: all $(DEMO_BIN) $(BUILD)/tests/test_pictures
	$(call render_pictures,$(TEST_PICTURES_OUT))
	$(call run_san,$(BUILD)/tests/test_pictures,$(BUILD)/tests/test_pictures.log)
