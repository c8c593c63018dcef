#!/usr/bin/env bash
# Rewrites the golden series of tests/golden/series/ (series.csv and VTK files of every run listed
# in tests/golden/series/runs.txt) with the program as built now, at one thread, and checks that
# two threads write the same bytes.
#
# Regenerate them ONLY when the physics changes on purpose (a new law, a fixed bug in a force):
# the test series_golden (tests/golden/series/check_series.sh) exists so that a move of code
# cannot change a single bit of any shipped scene's results. Say in the commit why they changed.
#
#   scripts/make-golden-series.sh [PERIFLEX]     default: build/src/periflex
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
periflex=${1:-$root/build/src/periflex}
golden=$root/tests/golden/series
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# a field of runs.txt without its surrounding blanks
trim() {
  local text=$1
  text=${text#"${text%%[![:space:]]*}"}
  echo "${text%"${text##*[![:space:]]}"}"
}

while IFS='|' read -r name scene args; do
  [[ $name =~ ^[[:space:]]*(#|$) ]] && continue
  name=$(trim "$name")
  scene=$(trim "$scene")
  read -r -a argv <<<"$args"
  echo "== $name"
  OMP_NUM_THREADS=1 "$periflex" run "$root/$scene" "${argv[@]}" --threads 1 --quiet --out "$work/$name"
  rm -rf "${golden:?}/$name"
  mkdir -p "$golden/$name"
  cp "$work/$name/series.csv" "$golden/$name/"
  [[ -d $work/$name/vtk ]] && cp -r "$work/$name/vtk" "$golden/$name/"
done <"$golden/runs.txt"

# the same bytes at two threads, or the golden files could not serve both
"$golden/check_series.sh" "$periflex" "$work/check"
