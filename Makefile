# The two commands of the README: `make demo` and `make test`.
# Both install what is missing (Debian packages), configure and build.
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release -DPEDESIS_WERROR=ON

.PHONY: all deps build demo test validation bench format clean python sanitize fuzz ci

all: build

deps:
	@./scripts/install-deps.sh

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) $(CMAKE_FLAGS)

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)
	@echo "python: import pedesis with PYTHONPATH=$(abspath $(BUILD))/python /usr/bin/python3 (or run: make python)"

# Puts a path file (pedesis.pth) into Debian's python3's user site-packages, so that
# `python3 -c "import pedesis"` finds this build from any directory.
python: build
	@/usr/bin/python3 scripts/install_python_path.py $(abspath $(BUILD))/python

demo: build
	./$(BUILD)/pedesis run examples/course_1_relaxation.toml --out runs/demo
	./$(BUILD)/pedesis analyze speed runs/demo
	./$(BUILD)/pedesis render runs/demo --out runs/demo/movie.mp4 --color speed
	@echo "demo: speed plot runs/demo/speed_distribution.png, movie runs/demo/movie.mp4"
	@echo "demo: see it in the browser: ./$(BUILD)/pedesis view runs/demo   (then open the address it prints)"

# ctest runs tests side by side, each with OpenMP threads: passive waiting keeps idle
# threads from spinning on cores another test needs (10x slower on 2 busy cores).
test: build
	cd $(BUILD) && OMP_WAIT_POLICY=passive ctest --output-on-failure -j $(JOBS) -LE "validation|gpu"

validation: build
	cd $(BUILD) && OMP_WAIT_POLICY=passive ctest --output-on-failure -j $(JOBS) -L validation

# The unit and CLI tests once more, built with AddressSanitizer and UBSan (build-asan/;
# only they and the binary are built: the physics tests' long runs are the release build's).
# Warnings are the release build's job: at -O1 with the sanitizers GCC 12 warns about
# its own <regex> (maybe-uninitialized).
sanitize: deps
	cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS=-O1 -DPEDESIS_SANITIZE=ON -DPEDESIS_WERROR=OFF
	cmake --build build-asan -j $(JOBS) --target unit_and_cli_tests
	cd build-asan && OMP_WAIT_POLICY=passive ASAN_OPTIONS=detect_leaks=1 \
	  LSAN_OPTIONS=suppressions=$(abspath scripts/lsan-suppressions.txt) \
	  ctest --output-on-failure -j $(JOBS) -L "unit|cli"

# Every reader under libFuzzer for FUZZ_SECONDS each (clang, build-fuzz/).
FUZZ_SECONDS ?= 60
fuzz: deps
	cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPEDESIS_FUZZ=ON -DPEDESIS_TESTS=OFF
	cmake --build build-fuzz -j $(JOBS) --target fuzz_targets
	RUNS=$(FUZZ_RUNS) ./scripts/run-fuzzers.sh $(abspath build-fuzz) $(FUZZ_SECONDS)

# What CI runs: the tests, then the sanitizer build's tests and a fuzzing run of a fixed
# 20000 inputs per target from seed 1 (the same inputs every time: CI cannot fail on a
# new random find; longer `make fuzz` runs are where new finds come from).
ci: test sanitize
	$(MAKE) fuzz FUZZ_RUNS=20000

FUZZ_RUNS ?=

format:
	find src apps tests bench python/src -name '*.hpp' -o -name '*.cpp' | xargs clang-format -i

clean:
	rm -rf $(BUILD)
