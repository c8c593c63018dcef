#!/usr/bin/env bash
# Fuzzes the scene parser with libFuzzer for a bounded time.
#
#   scripts/fuzz-scene-parser.sh [seconds] [jobs]     (defaults: 60 seconds, 1 job)
#
# Builds fuzz/ with clang in build-fuzz/, seeds the corpus with every scene in the tree (the
# hostile-input corpus tests/data/hostile/ included), and
# copies any input that crashes, leaks or hangs into tests/data/scenes/fuzz/, where the scene
# tests load it as a regression case. Exit status: 0 when nothing was found, 1 otherwise.
set -euo pipefail

seconds="${1:-60}"
jobs="${2:-1}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${root}/build-fuzz"
corpus="${build}/corpus"
findings="${build}/findings"
regressions="${root}/tests/data/scenes/fuzz"

# build the fuzzer on its own: no need for the GUI, tests or benchmarks
cmake -S "${root}/fuzz" -B "${build}" -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "${build}" --target scene_parser_fuzz

# seed corpus: shipped scenes, test scenes and earlier findings
mkdir -p "${corpus}" "${findings}" "${regressions}"
while IFS= read -r -d '' seed; do
  relative="${seed#"${root}/"}"
  cp -f "${seed}" "${corpus}/${relative//\//_}"
done < <(find "${root}/scenes" "${root}/tests/data/scenes" "${root}/tests/data/hostile/scenes" "${root}/fuzz/seeds" \
           -type f -name '*.toml' -size -8k -print0)

"${build}/scene_parser_fuzz" "${corpus}" \
  -dict="${root}/fuzz/scene.dict" \
  -max_total_time="${seconds}" -timeout=10 -rss_limit_mb=2048 -max_len=8192 \
  -jobs="${jobs}" -workers="${jobs}" \
  -artifact_prefix="${findings}/" -print_final_stats=1 || true

# keep what it found as regression inputs
found=0
for artifact in "${findings}"/crash-* "${findings}"/leak-* "${findings}"/timeout-* "${findings}"/oom-*; do
  [ -e "${artifact}" ] || continue
  cp "${artifact}" "${regressions}/$(basename "${artifact}").toml"
  echo "finding kept: tests/data/scenes/fuzz/$(basename "${artifact}").toml"
  found=1
done
[ "${found}" -eq 0 ] && echo "no crashing input found in ${seconds} s"
exit "${found}"
