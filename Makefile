# The two commands of the README: `make demo` and `make test`. Everything else is a helper.
JOBS ?= $(shell nproc)
# ccache hashes compile commands with paths relative to the checkout, so clones and worktrees in
# other folders (CI's fresh clone among them) share one cache.
export CCACHE_BASEDIR ?= $(CURDIR)
FUZZ_RUNS ?= 100000
BUILD_DIR := build
FAIRSHAPE := $(BUILD_DIR)/bin/fairshape

.PHONY: deps configure build install test test-long test-all package-test demo sanitize-configure sanitize asan-test fuzz-run bench clean

deps:
	bash scripts/install-deps.sh

configure: deps
	cmake --preset release $(CMAKE_ARGS)

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

# The CLI, the libraries, their headers (include/fairshape/) and the CMake package
# (lib/cmake/fairshape: find_package(fairshape)); PREFIX=/path to install elsewhere.
PREFIX ?= /usr/local
install: build
	cmake --install $(BUILD_DIR) --prefix $(PREFIX)

# `make test`: the tests to run often (unit, conformance, Python, the quick command-line ones).
# `make test-long`: the command-line tests of a minute or more (every config's smoke run, the
# harness across processes, Slurm, MPI); CI runs both. tests/README.md lists the labels.
test: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS) -LE 'slow|package|long' --timeout 600

test-long: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS) -L long --timeout 600

test-all: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

demo: build
	bash scripts/demo.sh

# The unit tests under AddressSanitizer + UBSan and the libFuzzer targets share one clang tree
# (preset sanitize): the fuzzers need only the readers' libraries built there, the unit tests all
# of them. Catch cases tagged [slow] (minutes under ASan, seconds in release; each has a smaller
# sanitized sibling) are not discovered there: the preset sets FAIRSHAPE_CATCH_TEST_SPEC.
FUZZ_TARGETS := fuzz_read_obj fuzz_read_off fuzz_read_ply fuzz_read_vtp fuzz_config fuzz_read_sheet

sanitize-configure: deps
	cmake --preset sanitize

sanitize: sanitize-configure
	cmake --build build-sanitize -j $(JOBS) --target unit_tests $(FUZZ_TARGETS)

asan-test: sanitize-configure
	cmake --build build-sanitize -j $(JOBS) --target unit_tests
	cd build-sanitize && ASAN_OPTIONS=detect_leaks=0 ctest --output-on-failure -j $(JOBS) -L unit

fuzz-run: sanitize-configure
	cmake --build build-sanitize -j $(JOBS) --target $(FUZZ_TARGETS)
	bash scripts/fuzz.sh $(FUZZ_RUNS)

# Builds of other CMake trees (the installed package's consumer, fairshape without its optional
# dependencies): minutes of compiling, so a CI step of their own rather than part of `make test`.
package-test: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS) -L package --timeout 900

bench: build
	bash scripts/bench.sh

clean:
	rm -rf $(BUILD_DIR) build-debug build-sanitize
