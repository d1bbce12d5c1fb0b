# shapebench: the two commands of the README. Both install what is missing (Debian 12,
# apt-get, idempotent, no prompts), configure with CMake (Release, Ninja) and build.
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
PACKAGES = cmake ninja-build g++ libsundials-dev libeigen3-dev libyaml-cpp-dev libgtest-dev \
           libcli11-dev nlohmann-json3-dev gnuplot-nox libxml2-utils universal-ctags chromium \
           $(PYTHON_PACKAGES)
# The Python module (python/, docs/python.md) and what its tests and examples use.
PYTHON_PACKAGES = pybind11-dev python3-dev python3-pytest python3-numpy python3-scipy python3-yaml
# recommend: the Welch PSD of accelerometer logs (bench/measured/welch_psd.h)
PACKAGES += libfftw3-dev pkgconf
# run --out's trace.mat and a sweep's results.mat (bench/output/mat_file.h); dygraphs (MIT),
# inlined into run --report's interactive trace (bench/output/interactive_trace.h)
PACKAGES += libmatio-dev libjs-dygraphs
# identify: the nonlinear refinement of modes (model/modal_refinement.h)
PACKAGES += libceres-dev
# design: the linear programs of pattern synthesis (controller/pattern_design.h), COIN-OR CLP
PACKAGES += coinor-libclp-dev
# sweep and check on MPI ranks (docs/scaling.md): Open MPI, found by CMake's FindMPI
PACKAGES += libopenmpi-dev openmpi-bin
# FMI co-simulation (docs/fmi.md): FMUs are zip archives (libzip) with a modelDescription.xml
# (pugixml reads it on import; xmllint checks it against the standard's schema)
PACKAGES += libzip-dev libpugixml-dev

.PHONY: deps configure build demo test clean

deps:
	@scripts/install-deps.sh $(PACKAGES)

# SHAPEBENCH_SANITIZE is cleared: make test-sanitize's twins (below) leave the tree, or
# ctest would list the unbuilt ones.
configure: deps
	@cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release -DSHAPEBENCH_SANITIZE= >/dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

demo: build
	@echo "== unshaped (pattern.method none) =="
	@$(BUILD_DIR)/shapebench run configs/demo.yaml --set controller.pattern.method=none --out $(BUILD_DIR)/demo/unshaped
	@echo
	@echo "== shaped (pattern.method 1, mode both) =="
	@$(BUILD_DIR)/shapebench run configs/demo.yaml --out $(BUILD_DIR)/demo/method1
	@echo
	@echo "plots: $(BUILD_DIR)/demo/unshaped/deflection.png $(BUILD_DIR)/demo/method1/deflection.png"

test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS) -LE sanitize

clean:
	@rm -rf $(BUILD_DIR)

# `make test-sanitize`: the suite again under AddressSanitizer and UndefinedBehaviorSanitizer,
# in the same build tree: the libraries and the CLI get sanitized twins (-O1, any report
# fails the test that triggered it), the test executables twins linked from the test code
# `make test` compiled (cmake/sanitize.cmake; tests labelled `sanitize`, named
# sanitized.*). The source-only checks (includes, file sizes, docs links) have no twin:
# they run no code.
# `make fuzz`: each libFuzzer target (clang) for FUZZ_SECONDS, seeded from fuzz/corpus/.
.PHONY: test-sanitize fuzz
SANITIZE_ENV = ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1 \
               UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
test-sanitize: configure
	@cmake -S . -B $(BUILD_DIR) -DSHAPEBENCH_SANITIZE=address,undefined >/dev/null
	@cmake --build $(BUILD_DIR) -j $(JOBS) --target shapebench_sanitized_tests
	@cd $(BUILD_DIR) && $(SANITIZE_ENV) ctest --output-on-failure -j $(JOBS) -L sanitize

FUZZ_DIR ?= build-fuzz
FUZZ_SECONDS ?= 60
FUZZ_TARGETS = fuzz_scenario fuzz_set fuzz_sweep fuzz_gcode fuzz_manifest fuzz_rows fuzz_uff58
FUZZ_TARGETS += fuzz_accel_log fuzz_modal_file
fuzz:
	@scripts/install-deps.sh $(PACKAGES) clang libclang-rt-14-dev
	@CC=clang CXX=clang++ cmake -S . -B $(FUZZ_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Fuzz \
	  -DCMAKE_CXX_FLAGS_FUZZ="-O1 -g -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all" \
	  -DSHAPEBENCH_FUZZ=ON -DSHAPEBENCH_PYTHON=OFF >/dev/null
	@cmake --build $(FUZZ_DIR) -j $(JOBS) --target $(FUZZ_TARGETS)
	@fuzz/run.sh $(FUZZ_DIR) $(FUZZ_SECONDS) $(FUZZ_TARGETS)

# `make bench`: Google Benchmark over benchmarks/cases/ (case 1 one mode, case 2
# the moving column with the servo, case 3 a 1000-point sweep, CVODE's choices at equal
# accuracy, case 4 the moving column with LuGre guides on a 10 s circle, case 4d case 3
# damped 2% with every metric, the floor: case 1's bare exact ZOH loop), the Python
# baselines on cases 1 and 4 (scripts/baseline.py; needs python3-scipy and
# python3-numpy, skipped without), a 1,000,000-point sweep under /usr/bin/time -v (peak
# resident memory; a few minutes), then one table of it all (scripts/baseline_table.py),
# then four Python threads running at once against one (benchmarks/python_threads.py: the
# GIL is released while simulating), then 1 vs 2 MPI ranks on a 200,000-point sweep
# (scripts/mpi_scaling.py; docs/scaling.md). docs/performance.md quotes it. Everything lands in
# $(BUILD_DIR)/bench.
.PHONY: bench
BENCH_OUT = $(BUILD_DIR)/bench
bench: deps
	@scripts/install-deps.sh libbenchmark-dev
	@scripts/install-deps.sh python3-scipy python3-numpy || echo "(no python3-scipy/numpy: the baselines are skipped)"
	@cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD_DIR) -j $(JOBS) --target shapebench shapebench_benchmarks shapebench_py
	@mkdir -p $(BENCH_OUT)
	@$(BUILD_DIR)/benchmarks/shapebench_benchmarks --export_case1=$(BENCH_OUT)/case1.json
	@$(BUILD_DIR)/benchmarks/shapebench_benchmarks --export_case4=$(BENCH_OUT)/case4.json
	@/usr/bin/python3 scripts/baseline.py $(BENCH_OUT)/case1.json $(BENCH_OUT)/case4.json > $(BENCH_OUT)/baseline.json
	@$(BUILD_DIR)/benchmarks/shapebench_benchmarks --benchmark_out=$(BENCH_OUT)/benchmarks.json \
	  --benchmark_out_format=json > $(BENCH_OUT)/benchmarks.txt
	@rm -rf $(BENCH_OUT)/million
	@/usr/bin/time -v -o $(BENCH_OUT)/memory.txt $(BUILD_DIR)/shapebench sweep \
	  benchmarks/cases/million_sweep.yaml --jobs 2 --out $(BENCH_OUT)/million > $(BENCH_OUT)/million.txt
	@cat $(BENCH_OUT)/million.txt >> $(BENCH_OUT)/memory.txt
	@rm -rf $(BENCH_OUT)/million
	@/usr/bin/python3 scripts/baseline_table.py $(BENCH_OUT)/benchmarks.json \
	  $(BENCH_OUT)/baseline.json $(BENCH_OUT)/memory.txt
	@PYTHONPATH=$(BUILD_DIR)/python /usr/bin/python3 benchmarks/python_threads.py | tee $(BENCH_OUT)/python_threads.txt
	@/usr/bin/python3 scripts/mpi_scaling.py $(BUILD_DIR)/shapebench benchmarks/cases/mpi_sweep.yaml \
	  $(BENCH_OUT)/mpi | tee $(BENCH_OUT)/mpi_scaling.txt

# `make bench-compare REF=<commit>`: REF's benchmarks built from `git archive` beside this
# tree's, then case 1 exact and case 3 timed with the two binaries interleaved, medians
# of 5 rounds (scripts/bench_compare.py; exit 1 when one is more than 3% slower).
.PHONY: bench-compare
REF ?= HEAD
bench-compare: deps
	@scripts/install-deps.sh libbenchmark-dev
	@rm -rf $(BUILD_DIR)/ref-src && mkdir -p $(BUILD_DIR)/ref-src
	@git archive $(REF) | tar -x -C $(BUILD_DIR)/ref-src
	@cmake -S $(BUILD_DIR)/ref-src -B $(BUILD_DIR)/ref-build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD_DIR)/ref-build -j $(JOBS) --target shapebench_benchmarks
	@cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD_DIR) -j $(JOBS) --target shapebench_benchmarks
	@/usr/bin/python3 scripts/bench_compare.py $(BUILD_DIR)/ref-build/benchmarks/shapebench_benchmarks \
	  $(BUILD_DIR)/benchmarks/shapebench_benchmarks
