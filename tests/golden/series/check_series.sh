#!/usr/bin/env bash
# Runs every shipped scene listed in runs.txt (beside this file) through the program as typed,
# at one and at two threads, and compares series.csv and the VTK files it writes, byte for byte,
# with the files kept here (written by scripts/make-golden-series.sh). A move of code must leave
# them identical; only a change of physics made on purpose may change them.
#
#   tests/golden/series/check_series.sh PERIFLEX [WORK_DIR]
#
# On a difference it names the run, the thread count and the file, and for series.csv the first
# differing row and column with both values; for a VTK file the first differing byte.
set -uo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../../.." && pwd)
periflex=${1:?usage: check_series.sh PERIFLEX [WORK_DIR]}
work=${2:-$(mktemp -d)}
mkdir -p "$work"

# first differing row and column of two CSV files, or nothing when they are identical
first_csv_difference() {
  awk -F, -v golden="$1" '
    NR == FNR { want[FNR] = $0; rows = FNR; next }
    FNR == 1 { split($0, header, ",") }
    {
      if (!(FNR in want)) { printf "line %d: a line the golden file lacks: %s\n", FNR, $0; found = 1; exit }
      if ($0 != want[FNR]) {
        n = split(want[FNR], expected, ",")
        for (c = 1; c <= (NF > n ? NF : n); ++c) {
          if ($c != expected[c]) {
            printf "line %d, column %d (%s): golden %s, run %s\n", FNR, c, header[c], expected[c], $c
            found = 1; exit
          }
        }
      }
    }
    END { if (!found && FNR < rows) printf "line %d: the run ends; the golden file goes on to line %d\n", FNR + 1, rows }
  ' "$1" "$2"
}

failures=0
compare_file() {  # golden, produced, label
  local golden=$1 got=$2 label=$3
  if [[ ! -f $got ]]; then
    echo "FAIL $label: the run wrote no $(basename "$golden")"
    failures=$((failures + 1))
    return
  fi
  cmp -s "$golden" "$got" && return
  failures=$((failures + 1))
  if [[ $golden == *.csv ]]; then
    local where
    where=$(first_csv_difference "$golden" "$got")
    echo "FAIL $label: series.csv differs: ${where:-in bytes only (line endings?)}"
  else
    echo "FAIL $label: $(basename "$golden") differs: $(cmp "$golden" "$got" 2>&1 | head -1)"
  fi
}

runs=0
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
  golden=$here/$name
  for threads in 1 2; do
    out=$work/$name-t$threads
    rm -rf "$out"
    label="$name ($threads thread$([[ $threads == 1 ]] || echo s))"
    if ! OMP_NUM_THREADS=$threads "$periflex" run "$root/$scene" "${argv[@]}" --threads "$threads" --quiet \
         --out "$out" >"$out.log" 2>&1; then
      echo "FAIL $label: the run failed:"; sed 's/^/    /' "$out.log" | tail -5
      failures=$((failures + 1))
      continue
    fi
    runs=$((runs + 1))
    compare_file "$golden/series.csv" "$out/series.csv" "$label"
    # every VTK file kept, and no VTK file the golden run did not write
    if [[ -d $golden/vtk || -d $out/vtk ]]; then
      for f in "$golden"/vtk/*; do compare_file "$f" "$out/vtk/$(basename "$f")" "$label"; done
      for f in "$out"/vtk/*; do
        [[ -f $golden/vtk/$(basename "$f") ]] || { echo "FAIL $label: unexpected $(basename "$f")"; failures=$((failures + 1)); }
      done
    fi
  done
done <"$here/runs.txt"

if ((runs == 0)); then
  echo "FAIL: no run listed in $here/runs.txt"
  exit 1
fi
if ((failures > 0)); then
  echo "$failures difference(s) from the golden series (regenerate only after a change of physics made on purpose: scripts/make-golden-series.sh)"
  exit 1
fi
echo "all $runs runs identical to the golden series, byte for byte"
