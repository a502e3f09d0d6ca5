# aalab — the commands of the quick start: `make run` and `make test`; `make bench` measures
# the harness against limits measured in the same run (writes bench.json).
BUILD     ?= build
JOBS      ?= $(shell nproc 2>/dev/null || echo 2)
OUT       ?= out
RUN_ARGS  ?=
CMAKE_FLAGS ?=
BENCH_ARGS ?=

.PHONY: all deps configure build run test bench clean test-asan fuzz

all: build

deps:
	@bash scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS) > $(BUILD).configure.log 2>&1 || { cat $(BUILD).configure.log; exit 1; }

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# `make run` builds only the aalab binary (not the test executables) before running it.
run: configure
	@cmake --build $(BUILD) -j $(JOBS) --target aalab
	@./$(BUILD)/aalab run --out $(OUT) $(RUN_ARGS)

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

bench: configure
	@cmake --build $(BUILD) -j $(JOBS) --target aalab aalab_bench
	@./$(BUILD)/bench/aalab_bench --json bench.json $(BENCH_ARGS)

# AddressSanitizer + UndefinedBehaviorSanitizer: every test, then the hard suite through the
# CLI (not part of `make test`; see docs/hard-cases.md).
test-asan: deps
	@bash scripts/test-asan.sh

# libFuzzer targets (clang), FUZZ_SECONDS per target (default 60).
fuzz: deps
	@bash scripts/fuzz.sh

clean:
	rm -rf $(BUILD) $(BUILD).configure.log build-asan build-asan.configure.log build-fuzz build-fuzz.configure.log
