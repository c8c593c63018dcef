#!/usr/bin/env bash
# Compares two build trees on the benchmarks a change to the solver must not slow down: the bond
# kernels (pd_kernel_bench), a coupled step (coupled_step_bench), rigid steps (rigid_step_bench)
# and the glass branching scene's whole run (`periflex run`, its solver time from summary.json).
# The two builds run alternately, round after round, so that a change in the machine's load falls
# on both; each benchmark's median over the rounds is compared.
#
#   bash bench/compare_builds.sh BEFORE_BUILD AFTER_BUILD [ROUNDS]
#
# Prints one row per benchmark (before, after, change) and exits 1 when any is slower by more than
# PERIFLEX_BENCH_TOLERANCE percent (3 unless set). A build tree is a folder with bench/ and src/
# as `cmake --build` leaves them.
set -euo pipefail
if (($# < 2)); then
  echo "usage: bash bench/compare_builds.sh BEFORE_BUILD AFTER_BUILD [ROUNDS]" >&2
  exit 2
fi
before="$(cd "$1" && pwd)"
after="$(cd "$2" && pwd)"
rounds="${3:-3}"
tolerance="${PERIFLEX_BENCH_TOLERANCE:-3}"
root="$(cd "$(dirname "$0")/.." && pwd)"
programs=(pd_kernel_bench coupled_step_bench rigid_step_bench)
for build in "$before" "$after"; do
  for p in "${programs[@]}" ; do
    [[ -x "$build/bench/$p" ]] || { echo "compare_builds: $build/bench/$p is missing" >&2; exit 2; }
  done
  [[ -x "$build/src/periflex" ]] || { echo "compare_builds: $build/src/periflex is missing" >&2; exit 2; }
done

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for ((r = 1; r <= rounds; ++r)); do
  # the order alternates: before first in odd rounds, after first in even ones
  order=(before after)
  ((r % 2 == 0)) && order=(after before)
  for side in "${order[@]}"; do
    build="$before"
    [[ "$side" == after ]] && build="$after"
    for p in "${programs[@]}"; do
      "$build/bench/$p" --benchmark_format=json --benchmark_out="$work/$side.$p.$r.json" >/dev/null
    done
    "$build/src/periflex" run "$root/scenes/glass_branching.toml" --quiet --out "$work/$side.glass.$r" >/dev/null
    echo "round $r/$rounds: $side done" >&2
  done
done

python3 - "$work" "$rounds" "$tolerance" <<'EOF'
import json, pathlib, statistics, sys

work, rounds, tolerance = pathlib.Path(sys.argv[1]), int(sys.argv[2]), float(sys.argv[3])
times = {"before": {}, "after": {}}
for side in times:
    for r in range(1, rounds + 1):
        for f in sorted(work.glob(f"{side}.*.{r}.json")):
            for b in json.loads(f.read_text())["benchmarks"]:
                if b.get("run_type", "iteration") != "iteration":
                    continue
                scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b["time_unit"]]
                times[side].setdefault(b["name"], []).append(b["real_time"] * scale)
        summary = json.loads((work / f"{side}.glass.{r}" / "summary.json").read_text())
        times[side].setdefault("glass_branching whole run (solver s)", []).append(summary["solver_time"])

slower = []
print(f"{'benchmark':60s} {'before':>12s} {'after':>12s} {'change':>8s}")
for name in times["before"]:
    if name not in times["after"]:
        continue
    b, a = statistics.median(times["before"][name]), statistics.median(times["after"][name])
    change = 100.0 * (a / b - 1.0)
    print(f"{name:60s} {b:12.4g} {a:12.4g} {change:+7.1f}%")
    if change > tolerance:
        slower.append(name)
if slower:
    print(f"slower by more than {tolerance}%: " + ", ".join(slower))
    sys.exit(1)
print(f"none slower by more than {tolerance}% (medians of {rounds} alternated rounds)")
EOF
