#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on the bundled
# examples: the modes of the rig's fixed frame, written for ParaView, and
# the fixed and carrying frames reduced onto their joints, then the large
# rig's design check, a virtual measurement (6 histories) and its
# identification by the rigid and the flexible algorithm.
set -euo pipefail
cd "$(dirname "$0")/.."
# Only what the demo needs: no test suite, benchmarks or test oracles
# (scripts/test.sh installs and builds those).
bash scripts/install-deps.sh demo
bash scripts/build.sh -DRIGFLEX_BUILD_TESTS=OFF -DRIGFLEX_BUILD_BENCH=OFF
bash scripts/run_demo.sh build/rigflex out
