# `make run` and `make test` each create the virtual environment when it is missing.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed

.PHONY: run test lint xvfb bench screenshots clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip

$(STAMP): $(BIN)/python pyproject.toml
	$(BIN)/pip install --quiet -e '.[test]'
	touch $(STAMP)

run: $(STAMP)
	$(BIN)/teach replay dialogues/quickstart.dialogue

# One worker per core (pytest-xdist); every test keeps its own temporary folder and ports.
test: lint xvfb
	$(BIN)/python -m pytest -n auto

# The MuJoCo viewer's tests need an X server: Xvfb, installed with apt-get where we may (root);
# elsewhere they are skipped, and this says so.
xvfb:
	@command -v Xvfb >/dev/null 2>&1 || { test "$$(id -u)" = 0 && command -v apt-get >/dev/null 2>&1 \
	  && { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq xvfb; } >/dev/null 2>&1; } \
	  || echo "Xvfb is not installed (apt-get install xvfb): the MuJoCo viewer's tests will be skipped"

lint: $(STAMP)
	$(BIN)/ruff check teach tests bench
	$(BIN)/mypy

bench: $(STAMP)
	for b in bench/bench_*.py; do echo "== $$b"; $(BIN)/python $$b || exit 1; done

# Not part of `make test`: needs chromium, Xvfb and ImageMagick (installed with apt-get when missing); a few minutes.
SHOTLIB := build/screenshots-lib

$(SHOTLIB)/.installed: $(STAMP)
	$(BIN)/pip install --quiet --target $(SHOTLIB) playwright
	touch $@

recordings/quickstart.rrd:
	$(MAKE) run

screenshots: $(SHOTLIB)/.installed recordings/quickstart.rrd
	command -v chromium >/dev/null || apt-get install -y chromium
	PYTHONPATH=$(SHOTLIB) $(BIN)/python tools/screenshots.py recordings/quickstart.rrd
	command -v Xvfb >/dev/null && command -v import >/dev/null || apt-get install -y xvfb imagemagick
	$(BIN)/python tools/viewer_screenshot.py

clean:
	rm -rf $(VENV) build *.egg-info
