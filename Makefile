# crankdyn: two commands for a newcomer (see README), plus a few for developers.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
OUT    ?= crankdyn-demo

.PHONY: demo test lint bench fuzz clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install -q --upgrade pip

$(VENV)/.stamp-base: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install -q -e .
	@touch $@

$(VENV)/.stamp-test: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install -q -e '.[test]'
	@touch $@ $(VENV)/.stamp-base

## make demo: install and run the main job on the built-in inline-6 diesel
demo: $(VENV)/.stamp-base
	$(BIN)/crankdyn demo -o $(OUT) --force

## make test: install with test extras, lint, run the whole suite
test: $(VENV)/.stamp-test
	@bash scripts/install-browser.sh
	$(BIN)/ruff check src tests bench docs/examples
	$(BIN)/ruff format --check src tests bench docs/examples
	$(BIN)/python -m pytest -n 2 -q

## make fuzz: the long property-based campaign over every input path (docs/robustness.md)
FUZZ_EXAMPLES ?= 5000
fuzz: $(VENV)/.stamp-test
	HYPOTHESIS_PROFILE=fuzz CRANKDYN_FUZZ_EXAMPLES=$(FUZZ_EXAMPLES) $(BIN)/python -m pytest -n 2 -q -p no:cacheprovider tests/robustness

## make bench: side-by-side benchmarks against openTorsion and pylinkage in their own environment
## (docs/benchmarks.md); `make bench BENCH_ARGS=--write-docs` also rewrites the doc's table
BENCH_VENV := .venv-bench
BENCH_ARGS ?=

$(BENCH_VENV)/.stamp: pyproject.toml bench/requirements.txt
	$(PYTHON) -m venv $(BENCH_VENV)
	$(BENCH_VENV)/bin/python -m pip install -q --upgrade pip
	$(BENCH_VENV)/bin/python -m pip install -q -e . -r bench/requirements.txt
	$(BENCH_VENV)/bin/python -m pip install -q numba || echo "bench: numba did not install; pylinkage's compiled path is reported as not measured"
	@touch $@

bench: $(BENCH_VENV)/.stamp
	$(BENCH_VENV)/bin/python -m bench.run $(BENCH_ARGS)

lint: $(VENV)/.stamp-test
	$(BIN)/ruff check src tests bench docs/examples
	$(BIN)/ruff format --check src tests bench docs/examples

clean:
	rm -rf $(VENV) $(OUT) build .pytest_cache .ruff_cache .hypothesis
