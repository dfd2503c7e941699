# The Python package (ctypes, plugin/python/physpix) and the project's virtual environment.
# - venv (run by `make deps`): build/venv from $(PYTHON), seeing the system's packages; numpy, pytest,
#   setuptools and wheel are installed into it from PyPI only if it cannot import them. Nothing is ever
#   installed into the system interpreter (Debian's is externally managed, PEP 668). The wheels pip used
#   stay in build/wheelhouse, so the packaging test installs into fresh environments offline.
# - wheel: build/wheel/physpix-<version>-*.whl, carrying libphyspix.so (plugin/python/setup.py).
# - test-python: tests/python with pytest against the freshly built library. The layout helper prints the
#   C struct layouts for the tests.
VENV          := $(BUILD)/venv
VENV_PY       := $(VENV)/bin/python
PY_DEPS       := numpy pytest setuptools wheel
PY_WHEELHOUSE := $(BUILD)/wheelhouse
PY_LAYOUT     := $(BUILD)/tests/pp_layout

.PHONY: venv wheel

venv:
	@if [ ! -x $(VENV_PY) ]; then \
	  echo "make deps: creating $(VENV) from $$(command -v $(PYTHON))"; \
	  $(PYTHON) -m venv --system-site-packages $(VENV) || { rm -rf $(VENV); \
	    echo "make deps: '$(PYTHON) -m venv' failed; for Debian's python3 install python3-venv"; exit 1; }; \
	fi
	@$(VENV_PY) -c 'import numpy, pytest, setuptools, wheel' 2>/dev/null || { \
	  echo "make deps: installing into $(VENV) from PyPI: $(PY_DEPS)"; \
	  $(VENV_PY) -m pip download --quiet --dest $(PY_WHEELHOUSE) $(PY_DEPS) && \
	  $(VENV_PY) -m pip install --quiet --no-index --find-links $(PY_WHEELHOUSE) $(PY_DEPS); }

wheel: lib venv
	rm -rf $(BUILD)/wheel
	$(VENV_PY) -m pip wheel --quiet --no-deps --no-build-isolation --wheel-dir $(BUILD)/wheel plugin/python
	@ls $(BUILD)/wheel/*.whl

$(PY_LAYOUT): tests/python/layout.c include/physpix.h | $(BUILD)/tests
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O0 -o $@ $<

test-python: all venv $(PY_LAYOUT)
	PHYSPIX_LIBRARY=$(abspath $(SHARED)) PHYSPIX_LAYOUT_HELPER=$(abspath $(PY_LAYOUT)) \
	  PYTHONPATH=$(abspath plugin/python) $(VENV_PY) -m pytest -q -p no:cacheprovider tests/python
