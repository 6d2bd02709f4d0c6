# Two commands for a bare Debian 12 (as root, or with sudo):
#   make demo   the main job
#   make test   build everything and run every test (gtest + rostest, via ctest)
# Both install missing Debian packages first, then configure and build the repository as a catkin
# workspace (one package per folder): CMake's files go to build/, the devel space (executables,
# libraries, setup.bash) to devel/, as catkin_make does. A user who is not root needs no sudo once
# the packages are installed; with some missing and no way to install them, deps prints the
# apt-get line to run as root and stops before anything is built.

# Debian's python must come first: catkin needs its ROS modules (a pyenv python has none).
export PATH := /usr/bin:/bin:$(PATH)
export ROS_HOSTNAME ?= localhost
# ccache keys on paths relative to the checkout, so clones and worktrees share one cache.
export CCACHE_BASEDIR ?= $(CURDIR)
BUILD ?= build
DEVEL ?= devel
JOBS ?= 2
CMAKE_FLAGS = -DPYTHON_EXECUTABLE=/usr/bin/python3 -DPython3_EXECUTABLE=/usr/bin/python3 \
              -DCMAKE_BUILD_TYPE=Release -DCATKIN_ENABLE_TESTING=ON \
              -DCATKIN_DEVEL_PREFIX=$(abspath $(DEVEL))
OUT ?= out/demo

.PHONY: deps configure build tests test demo bench fuzz clean

# Also stops when HOME cannot be written: npm (the Designer's page), ccache and ROS (logs, ~/.ros)
# keep their files there, and would fail later, deep in the build or in every rostest.
deps:
	@scripts/install-deps
	@[ -n "$$HOME" ] && [ -d "$$HOME" ] && [ -w "$$HOME" ] || { echo "make: HOME ($${HOME:-unset}) is not a \
	writable folder: npm, ccache and ROS keep their caches and logs there. Give this user a home, or run \
	e.g. HOME=\$$(mktemp -d) make $(MAKECMDGOALS)" >&2; exit 1; }

# Configures once; again only when the build folder's devel space is not $(DEVEL) (older layout).
# Without ROS_PACKAGE_PATH: catkin caches the environment the devel space adds (the tests run in
# it), and a shell that sourced devel/setup.bash already would leave the workspace out of it.
configure: deps
	@mkdir -p $(BUILD) $(DEVEL) && touch $(BUILD)/CATKIN_IGNORE $(DEVEL)/CATKIN_IGNORE  # not packages
	@grep -qx 'CATKIN_DEVEL_PREFIX:PATH=$(abspath $(DEVEL))' $(BUILD)/CMakeCache.txt 2>/dev/null || \
	  env -u ROS_PACKAGE_PATH cmake -S . -B $(BUILD) $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD) -j$(JOBS)

tests: build
	cmake --build $(BUILD) --target tests -j$(JOBS)

test: tests
	ctest --test-dir $(BUILD) --output-on-failure

demo: build
	scripts/demo $(DEVEL) $(OUT)

bench: build
	cmake --build $(BUILD) --target benchmarks -j$(JOBS)
	scripts/run-benchmarks $(DEVEL)

# libFuzzer targets for every parser of outside input, FUZZ_SECONDS (60) each; clang build in build/fuzz.
fuzz: deps
	scripts/fuzz

clean:
	rm -rf $(BUILD) $(DEVEL) out
