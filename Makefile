# Thin wrapper over CMake. `make demo` and `make test` first install missing dependencies.
BUILD ?= build
PREFIX ?= /usr/local
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
WERROR ?= OFF
CMAKE_FLAGS ?=
CONFIGURE = cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=$(PREFIX) \
            -DGM_WERROR=$(WERROR) $(CMAKE_FLAGS)

.PHONY: all deps build test test-sanitize demo bench examples install clean fuzz

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

# Fuzz the mesh readers with libFuzzer (clang), seeded with tests/data; FUZZ_TIME seconds.
FUZZ_TIME ?= 60
fuzz:
	cmake -S . -B $(BUILD)-fuzz -DCMAKE_C_COMPILER=clang -DCMAKE_BUILD_TYPE=Debug -DGM_FUZZ=ON \
	  -DGM_BUILD_TESTS=OFF > /dev/null
	cmake --build $(BUILD)-fuzz -j $(JOBS) --target fuzz_mesh_readers
	@mkdir -p $(BUILD)-fuzz/corpus
	@for f in tests/data/*.msh; do { printf '\000'; cat $$f; } > $(BUILD)-fuzz/corpus/$$(basename $$f); done
	@printf '\001OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' > $(BUILD)-fuzz/corpus/tri.off
	$(BUILD)-fuzz/fuzz_mesh_readers -max_total_time=$(FUZZ_TIME) -max_len=65536 \
	  -print_final_stats=1 -artifact_prefix=$(BUILD)-fuzz/ $(BUILD)-fuzz/corpus

install: build
	cmake --install $(BUILD)

clean:
	rm -rf $(BUILD) $(BUILD)-sanitize $(BUILD)-fuzz demo-output
