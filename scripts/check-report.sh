#!/usr/bin/env bash
# check-report.sh - render an alea report.html in headless Chromium and check the screenshot.
#
# Usage:
#   scripts/check-report.sh [REPORT_HTML] [OUT_PNG]
#
#   REPORT_HTML  the page to render. Default: build one from the report module's synthetic test
#                study (cargo test -p alea-report --release tests::full_report_is_written, with
#                ALEA_REPORT_TEST_OUT pointing at a fresh directory) and render that.
#   OUT_PNG      the screenshot to write (default: report-screenshot.png in the current dir).
#
# What it does:
#   1. installs Debian's `chromium` if it is missing (apt-get; needs root and the package
#      registry; no browser is downloaded any other way);
#   2. renders the page headless at 1280 x 4000 CSS pixels to OUT_PNG (no network, no GPU,
#      a throw-away profile);
#   3. checks the screenshot exists, is a PNG of that size (signature and IHDR) and is not
#      blank (a blank page of that size compresses to a few kB; a rendered report is far larger).
# Exit status 0 when all checks pass. Look at OUT_PNG yourself for the layout.
#
# Environment: CARGO_TARGET_DIR is honoured when the default report is built.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
report="${1:-}"
out="${2:-report-screenshot.png}"
width=1280
height=4000

if [[ -z "$report" ]]; then
    dir="$(mktemp -d)"
    echo "building the synthetic test report in $dir"
    (cd "$here" && ALEA_REPORT_TEST_OUT="$dir" \
        cargo test -p alea-report --release tests::full_report_is_written -- --exact >/dev/null)
    report="$dir/report.html"
fi
[[ -f "$report" ]] || { echo "error: no report at $report" >&2; exit 2; }
report="$(cd "$(dirname "$report")" && pwd)/$(basename "$report")"

browser=""
for b in chromium chromium-browser google-chrome; do
    if command -v "$b" >/dev/null 2>&1; then browser="$b"; break; fi
done
if [[ -z "$browser" ]]; then
    echo "installing Debian's chromium"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update >/dev/null
    apt-get install -y chromium >/dev/null || apt-get install -y chromium >/dev/null
    browser=chromium
fi

profile="$(mktemp -d)"
trap 'rm -rf "$profile"' EXIT
rm -f "$out"
"$browser" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync \
    --hide-scrollbars --user-data-dir="$profile" \
    --screenshot="$out" --window-size="$width,$height" "file://$report" >/dev/null 2>&1 || true

[[ -s "$out" ]] || { echo "error: no screenshot written" >&2; exit 1; }
sig="$(head -c 8 "$out" | od -An -tx1 | tr -d ' \n')"
[[ "$sig" == "89504e470d0a1a0a" ]] || { echo "error: $out is not a PNG" >&2; exit 1; }
w=$((16#$(dd if="$out" bs=1 skip=16 count=4 2>/dev/null | od -An -tx1 | tr -d ' \n')))
h=$((16#$(dd if="$out" bs=1 skip=20 count=4 2>/dev/null | od -An -tx1 | tr -d ' \n')))
size=$(stat -c %s "$out")
echo "screenshot $out: ${w} x ${h} px, $size bytes"
[[ "$w" -eq "$width" && "$h" -eq "$height" ]] || { echo "error: unexpected size" >&2; exit 1; }
# A blank 1280 x 4000 page compresses to a few kB; a rendered report is far larger.
[[ "$size" -gt 50000 ]] || { echo "error: screenshot looks blank ($size bytes)" >&2; exit 1; }
echo "ok: $report renders"
