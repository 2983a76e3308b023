#!/usr/bin/env bash
# The compare-diagnose loop of README.md, start to end:
#   bash run.sh RIGFLEX OUT_DIR
# simulates the lab's measurements from truth.yaml (the fixed frame
# deforms), compares the engineer's model rig.yaml (rigid fixed frame) with
# them, diagnoses the missing effect, adds the fitted stand-in and then the
# proper FE frame model, comparing each version into one study folder.
# The test suite runs it (tests/apps/test_tutorial_hidden_effect.cpp).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
rigflex=$(realpath "${1:-./rigflex}")
out=${2:-hidden-effect-run}
mkdir -p "$out"
cd "$out"
"$rigflex" simulate "$here/truth.yaml" --sets 1 --histories 6 --duration 15 --seed 3 --out data --quiet
echo "== 1. the engineer's model against the measurements"
"$rigflex" compare "$here/rig.yaml" data --study study --out compare-1 --quiet
echo "== 2. which effect does it miss?"
"$rigflex" diagnose "$here/rig.yaml" data --out diagnosis --quiet
echo "== 3. the fitted stand-in added"
"$rigflex" compare "$here/rig.yaml" data --effects diagnosis/effects/fixed_frame_flexibility.yaml --study study \
  --out compare-2 --quiet
echo "== 4. the fixed frame's FE model added, as the diagnosis advises"
"$rigflex" compare "$here/rig.yaml" data --effects "$here/fixed-frame-effect.yaml" --study study --out compare-3 --quiet
