#!/usr/bin/env bash
# Reports that tumble itself writes, in a real browser (viewer/tests/browser.mjs: Debian's chromium
# driven by playwright-core): the T-handle's, and a run of 10⁵ samples, which must stay under 20 MB and
# be ready in under 3 s.
#   report_browser_test.sh TUMBLE SOURCE_DIR WORK_DIR
set -euo pipefail
tumble=$1 source=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
"$tumble" run "$source/examples/t_handle.toml" -o "$work/t_handle.csv" --report "$work/t_handle.html" --quiet
node "$source/viewer/tests/browser.mjs" "$work/t_handle.html"
"$tumble" run "$source/examples/t_handle.toml" -o "$work/long.h5" --timestep 2e-4 --output-interval 2e-4 \
  --report "$work/long.html" --quiet
size=$(stat -c %s "$work/long.html")
echo "a 1e5-sample run's report: $size bytes"
[ "$size" -lt 20000000 ] || { echo "FAIL: over 20 MB"; exit 1; }
TUMBLE_REPORT_READY_MS=3000 node "$source/viewer/tests/browser.mjs" "$work/long.html"
