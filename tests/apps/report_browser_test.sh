#!/usr/bin/env bash
# Reports that tumble itself writes, in a real browser (viewer/tests/browser.mjs: Debian's chromium
# driven by playwright-core): the T-handle's; a run of 10⁵ samples, which must stay under 20 MB and be
# ready in under 3 s; and a run of 10⁵ bodies (a debris field given as a body table, drawn as instances
# of one shared box), which must be ready in under 10 s.
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

# 10⁵ tumbling boxes a few centimetres long within 300 m (a debris field), moving 10 m or so in the
# run's 0.2 s. (Bodies packed closer overdraw each other, at seconds a frame in software WebGL.)
awk 'BEGIN { srand(2026); print "name,mass,I1,I2,I3,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz";
  for (i = 0; i < 100000; i++) { s = 0.01 + 0.02 * rand();
    printf "b%d,1,%g,%g,%g,%g,%g,%g,1,0,0,0,%g,%g,%g,%g,%g,%g\n", i, s, 1.5 * s, 2 * s,
      300 * rand() - 150, 300 * rand() - 150, 300 * rand(), 100 * rand() - 50, 100 * rand() - 50, 100 * rand() - 50,
      20 * rand() - 10, 20 * rand() - 10, 20 * rand() - 10 } }' > "$work/crowd.csv"
printf '[simulation]\nduration = 0.2\ntimestep = 0.01\noutput_interval = 0.05\n[[body_tables]]\nfile = "crowd.csv"\n' > "$work/crowd.toml"
"$tumble" run "$work/crowd.toml" -o "$work/crowd.csv.out.csv" --report "$work/crowd.html" --quiet
echo "a 1e5-body run's report: $(stat -c %s "$work/crowd.html") bytes"
TUMBLE_REPORT_READY_MS=10000 node "$source/viewer/tests/browser.mjs" "$work/crowd.html"
