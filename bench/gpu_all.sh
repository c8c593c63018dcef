#!/usr/bin/env bash
# Every GPU measurement in one go, into one file (default gpu_all_results.txt), for a run on a
# machine with a GPU. From the project root:
#   here, on a build tree:             bench/gpu_all.sh build
#   on a GPU machine with the pack:    bash .device/run.sh bash bench/gpu_all.sh
#     (the pack: ../shared/device/make-bundle.sh build; see docs/gpu.md)
# Prints the machine and its GPU, the bond evaluations per second of the force pass on the GPU
# and on the CPU (medians of 5), the GPU-against-CPU tests (from a build tree only: they read the
# scenes of the source tree they were built in), and the default notched plate run to
# its end on each path (wall-clock seconds). GPU_BENCH_FILTER picks benchmarks (a regex),
# GPU_ALL_UNTIL ends the notched plate early (a quick check of the script).
# each section reports its own failure and the next runs: one run on a GPU machine gives all it can
set -uo pipefail
build=${1:-}
out=${GPU_ALL_OUT:-gpu_all_results.txt}
# the programs: from the build tree when one is named, else from PATH (the pack's bin/)
program() {
  if [[ -n "$build" ]]; then
    for p in "$build/src/$1" "$build/bench/$1" "$build/tests/$1"; do [[ -x "$p" ]] && { echo "$p"; return; }; done
  fi
  command -v "$1" || true
}
periflex=$(program periflex)
bench=$(program gpu_pd_bench)
tests=${GPU_ALL_TESTS:-}
[[ -n "$build" && -x "$build/tests/test_gpu" ]] && tests="$build/tests/test_gpu"
[[ -n "$periflex" && -n "$bench" ]] || { echo "periflex or gpu_pd_bench not found (build them, or run through the pack)"; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

{
  echo "== machine"
  date -u
  uname -srm
  echo "cores: $(nproc); load: $(cut -d' ' -f1-3 /proc/loadavg)"
  nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader 2>/dev/null || echo "no nvidia-smi"

  echo "== bond evaluations per second, force pass with the fracture check (medians of 5)"
  "$bench" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
    --benchmark_filter="${GPU_BENCH_FILTER:-.}" 2>&1 | grep -E "^Benchmark|^-+$|_median|ERROR|error|what|Abort" ||
    echo "(the benchmarks ended with exit $?)"

  if [[ -n "$tests" ]]; then
    echo "== GPU forces and breaks against the CPU (test_gpu)"
    "$tests" --gtest_brief=1 ${GPU_ALL_TEST_FILTER:+--gtest_filter="$GPU_ALL_TEST_FILTER"} 2>&1 | tail -n 20 ||
      echo "(the tests ended with exit $?)"
  fi

  echo "== the default notched plate to its end, each path (wall-clock seconds)"
  for device in cpu gpu; do
    start=$(date +%s.%N)
    if "$periflex" run scenes/notched_plate.toml --quiet --device "$device" ${GPU_ALL_UNTIL:+--until "$GPU_ALL_UNTIL"} \
      --out "$work/$device" >"$work/$device.log" 2>&1; then
      end=$(date +%s.%N)
      echo "$device: $(echo "$end - $start" | bc) s; $(tail -n 1 "$work/$device.log")"
    else
      echo "$device: failed (exit $?): $(tail -n 3 "$work/$device.log")"
    fi
  done

  # one field of summary.json (numbers and strings, as written one per line)
  field() { sed -n "s/^ *\"$2\": \"\{0,1\}\([^\",]*\).*/\1/p" "$1" | head -n 1; }
  echo "== the notched plate at 1M particles (dx = 62.5 um, dt = 25 ns), 100 steps, each path"
  for path in cpu gpu:fp64 gpu:fp32; do
    device=${path%%:*}; precision=${path#*:}; [[ "$precision" == "$path" ]] && precision=fp64
    name="big_${device}_$precision"
    start=$(date +%s.%N)
    if "$periflex" run scenes/notched_plate.toml --quiet --device "$device" --until 2.5e-6 \
      --set flex_body.plate.grid_spacing=6.25e-5 --set solver.dt=2.5e-8 --set solver.precision="$precision" \
      --out "$work/$name" >"$work/$name.log" 2>&1; then
      end=$(date +%s.%N)
      summary="$work/$name/summary.json"
      echo "$path: $(echo "$end - $start" | bc) s in all; solver $(field "$summary" solver_time) s," \
        "$(field "$summary" steps_per_second) steps/s; particles $(field "$summary" particles)"
      tail -n 1 "$work/$name/series.csv" | cut -c1-160
    else
      echo "$path: failed (exit $?): $(tail -n 3 "$work/$name.log")"
    fi
  done
} 2>&1 | tee "$out"
echo "written: $out"
