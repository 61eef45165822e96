# tyrelab — two commands from a fresh clone:
#   make all    create .venv, install, generate the demo campaign, run every stage, render the report
#   make test   create .venv, install, run the test suite
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
# One stamp per (scale, seed): changing SCALE or SEED regenerates the demo campaign.
STAMP  := $(DEMO)/.generated-$(SCALE)-seed$(SEED)
EXTRAS ?= dev,dask,formats,browser
# Extra arguments of tools/mutation.py, e.g. MUTATION_ARGS="--sample 40 vehicle/iso2631.py".
MUTATION_ARGS ?=

.PHONY: all install compile data run test test-steady test-package test-all mutation bench docs clean distclean

all: run

$(BIN)/tyrelab: pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[$(EXTRAS)]'
	@touch $@

install: $(BIN)/tyrelab

# Byte-compile the package's sources, as pip does for a wheel: an editable install leaves it to
# the first import, and with PYTHONDONTWRITEBYTECODE=1 (set on our CI machines) every process
# compiled its ~60 modules from source again (~0.1-0.2 s of each `tyrelab` command).
compile: install
	@$(BIN)/python -m compileall -q pipeline

$(STAMP): | $(BIN)/tyrelab
	rm -rf $(DEMO)
	$(BIN)/tyrelab generate --out $(DEMO) --scale $(SCALE) --seed $(SEED)
	touch $@

data: $(STAMP)

run: data compile
	$(BIN)/tyrelab run --raw $(RAW) --build $(BUILD)
	@echo "report: $(BUILD)/reports/index.html — query: $(BIN)/tyrelab sql \"SELECT * FROM table_iii\""

test: install compile
	$(BIN)/lint-imports --no-cache
	$(BIN)/python -m pytest -q -m "not slow" -n auto

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

$(VENV)/.docs-extra: pyproject.toml | $(BIN)/tyrelab
	$(BIN)/python -m pip install --quiet -e '.[$(EXTRAS),docs]'
	@touch $@

docs: $(VENV)/.docs-extra compile
	@test -f $(DOCS_WORK)/raw/demo/manifest.csv || $(BIN)/tyrelab generate --out $(DOCS_WORK)/raw/demo --scale small --seed 1991
	$(BIN)/tyrelab run -q --raw $(DOCS_WORK)/raw --build $(DOCS_WORK)/build
	rm -rf $(BUILD)/docs $(BUILD)/docs-doctrees $(BUILD)/docs-doctest
	$(DOCS_ENV) $(BIN)/sphinx-build -W --keep-going -q -b html -d $(BUILD)/docs-doctrees docs/site $(BUILD)/docs
	$(DOCS_ENV) $(BIN)/sphinx-build -W --keep-going -q -b doctest -d $(BUILD)/docs-doctrees docs/site $(BUILD)/docs-doctest
	@echo "docs: $(BUILD)/docs/index.html"

bench: install
	$(BIN)/python bench/run_all.py

clean:
	rm -rf $(BUILD)

distclean: clean
	rm -rf $(VENV) $(DEMO)
