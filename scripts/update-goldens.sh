#!/usr/bin/env bash
# Regenerates the golden images in tests/golden/ after an intended change of the pictures.
# Look at every changed image (git diff --stat tests/golden) before committing them.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset release >/dev/null
cmake --build --preset release --target test_headless
PERIFLEX_UPDATE_GOLDENS=1 build/tests/test_headless --gtest_filter='ShippedScenes/SceneGolden.*:MagnifiedGolden.*'
