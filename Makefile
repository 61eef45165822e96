# tyrelab — two commands from a fresh clone:
#   make all    create .venv, install, generate the demo campaign, run every stage, render the report
#   make test   create .venv, install, run the test suite
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
EXTRAS ?= dev,dask,formats

.PHONY: all install data run test test-all bench clean distclean

all: run

$(BIN)/tyrelab: pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[$(EXTRAS)]'
	@touch $@

install: $(BIN)/tyrelab

$(STAMP): | $(BIN)/tyrelab
	rm -rf $(DEMO)
	$(BIN)/tyrelab generate --out $(DEMO) --scale $(SCALE) --seed $(SEED)
	touch $@

data: $(STAMP)

run: data
	$(BIN)/tyrelab run --raw $(RAW) --build $(BUILD)
	@echo "report: $(BUILD)/reports/index.html — query: $(BIN)/tyrelab sql \"SELECT * FROM table_iii\""

test: install
	$(BIN)/python -m pytest -q -m "not slow" -n auto

test-all: install
	$(BIN)/python -m pytest -q

bench: install
	$(BIN)/python bench/run_all.py

clean:
	rm -rf $(BUILD)

distclean: clean
	rm -rf $(VENV) $(DEMO)
