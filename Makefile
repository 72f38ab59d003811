# crankdyn: two commands for a newcomer (see README), plus a few for developers.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
OUT    ?= crankdyn-demo

.PHONY: demo test lint docs typecheck dist bench fuzz clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

LINTED := src tests bench docs/examples docs/conf.py docs/_ext setup.py notebooks

$(VENV)/.stamp-base: pyproject.toml setup.py | $(BIN)/python
	$(BIN)/python -m pip install -q -e .
	@touch $@

# the test extras through uv where it installs (one small wheel from PyPI): it fetches and
# unpacks in parallel and compiles the bytecode on every core (measured: about 20 s against
# pip's 56 s on 2 cores); pip otherwise (no uv, or uv failed), the same packages
$(VENV)/.stamp-test: pyproject.toml setup.py | $(BIN)/python
	@if $(BIN)/python -m pip install -q uv >/dev/null 2>&1 && \
	  $(BIN)/uv pip install -q --python $(BIN)/python --compile-bytecode -e '.[test]'; then :; \
	else \
	  $(BIN)/python -m pip install -q -e '.[test]'; \
	fi
	@touch $@ $(VENV)/.stamp-base

## make demo: install and run the main job on the built-in inline-6 diesel
demo: $(VENV)/.stamp-base
	$(BIN)/crankdyn demo -o $(OUT) --force

## make test: install with test extras (studies, docs tools), lint, type-check the package,
## run the whole suite (the browser's Debian packages installed beside the Python ones where
## missing; with the docstring examples of the modules in pyproject's testpaths; it
## builds the documentation site with warnings as errors and opens it in a headless browser);
## mypy runs beside the suite (scripts/types-and-tests.sh), both must pass
test: | $(BIN)/python
	@bash scripts/install-browser.sh & browser=$$!; \
	  $(MAKE) --no-print-directory $(VENV)/.stamp-test; installed=$$?; \
	  wait $$browser; exit $$installed
	@# the package's bytecode written once, on both cores: every process of the suite (the CLI's
	@# subprocesses, the docs build, the notebooks' kernels, the pools' workers) then loads it
	@# instead of compiling the sources again (none is written where PYTHONDONTWRITEBYTECODE is set)
	@$(BIN)/python -m compileall -q -j 0 src
	@# and the test modules' assertion-rewritten bytecode, which pytest reads but (where
	@# PYTHONDONTWRITEBYTECODE is set) does not write: both workers would rewrite them all
	@$(BIN)/python scripts/rewrite-tests.py tests
	$(BIN)/ruff check $(LINTED)
	$(BIN)/ruff format --check $(LINTED)
	@bash scripts/types-and-tests.sh $(BIN)

## make docs: the documentation site in docs/_build/html (user guide, theory, command and API
## reference, validation cases, worked examples run at build time); warnings are errors
docs: $(VENV)/.stamp-test
	$(BIN)/python -m sphinx -W --keep-going -q -b html -d docs/_build/doctrees docs docs/_build/html
	@echo "docs: open docs/_build/html/index.html (or: crankdyn docs --html)"

## make typecheck: mypy on the whole package (configuration in pyproject.toml), as make test runs it
typecheck: $(VENV)/.stamp-test
	$(BIN)/mypy

## make dist: the sdist and a wheel that also carries the HTML site (crankdyn docs --html)
dist: docs
	rm -rf dist
	$(BIN)/python -m build --sdist -o dist .
	CRANKDYN_DOCS_HTML=1 $(BIN)/python -m build --wheel -o dist .

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
	$(BENCH_VENV)/bin/python -m pip install -q -e '.[studies]' -r bench/requirements.txt
	$(BENCH_VENV)/bin/python -m pip install -q numba || echo "bench: numba did not install; pylinkage's compiled path is reported as not measured"
	@touch $@

bench: $(BENCH_VENV)/.stamp
	$(BENCH_VENV)/bin/python -m bench.run $(BENCH_ARGS)

lint: $(VENV)/.stamp-test
	$(BIN)/ruff check $(LINTED)
	$(BIN)/ruff format --check $(LINTED)

clean:
	rm -rf $(VENV) $(OUT) build dist docs/_build docs/reference/api .pytest_cache .ruff_cache .hypothesis .mypy_cache
