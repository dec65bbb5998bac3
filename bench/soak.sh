#!/usr/bin/env bash
# Soak: 10^7 steps of a tumbling body with a sample every step (issue 10). Memory must stay flat over the
# run (the resident set sampled every second), and the output must be complete (10^7 + 1 samples).
#
#   bash bench/soak.sh [STEPS] [FORMAT]     # defaults: 10000000 hdf5 (csv also works; ~3 GB at 10^7)
#
# Prints the machine, the settings, the resident set over time (min, max, first and last samples) and
# the sample count found in the output; exits 1 if the memory grew by more than 10 % after the first
# 10 % of the run or if samples are missing.
set -euo pipefail
cd "$(dirname "$0")/.."
steps=${1:-10000000}
format=${2:-hdf5}
tumble=build/release/bin/tumble
[ -x "$tumble" ] || bash scripts/build.sh release >/dev/null
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
h=0.001
duration=$(awk -v n="$steps" -v h="$h" 'BEGIN { printf "%.17g", n * h }')
cat > "$work/soak.toml" <<TOML
# A T-handle-like box tumbling about its intermediate axis, sampled every step.
[simulation]
duration = $duration
timestep = $h
integrator = "rk4"
output_interval = 0

[[bodies]]
name = "box"
shape = { type = "box", size = [0.1, 0.2, 0.3] }
density = 2700
angular_velocity = [0.01, 10, 0]
angular_velocity_frame = "principal"
TOML
ext=$([ "$format" = hdf5 ] && echo h5 || echo csv)
echo "soak: $steps steps of rk4 (h = $h s), a sample every step, $format output"
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'), $(nproc) hardware threads"
"$tumble" run "$work/soak.toml" -o "$work/out.$ext" --quiet --force &
pid=$!
rss=()
while kill -0 "$pid" 2>/dev/null; do
  kb=$(awk '/VmRSS/ { print $2 }' "/proc/$pid/status" 2>/dev/null || true)
  [ -n "$kb" ] && rss+=("$kb")
  sleep 1
done
wait "$pid"
n=${#rss[@]}
printf '%s\n' "${rss[@]}" | sort -n > "$work/rss"
echo "resident set (MiB), sampled every second ($n samples): min $(( $(head -1 "$work/rss") / 1024 )), max $(( $(tail -1 "$work/rss") / 1024 )), first ${rss[0]:+$(( rss[0] / 1024 ))}, last ${rss[n-1]:+$(( rss[n-1] / 1024 ))}"
if [ "$format" = hdf5 ]; then
  samples=$(/usr/bin/python3 -c "import h5py, sys; print(h5py.File(sys.argv[1])['t'].shape[0])" "$work/out.h5")
else
  samples=$(( $(wc -l < "$work/out.csv") - 1 ))
fi
echo "output: $(du -h "$work/out.$ext" | cut -f1), $samples samples (expected $((steps + 1)))"
status=0
[ "$samples" -eq $((steps + 1)) ] || { echo "soak: samples missing"; status=1; }
# Flat: after the first tenth of the run (start-up, buffers filling), at most 10 % growth.
if [ "$n" -ge 10 ]; then
  after=("${rss[@]:$((n / 10))}")
  lo=$(printf '%s\n' "${after[@]}" | sort -n | head -1)
  hi=$(printf '%s\n' "${after[@]}" | sort -n | tail -1)
  echo "after the first tenth: $((lo / 1024)) to $((hi / 1024)) MiB"
  [ "$hi" -le $((lo + lo / 10)) ] || { echo "soak: memory grew"; status=1; }
fi
exit $status
