#!/usr/bin/env bash
# Regenerates docs/stability.md: builds periflex, runs the stability suite, writes the report.
#
#   scripts/make-stability-report.sh            full suite (long runs included; tens of minutes)
#   scripts/make-stability-report.sh --quick    the quick subset that ctest runs (a few minutes)
#
# Environment: BUILD_DIR (default build-stability-report), PERIFLEX (use this binary instead of
# building one), PROGRAM (the periflex each case runs; default PERIFLEX itself), OUT (default
# out/stability).
set -euo pipefail
cd "$(dirname "$0")/.."

mode=()
if [[ "${1:-}" == "--quick" ]]; then mode=(--quick); fi
build="${BUILD_DIR:-build-stability-report}"
out="${OUT:-out/stability}"

if [[ -z "${PERIFLEX:-}" ]]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPERIFLEX_TESTS=OFF -DPERIFLEX_BENCH=OFF >/dev/null
  cmake --build "$build" --target periflex -j"$(nproc)"
  PERIFLEX="$build/src/periflex"
fi

# the suite's exit code says whether every case behaved as expected; the report is written either way
status=0
program=()
if [[ -n "${PROGRAM:-}" ]]; then program=(--program "$PROGRAM"); fi
"$PERIFLEX" stability "${mode[@]}" "${program[@]}" --out "$out" || status=$?
if [[ ! -f "$out/stability.md" ]]; then
  echo "make-stability-report: the suite wrote no table (exit $status)" >&2
  exit 1
fi

suite="full"
command_line="scripts/make-stability-report.sh"
if [[ ${#mode[@]} -gt 0 ]]; then suite="quick"; command_line="scripts/make-stability-report.sh --quick"; fi
{
  sed -e "s/@SUITE@/$suite/" -e "s|@COMMAND@|$command_line|" -e "s/@DATE@/$(date -u +%Y-%m-%d)/" \
      -e "s/@HOST@/$(nproc) cores/" docs/stability.md.in
  # the generated table, without its own title line
  tail -n +2 "$out/stability.md"
} > docs/stability.md
echo "docs/stability.md written ($suite suite, exit $status)"
exit "$status"
