# Two commands for a bare Debian 12 (as root, or with sudo):
#   make demo   the main job
#   make test   build everything and run every test (gtest + rostest, via ctest)
# Both install missing Debian packages first, then configure and build into build/.

# Debian's python must come first: catkin needs its ROS modules (a pyenv python has none).
export PATH := /usr/bin:/bin:$(PATH)
export ROS_HOSTNAME ?= localhost
BUILD ?= build
JOBS ?= 2
CMAKE_FLAGS = -DPYTHON_EXECUTABLE=/usr/bin/python3 -DPython3_EXECUTABLE=/usr/bin/python3 \
              -DCMAKE_BUILD_TYPE=Release -DCATKIN_ENABLE_TESTING=ON
OUT ?= out/demo

.PHONY: deps configure build tests test demo bench clean

deps:
	@scripts/install-deps

configure: deps
	@test -f $(BUILD)/CMakeCache.txt || cmake -S . -B $(BUILD) $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD) -j$(JOBS)

tests: build
	cmake --build $(BUILD) --target tests -j$(JOBS)

test: tests
	ctest --test-dir $(BUILD) --output-on-failure

demo: build
	scripts/demo $(BUILD) $(OUT)

bench: build
	cmake --build $(BUILD) --target benchmarks -j$(JOBS)
	scripts/run-benchmarks $(BUILD)

clean:
	rm -rf $(BUILD) out
