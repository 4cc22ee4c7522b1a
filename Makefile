# Thin wrapper over CMake. `make demo` and `make test` first install missing dependencies.
BUILD ?= build
PREFIX ?= /usr/local
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
WERROR ?= OFF
CMAKE_FLAGS ?=
CONFIGURE = cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=$(PREFIX) \
            -DGM_WERROR=$(WERROR) $(CMAKE_FLAGS)

.PHONY: all deps build test test-sanitize demo bench examples install clean

all: build

deps:
	@scripts/install-deps

build: deps
	@$(CONFIGURE) > /dev/null
	cmake --build $(BUILD) -j $(JOBS)

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

# The whole suite again under AddressSanitizer and UndefinedBehaviorSanitizer.
test-sanitize:
	$(MAKE) test BUILD=$(BUILD)-sanitize CMAKE_FLAGS="$(CMAKE_FLAGS) -DGM_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo"

demo: build
	./$(BUILD)/geomint demo --out demo-output

bench: build
	@mkdir -p bench/results
	@for b in $(BUILD)/bench_*; do echo "== $$b"; ./$$b bench/results || exit 1; done

examples: build
	@for e in $(BUILD)/example_*; do echo "== $$e"; ./$$e || exit 1; done

install: build
	cmake --install $(BUILD)

clean:
	rm -rf $(BUILD) $(BUILD)-sanitize demo-output
