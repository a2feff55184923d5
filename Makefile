# The two commands of the README:
#   make demo   installs what is missing and runs the main job, writing results and figures to out/
#   make test   installs what is missing and runs every test (C++, C++ under sanitizers, Python)
PY ?= python3
OUT ?= out

.PHONY: demo full test install test-cpp test-py bench

install:
	bash scripts/install_deps.sh test

demo: install
	$(PY) -m vofdem run scenes/maeno2008.toml --quick --out $(OUT)/maeno2008_quick

# the whole scenario on the paper's grid and hydrograph (long: see the README for its cost)
full: install
	$(PY) -m vofdem run scenes/maeno2008.toml --out $(OUT)/maeno2008

test: install test-cpp test-py

test-cpp:
	bash scripts/test_cpp.sh

test-py:
	$(PY) -m pytest -q -p no:cacheprovider tests

bench: install
	$(PY) benchmarks/porosity_lookup_cost.py
