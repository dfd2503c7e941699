# The demo: the default destruction scene through the reference plugin host, rendered to PNG.
DEMO_SRC := demo/demo.c

$(BUILD)/demo/demo: $(DEMO_SRC) $(SHARED)
	mkdir -p $(BUILD)/demo
	$(CC) $(CFLAGS_) -O2 -g -o $@ $(DEMO_SRC) -L$(BUILD) -lphyspix -Wl,-rpath,'$$ORIGIN/..' $(LIBS)

demo: deps
	$(MAKE) all $(BUILD)/demo/demo $(BUILD)/demo/host
	$(BUILD)/demo/demo
	$(BUILD)/demo/host plugin/physpix.plugin

test-demo:
	@echo "test-demo: not yet written"; exit 1
