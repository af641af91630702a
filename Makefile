# Thin front door over CMake: `make demo` and `make test` work on a fresh Debian 12 machine.
# Every target first installs missing Debian packages (scripts/install-deps).
PRESET ?= release
JOBS ?= $(shell nproc)
FUZZ_SECONDS ?= 60

.PHONY: deps configure build test test-python test-devices test-asan fuzz demo bench bench-peers architecture clean

deps:
	@scripts/install-deps

configure: deps
	@cmake --preset $(PRESET) >/dev/null

build: configure
	@cmake --build --preset $(PRESET) -j $(JOBS)

# The C++ tests (one shard a core, scripts/test-shards), the layer check on its planted violations
# (scripts/check-layers --self-test), the engine check's harness on its own snippets
# (scripts/engine-check --self-test; the check itself needs engine checkouts, docs/profiles.md), then
# the Python package's (tests/python) in build/venv-python: pinned build and test tools
# (python/requirements.txt), the package built by `pip install .` into a persistent build dir
# (build/python-<tag>/: only what changed recompiles).
PYTHON ?= /usr/bin/python3
VENV := build/venv-python

test: build
	@scripts/test-shards build/bin/brdfcl-tests --gtest_brief=1
	@scripts/engine-check --self-test >/dev/null || scripts/engine-check --self-test
	@scripts/check-layers --self-test >/dev/null || scripts/check-layers --self-test
	@$(MAKE) --no-print-directory test-python

test-python: build
	@test -x $(VENV)/bin/python || $(PYTHON) -m venv $(VENV)
	@$(VENV)/bin/python -m pip install -q --disable-pip-version-check -r python/requirements.txt
	@CMAKE_BUILD_PARALLEL_LEVEL=$(JOBS) $(VENV)/bin/python -m pip install -q --disable-pip-version-check --no-build-isolation .
	@BRDFCL_CLI=$(CURDIR)/build/bin/brdfcl $(VENV)/bin/python -m pytest -q tests/python

# The accuracy, edge and shading tests once per OpenCL device (scripts/test-devices), Intel's
# CPU runtime included when scripts/install-intel-opencl has installed it into build/.
test-devices: configure
	@cmake --build --preset $(PRESET) -j $(JOBS) --target brdfcl brdfcl-tests
	@scripts/test-devices

# The host code and tests under AddressSanitizer + UndefinedBehaviorSanitizer (build-asan/).
test-asan: deps
	@cmake --preset asan >/dev/null
	@cmake --build --preset asan -j $(JOBS) --target brdfcl-tests brdfcl
	@ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:allocator_may_return_null=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/tests/sanitizers/lsan.supp:print_suppressions=0 scripts/test-shards build-asan/bin/brdfcl-tests --gtest_brief=1

# libFuzzer harnesses of the file readers (clang-14, ASan + UBSan, build-fuzz/), FUZZ_SECONDS
# each; fails on any crash, leak or timeout (artifacts in build-fuzz/artifacts/).
fuzz: deps
	@cmake --preset fuzz >/dev/null
	@cmake --build --preset fuzz -j $(JOBS)
	@FUZZ_SECONDS=$(FUZZ_SECONDS) tests/fuzz/run

# The demo needs the CLI alone: the tests and benchmarks are not built for it.
demo: configure
	@cmake --build --preset $(PRESET) -j $(JOBS) --target brdfcl
	@build/bin/brdfcl demo

bench: build
	@mkdir -p out
	@build/bin/brdfcl-bench --benchmark_out=out/bench.json --benchmark_out_format=json

# Mitsuba 3, then the spec material written in Dr.Jit, as peers (docs/performance.md): a venv in
# build/venv-peers with mitsuba (and so drjit) from PyPI and Debian's libllvm19; needs the network
# the first time. The Dr.Jit peer runs on its CUDA backend too where an NVIDIA GPU is (exit 3: none).
# Not part of `make test`.
bench-peers: configure
	@cmake --build --preset $(PRESET) -j $(JOBS) --target brdfcl
	@mkdir -p out
	@bench/peers/run-mitsuba-peer --check --json out/bench-peers.json
	@bench/peers/run-mitsuba-peer --op sample --json out/bench-peers-sample.json
	@bench/peers/run-drjit-peer --check --mitsuba-json out/bench-peers.json --json out/bench-peers-drjit.json
	@bench/peers/run-drjit-peer --backend cuda --check --json out/bench-peers-drjit-cuda.json || test $$? -eq 3

# docs/architecture.svg: the host library's modules and their links from CMake's own graph
# (cmake --graphviz, filtered by CMakeGraphVizOptions.cmake), without the legend and without the
# arrows that follow from others (Graphviz's tred), laid out by dot with the lowest layer at the bottom.
architecture: configure
	@mkdir -p build/graphviz
	@cmake --preset $(PRESET) --graphviz=build/graphviz/brdfcl.dot >/dev/null
	@sed '/subgraph clusterLegend/,/^}/d' build/graphviz/brdfcl.dot | tred | dot -Tsvg -o docs/architecture.svg
	@echo "wrote docs/architecture.svg"

clean:
	@rm -rf build build-asan build-fuzz
