#!/bin/sh
# Runs the clamped-plate benchmark (bench/bench_plate_modes.cpp) the way its
# table in the issue was produced: all peers up to 150k DOFs, rigflex alone
# above; rigflex timings are the best of two runs. The machine should be
# otherwise idle (the table reports the load average at the start of each
# size); under load, OPENBLAS_NUM_THREADS=1 makes CHOLMOD's solves less
# sensitive to the competition for the cores.
#
# Usage: bench/run_plate_bench.sh <build-dir> [sizes] [extra options...]
#   e.g. bench/run_plate_bench.sh ../build 10k,100k,500k,1M
# The markdown tables go to stdout and to <build-dir>/bench_plate_modes.md,
# progress to stderr.
set -eu
build=${1:?usage: run_plate_bench.sh <build-dir> [sizes] [options...]}
sizes=${2:-10k,100k,500k,1M}
[ $# -ge 2 ] && shift 2 || shift $#
here=$(cd "$(dirname "$0")" && pwd)
"$build/bench/bench_plate_modes" --sizes "$sizes" --max-peer-dofs 150000 --repeat 2 \
  --scipy-script "$here/scipy_eigsh.py" "$@" | tee "$build/bench_plate_modes.md"
