# The README's two commands are ./quickstart render and ./quickstart test, which install what is
# missing (make itself included) and then run these targets:
#   make render   build (Release), render the lecture scene to lecture.png
#   make test     build, run the whole test suite
# Other targets: make build, make deps, make clean.

BUILD_DIR ?= build
JOBS      ?= $(shell nproc)
.PHONY: render test build deps clean

render: build
	$(BUILD_DIR)/bin/strahl -o lecture.png

test: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release -DSTRAHL_WERROR=ON
	cmake --build $(BUILD_DIR) -j $(JOBS)
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

build: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release  # keeps STRAHL_WERROR as the cache has it
	cmake --build $(BUILD_DIR) -j $(JOBS)

# Installs only what is missing (the package list lives in ./quickstart).
deps:
	./quickstart deps

clean:
	rm -rf $(BUILD_DIR)
