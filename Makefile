# The two commands a new user types are `make demo` and `make test`; each installs
# what is missing, builds, and runs. PRESET picks the CMake preset (see CMakePresets.json).
PRESET ?= ci
BUILD  := build/$(PRESET)
PYTHON := /usr/bin/python3

.PHONY: all deps configure build test test-cpp test-python test-asan test-tsan test-browser web-deps demo bench asan fuzz clean

all: build

deps:
	@scripts/install-deps.sh build

configure: deps
	@cmake --preset $(PRESET) >/dev/null

build: configure
	cmake --build --preset $(PRESET)

# The C++ suite is built and run once, under ASan + UBSan (test-asan); the optimised `ci` build
# is what pytest (Python and the CLI), the browser tests and ctest's install test run.
# pytest runs as two processes at once (scripts/run-pytest.sh), each about one core's worth.
test: build test-asan test-tsan test-browser
	ctest --preset $(PRESET)
	RIGID_PYTHON_DIR=$(CURDIR)/$(BUILD)/python RIGID_EXE=$(CURDIR)/$(BUILD)/bin/rigid \
	  scripts/run-pytest.sh $(PYTHON) python/tests tests/cli

demo: build
	$(BUILD)/bin/rigid demo
	@echo "rigid is $(CURDIR)/$(BUILD)/bin/rigid; to run it as plain 'rigid', put it on PATH: export PATH=\"$(CURDIR)/$(BUILD)/bin:\$$PATH\""

bench:
	@scripts/install-deps.sh bench
	cmake --preset bench >/dev/null
	cmake --build --preset bench
	scripts/run-benchmarks.sh build/bench

# The whole C++ suite (every module's tests and the fuzz regression replays) under
# AddressSanitizer + UBSan, float-cast-overflow included (docs/reliability.md has the cost);
# the install test is left out (its consumer links without the sanitizer runtime).
test-asan: deps
	cmake --preset asan >/dev/null
	cmake --build --preset asan
	ctest --preset asan

# One model run from several threads at once, under ThreadSanitizer: a Lagrangian system
# (per-run workspaces), scenes (immutable models) and sweeps (the runs of a coordinate scene
# share one derivation; the journal's writer thread and the outputs formatted on several
# threads), robot trees (TreeDynamics, a robot scene); builds only the test binary
# that holds those tests (rigid_threads_tests, tests/CMakeLists.txt).
TSAN_SUITES := Workspace.*:ModelThreads.*:SweepRun.*:SweepJournal.*:SweepOutputs.*:SymbolicThreads.*:RobotSceneThreads.*:TreeDynamicsThreads.*
test-tsan: deps
	cmake --preset tsan >/dev/null
	cmake --build --preset tsan --target rigid_threads_tests
	TSAN_OPTIONS=halt_on_error=1 build/tsan/bin/rigid_threads_tests --gtest_brief=1 --gtest_filter='$(TSAN_SUITES)'

asan: test-asan

# The report page in a real browser: tests/browser/*.test.mjs drive Debian's chromium through
# playwright-core (no browser download) on pages written by this build's rigid; screenshots go
# to $(BUILD)/browser-screenshots/. `npm ci` runs only when web/package-lock.json (or
# package.json) is newer than npm's own record of the last install, the same stamp as the
# CMake build's (src/report/CMakeLists.txt), so the two never install twice.
WEB_STAMP := web/node_modules/.package-lock.json
$(WEB_STAMP): web/package-lock.json web/package.json
	cd web && PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund
	@touch $@

web-deps: $(WEB_STAMP)

test-browser: build web-deps
	RIGID_EXE=$(CURDIR)/$(BUILD)/bin/rigid RIGID_SCREENSHOT_DIR=$(CURDIR)/$(BUILD)/browser-screenshots \
	  node --test tests/browser/

# Every fuzz target (fuzz/targets.def: mesh readers, scenes, robot models and inertials, the
# inertial fixer, expressions, run schemas, sweep journals, CSV tables, the CLI's arguments) for
# SECONDS seconds each, JOBS at a time, built with clang, libFuzzer, ASan and UBSan in
# build/fuzz. Findings go to build/fuzz/fuzz-findings/<target>/; the exit status is 1 when
# there are any.
SECONDS ?= 60
JOBS ?= 1
fuzz:
	@scripts/install-deps.sh fuzz
	cmake --preset fuzz >/dev/null
	cmake --build --preset fuzz
	RIGID_FUZZ_JOBS=$(JOBS) scripts/run-fuzz.sh build/fuzz $(SECONDS)

clean:
	rm -rf build
