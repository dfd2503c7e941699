# The Python package (ctypes, plugin/python/physpix): test-python runs tests/python with pytest
# against the freshly built library. The layout helper prints the C struct layouts for the tests.
PY_LAYOUT := $(BUILD)/tests/pp_layout

$(PY_LAYOUT): tests/python/layout.c include/physpix.h | $(BUILD)/tests
	$(CC) $(CFLAGS_) -O0 -o $@ $<

test-python: all $(PY_LAYOUT)
	PHYSPIX_LIBRARY=$(abspath $(SHARED)) PHYSPIX_LAYOUT_HELPER=$(abspath $(PY_LAYOUT)) \
	  PYTHONPATH=$(abspath plugin/python) $(PYTHON) -m pytest -q -p no:cacheprovider tests/python
