#!/usr/bin/env bash
# Reports that tumble itself writes, in a real browser (viewer/tests/browser.mjs: Debian's chromium
# driven by playwright-core): the T-handle's; bodies that travel (a thrown box, a satellite over an
# orbit, two boxes flying apart), which must stay in view at every time checked; a run of 10⁵ samples, which must stay under 20 MB and be
# ready in under 3 s; and a run of 10⁵ bodies (a debris field given as a body table, drawn as instances
# of one shared box), which must be ready in under 10 s.
#   report_browser_test.sh TUMBLE SOURCE_DIR WORK_DIR
set -euo pipefail
tumble=$1 source=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
"$tumble" run "$source/examples/t_handle.toml" -o "$work/t_handle.csv" --report "$work/t_handle.html" --quiet
node "$source/viewer/tests/browser.mjs" "$work/t_handle.html"
for travels in thrown_box satellite; do
  "$tumble" run "$source/examples/$travels.toml" -o "$work/$travels.csv" --report "$work/$travels.html" --quiet
  node "$source/viewer/tests/browser.mjs" "$work/$travels.html"
done
cat > "$work/apart.toml" <<'TOML'
[simulation]
duration = 2.0
timestep = 0.01
output_interval = 0.05
[[bodies]]
name = "left"
shape = { type = "box", size = [0.1, 0.2, 0.3] }
density = 500.0
velocity = [-5.0, 0.0, 1.0]
angular_velocity = [3.0, 1.0, 8.0]
[[bodies]]
name = "right"
shape = { type = "box", size = [0.3, 0.2, 0.1] }
density = 500.0
position = [0.5, 0.0, 0.0]
velocity = [5.0, 2.0, 0.0]
angular_velocity = [0.0, 4.0, 1.0]
TOML
"$tumble" run "$work/apart.toml" -o "$work/apart.csv" --report "$work/apart.html" --quiet
node "$source/viewer/tests/browser.mjs" "$work/apart.html"
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
