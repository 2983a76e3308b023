#!/usr/bin/env bash
# Installs what is missing, builds, and runs the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
# Explicitly on: a build folder the demo configured has them off.
bash scripts/build.sh -DRIGFLEX_BUILD_TESTS=ON -DRIGFLEX_BUILD_BENCH=ON
ctest --test-dir "${BUILD_DIR:-build}" --output-on-failure -j "${JOBS:-2}"
