#!/usr/bin/env bash
# Installs what is missing, builds (the Python module too: build/python;
# and the MPI eigen backend),
# installs the Python module where Debian's python3 finds it
# (/usr/local/lib/python3.X/dist-packages: `import rigflex` from anywhere),
# and runs the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
# Explicitly on: a build folder the demo configured has them off.
# Debian's python3, the one install-deps gave NumPy, SciPy and pytest (not
# whichever python3 comes first on PATH).
bash scripts/build.sh -DRIGFLEX_BUILD_TESTS=ON -DRIGFLEX_BUILD_BENCH=ON -DRIGFLEX_PYTHON=ON -DRIGFLEX_SLEPC=ON \
  -DPython3_EXECUTABLE=/usr/bin/python3
cmake --install "${BUILD_DIR:-build}" --component python
ctest --test-dir "${BUILD_DIR:-build}" --output-on-failure -j "${JOBS:-2}"
