#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on the bundled
# example: the modes of the rig's fixed frame, written for ParaView.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
./build/rigflex mass examples/beam-frame/model.yaml
./build/rigflex modes examples/beam-frame/model.yaml --count 8 --out out/beam-frame
