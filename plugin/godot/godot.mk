# The Godot 3.2 GDNative adapter: libphyspix_godot.so (NativeScript class PhysPixWorld) from the committed
# API struct declarations; the addon (plugin/godot/addons/physpix/ with both libraries beside its .gdnlib)
# assembled in build/addons/physpix/, ready to copy into a project's addons/; and test-godot, which runs the
# headless projects tests/godot and plugin/godot/example inside godot3-server.

GODOT_API_H := plugin/godot/gdnative_api_structs.h
GODOT_LIB   := $(BUILD)/libphyspix_godot.so
GODOT_SRC   := $(wildcard plugin/godot/*.c)
GODOT_ADDON_SRC := $(wildcard plugin/godot/addons/physpix/*)
GODOT_ADDON := $(BUILD)/addons/physpix
# What `make all` builds for Godot.
GODOT_ALL   := $(GODOT_LIB) $(GODOT_ADDON)/libphyspix_godot.so

.PHONY: godot-api godot-example godot-pictures godot-frame-cost

# The build never reads Godot's JSON; this regenerates the committed header from your own godot-headers
# (gdnative_api.json of tag godot-3.2.3-stable): make godot-api GODOT_API_JSON=/path/to/gdnative_api.json
godot-api:
	@test -n "$(GODOT_API_JSON)" || { echo "make godot-api: set GODOT_API_JSON to godot-headers' gdnative_api.json"; exit 1; }
	$(PYTHON) plugin/godot/gen_gdnative_api.py $(GODOT_API_JSON) $(GODOT_API_H) --ext nativescript

# Exports only the three godot_* entry points; finds libphyspix.so.0 beside itself ($ORIGIN).
$(GODOT_LIB): $(GODOT_SRC) $(wildcard plugin/godot/*.h) plugin/api/def_fields.h include/physpix.h $(SHARED)
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O2 -g -fPIC -fvisibility=hidden $(USER_CFLAGS) -shared -Wl,--no-undefined \
	  -o $@ $(GODOT_SRC) $(LDFLAGS) -L$(BUILD) -lphyspix -Wl,-rpath,'$$ORIGIN'

# -L: the soname is a symlink in build/; the addon needs the file itself. plugin.cfg is committed (a project may
# copy the addon from the source tree), so the build checks that its version is the header's, the one version source.
GODOT_PLUGIN_CFG := plugin/godot/addons/physpix/plugin.cfg
$(GODOT_ADDON)/libphyspix_godot.so: $(GODOT_LIB) $(SHARED) $(GODOT_ADDON_SRC)
	$(Q)grep -qx 'version="$(VERSION)"' $(GODOT_PLUGIN_CFG) || { echo "$(GODOT_PLUGIN_CFG): expected" \
	  'version="$(VERSION)"' "(PHYSPIX_VERSION_* in include/physpix.h), found $$(grep '^version=' $(GODOT_PLUGIN_CFG))"; exit 1; }
	$(Q)rm -rf $(GODOT_ADDON) && mkdir -p $(GODOT_ADDON)
	$(Q)cp $(GODOT_ADDON_SRC) $(GODOT_ADDON)/
	$(Q)cp -L $(BUILD)/$(SONAME) $(GODOT_ADDON)/
	$(Q)cp $(GODOT_LIB) $(GODOT_ADDON)/

# The example with the addon in its addons/, ready to run: godot3 --path build/godot-example (-e: the editor).
# The editor imports its PNGs first (-e --quit, as a user's first opening does): a project never imported has no
# loader for res://terrain.png. The editor's scan races its quit (on a busy machine it can print "Scan thread
# aborted" and import nothing), so the import runs again until every PNG has its .import, three times at most.
# Every Godot target below starts from this one.
GODOT_ENV = env LANG=en_US.UTF-8 HOME=$(CURDIR)/$(BUILD)/godot-home XDG_CONFIG_HOME=$(CURDIR)/$(BUILD)/godot-home \
  XDG_DATA_HOME=$(CURDIR)/$(BUILD)/godot-home XDG_CACHE_HOME=$(CURDIR)/$(BUILD)/godot-home
GODOT_IMPORT_LOG := $(BUILD)/godot-home/import.txt
godot-example: $(GODOT_ADDON)/libphyspix_godot.so
	$(Q)rm -rf $(BUILD)/godot-example && mkdir -p $(BUILD)/godot-example/addons $(BUILD)/godot-home
	$(Q)cp -R plugin/godot/example/. $(BUILD)/godot-example/
	$(Q)cp -R $(GODOT_ADDON) $(BUILD)/godot-example/addons/
	@for try in 1 2 3; do \
	  $(GODOT_ENV) timeout 120 godot3-server --path $(BUILD)/godot-example -e --quit > $(GODOT_IMPORT_LOG) 2>&1 \
	    || { cat $(GODOT_IMPORT_LOG); echo "make godot-example: importing the project failed"; exit 1; }; \
	  missing=; for png in plugin/godot/example/*.png; do \
	    test -f $(BUILD)/godot-example/$${png##*/}.import || missing="$$missing $${png##*/}"; done; \
	  [ -z "$$missing" ] && break; \
	  echo "make godot-example: the editor quit before importing$$missing (its scan is a race); try $$try of 3"; \
	done; [ -z "$$missing" ] || { cat $(GODOT_IMPORT_LOG); exit 1; }
	@echo "make godot-example: imported $$(ls $(BUILD)/godot-example/*.import | wc -l) resources"
	@echo "make godot-example: run it with godot3 --path $(BUILD)/godot-example (add -e to open the editor)"

# One-off: the example rendered by the real Godot 3.2 (godot3 under Xvfb, Mesa's GLES2), its viewport saved at
# the start and after blasts as plugin/godot/example-*.png (capture.gd).
godot-pictures: godot-example
	cp plugin/godot/capture.gd $(BUILD)/godot-example/
	$(GODOT_ENV) timeout 300 xvfb-run -a -s "-screen 0 1024x600x24" godot3 --path $(BUILD)/godot-example --fixed-fps 60 \
	  -s capture.gd -- $(CURDIR)/plugin/godot

# One-off: the example's cost per physics frame in godot3-server, in real time (measure.gd).
godot-frame-cost: godot-example
	cp plugin/godot/measure.gd $(BUILD)/godot-example/
	$(GODOT_ENV) timeout 120 godot3-server --path $(BUILD)/godot-example -s measure.gd

# The example's test runs in a copy of what `make godot-example` made, so a missing import step fails it.
test-godot: all godot-example
	BUILD=$(BUILD) tests/godot/run.sh
