# The two commands of the README, and a few conveniences.
#   make demo  - install what is missing, build the srp executable only, run the main job on the bundled default
#   make test  - install what is missing (with the test packages), configure with the tests, notebooks and
#                benchmarks on, build everything, run the test suite
#   make test-slow - the acceptance suites (.ci/run runs them after make test)
#   make package   - the Debian packages (srp, srp-data, libsrp-dev) in $(BUILD_DIR)/
BUILD_DIR ?= build
BUILD_TYPE ?= RelWithDebInfo
JOBS ?= $(shell nproc)
CTEST_ARGS ?=
# ccache, when the machine has it, makes rebuilds of unchanged files free.
CCACHE := $(shell command -v ccache 2>/dev/null)
LAUNCHER := $(if $(CCACHE),-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache,)
# RelWithDebInfo with line tables only (-g1): backtraces, sanitizer reports and profiles keep file:line,
# and the compiler does about half the work of full debug info (-g) on our heaviest files. The code is
# the same (-g never changes it). BUILD_TYPE=Debug, or DEBUG_INFO=-g, for full debug info.
DEBUG_INFO ?= -g1
FLAGS := -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 $(DEBUG_INFO) -DNDEBUG" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 $(DEBUG_INFO) -DNDEBUG"

.PHONY: all deps deps-test configure configure-demo build build-demo test test-slow test-sanitize demo bench package clean

SANITIZE_DIR ?= build-sanitize
# The tests, notebooks and benchmarks: on for make test, off for make demo.
WITH_TESTS := -DSRP_BUILD_TESTS=ON -DSRP_BUILD_NOTEBOOKS=ON -DSRP_BUILD_BENCHMARKS=ON
WITHOUT_TESTS := -DSRP_BUILD_TESTS=OFF -DSRP_BUILD_NOTEBOOKS=OFF -DSRP_BUILD_BENCHMARKS=OFF

all: build

deps:
	@bash scripts/install-deps.sh

deps-test:
	@bash scripts/install-deps.sh --test

configure: deps-test
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) $(FLAGS) $(LAUNCHER) $(WITH_TESTS) > $(BUILD_DIR).configure.log 2>&1 \
	  || (cat $(BUILD_DIR).configure.log; exit 1)
	@echo "configured $(BUILD_DIR) ($(BUILD_TYPE), with tests, notebooks and benchmarks)"

configure-demo: deps
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) $(FLAGS) $(LAUNCHER) $(WITHOUT_TESTS) > $(BUILD_DIR).configure.log 2>&1 \
	  || (cat $(BUILD_DIR).configure.log; exit 1)
	@echo "configured $(BUILD_DIR) ($(BUILD_TYPE))"

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

build-demo: configure-demo
	@cmake --build $(BUILD_DIR) -j $(JOBS) --target srp

test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS) -LE slow $(CTEST_ARGS)

# The acceptance suites (label `slow`: Appendix A, random scenes, perception, end to end).
test-slow: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS) -L slow $(CTEST_ARGS)

# The rawlog reader and its fuzz test, and the safety sweep's hostile meshes and
# task-database cells, under AddressSanitizer + UBSan, in a build dir of its own
# (huge allocations return an error instead of aborting, as the fuzz tests'
# memory limit expects).
test-sanitize: deps-test
	@cmake -S . -B $(SANITIZE_DIR) -DCMAKE_BUILD_TYPE=RelWithDebInfo $(FLAGS) -DSRP_BUILD_BENCHMARKS=OFF $(LAUNCHER) \
	  -DCMAKE_CXX_FLAGS="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined" \
	  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" > $(SANITIZE_DIR).configure.log 2>&1 \
	  || (cat $(SANITIZE_DIR).configure.log; exit 1)
	@cmake --build $(SANITIZE_DIR) --target srp_rawlog_tests srp_safety_tests -j $(JOBS)
	@cd $(SANITIZE_DIR) && ASAN_OPTIONS=allocator_may_return_null=1:max_allocation_size_mb=1024:detect_leaks=1 \
	  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ./libs/rawlog/srp_rawlog_tests
	@cd $(SANITIZE_DIR) && ASAN_OPTIONS=allocator_may_return_null=1:max_allocation_size_mb=1024:detect_leaks=1 \
	  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ./tests/safety/srp_safety_tests \
	  --gtest_filter='HostileMeshes.*:HostileTaskDatabase.*:DecompressionBombs.*'

demo: build-demo
	@bash scripts/demo.sh $(BUILD_DIR)

package: build-demo
	@cmake --build $(BUILD_DIR) --target package

bench: build
	@bash scripts/bench.sh $(BUILD_DIR)

clean:
	rm -rf $(BUILD_DIR) $(BUILD_DIR).configure.log $(SANITIZE_DIR) $(SANITIZE_DIR).configure.log
