# Two entry points (see README): `make report` runs the main job, `make test` the test suite.
# Both create a local virtual environment (.venv) and install the project into it first.
PYTHON ?= python3
# the package's and the tests' bytecode is written on first import (beside numba's cache in
# __pycache__): with PYTHONDONTWRITEBYTECODE set, every test process and every mrsus command
# the tests start compiled the package from source again, and each pytest process rewrote
# every test module's asserts (collection 16 s instead of 8 s)
unexport PYTHONDONTWRITEBYTECODE
VENV := .venv
BIN := $(VENV)/bin
OUT ?= results

.PHONY: report test lint bench clean system-deps

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

# reinstall only when the project metadata changes (`report` and `test` then compile the
# kernels into numba's cache, so the first command does not wait for them)
# (with uv, which installs the same versions in 25 s where pip takes a minute; pip if uv
# cannot; bytecode compiled, as pip does: without it every test process compiles numpy,
# scipy, ... from source, measured +20 % CPU on the suite with PYTHONDONTWRITEBYTECODE)
$(VENV)/.stamp-install: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install --quiet uv
	$(BIN)/uv pip install --quiet --compile-bytecode --python $(BIN)/python -e ".[dev,plot,optimal]" \
	  || $(BIN)/python -m pip install --quiet -e ".[dev,plot,optimal]"
	touch $@

report: $(VENV)/.stamp-install
	$(BIN)/mrsus cache warm
	$(BIN)/mrsus reproduce --out $(OUT)

# mypy keeps its incremental cache outside the clone (MYPY_CACHE), so a fresh clone's CI
# checks in about 1 s what takes 26 s cold; the cache is validated against each file's
# content, so a changed file is checked again whatever the clone
MYPY_CACHE ?= $(or $(XDG_CACHE_HOME),$(HOME)/.cache)/mrsuspension-dev/mypy
lint: $(VENV)/.stamp-install
	$(BIN)/ruff check src tests benchmarks examples tools
	$(BIN)/ruff format --check src tests benchmarks examples tools
	$(BIN)/mypy --cache-dir "$(MYPY_CACHE)"

# Debian's chromium for the browser tests (Playwright drives it; no browser download)
system-deps:
	@if ! command -v chromium >/dev/null 2>&1; then \
	  if [ "$$(id -u)" = 0 ]; then SUDO=; else SUDO=sudo; fi; \
	  $$SUDO apt-get update -qq && $$SUDO apt-get install -y -qq chromium; \
	fi

# warm first (a few seconds when nothing changed): the tests' processes then load the
# compiled kernels instead of each compiling them. The suite runs on JOBS workers
# (pytest-xdist; a test module stays on one worker, so its fixtures are built once),
# then the tests that keep 1 kHz deadlines (marker `realtime`) run alone on a quiet machine
# (the kernels compile beside the lint, whose mypy takes ~30 s: the warm's steps compile
# separate kernels, ~75 s on one core, on one process per core, longest first; its lines
# are printed when both are done). Three workers on two cores were measured (2026-11-27):
# the main phase took 341 s once and 386 s once, against 359-365 s with two: no gain
JOBS ?= 2
test: $(VENV)/.stamp-install system-deps
	@log=$$(mktemp); echo "$(BIN)/mrsus cache warm (beside the lint)"; \
	  $(BIN)/mrsus cache warm >$$log 2>&1 & warm=$$!; \
	  $(MAKE) --no-print-directory lint; lint=$$?; \
	  wait $$warm; compiled=$$?; cat $$log; rm -f $$log; \
	  [ $$lint = 0 ] && [ $$compiled = 0 ]
	$(BIN)/python -m pytest -n $(JOBS) --dist loadscope -m "not realtime" --durations=25
	$(BIN)/python -m pytest -m realtime tests/integration/test_hil.py \
	  tests/integration/test_hil_udp.py tests/integration/test_monitor.py  # REALTIME_FILES

bench: $(VENV)/.stamp-install
	$(BIN)/python benchmarks/bench_damper.py
	$(BIN)/python benchmarks/bench_engine.py
	$(BIN)/python benchmarks/bench_identify.py
	$(BIN)/python benchmarks/bench_hil.py --duration 20

clean:
	rm -rf $(VENV) .pytest_cache .mypy_cache .ruff_cache $(OUT)
