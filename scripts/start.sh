#!/usr/bin/env bash
# Quick start, command 1: install what is missing, build Release, run the default scene.
# With a display the visualiser opens; without one the scene is recorded off-screen
# (frames, a movie when ffmpeg is present, series.csv and summary.json under out/).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j"$(nproc)"
exec build/src/periflex "$@"
