# The README's two commands:
#   make render   install missing Debian packages, build (Release), render the lecture scene to lecture.png
#   make test     install missing Debian packages, build, run the whole test suite
# Other targets: make build, make deps, make clean.

BUILD_DIR ?= build
JOBS      ?= $(shell nproc)
# Debian 12 packages strahl builds with (found by CMake's find_package / pkg-config).
DEB_PACKAGES := g++ cmake make pkg-config libyaml-cpp-dev libcli11-dev libstb-dev libopenexr-dev \
                libtinyobjloader-dev libtbb-dev libfmt-dev libgtest-dev
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

.PHONY: render test build deps clean

render: build
	$(BUILD_DIR)/bin/strahl -o lecture.png

test: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release -DSTRAHL_WERROR=ON
	cmake --build $(BUILD_DIR) -j $(JOBS)
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

build: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD_DIR) -j $(JOBS)

# Installs only what is missing, so it is quick and needs no root when nothing is.
deps:
	@missing=$$(for p in $(DEB_PACKAGES); do dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q '^install ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "installing missing Debian packages:" $$missing; \
	  $(SUDO) apt-get update && $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends $$missing; \
	fi

clean:
	rm -rf $(BUILD_DIR)
