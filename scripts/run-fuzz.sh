#!/bin/bash
# make fuzz: runs each libFuzzer target of tests/fuzz for SECONDS, growing its corpus in
# BUILD_DIR/corpus/<target> from the seeds in tests/fuzz/corpus/<target>. A crash is written to
# tests/fuzz/regressions/<target>/, where the normal build's replay test keeps it once fixed.
# Usage: scripts/run-fuzz.sh BUILD_DIR SECONDS TARGET...
set -u
build=$1 seconds=$2
shift 2
here=$(cd "$(dirname "$0")/.." && pwd)
status=0
printf '%-18s %10s %12s %8s %8s\n' target seconds executions corpus crashes
for target in "$@"; do
  corpus=$build/corpus/$target regressions=$here/tests/fuzz/regressions/$target
  mkdir -p "$corpus" "$regressions"
  before=$(find "$regressions" -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' | wc -l)
  log=$build/fuzz_$target.log started=$SECONDS
  LSAN_OPTIONS=suppressions=$here/tests/sanitizers/lsan.supp:print_suppressions=0 \
    "$build/tests/fuzz/fuzz_$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$regressions/" "$corpus" \
    "$here/tests/fuzz/corpus/$target" >"$log" 2>&1
  after=$(find "$regressions" -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' | wc -l)
  executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  # Seconds actually run: a finding stops the target early.
  printf '%-18s %10s %12s %8s %8s\n' "$target" "$((SECONDS - started))" "${executions:-?}" \
    "$(find "$corpus" -type f | wc -l)" "$((after - before))"
  if [ "$after" -ne "$before" ]; then
    echo "  new finding in $regressions; details: $log"
    status=1
  fi
done
exit $status
