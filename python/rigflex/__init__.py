"""rigflex from Python: flexible models of multi-filar pendulum rigs.

Finite-element frames and their modes, reduction onto the joints, rig
simulation with virtual sensors, identification of mass properties, and
compare / diagnose of a model against measurements - the library behind the
`rigflex` command line, with NumPy arrays and SciPy sparse matrices in and
out (docs/python.md). Long calls release the GIL, so threads can run them
side by side.

    import rigflex
    frame = rigflex.read_model("examples/beam-frame/model.yaml")
    modes = rigflex.modes(frame, count=8)          # modes["frequencies_hz"]
    rig = rigflex.read_rig("examples/large-rig/rig.yaml")
    sets = rigflex.simulate(rig, histories=6, seed=1)
    result = rigflex.identify(rig, sets, algorithm="both")
    print(result["mean"]["cog"])                   # as identification.json

Bad input raises ValueError (rigflex.InputError, rigflex.ModelError) with
the file, line and key named, as the command line reports it.
"""

from ._rigflex import (  # noqa: F401  (the public API)
    InputError,
    Model,
    ModelError,
    Record,
    Rig,
    assemble,
    compare,
    diagnose,
    identify,
    modes,
    read_measurements,
    read_model,
    read_rig,
    reduce,
    simulate,
)

__all__ = [
    "InputError", "Model", "ModelError", "Record", "Rig", "assemble", "compare", "diagnose", "identify", "modes",
    "read_measurements", "read_model", "read_rig", "reduce", "simulate",
]
