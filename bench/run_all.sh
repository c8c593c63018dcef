#!/usr/bin/env bash
# Runs every benchmark program in the build tree and prints their tables.
set -euo pipefail
dir="${BENCH_BIN_DIR:-build/bench}"
for b in "$dir"/*_bench; do
  [[ -x "$b" ]] || continue
  echo "== $(basename "$b")"
  "$b" --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
done
