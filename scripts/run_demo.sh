#!/usr/bin/env bash
# The demo's commands on the bundled examples, with a given binary into a
# given folder (relative to the repository root, or absolute):
#   bash scripts/run_demo.sh RIGFLEX OUT_DIR
# scripts/demo.sh runs it after installing and building; scripts/demo_diff.sh
# runs it with two binaries to show that a change left every output alone.
set -euo pipefail
cd "$(dirname "$0")/.."
rigflex=$(realpath "${1:-build/rigflex}")
out=${2:-out}
"$rigflex" mass examples/beam-frame/model.yaml
"$rigflex" modes examples/beam-frame/model.yaml --count 8 --out "$out/beam-frame"
"$rigflex" reduce examples/beam-frame/model.yaml --interface upper_joints --out "$out/fixed-frame-reduced"
"$rigflex" reduce examples/carrying-frame/model.yaml --interface lower_joints \
  --method craig-bampton --modes 12 --out "$out/carrying-frame-reduced"
"$rigflex" check examples/large-rig/rig.yaml --out "$out/large-rig-check"
"$rigflex" simulate examples/large-rig/rig.yaml --sets 1 --histories 6 --duration 15 --seed 1 \
  --out "$out/large-rig-measurement"
"$rigflex" identify examples/large-rig/rig.yaml "$out/large-rig-measurement" --algorithm both \
  --out "$out/large-rig-identification"
# The compare-diagnose loop (examples/hidden-effect/README.md): the model
# misses the fixed frame's flexibility; diagnose finds it; the error falls.
bash examples/hidden-effect/run.sh "$rigflex" "$out/hidden-effect"
