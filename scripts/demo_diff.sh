#!/usr/bin/env bash
# Shows that a change left the demo's outputs alone: builds the command line
# of BASE (a commit, default HEAD~1) in a temporary worktree, runs
# scripts/run_demo.sh with it and with this checkout's build, and compares
# every output file byte for byte.
#   bash scripts/demo_diff.sh [BASE] [BUILD_DIR]
# Files that record when or how fast a run went are compared with those
# fields masked (see mask() below); all others exactly. Exit 0 when identical.
# BASE_RIGFLEX=path/to/rigflex uses that binary as the base instead of
# building BASE (a copy kept from before a change saves a build).
set -euo pipefail
cd "$(dirname "$0")/.."
base=${1:-HEAD~1}
build=${2:-build}
work=$(mktemp -d)
trap 'git worktree remove --force "$work/base" >/dev/null 2>&1 || true; rm -rf "$work"' EXIT
if [ -n "${BASE_RIGFLEX:-}" ]; then
  base_rigflex=$(realpath "$BASE_RIGFLEX")
else
  git worktree add --detach "$work/base" "$base" >/dev/null
  if [ -d third_party/js/node_modules ]; then cp -r third_party/js/node_modules "$work/base/third_party/js/"; fi
  echo "demo_diff: building $base"
  cmake -S "$work/base" -B "$work/base-build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DRIGFLEX_BUILD_TESTS=OFF -DRIGFLEX_BUILD_BENCH=OFF >/dev/null
  cmake --build "$work/base-build" -j "${JOBS:-2}" --target rigflex >/dev/null
  base_rigflex="$work/base-build/rigflex"
fi
cmake --build "$build" -j "${JOBS:-2}" --target rigflex >/dev/null
echo "demo_diff: running the demo with both"
# The demo's examples are the same in both trees (the run uses this checkout's).
# Both into the same folder, which files and the terminal name, then set aside.
bash scripts/run_demo.sh "$base_rigflex" "$work/out" >"$work/before.log" 2>&1
mv "$work/out" "$work/before"
bash scripts/run_demo.sh "$build/rigflex" "$work/out" >"$work/after.log" 2>&1
mv "$work/out" "$work/after"
# Wall-clock figures: timings in JSON ("..._seconds": x, "seconds": x,
# "elapsed_s": x) and on the terminal ("in 1.23 s").
mask() {
  sed -E 's/("[a-z_]*(seconds|elapsed_s|_time_s)": )[-0-9.eE+]+/\1T/g; s/[0-9.]+ ?s\b/T s/g' "$1"
}
status=0
while IFS= read -r f; do
  a="$work/before/$f"; b="$work/after/$f"
  if [ ! -f "$b" ]; then echo "only before: $f"; status=1; continue; fi
  if ! cmp -s "$a" "$b"; then
    if [[ "$f" == *.json || "$f" == *.html ]] && diff -q <(mask "$a") <(mask "$b") >/dev/null; then
      echo "same but for timings: $f"
    else
      echo "differs: $f"; status=1
    fi
  fi
done < <(cd "$work/before" && find . -type f | sort)
while IFS= read -r f; do
  [ -f "$work/before/$f" ] || { echo "only after: $f"; status=1; }
done < <(cd "$work/after" && find . -type f | sort)
if ! diff -q <(mask "$work/before.log") <(mask "$work/after.log") >/dev/null; then
  echo "the terminal output differs:"; diff <(mask "$work/before.log") <(mask "$work/after.log") | head -40; status=1
fi
n=$(cd "$work/before" && find . -type f | wc -l)
if [ $status -eq 0 ]; then echo "demo_diff: all $n output files and the terminal output identical"; fi
exit $status
