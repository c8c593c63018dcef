#!/usr/bin/env bash
# The sanitizer configurations CI runs after the main suite:
#   AddressSanitizer + UBSan over the solver, peridynamics, the scene parser (malformed scenes)
#   and the command line;
#   ThreadSanitizer over the threaded parts of the visualiser (snapshot exchange, command queue,
#   simulation thread).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
jobs="$(nproc)"

cmake --preset asan -DPERIFLEX_GUI=OFF -DPERIFLEX_HEADLESS=OFF >/dev/null
cmake --build --preset asan -j"$jobs"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --preset asan -j"$jobs" -L '^(core|scene|mbs|pd|solve|cli|output)$' --timeout 900

cmake --preset tsan >/dev/null
cmake --build --preset tsan -j"$jobs" --target test_app
TSAN_OPTIONS="suppressions=$PWD/scripts/tsan.supp second_deadlock_stack=1" \
  ctest --preset tsan -j"$jobs" -L '^app$' --timeout 900
