#!/usr/bin/python3
"""Rebuilds a Simscape Reduced Order Flexible Solid's inputs from a reduced.mat
with SciPy (a MATLAB-compatible reader independent of matio) and prints what
it found as JSON; tests/apps/test_cli_reduce.cpp judges it.

    /usr/bin/python3 simscape_inputs.py DIR/reduced.mat   (Debian's, with python3-scipy)

The block takes the interface frame origins, the number of modes, K, M and a
damping matrix, the coordinates ordered six DOFs per frame (translations then
rotations) followed by the modes.
"""
import json
import sys

import numpy as np
import scipy.io as sio


def main(path):
    v = sio.loadmat(path)
    origins = np.asarray(v["interface_coordinates"], dtype=float)
    frames = origins.shape[0]
    nodes = np.asarray(v["interface_nodes"], dtype=float).ravel()
    K, M, C = (np.asarray(v[k], dtype=float) for k in ("K", "M", "C"))
    n = K.shape[0]
    modes = np.asarray(v["mode_frequencies_hz"]).size
    dof_node = np.asarray(v["dof_node"], dtype=float).ravel()
    dof_index = np.asarray(v["dof_index"], dtype=float).ravel()
    six_per_frame = (
        dof_index.size == 6 * frames
        and bool(np.all(dof_index.reshape(frames, 6) == np.arange(1, 7)))
        and bool(np.all(dof_node.reshape(frames, 6) == nodes[:, None]))
    )
    symmetric = max(np.abs(X - X.T).max() / np.abs(X).max() for X in (K, M, C))
    try:
        np.linalg.cholesky(M)
        mass_positive = True
    except np.linalg.LinAlgError:
        mass_positive = False
    # LAPACK's geev balances first, which isolates the exact structural
    # zeros that the modal form holds.
    lam = np.linalg.eigvals(np.asarray(v["A"], dtype=float))
    zero = int(np.count_nonzero(lam == 0))
    nonzero = lam[lam != 0]
    # The same frame in physical coordinates, x = [z; z'], for comparison.
    Minv = np.linalg.inv(M)
    A_phys = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ C]])
    lam_phys = np.linalg.eigvals(A_phys)
    smallest_phys = np.sort(np.abs(lam_phys))[:12]
    print(json.dumps({
        "frames": frames,
        "coordinates": n,
        "modes": modes,
        "six_dofs_per_frame": six_per_frame,
        "origins_finite": bool(np.all(np.isfinite(origins))),
        "symmetry_error": float(symmetric),
        "mass_positive_definite": mass_positive,
        "A_zero_eigenvalues": zero,
        "A_largest_real_part_of_the_others": float(nonzero.real.max()) if nonzero.size else None,
        "T_shape": list(np.asarray(v["T"]).shape),
        "physical_A_largest_of_12_smallest_eigenvalues": float(smallest_phys.max()),
        "physical_A_largest_real_part": float(lam_phys.real.max()),
    }))


if __name__ == "__main__":
    main(sys.argv[1])
