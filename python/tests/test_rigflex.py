"""The Python module against the command line (the same library through two
doors must give the same numbers) and against independent checks (SciPy on
the matrices the module returns). Run by ctest (python_module) with
PYTHONPATH at the build's package, RIGFLEX_CLI the command line and
RIGFLEX_SOURCE_DIR the checkout."""
import json
import os
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest
import scipy.io
import scipy.sparse

import rigflex

SOURCE = Path(os.environ.get("RIGFLEX_SOURCE_DIR", Path(__file__).resolve().parents[2]))
CLI = os.environ.get("RIGFLEX_CLI", str(SOURCE / "build" / "rigflex"))
BEAM_FRAME = SOURCE / "examples" / "beam-frame" / "model.yaml"
LARGE_RIG = SOURCE / "examples" / "large-rig" / "rig.yaml"
SMALL_RIG = SOURCE / "examples" / "small-rig" / "rig.yaml"
# The large rig with rigid frames (examples/hidden-effect): compare and diagnose in seconds.
RIGID_FRAMES_RIG = SOURCE / "examples" / "hidden-effect" / "rig.yaml"


def cli(*args, cwd=None):
    done = subprocess.run([CLI, *map(str, args)], cwd=cwd, capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    return done


@pytest.fixture(scope="module")
def measurement(tmp_path_factory):
    """The demo's virtual measurement of the large rig, written by the command line."""
    out = tmp_path_factory.mktemp("meas") / "large-rig-measurement"
    cli("simulate", LARGE_RIG, "--sets", 1, "--histories", 6, "--duration", 15, "--seed", 1, "--quiet", "--out", out)
    return out


def test_modes_equal_the_command_lines_and_are_eigenpairs(tmp_path):
    frame = rigflex.read_model(str(BEAM_FRAME))
    modes = rigflex.modes(frame, count=8)
    cli("modes", BEAM_FRAME, "--count", 8, "--quiet", "--out", tmp_path)
    written = json.loads((tmp_path / "modes.json").read_text())
    f_cli = np.array([m["frequency_hz"] for m in written["modes"]])
    # The same solver on the same matrices: equal to the JSON's printed digits.
    np.testing.assert_allclose(modes["frequencies_hz"], f_cli, rtol=1e-9)
    # Independently of the solver: K x = lambda M x and X' M X = I with SciPy's sparse products.
    system = rigflex.assemble(frame)
    K, M, X = system["K"], system["M"], modes["shapes"]
    assert scipy.sparse.issparse(K) and K.shape == (len(system["dofs"]),) * 2
    lam = (2 * np.pi * modes["frequencies_hz"]) ** 2
    residual = np.linalg.norm(K @ X - (M @ X) * lam, axis=0) / np.linalg.norm(K @ X, axis=0)
    assert residual.max() < 1e-8
    assert np.abs(X.T @ (M @ X) - np.eye(8)).max() < 1e-10
    assert modes["orthogonality_error"] < 1e-10
    # The clamped frame: no mode of zero frequency, none ill-determined, as modes.json says.
    assert modes["zero_frequency_modes"] == written["zero_frequency_modes"] == []
    assert modes["ill_determined_modes"] == written["ill_determined_modes"] == []


# A 1 kg block on 1 N/m springs carrying two 1 g parts on 1e10 N/m springs:
# rounding leaves the mount modes' frequencies to about 1e-5 (the C++ test,
# tests/reduction/test_ill_determined_modes.cpp); the module and modes.json
# list the same modes.
STIFF_BRACKET = """
nodes:
  - [1, 0, 0, 0]
  - [2, 0.1, 0, 0]
  - [3, 0.2, 0, 0]
point_masses:
  - {id: block, node: 1, mass: 1, inertia: [1e-2, 1e-2, 1e-2, 0, 0, 0]}
  - {id: p2, node: 2, mass: 1e-3, inertia: [1e-5, 1e-5, 1e-5, 0, 0, 0]}
  - {id: p3, node: 3, mass: 1e-3, inertia: [1e-5, 1e-5, 1e-5, 0, 0, 0]}
springs:
  - {id: mount, node: 1, stiffness: [1, 1, 1, 1, 1, 1]}
  - {id: b2, node: 1, other: 2, stiffness: [1e10, 1e10, 1e10, 1e10, 1e10, 1e10]}
  - {id: b3, node: 2, other: 3, stiffness: [1e10, 1e10, 1e10, 1e10, 1e10, 1e10]}
"""


def test_ill_determined_modes_are_listed_as_by_the_command_line(tmp_path):
    path = tmp_path / "bracket.yaml"
    path.write_text(STIFF_BRACKET)
    modes = rigflex.modes(rigflex.read_model(str(path)), count=8)
    vague = modes["ill_determined_modes"]
    assert vague and vague[0]["mode"] == 1
    assert all(1e-6 < v["relative_error"] < 1 for v in vague)
    cli("modes", path, "--count", 8, "--quiet", "--out", tmp_path / "out")
    written = json.loads((tmp_path / "out" / "modes.json").read_text())
    assert [v["mode"] for v in vague] == [v["mode"] for v in written["ill_determined_modes"]]


def test_identification_equals_the_command_lines(measurement, tmp_path):
    rig = rigflex.read_rig(str(LARGE_RIG))
    sets = rigflex.read_measurements([str(measurement)])
    assert len(sets) == 1 and len(sets[0]) == 6 and sets[0][0].force.shape == (sets[0][0].t.size, rig.rods)
    result = rigflex.identify(rig, sets, algorithm="both")
    cli("identify", LARGE_RIG, measurement, "--algorithm", "both", "--quiet", "--out", tmp_path)
    written = json.loads((tmp_path / "identification.json").read_text())
    for algorithm in ("rigid", "flexible"):
        mine, theirs = result["algorithms"][algorithm], written["algorithms"][algorithm]
        np.testing.assert_allclose(mine["mean"]["cog"], theirs["mean"]["cog"], rtol=0, atol=1e-12)
        np.testing.assert_allclose(mine["mean"]["inertia"], theirs["mean"]["inertia"], rtol=1e-12)
        assert len(mine["tests"]) == 6
        for a, b in zip(mine["tests"], theirs["tests"]):
            np.testing.assert_allclose(a["cog"], b["cog"], rtol=0, atol=1e-12)
    # The flexible algorithm finds the large rig's CoG height (examples/large-rig/rig.yaml: -0.598 m).
    assert abs(result["mean"]["cog"][2] - rig.body["cog"][2]) < 0.002


def test_quickstart_script_reproduces_the_command_line(measurement, tmp_path):
    script = SOURCE / "examples" / "python" / "quickstart.py"
    code = [l for l in script.read_text().split('"""')[2].splitlines() if l.strip()]
    assert len(code) <= 10, "the quickstart is ten lines of code"
    env = dict(os.environ)
    done = subprocess.run([sys.executable, str(script), str(measurement)], cwd=SOURCE, env=env, capture_output=True,
                          text=True)
    assert done.returncode == 0, done.stderr
    printed = json.loads(done.stdout)
    cli("modes", BEAM_FRAME, "--count", 8, "--quiet", "--out", tmp_path / "modes")
    f_cli = [m["frequency_hz"] for m in json.loads((tmp_path / "modes" / "modes.json").read_text())["modes"]]
    np.testing.assert_allclose(printed["frequencies_hz"], f_cli, rtol=1e-9)
    cli("identify", LARGE_RIG, measurement, "--algorithm", "both", "--quiet", "--out", tmp_path / "id")
    written = json.loads((tmp_path / "id" / "identification.json").read_text())
    np.testing.assert_allclose(printed["cog"], written["mean"]["cog"], rtol=0, atol=1e-12)
    np.testing.assert_allclose(printed["cog_rigid"], written["algorithms"]["rigid"]["mean"]["cog"], rtol=0, atol=1e-12)


def test_the_mass_sweep_example_plots_the_rigid_error_growing(tmp_path):
    script = SOURCE / "examples" / "python" / "mass_sweep.py"
    png = tmp_path / "sweep.png"
    done = subprocess.run([sys.executable, str(script), "--scales", "0.5,1,2", "--out", str(png)], cwd=SOURCE,
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert png.stat().st_size > 10000 and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    rows = [l for l in done.stdout.splitlines() if l.startswith("mass ")]
    rigid = [float(l.split("rigid zG error ")[1].split(" mm")[0]) for l in rows]
    flexible = [float(l.split("flexible ")[1].split(" mm")[0]) for l in rows]
    # The soft frame: the rigid algorithm's error grows with the load, the flexible one stays within 2 mm.
    assert len(rows) == 3 and abs(rigid[0]) < abs(rigid[1]) < abs(rigid[2]) and abs(rigid[0]) > 5
    assert max(abs(f) for f in flexible) < 2


def test_simulation_is_the_command_lines_to_the_files_digits(tmp_path):
    rig = rigflex.read_rig(str(SMALL_RIG))
    sets = rigflex.simulate(rig, sets=1, histories=2, duration=3.0, seed=4)
    cli("simulate", SMALL_RIG, "--sets", 1, "--histories", 2, "--duration", 3, "--seed", 4, "--quiet", "--out", tmp_path)
    files = rigflex.read_measurements([str(tmp_path)])
    for mine, read in zip(sets[0], files[0]):
        np.testing.assert_allclose(mine.t, read.t, rtol=0, atol=1e-9)
        # The files keep 9 significant digits (docs/measurement-files.md).
        np.testing.assert_allclose(mine.force, read.force, rtol=1e-8, atol=1e-6)
        np.testing.assert_allclose(mine.alpha, read.alpha, rtol=0, atol=1e-9)


def test_reduction_equals_the_command_lines_files(tmp_path):
    frame_file = SOURCE / "examples" / "carrying-frame" / "model.yaml"
    frame = rigflex.read_model(str(frame_file))
    cli("reduce", frame_file, "--interface", "lower_joints", "--method", "craig-bampton", "--modes", 6, "--quiet",
        "--out", tmp_path)
    reduced = rigflex.reduce(frame, "lower_joints", method="craig-bampton", modes=6)
    K = scipy.io.mmread(str(tmp_path / "K.mtx"))
    K = K.toarray() if scipy.sparse.issparse(K) else K
    np.testing.assert_allclose(reduced["K"], K, rtol=1e-12, atol=1e-12 * np.abs(K).max())
    assert len(reduced["interface_dofs"]) == 6 * 3 and reduced["K"].shape == (24, 24)
    # A free frame's state space: exactly twelve zero eigenvalues (six rigid motions), the rest stable.
    eig = np.linalg.eigvals(reduced["state_space"]["A"])
    assert np.sum(eig == 0) == 12
    assert eig.real.max() <= 0


def test_compare_and_diagnose_on_clean_records():
    rig = rigflex.read_rig(str(RIGID_FRAMES_RIG))
    records = rigflex.simulate(rig, sets=1, histories=2, duration=8.0, seed=2)[0]
    compared = rigflex.compare(rig, records, hold_body=True)
    assert compared["overall_nrmse"] < 0.05
    assert len(compared["model_channels"]) == 2 and compared["model_channels"][0].shape == (records[0].t.size,
                                                                                            3 * rig.rods)
    found = rigflex.diagnose(rig, records)
    assert found["missing_effect"] is None, found["summary"]
    assert found["baseline"]["gate"] == 1 + max(3.0, found["baseline"]["numerics_allowance"])
    strict = rigflex.diagnose(rig, records, period_tolerance=0.0)
    assert strict["baseline"]["numerics_allowance"] == 0.0 and strict["baseline"]["gate"] == 4.0


def test_long_calls_release_the_gil():
    rig = rigflex.read_rig(str(RIGID_FRAMES_RIG))
    records = rigflex.simulate(rig, sets=1, histories=2, duration=8.0, seed=3)[0]
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    start = time.perf_counter()
    rigflex.compare(rig, records)  # seconds of C++ work
    end = time.perf_counter()
    done.set()
    counter.join()
    during = [t for t in ticks if start < t < end]
    # With the GIL held the counter could not run until compare returned.
    assert end - start > 0.2 and len(during) > 10


def test_bad_input_names_the_file_and_line(tmp_path):
    bad = tmp_path / "rig.yaml"
    text = RIGID_FRAMES_RIG.read_text()
    assert "\n  mass: " in text
    bad.write_text(text.replace("\n  mass: ", "\n  mass: -", 1))  # the body's mass
    with pytest.raises(ValueError, match=str(bad)):
        rigflex.read_rig(str(bad))
    with pytest.raises(ValueError):
        rigflex.read_model(str(tmp_path / "missing.yaml"))
    rig = rigflex.read_rig(str(RIGID_FRAMES_RIG))
    with pytest.raises(ValueError):
        rig.with_body(mass=-1.0)
    with pytest.raises(ValueError, match="algorithm"):
        rigflex.identify(rig, [[]], algorithm="magic")
