"""The command line's modes and identification in ten lines of Python.

Sample run (from the repository root, after scripts/test.sh or with
PYTHONPATH=build/python):
    $ python3 examples/python/quickstart.py out/large-rig-measurement
    {"frequencies_hz": [9.1, ...], "cog": [0.511, -0.008, -0.598], "cog_rigid": [...]}
The first argument is a measurement folder (rigflex simulate's --out); the
beam frame's eight modes and both algorithms' CoG (m) print as JSON.
"""
import json, sys
import rigflex

modes = rigflex.modes(rigflex.read_model("examples/beam-frame/model.yaml"), count=8)
rig = rigflex.read_rig("examples/large-rig/rig.yaml")
result = rigflex.identify(rig, rigflex.read_measurements([sys.argv[1]]), algorithm="both")
print(json.dumps({"frequencies_hz": modes["frequencies_hz"].tolist(), "cog": result["mean"]["cog"],
                  "cog_rigid": result["algorithms"]["rigid"]["mean"]["cog"]}))
