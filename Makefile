# tyrelab — two commands from a fresh clone:
#   make all    create .venv, install, generate the demo campaign, run every stage, render the report
#   make test   create .venv, install, run the test suite
#   make test-latest  the suite on the newest versions pyproject.toml allows (.venv-latest), not the lock
#   make test-steady  the suite again and again (-n auto, -n 1, STEADY_LOAD busy processes beside): the next flaky test
#   make docs   the documentation site (Sphinx) -> build/docs/index.html, every example run
#   make mutation  mutation testing of the physics and statistics (slow: hours; not in make test)
PYTHON ?= python3
VENV   ?= .venv
BIN    := $(VENV)/bin
SCALE  ?= small
SEED   ?= 1991
DEMO   ?= raw/demo
RAW    ?= $(DEMO)
BUILD  ?= build
# The demo campaign is a product of the code that writes it (the virtual rig, vehicles and roads):
# one stamp per (scale, seed, sources), so changing SCALE, SEED or any module of the package
# regenerates it (a campaign written by an older generator is not silently reused).
GEN_KEY := $(shell find pipeline -name '*.py' -not -path '*/__pycache__/*' | LC_ALL=C sort | xargs cat | sha256sum | cut -c1-12)
STAMP  := $(DEMO)/.generated-$(SCALE)-seed$(SEED)-$(GEN_KEY)
EXTRAS ?= dev,dask,formats,browser
# Extra arguments of tools/mutation.py, e.g. MUTATION_ARGS="--sample 40 vehicle/iso2631.py".
MUTATION_ARGS ?=

.PHONY: all install compile data run test test-steady test-latest lock lock-upgrade test-package test-all mutation bench docs docs-outputs clean distclean

all: run

# .venv is built from the lock (requirements.lock: every package of the dependency tree of the extras
# dev, dask, formats, browser and docs pinned with its hashes, for every platform and Python >= 3.11),
# then tyrelab itself without dependencies: the same versions on every machine and in CI. pyproject.toml
# keeps the ranges a library user needs; `make test-latest` tests the newest versions they allow.
# With uv on PATH the same lock is installed by uv (seconds from its cache instead of minutes; `make
# install UV=` forces pip), else by plain pip, with the package index pip is configured with.
LOCK := requirements.lock
UV ?= $(shell command -v uv 2>/dev/null)
$(BIN)/tyrelab: pyproject.toml $(LOCK)
	rm -rf $(VENV)
ifneq ($(UV),)
	$(UV) venv -q --seed --python $(PYTHON) $(VENV)
	$(UV) pip install -q --python $(BIN)/python --compile-bytecode --require-hashes -r $(LOCK)
	$(UV) pip install -q --python $(BIN)/python --no-deps -e .
else
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --require-hashes -r $(LOCK)
	$(BIN)/python -m pip install --quiet --no-deps -e .
endif
	@touch $@

install: $(BIN)/tyrelab

# Byte-compile the package's sources, as pip does for a wheel: an editable install leaves it to
# the first import, and with PYTHONDONTWRITEBYTECODE=1 (set on our CI machines) every process
# compiled its ~60 modules from source again (~0.1-0.2 s of each `tyrelab` command). The
# dependencies are compiled when installed: pip does it by default, uv only with --compile-bytecode —
# without it every `tyrelab` subprocess and pool worker of the tests compiled scipy and pandas from
# source (~1,000 modules: an ingest of 3 runs took 16 s instead of 4 s; ~40 % of `make test`).
compile: install
	@$(BIN)/python -m compileall -q pipeline

# $(call generate_demo,FOLDER,SCALE,SEED,ALSO): a fresh demo campaign in FOLDER (ALSO removed with it: a
# build made from the old one), then the target's stamp. The one recipe of $(STAMP) and $(DOCS_STAMP).
generate_demo = rm -rf $(1) $(4) && $(BIN)/tyrelab generate --out $(1) --scale $(2) --seed $(3) && touch $@

$(STAMP): | $(BIN)/tyrelab
	$(call generate_demo,$(DEMO),$(SCALE),$(SEED))

data: $(STAMP)

run: data compile
	$(BIN)/tyrelab run --raw $(RAW) --build $(BUILD)
	@echo "report: $(BUILD)/reports/index.html — query: $(BIN)/tyrelab sql \"SELECT * FROM table_iii\""

test: install compile
	$(BIN)/lint-imports --no-cache
	$(BIN)/python -m pytest -q -m "not slow" -n auto --durations=25

# The lock again from pyproject.toml's ranges: `make lock` keeps every pin the ranges still allow (and
# adds what a changed range needs); `make lock-upgrade` takes the newest of everything. Needs uv.
LOCK_EXTRAS := --extra dev --extra dask --extra formats --extra browser --extra docs
LOCK_COMPILE = uv pip compile pyproject.toml $(LOCK_EXTRAS) --generate-hashes --universal --python-version 3.11 \
	--custom-compile-command "make lock" -o $(LOCK)
lock:
	$(LOCK_COMPILE)

lock-upgrade:
	$(LOCK_COMPILE) --upgrade

# The suite on the newest versions pyproject.toml's ranges allow (not the lock), in a virtualenv of its
# own (.venv-latest, made again each time): what a library user who installs tyrelab today gets.
LATEST ?= .venv-latest
test-latest:
	rm -rf $(LATEST)
	$(PYTHON) -m venv $(LATEST)
	$(LATEST)/bin/python -m pip install --quiet --upgrade --upgrade-strategy eager -e '.[$(EXTRAS)]'
	$(LATEST)/bin/python -m pip list --format=freeze | grep -iE '^(numpy|scipy|pandas|pyarrow|duckdb|statsmodels|matplotlib)=='
	$(LATEST)/bin/python -m compileall -q pipeline
	$(LATEST)/bin/python -m pytest -q -m "not slow" -n auto

# The default suite STEADY_ROUNDS times under -n auto and -n 1, with STEADY_LOAD busy processes beside
# it: finds the next flaky test (tools/test_steady.sh; docs/testing.md). Long: run it on a machine of its own.
STEADY_ROUNDS ?= 2
STEADY_LOAD ?= 0
test-steady: install compile
	PYTHON_BIN=$(BIN)/python tools/test_steady.sh $(STEADY_ROUNDS) $(STEADY_LOAD)

# The built wheel in a fresh virtualenv: generate -> run -> sql -> report from an empty folder.
test-package: install
	$(BIN)/python -m pytest -q tests/test_wheel.py

test-all: install
	$(BIN)/python -m pytest -q

# cosmic-ray on a copy of the package (tools/mutation.py); the score per module is printed at
# the end and build/mutation/ keeps the sessions (--report, --survivors, --resume).
mutation: install
	$(BIN)/python -m pip install --quiet -e '.[$(EXTRAS),mutation]'
	$(BIN)/python tools/mutation.py $(MUTATION_ARGS)

# The documentation site: tutorials, how-tos, the reference generated from the code (parser,
# schemas, declared tables, docstrings) and the explanation documents of docs/. Sphinx runs with
# -W (a warning fails the build); the tutorials' commands run while the pages are read (their
# output is shown) and their Python examples under `-b doctest`. The tutorials read a build of
# the small demo campaign in build/docs-work/ (the tyre engineer's tutorial's two commands).
DOCS_WORK := build/docs-work
DOCS_ENV = PATH="$(abspath $(BIN)):$$PATH" TYRELAB_DOCS_WORK="$(abspath $(DOCS_WORK))" \
	TYRELAB_DOCS_BUILD="$(abspath $(DOCS_WORK))/build" PYTHONHASHSEED=0
# The docs' demo campaign, regenerated (and its build dropped) when the sources change, as $(STAMP).
DOCS_STAMP := $(DOCS_WORK)/raw/demo/.generated-small-seed1991-$(GEN_KEY)

$(DOCS_STAMP): | $(BIN)/tyrelab
	$(call generate_demo,$(DOCS_WORK)/raw/demo,small,1991,$(DOCS_WORK)/build)

# Sphinx and its extensions (the extra docs) are in the lock, installed with the rest: the stamp only
# says so to the targets that name it.
$(VENV)/.docs-extra: $(BIN)/tyrelab
	@touch $@

docs: $(VENV)/.docs-extra compile $(DOCS_STAMP)
	$(BIN)/tyrelab run -q --raw $(DOCS_WORK)/raw --build $(DOCS_WORK)/build
	rm -rf $(BUILD)/docs $(BUILD)/docs-doctrees $(BUILD)/docs-doctest
	$(DOCS_ENV) $(BIN)/sphinx-build -W --keep-going -q -b html -d $(BUILD)/docs-doctrees docs/site $(BUILD)/docs
	$(DOCS_ENV) $(BIN)/sphinx-build -W --keep-going -q -b doctest -d $(BUILD)/docs-doctrees docs/site $(BUILD)/docs-doctest
	@echo "docs: $(BUILD)/docs/index.html"

# The outputs shown in README.md and docs/*.md, written from their commands (make docs checks them:
# docs/site/_ext/tyrelab_outputs.py).
docs-outputs: $(VENV)/.docs-extra compile $(DOCS_STAMP)
	$(BIN)/tyrelab run -q --raw $(DOCS_WORK)/raw --build $(DOCS_WORK)/build
	$(DOCS_ENV) $(BIN)/python docs/site/_ext/tyrelab_outputs.py --update --work $(DOCS_WORK)

bench: install
	$(BIN)/python bench/run_all.py

clean:
	rm -rf $(BUILD)

distclean: clean
	rm -rf $(VENV) $(LATEST) $(DEMO)
