# shapebench: the two commands of the README. Both install what is missing (Debian 12,
# apt-get, idempotent, no prompts), configure with CMake (Release, Ninja) and build.
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
PACKAGES = cmake ninja-build g++ libsundials-dev libeigen3-dev libyaml-cpp-dev libgtest-dev \
           libcli11-dev nlohmann-json3-dev gnuplot-nox libxml2-utils

.PHONY: deps configure build demo test clean

deps:
	@scripts/install-deps.sh $(PACKAGES)

configure: deps
	@cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null

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
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

clean:
	@rm -rf $(BUILD_DIR)
