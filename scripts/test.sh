#!/usr/bin/env bash
# Every test: the formatting check, the GCC release build (warnings are errors), then the same suite
# built with Clang 14 under AddressSanitizer + UndefinedBehaviorSanitizer; that build's ctest also runs
# each libFuzzer target (fuzz/) for 5 s from its seed corpus (bench/fuzz.sh fuzzes for longer).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
status=0
echo "== formatting (.clang-format) =="
bash scripts/check-format.sh || status=1
for preset in release sanitize; do
  echo "== building and testing preset '$preset' =="
  bash scripts/build.sh "$preset"
  ctest --preset "$preset" -j "$(nproc)" || status=1
done
exit $status
