#!/usr/bin/python3
"""SciPy peer of bench/bench_plate_modes.cpp.

Reads K and M (Matrix Market, as written by the benchmark), solves
K x = lambda M x for the `count` eigenvalues nearest `sigma` with ARPACK
shift-invert (scipy.sparse.linalg.eigsh, which factors K - sigma M with
SuperLU), and prints one JSON line: the eigsh wall time (reading the files
is timed separately and is not part of it), the frequencies in Hz, the
largest relative residual ||K x - lambda M x|| / ||K x|| and the process's
peak RSS before and after eigsh.

Usage: scipy_eigsh.py K.mtx M.mtx count sigma tol
Run with Debian's /usr/bin/python3 (python3-scipy).
"""
import json
import resource
import sys
import time

import numpy as np
import scipy
import scipy.io
import scipy.sparse.linalg as sla


def peak_rss_kb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss


def main():
    k_file, m_file, count, sigma, tol = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
    t0 = time.perf_counter()
    K = scipy.io.mmread(k_file).tocsc()
    M = scipy.io.mmread(m_file).tocsc()
    read_seconds = time.perf_counter() - t0
    rss_read = peak_rss_kb()

    t0 = time.perf_counter()
    vals, vecs = sla.eigsh(K, k=count, M=M, sigma=sigma, which="LM", tol=tol)
    eigsh_seconds = time.perf_counter() - t0

    order = np.argsort(vals)
    vals, vecs = vals[order], vecs[:, order]
    KX = K @ vecs
    R = KX - (M @ vecs) * vals
    residual = float(np.max(np.linalg.norm(R, axis=0) / np.linalg.norm(KX, axis=0)))
    print(json.dumps({
        "scipy": scipy.__version__,
        "n": K.shape[0],
        "read_seconds": read_seconds,
        "eigsh_seconds": eigsh_seconds,
        "frequencies_hz": [float(np.sqrt(max(v, 0.0)) / (2 * np.pi)) for v in vals],
        "max_residual": residual,
        "peak_rss_kb_after_read": rss_read,
        "peak_rss_kb": peak_rss_kb(),
    }))


if __name__ == "__main__":
    main()
