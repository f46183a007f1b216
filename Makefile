# bounce: `make demo` renders the built-in scenes, `make test` runs every test.
# Both install missing Debian packages first (scripts/install-deps.sh) and build in build/.
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release
DEMO_SIZE ?= 512x512

.PHONY: all deps build test check test-sanitize demo bench clean

all: build

deps:
	@./scripts/install-deps.sh

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) $(CMAKE_FLAGS)

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

# Every test: the ordinary build's suite, then the sanitizer build's (ASan + UBSan, libFuzzer runs),
# one after the other even under make -j (each already uses every core).
test: check
	$(MAKE) test-sanitize

# The ordinary build's suite only (unit, GPU on llvmpipe, CLI, viewer, studies).
check: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# CMakePresets.json `sanitize` (docs/reliability.md): clang, build-sanitize/, labels unit, sanitize, fuzz.
test-sanitize: deps
	cmake --preset sanitize
	cmake --build --preset sanitize -j $(JOBS)
	ctest --preset sanitize -j $(JOBS)

demo: build
	./scripts/demo.sh $(BUILD)/src/app/bounce out $(DEMO_SIZE)

bench: build
	$(BUILD)/bench/bounce_bench

clean:
	rm -rf $(BUILD) build-sanitize out
