# The Godot 3.2 GDNative adapter: libphyspix_godot.so (NativeScript class PhysPixWorld) from the committed
# API struct declarations, and test-godot, which runs the headless project in tests/godot inside godot3-server.

GODOT_API_H := plugin/godot/gdnative_api_structs.h
GODOT_LIB   := $(BUILD)/libphyspix_godot.so
GODOT_SRC   := $(wildcard plugin/godot/*.c)

.PHONY: godot-api

# The build never reads Godot's JSON; this regenerates the committed header from your own godot-headers
# (gdnative_api.json of tag godot-3.2.3-stable): make godot-api GODOT_API_JSON=/path/to/gdnative_api.json
godot-api:
	@test -n "$(GODOT_API_JSON)" || { echo "make godot-api: set GODOT_API_JSON to godot-headers' gdnative_api.json"; exit 1; }
	$(PYTHON) plugin/godot/gen_gdnative_api.py $(GODOT_API_JSON) $(GODOT_API_H) --ext nativescript

# Exports only the three godot_* entry points; finds libphyspix.so.0 beside itself ($ORIGIN).
$(GODOT_LIB): $(GODOT_SRC) $(wildcard plugin/godot/*.h) include/physpix.h $(SHARED)
	$(CC) $(PP_CFLAGS) -O2 -g -fPIC -fvisibility=hidden $(USER_CFLAGS) -shared -Wl,--no-undefined \
	  -o $@ $(GODOT_SRC) $(LDFLAGS) -L$(BUILD) -lphyspix -Wl,-rpath,'$$ORIGIN'

test-godot: all $(GODOT_LIB)
	BUILD=$(BUILD) tests/godot/run.sh
