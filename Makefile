# linkgen: `make demo` builds a sample, `make test` passes the tests; both install what they need.
PYTHON ?= python3
VENV ?= .venv
PY := $(VENV)/bin/python
LINKGEN := $(VENV)/bin/linkgen
SAMPLES := $(wildcard samples/*/*.yaml)
STAMP := $(VENV)/.installed

.PHONY: install octave demo test lint bench regen check clean

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[test]'
	touch $(STAMP)

install: $(STAMP)

# GNU Octave runs the generated MATLAB/Octave programs in the tests.
octave:
	@command -v octave-cli >/dev/null 2>&1 || { \
	  SUDO=$$( [ "$$(id -u)" = 0 ] || echo sudo ); \
	  $$SUDO apt-get update -qq && $$SUDO apt-get install -y -qq --no-install-recommends octave >/dev/null; }

demo: install
	$(LINKGEN) build samples/fourbar/fourbar.yaml -o build/fourbar
	$(LINKGEN) procedure samples/fourbar/fourbar.yaml
	$(LINKGEN) run samples/fourbar/fourbar.yaml --samples 5

test: install octave
	$(PY) -m pytest -q

lint: install
	$(VENV)/bin/ruff check linkgen tests bench

bench: install
	$(PY) bench/run.py

# Rewrite the golden files of every sample (review the git diff like source code).
regen: install
	@for f in $(SAMPLES); do $(LINKGEN) build $$f -o $$(dirname $$f)/expected || exit 1; done

check: install
	@for f in $(SAMPLES); do $(LINKGEN) build --check $$f -o $$(dirname $$f)/expected || exit 1; done

clean:
	rm -rf build .pytest_cache bench/out
