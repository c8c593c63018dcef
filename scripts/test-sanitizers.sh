#!/usr/bin/env bash
# The sanitizer configurations CI runs after the main suite:
#   AddressSanitizer + UBSan over the solver, peridynamics, coupling, contact, the scene parser
#   (malformed scenes) and the command line;
#   ThreadSanitizer over the solver's team of threads (core/thread_pool.h) and the threaded parts
#   of the visualiser: the unit tests (snapshot exchange, command queue, simulation thread) and
#   the GUI smoke tests, scripted runs of the program under
#   Xvfb that drive the simulation thread while the window draws (tests/gui_smoke.cmake, label
#   gui; the first report fails the test).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
jobs="$(nproc)"

# only what those labels run is built: the program and their test programs
asan_labels=(core scene mbs pd coupling contact solve cli output io)
cmake --preset asan -DPERIFLEX_GUI=OFF -DPERIFLEX_HEADLESS=OFF >/dev/null
cmake --build --preset asan -j"$jobs" --target periflex "${asan_labels[@]/#/test_}"
# Left out under ASan: validation sweeps that run code the other tests of their files run, at
# many step sizes or for many periods (each over 15 s there: 354 s of the stage's 836 s of test
# time), and the glass plate's branching run (24 s there; SpecimenFiles runs its first steps).
# The Release suite runs them.
asan_sweeps=(SingularPassageSweep RigidLimit PdStateBasedWaves.PAndSWaveSpeeds PdStateBasedVibration
             PdBranching.TipPositionSpreads SingularPositions.BenchmarkA02OverTenSeconds
             PdBranching.GlassPlateCrackRuns)
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --preset asan -j"$jobs" -L "^($(IFS='|'; echo "${asan_labels[*]}"))\$" \
        -E "^($(IFS='|'; echo "${asan_sweeps[*]}"))" --timeout 900

# one build for both: the program (with the GUI) and the unit tests, nothing else
cmake --preset tsan >/dev/null
tsan_targets=(test_app test_core periflex)
if command -v xvfb-run >/dev/null; then tsan_targets+=(gui_png_check); fi
cmake --build --preset tsan -j"$jobs" --target "${tsan_targets[@]}"
TSAN_OPTIONS="suppressions=$PWD/scripts/tsan.supp second_deadlock_stack=1" \
  ctest --preset tsan -j"$jobs" -L '^(app|gui)$' --timeout 900
TSAN_OPTIONS="second_deadlock_stack=1" ctest --preset tsan -j"$jobs" -R '^ThreadPool\.' --timeout 300
