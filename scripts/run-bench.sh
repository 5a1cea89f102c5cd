#!/usr/bin/env bash
# Runs the benchmarks pinned to one core (the timing protocol of the README) and prints the build
# flags beside the figures, since numbers without them cannot be compared. BENCH_BINARY picks the
# benchmark (default model_bench; sim_bench times the simulated cycle).
set -euo pipefail
build_dir=${1:-build}
bench=${build_dir}/bench/${BENCH_BINARY:-model_bench}
if [ ! -x "$bench" ]; then
  echo "run-bench: $bench not built; run 'make build' first" >&2
  exit 1
fi
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'), $(nproc) cores"
echo "build:   $(grep -E '^CMAKE_BUILD_TYPE|^COMPLY_NATIVE' "${build_dir}/CMakeCache.txt" | tr '\n' ' ')"
pin=()
if command -v taskset >/dev/null 2>&1 && [ "$(nproc)" -gt 1 ]; then
  pin=(taskset -c "$(($(nproc) - 1))")
fi
"${pin[@]}" "$bench" --benchmark_min_time=0.2 --benchmark_repetitions=5 \
  --benchmark_report_aggregates_only=true "${@:2}"
