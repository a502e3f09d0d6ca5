# aalab — the commands of the quick start: `make run` and `make test`; `make bench` measures
# the harness against limits measured in the same run (writes bench.json).
BUILD     ?= build
JOBS      ?= $(shell nproc 2>/dev/null || echo 2)
OUT       ?= out
RUN_ARGS  ?=
CMAKE_FLAGS ?=
BENCH_ARGS ?=

.PHONY: all deps configure build run test bench clean test-asan fuzz test-gpu test-slurm test-latex format

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

# Rewrites every C++/CUDA source with the repository's .clang-format (clang-format 14, as
# Debian 12 ships it; scripts/debian-packages.txt). `make test` checks it (Format.* in
# tests/design/format_test.cpp), so CI fails on a line that is not formatted.
format: deps
	@git ls-files '*.cpp' '*.h' '*.cu' '*.cuh' | xargs clang-format-14 -i --style=file

bench: configure
	@bash scripts/install-deps.sh scripts/debian-packages-bench.txt
	@cmake --build $(BUILD) -j $(JOBS) --target aalab aalab_bench
	@./$(BUILD)/bench/aalab_bench --json bench.json $(BENCH_ARGS)

# AddressSanitizer + UndefinedBehaviorSanitizer: every test, then the hard suite through the
# CLI (not part of `make test`; see docs/hard-cases.md).
test-asan: deps
	@bash scripts/test-asan.sh

# libFuzzer targets (clang), FUZZ_SECONDS per target (default 60).
fuzz: deps
	@bash scripts/fuzz.sh

# A real one-node Slurm cluster (munge, slurmctld, slurmd from Debian; needs root): the recipe of
# docs/cluster.md (job array of shards + dependent merge) against single-process runs, then it
# stops what it started. Not part of `make test` (it installs and starts daemons).
test-slurm: configure
	@BUILD=$(BUILD) JOBS=$(JOBS) bash scripts/test-slurm.sh

# `aalab export`'s LaTeX tables, figure snippet and references.bib in a minimal article through
# pdflatex + bibtex (docs/publishing.md). Installs TeX Live from Debian first
# (scripts/debian-packages-latex.txt, about 150 MB), so it is not part of `make test`, where
# the same test skips when pdflatex is missing.
test-latex: configure
	@bash scripts/install-deps.sh scripts/debian-packages-latex.txt
	@cmake --build $(BUILD) -j $(JOBS) --target aalab cli_test
	@cd $(BUILD) && ctest -R 'ExportCli\.LatexCompiles' --output-on-failure

# The CUDA twins of the post filters against the CPU methods, on a machine with an NVIDIA GPU
# and the CUDA toolkit (nothing else: gpu/ builds stand-alone). Synthetic frames always;
# GPU_FRAMES=DIR (from `aalab export-frames`) adds real frames. See docs/gpu.md.
BUILD_GPU ?= build-gpu
GPU_FRAMES ?=
test-gpu:
	@cmake -S gpu -B $(BUILD_GPU) -DCMAKE_BUILD_TYPE=Release > $(BUILD_GPU).configure.log 2>&1 || { cat $(BUILD_GPU).configure.log; exit 1; }
	@cmake --build $(BUILD_GPU) -j $(JOBS)
	@./$(BUILD_GPU)/aalab_gpu --self-test --no-timing --check
	@if [ -n "$(GPU_FRAMES)" ]; then ./$(BUILD_GPU)/aalab_gpu --frames $(GPU_FRAMES) --no-timing --check; fi

clean:
	rm -rf $(BUILD) $(BUILD).configure.log $(BUILD_GPU) $(BUILD_GPU).configure.log build-asan build-asan.configure.log build-fuzz build-fuzz.configure.log
