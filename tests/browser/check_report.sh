#!/usr/bin/env bash
# Opens an HTML report of rigflex (report/html_report) in headless Chromium and
# checks that it works: no errors in the page, every plot drawn, and a
# screenshot that is not blank. See docs/reports.md.
#   tests/browser/check_report.sh REPORT.html EXPECTED_PLOTS
# Needs Debian's chromium (scripts/install-deps.sh installs it) and node; the
# browser is taken from $CHROMIUM when set. Without a browser the check FAILS.
# Leaves the screenshot beside the report (REPORT.png).
set -euo pipefail

if [ "$#" -ne 2 ] || ! [[ "$2" =~ ^[0-9]+$ ]]; then
  echo "usage: $0 REPORT.html EXPECTED_PLOTS" >&2
  exit 2
fi
report=$(realpath "$1")
expected=$2
here=$(cd "$(dirname "$0")" && pwd)

fail() {
  echo "check_report: FAIL: $*" >&2
  exit 1
}

[ -f "$report" ] || fail "no report at $report"
browser=${CHROMIUM:-chromium}
command -v "$browser" >/dev/null 2>&1 ||
  fail "'$browser' not found: the browser test needs Debian's chromium (run scripts/install-deps.sh, or apt-get install chromium)"
command -v node >/dev/null 2>&1 || fail "node not found (run scripts/install-deps.sh)"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
url="file://$report"
# A fresh profile per run (parallel runs do not share one); no sandbox as
# root in containers; virtual time lets the page finish before the dump.
flags=(--headless=new --no-sandbox --disable-gpu --disable-dev-shm-usage --no-first-run
       --disable-extensions --hide-scrollbars --user-data-dir="$work/profile" --virtual-time-budget=5000)

run_browser() {  # log-file, then extra arguments
  local log=$1
  shift
  if ! timeout 180 "$browser" "${flags[@]}" "$@" "$url" 2>"$log"; then
    cat "$log" >&2
    fail "chromium failed on $report"
  fi
}

# 1. The page's own verdict, from the DOM after the scripts ran.
run_browser "$work/dom.log" --dump-dom >"$work/dom.html"
body=$(grep -o -m1 '<body[^>]*>' "$work/dom.html" || true)
[ -n "$body" ] || { cat "$work/dom.log" >&2; fail "no <body> in the DOM chromium dumped"; }
attr() { sed -n "s/.* $1=\"\\([^\"]*\\)\".*/\\1/p" <<<"$body"; }
plots=$(attr data-plots)
rendered=$(attr data-plots-rendered)
errors=$(attr data-errors)
blank=$(attr data-blank-plots)
echo "check_report: $report: $plots plots in the page, $rendered rendered, $errors errors (expected $expected plots)"
if [ "${errors:-x}" != "0" ]; then
  # The page lists its errors in <pre id="report-errors">.
  sed -n '/<pre id="report-errors"/,/<\/pre>/p' "$work/dom.html" | head -n 40 >&2
  [ -n "$errors" ] || fail "the page did not finish rendering (no data-errors on <body>: a script failed to run)"
  fail "$errors error(s) in the page"
fi
[ "$plots" = "$expected" ] || fail "the page has $plots plots, expected $expected"
[ "$rendered" = "$expected" ] || fail "$rendered of $expected plots rendered (blank: ${blank:-none})"

# 2. A screenshot tall enough for every plot, not blank.
height=$((600 + 500 * expected))
[ "$height" -le 12000 ] || height=12000
shot="${report%.html}.png"
run_browser "$work/shot.log" --window-size=1280,"$height" --screenshot="$shot" >/dev/null
[ -s "$shot" ] || { cat "$work/shot.log" >&2; fail "chromium wrote no screenshot"; }
stats=$(node "$here/png_stats.mjs" "$shot") || fail "screenshot $shot"
echo "check_report: screenshot $shot: $stats"
echo "check_report: OK"
