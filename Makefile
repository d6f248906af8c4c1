# Two commands do all the set-up on a fresh Debian machine (as root):
#   make demo   -> .venv + system packages + package with extras, then the main job
#   make test   -> the same set-up, then the whole test suite (it builds the docs site too)
#   make docs   -> the same set-up, then the documentation site into docs/_build/html
SHELL := /bin/bash
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
PIP := $(VENV)/bin/pip
SYSTEM_PACKAGES := xfoil xvfb xauth coinor-libipopt-dev liblapack-dev libblas-dev pkg-config chromium chromium-driver

.PHONY: demo test docs system venv clean

# System packages: XFOIL + Xvfb (airfoil polars), Ipopt headers (cyipopt builds from its sdist),
# Chromium + ChromeDriver (the docs site's browser test).  Re-checked when this Makefile changes.
system: .stamp-system
.stamp-system: Makefile
	@if command -v apt-get >/dev/null 2>&1; then \
	  missing=""; for p in $(SYSTEM_PACKAGES); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	  if [ -n "$$missing" ]; then \
	    SUDO=""; [ "$$(id -u)" = 0 ] || SUDO="sudo"; \
	    $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq $$missing; \
	  fi; \
	else echo "apt-get not found: install $(SYSTEM_PACKAGES) by hand"; fi
	@touch $@

venv: $(VENV)/.stamp-install
$(VENV)/.stamp-install: pyproject.toml .stamp-system
	$(PYTHON) -m venv $(VENV)
	$(PIP) install -q --upgrade pip
	$(PIP) install -q -e ".[all]"
	@touch $@

demo: venv
	$(VENV)/bin/bild-mdo demo

# The test suite builds the site too (tests/docs/, into a temporary folder).
test: venv
	$(PY) -m pytest -q -p no:cacheprovider

# Every example on the site runs; any warning fails the build (docs/build.py).
docs: venv
	$(PY) docs/build.py docs/_build

clean:
	rm -rf $(VENV) .stamp-system
