# Thin front door over CMake: `make demo` and `make test` work on a fresh Debian 12 machine.
# Every target first installs missing Debian packages (scripts/install-deps).
PRESET ?= release
JOBS ?= $(shell nproc)

.PHONY: deps configure build test test-asan demo bench clean

deps:
	@scripts/install-deps

configure: deps
	@cmake --preset $(PRESET) >/dev/null

build: configure
	@cmake --build --preset $(PRESET) -j $(JOBS)

test: build
	@build/bin/brdfcl-tests --gtest_brief=1

# The host code and tests under AddressSanitizer + UndefinedBehaviorSanitizer (build-asan/).
test-asan: deps
	@cmake --preset asan >/dev/null
	@cmake --build --preset asan -j $(JOBS) --target brdfcl-tests brdfcl
	@ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/tests/sanitizers/lsan.supp:print_suppressions=0 build-asan/bin/brdfcl-tests --gtest_brief=1

demo: build
	@build/bin/brdfcl demo

bench: build
	@mkdir -p out
	@build/bin/brdfcl-bench --benchmark_out=out/bench.json --benchmark_out_format=json

clean:
	@rm -rf build build-asan
