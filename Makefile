# The README's commands:
#   make demo   installs what is missing and runs the main job (the quick Maeno scene once and over 10 packings),
#               writing results and figures to out/
#   make test   installs what is missing and runs every test (C++, C++ under sanitizers, Python) and builds the docs
PY ?= python3
OUT ?= out
# the Python tests on one process a core (pytest-xdist); --dist loadgroup keeps each xdist_group (a module
# whose fixture is costly, the hard-case catalogue that writes its table) on one process
PYTEST = $(PY) -m pytest -q -p no:cacheprovider -n $(shell nproc) --dist loadgroup

.PHONY: demo full ensemble-demo maeno-fragility verdict verdict-small test test-fast install test-cpp test-py docs bench

install:
	bash scripts/install_deps.sh test

# the main job: the quick Maeno scene once (stage table, figures, animation), then over 10 packings on a
# local Dask cluster, ending with the fragility figure next to the experiment and the paper's model
demo: install
	$(PY) -m vofdem run scenes/maeno2008.toml --quick --out $(OUT)/maeno2008_quick
	$(PY) -m vofdem run scenes/maeno2008.toml --quick --seeds 0-9 --no-figures --no-animation --out $(OUT)/maeno2008_quick_fragility
	@echo "one run: $(OUT)/maeno2008_quick/ (figures/); over 10 packings: $(OUT)/maeno2008_quick_fragility/fragility.png"

# the whole scenario on the paper's grid and hydrograph (long: see docs/accuracy_cost.md for its cost)
full: install
	$(PY) -m vofdem run scenes/maeno2008.toml --out $(OUT)/maeno2008

# an ensemble of the quick scene over 20 packings on a local Dask cluster: its fragility curves in a few minutes
ensemble-demo: install
	$(PY) -m vofdem run scenes/maeno2008.toml --quick --seeds 0-19 --no-figures --no-animation --out $(OUT)/ensemble_demo
	@echo "fragility figure: $(OUT)/ensemble_demo/fragility.png (tables in $(OUT)/ensemble_demo/ensemble.md)"

# the whole scene over 30 packings (about 46 CPU-seconds per member: 12 minutes on 2 free cores; resumes where it stopped)
maeno-fragility: install
	$(PY) studies/maeno2008_fragility.py --seeds 0-29

# the prediction study: the verdict over 30 packings, the width sweep and accuracy against cost (hours; resumes)
verdict: install
	$(PY) studies/maeno2008_verdict.py

# its small version: the quick scenes over 6 packings, one or two settings per knob (minutes on 2 cores)
verdict-small: install
	$(PY) studies/maeno2008_verdict.py --small

test: install test-cpp test-py docs

# the documentation site into build/docs/html/: the guide of docs/, the results files, the notebooks (not
# executed) and the API reference from the installed package's docstrings; every warning is an error, and
# every page is read again (-E) so that a warning of an unchanged page is not hidden by the cache
docs: install
	$(PY) -m sphinx -E -W --keep-going -q -b html -c docs . build/docs/html
	@echo "documentation: build/docs/html/index.html"

# the developer's loop: the optimised C++ tests and the Python tests not marked slow (minutes less)
test-fast: install
	bash scripts/test_cpp.sh --fast
	$(PYTEST) -m "not slow" tests

test-cpp:
	bash scripts/test_cpp.sh

test-py:
	$(PYTEST) --durations=25 tests

bench: install
	$(PY) benchmarks/porosity_lookup_cost.py
