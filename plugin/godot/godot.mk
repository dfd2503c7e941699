# The Godot 3.2 GDNative adapter: the API structs generated from Godot's JSON description,
# libphyspix_godot.so (NativeScript class PhysPixWorld), and test-godot, which runs the
# headless project in tests/godot inside godot3-server.

# Godot's gdnative_api.json (godot-headers, tag godot-3.2.3-stable); point it at your own checkout if you like.
GODOT_API_JSON ?= ../shared/godot/gdnative_api.json

GODOT_GEN := $(BUILD)/gen/gdnative_api_structs.h
GODOT_LIB := $(BUILD)/libphyspix_godot.so
GODOT_SRC := $(wildcard plugin/godot/*.c)

# wildcard: a missing JSON reaches the generator, which says which file and which variable.
$(GODOT_GEN): plugin/godot/gen_gdnative_api.py $(wildcard $(GODOT_API_JSON)) | $(BUILD)/gen
	$(PYTHON) plugin/godot/gen_gdnative_api.py $(GODOT_API_JSON) $@ --ext nativescript

# Exports only the three godot_* entry points; finds libphyspix.so.0 beside itself ($ORIGIN).
$(GODOT_LIB): $(GODOT_SRC) $(wildcard plugin/godot/*.h) $(GODOT_GEN) include/physpix.h $(SHARED)
	$(CC) $(CFLAGS_) -I$(BUILD)/gen -O2 -g -fPIC -fvisibility=hidden -shared -Wl,--no-undefined \
	  -o $@ $(GODOT_SRC) -L$(BUILD) -lphyspix -Wl,-rpath,'$$ORIGIN'

test-godot: all $(GODOT_LIB)
	BUILD=$(BUILD) tests/godot/run.sh
