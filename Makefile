# The README's two commands are ./quickstart render and ./quickstart test, which install what is
# missing (make itself included) and then run these targets:
#   make render   build (Release), render the lecture scene to lecture.png
#   make test     the whole test suite three ways (CMakePresets.json): the Release build, then the
#                 library, CLI and tests again under AddressSanitizer + UBSan (build-asan), then each
#                 libFuzzer target for $(FUZZ_SECONDS) s over its seed corpus (build-fuzz, clang)
# Other targets: make build, make deps, make clean, make test-release (only the first of the three),
# make fuzz FUZZ_SECONDS=600 (longer fuzzing runs).

BUILD_DIR ?= build
JOBS      ?= $(shell nproc)
FUZZ_SECONDS ?= 20
.PHONY: render test test-release test-asan fuzz build deps clean

render: build
	$(BUILD_DIR)/bin/strahl -o lecture.png

test: test-release test-asan fuzz

test-release: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release -DSTRAHL_WERROR=ON
	cmake --build $(BUILD_DIR) -j $(JOBS)
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

test-asan: deps
	cmake --preset asan-ubsan
	cmake --build --preset asan-ubsan -j $(JOBS)
	ctest --preset asan-ubsan -j $(JOBS)

fuzz: deps
	cmake --preset fuzz
	cmake --build --preset fuzz -j $(JOBS)
	tools/run-fuzzers.sh build-fuzz $(FUZZ_SECONDS)

build: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release  # keeps STRAHL_WERROR as the cache has it
	cmake --build $(BUILD_DIR) -j $(JOBS)

# Installs only what is missing (the package list lives in ./quickstart).
deps:
	./quickstart deps

clean:
	rm -rf $(BUILD_DIR) build-asan build-fuzz
