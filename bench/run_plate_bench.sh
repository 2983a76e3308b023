#!/bin/sh
# Runs the clamped-plate benchmark (bench/bench_plate_modes.cpp) the way its
# table in docs/eigen-solver.md was produced: all peers up to 150k DOFs,
# rigflex alone above (pass --max-peer-dofs to change that); rigflex timings
# are the best of two runs; the Lanczos block size is the solver's automatic
# choice unless --block is given (the table reports the size used).
# The machine should be otherwise idle (the table reports the load average
# at the start of each size). Everything runs on one thread unless
# OPENBLAS_NUM_THREADS is set: CalculiX (--ccx-threads 1), SciPy and
# CHOLMOD's factorization (rigflex's solves always do). On the shared 2-core
# machine of the table, two OpenBLAS threads made the 100k factorization
# 5-10x slower whenever other work ran (0.4-0.9 s with one thread, 5-6 s with
# two, at load 5), and one thread was as fast or faster in every run there.
#
# Usage: bench/run_plate_bench.sh <build-dir> [sizes] [extra options...]
#   e.g. bench/run_plate_bench.sh ../build 10k,100k,500k,1M
#        bench/run_plate_bench.sh ../build 1M --skip-ccx --max-peer-dofs 2M
# The markdown tables go to stdout and to <build-dir>/bench_plate_modes.md,
# progress to stderr.
set -eu
build=${1:?usage: run_plate_bench.sh <build-dir> [sizes] [options...]}
sizes=${2:-10k,100k,500k,1M}
[ $# -ge 2 ] && shift 2 || shift $#
here=$(cd "$(dirname "$0")" && pwd)
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
"$build/bench/bench_plate_modes" --sizes "$sizes" --max-peer-dofs 150000 --repeat 2 \
  --scipy-script "$here/scipy_eigsh.py" "$@" | tee "$build/bench_plate_modes.md"
