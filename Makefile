# bounce: `make demo` renders the built-in scenes, `make test` runs every test.
# Both install missing Debian packages first (scripts/install-deps.sh) and build in build/.
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release
DEMO_SIZE ?= 512x512

.PHONY: all deps build test demo bench clean

all: build

deps:
	@./scripts/install-deps.sh

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) $(CMAKE_FLAGS)

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

demo: build
	./scripts/demo.sh $(BUILD)/src/app/bounce out $(DEMO_SIZE)

bench: build
	$(BUILD)/bench/bounce_bench

clean:
	rm -rf $(BUILD) out
