# linkgen: `make demo` builds a sample, `make test` passes the tests; both install what they need.
# Test tiers: `make test` before every commit (deterministic, a few minutes), `make test-long` the tests
# marked long and the property tests at full counts (CI runs both), `make explore` random property tests.
PYTHON ?= python3
VENV ?= .venv
PY := $(VENV)/bin/python
LINKGEN := $(VENV)/bin/linkgen
SAMPLES := $(wildcard samples/*/*.yaml)
STAMP := $(VENV)/.installed
JOBS ?= auto
PYTEST := $(PY) -m pytest -q -n $(JOBS) --dist loadgroup

.PHONY: install tools demo test test-long explore lint bench regen check clean

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[test]'
	touch $(STAMP)

# The package's bytecode, which an editable install leaves to the first import and which is never
# written where PYTHONDONTWRITEBYTECODE is set: compiling every module costs each command 0.1 s.
install: $(STAMP)
	@$(PY) -m compileall -q linkgen > /dev/null

# The tools the tests run the generated programs with, from apt where missing: GNU Octave, clang
# and clang's sanitizer runtime (gcc and g++ come with the machine); chromium and its driver for
# the browser test of NAME.html (tests/test_page.py).
tools:
	@missing=""; \
	command -v octave-cli >/dev/null 2>&1 || missing="$$missing octave"; \
	command -v clang >/dev/null 2>&1 || missing="$$missing clang"; \
	command -v chromium >/dev/null 2>&1 || missing="$$missing chromium"; \
	command -v chromedriver >/dev/null 2>&1 || missing="$$missing chromium-driver"; \
	if [ -n "$$missing" ]; then \
	  SUDO=$$( [ "$$(id -u)" = 0 ] || echo sudo ); \
	  $$SUDO apt-get update -qq && $$SUDO apt-get install -y -qq --no-install-recommends $$missing >/dev/null; \
	fi; \
	rt=libclang-rt-$$(clang -dumpversion | cut -d. -f1)-dev; \
	dpkg -s $$rt >/dev/null 2>&1 || { \
	  SUDO=$$( [ "$$(id -u)" = 0 ] || echo sudo ); \
	  $$SUDO apt-get install -y -qq --no-install-recommends $$rt >/dev/null; }

demo: install
	$(LINKGEN) build samples/fourbar/fourbar.yaml -o build/fourbar
	$(LINKGEN) procedure samples/fourbar/fourbar.yaml
	$(LINKGEN) run samples/fourbar/fourbar.yaml --samples 5

test: install tools
	$(PYTEST) -m "not long" --hypothesis-profile=test

test-long: install tools
	$(PYTEST) -m "long or hypothesis" --hypothesis-profile=long

# Random examples: a failure prints its blob and this seed (`make explore SEED=N` repeats the run); keep
# the counterexample as an @example or a regression test.
explore: install tools
	@seed=$(SEED); seed=$${seed:-$$(od -An -N4 -tu4 /dev/urandom | tr -d ' ')}; \
	echo "hypothesis seed $$seed: make explore SEED=$$seed repeats this run"; \
	$(PYTEST) -m hypothesis --hypothesis-profile=explore --hypothesis-seed=$$seed

# ruff, and mypy as [tool.mypy] in pyproject.toml configures it (strict, on the package)
lint: install
	$(VENV)/bin/ruff check linkgen tests bench
	$(VENV)/bin/mypy

# docs/performance.md and its plots (bench/run.py DOC); the peers come with the bench extra, and a peer
# that does not install is named in the doc while the rest runs (hence the '-'); the Cortex-M4 toolchain
# and QEMU (bench/mcu.py) from apt where missing.
bench: install
	-$(PY) -m pip install --quiet -e '.[bench]'
	-@command -v arm-none-eabi-gcc >/dev/null 2>&1 && command -v qemu-system-arm >/dev/null 2>&1 || { \
	  SUDO=$$( [ "$$(id -u)" = 0 ] || echo sudo ); \
	  $$SUDO apt-get install -y -qq --no-install-recommends gcc-arm-none-eabi libnewlib-arm-none-eabi \
	    qemu-system-arm >/dev/null; }
	$(PY) bench/run.py

# Rewrite the golden files of every sample (review the git diff like source code).
regen: install
	@for f in $(SAMPLES); do $(LINKGEN) build $$f -o $$(dirname $$f)/expected || exit 1; done

check: install
	@for f in $(SAMPLES); do $(LINKGEN) build --check $$f -o $$(dirname $$f)/expected || exit 1; done

clean:
	rm -rf build .pytest_cache bench/out
