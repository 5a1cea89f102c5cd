# comply: the README's commands. `make test` and `make demo` work as the first command on a fresh
# Debian 12 machine: each installs what it needs, configures, builds and runs.
BUILD_DIR ?= build
BUILD_TYPE ?= Release
JOBS ?= $(shell nproc)
CTEST_ARGS ?= -LE long
# Tests test-asan leaves out: out-of-tree projects built against the installed prefix, whose
# sanitized static libraries they link without the sanitizer's runtime.
ASAN_EXCLUDE ?= ^(simulink_plugin_|plugin_new_)
# Benchmarks run pinned to the last CPU, away from most interrupt and housekeeping work.
BENCH_CPU ?= $(shell echo $$(($$(nproc) - 1)))

.PHONY: deps configure build generated install test test-all test-ros2 test-asan test-asan-ci test-tsan \
	fuzz soak bench demo format tidy clean

deps:
	@scripts/install-deps.sh

configure: deps
	@if [ ! -f $(BUILD_DIR)/build.ninja ]; then \
	  cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) \
	    -DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache; \
	fi

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

# The files generated from the tables (docs, ROS 2 messages, DDS IDL), committed and compared by
# tests/schema, tests/transport and tests/pipeline: run after a change to a table (the command
# schema's, include/comply/schema/table.hpp; the host messages', include/comply/transport/
# message_tables.hpp; the options', include/comply/pipeline/option_table.hpp).
COMPLY_CLI = $(BUILD_DIR)/apps/comply/comply
IDL_DIR = src/transport/idl/comply_msgs/msg
generated: build
	@$(COMPLY_CLI) schema --format markdown > docs/command-schema.md
	@$(COMPLY_CLI) schema --format msg --kind cartesian > msg/CartesianCommand.msg
	@$(COMPLY_CLI) schema --format msg --kind joint > msg/JointCommand.msg
	@$(COMPLY_CLI) schema --format idl --kind cartesian > $(IDL_DIR)/CartesianCommand.idl
	@$(COMPLY_CLI) schema --format idl --kind joint > $(IDL_DIR)/JointCommand.idl
	@for m in ControllerState CommandOutcome ChunkTiming Diagnostics CommittedRequest; do \
	  $(COMPLY_CLI) schema --format msg --message $$m > msg/$$m.msg; \
	  $(COMPLY_CLI) schema --format idl --message $$m > $(IDL_DIR)/$$m.idl; \
	done
	@$(COMPLY_CLI) config --defaults --robot fr3 > config/cartesian_impedance.yaml
	@echo "generated: docs/command-schema.md msg/*.msg $(IDL_DIR)/*.idl (commands and host messages)," \
	  "config/cartesian_impedance.yaml (options)"

# Libraries, headers, the CLI, the reference plugins, robots and the CMake package `comply` under
# PREFIX; the installed comply finds its plugins and robots relative to its own location.
PREFIX ?= $(HOME)/.local
install: build
	@cmake --install $(BUILD_DIR) --prefix $(PREFIX)

# Unit and integration tests; long experiments carry the CTest label `long` and run with test-all.
test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS) $(CTEST_ARGS)

test-all: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer with the leak check on, and
# the threaded parts (pipeline, transport, the live host) under ThreadSanitizer, each in its own
# folder. tests/sanitizers/*.supp hold the suppressions, each naming one library that is not ours.
SANITIZER_CONFIGURE = -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCOMPLY_BUILD_BENCH=OFF \
	-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache
# ASAN_TARGETS empty builds everything.
test-asan: deps
	@cmake -S . -B build-asan $(SANITIZER_CONFIGURE) -DCOMPLY_SANITIZE="address;undefined" >/dev/null
	@cmake --build build-asan -j $(JOBS) $(if $(ASAN_TARGETS),--target $(ASAN_TARGETS))
	@cd build-asan && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
	  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/tests/sanitizers/lsan.supp:print_suppressions=0 \
	  ctest --output-on-failure -j $(JOBS) $(CTEST_ARGS) -E "$(ASAN_EXCLUDE)"

# CI's share of test-asan (CTest label asan_ci): the command, controller file, URDF and DDS
# readers with their fuzz regressions, the model, the wrapper, the transport and the recorder. The
# rest links the simulator, whose sanitized build would not fit CI's time.
ASAN_CI_TARGETS = schema_test schema_realtime_test pipeline_unit_test wrapper_test \
	wrapper_realtime_test triple_buffer_tsan_test model_unit_test model_reference_test \
	model_parsed_urdf_test model_allocation_test transport_test record_test export_unit_test \
	viewer_unit_test ur_unit_test franka_unit_test \
	fuzz_command_json fuzz_controller_yaml fuzz_dds_sample fuzz_urdf
test-asan-ci:
	@$(MAKE) --no-print-directory test-asan ASAN_TARGETS="$(ASAN_CI_TARGETS)" CTEST_ARGS="-L asan_ci"

TSAN_TESTS ?= pipeline|wrapper|Diagnostics|transport|Live|live|triple_buffer|spsc|Recorder|McapFile|FoxgloveServer|ClientQueue|RtdeTcp|UrBackend|FrankaArm|FciEmulator|FrankaLoop
test-tsan: deps
	@cmake -S . -B build-tsan $(SANITIZER_CONFIGURE) -DCOMPLY_SANITIZE=thread >/dev/null
	@cmake --build build-tsan -j $(JOBS)
	@cd build-tsan && \
	  TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1:suppressions=$(CURDIR)/tests/sanitizers/tsan.supp \
	  ctest --output-on-failure -j $(JOBS) $(CTEST_ARGS) -R "$(TSAN_TESTS)"

# libFuzzer on every text input reader (tests/fuzz), FUZZ_SECONDS each; needs clang.
FUZZ_SECONDS ?= 600
FUZZ_TARGETS ?= command_json controller_yaml dds_sample task_file urdf
fuzz: deps
	@command -v clang++ >/dev/null || { echo "make fuzz needs clang: apt-get install clang" >&2; exit 1; }
	@CC=clang CXX=clang++ cmake -S . -B build-fuzz $(SANITIZER_CONFIGURE) -DCOMPLY_FUZZ=ON \
	  -DCOMPLY_BUILD_TESTS=OFF -DCOMPLY_SANITIZE="address;undefined;fuzzer-no-link" >/dev/null
	@cmake --build build-fuzz -j $(JOBS) --target $(addprefix fuzz_,$(FUZZ_TARGETS))
	@scripts/run-fuzz.sh build-fuzz $(FUZZ_SECONDS) $(FUZZ_TARGETS)

# comply run --sim for SOAK_MINUTES under two senders of valid and invalid commands: every
# command accounted, no FAULT, flat memory (report.md, rss.csv, rss.png in out/soak).
SOAK_MINUTES ?= 30
soak: build
	@/usr/bin/python3 scripts/soak.py $(BUILD_DIR)/apps/comply/comply $(BUILD_DIR)/python \
	  config/sim/cartesian_impedance.yaml out/soak $(SOAK_MINUTES)

# The ROS 2 packages (ros2/) built with colcon and tested end to end; needs ROS 2 Humble sourced.
test-ros2: build
	@scripts/test-ros2.sh $(BUILD_DIR)

bench: build
	@scripts/run-bench.sh $(BUILD_DIR)
	@BENCH_BINARY=sim_bench scripts/run-bench.sh $(BUILD_DIR)
	@$(BUILD_DIR)/apps/comply/comply bench --robot all --iterations 10000 --cpu $(BENCH_CPU)

# The cross-platform check in simulation: four robots, one plugin, one command, one target.
DEMO_OUT ?= out/cross-platform
demo: build
	@mkdir -p $(dir $(DEMO_OUT))
	@$(BUILD_DIR)/apps/comply/comply experiment cross-platform --out $(DEMO_OUT)

format:
	@git ls-files '*.hpp' '*.cpp' '*.h' '*.c' | xargs clang-format -i

tidy: configure
	@git ls-files 'src/*.cpp' | xargs clang-tidy -p $(BUILD_DIR) --quiet

clean:
	@rm -rf $(BUILD_DIR)
