#!/usr/bin/env bash
# The whole `tumble run` process on 10^5 boxes beside MuJoCo's RK4, in one run (issue 21's targets):
#  - 10^5 boxes as the rows of a [[body_tables]] CSV file, gravity, 200 rk4 steps (h = 1 ms), samples
#    every 0.1 s (3 samples), CSV output: wall time and peak memory of the process;
#  - the same boxes as 10^5 [[bodies]] tables;
#  - MuJoCo 2.2.2's RK4 on 10^4 free boxes (bench/peers, built by bench/peers/run.sh): body-steps/s.
# The ratio is the time MuJoCo's RK4 would take for the run's 2·10^7 body-steps over tumble's whole
# process. REPEATS interleaved repetitions of each (default 3); min and median.
#   bash bench/whole_process.sh [REPEATS] [N]
#   TUMBLE=path/to/tumble bash bench/whole_process.sh     (another build of tumble, for an A/B)
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/lib.sh
repeats=${1:-3}
n=${2:-100000}
tumble=$(realpath "${TUMBLE:-build/release/bin/tumble}")
setup=build/release/bin/scene_setup
peers=build/peers/bin/peers
require_built "$tumble" "$setup"
require_peers "$peers"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$setup" --write "$work" "$n" 0.2 0.1

declare -A t m
mujoco_rates=""
for ((r = 0; r < repeats; r++)); do
  for scene in boxes bodies; do
    # GNU time: wall seconds and peak resident KiB of the whole process.
    read -r wall kib < <(cd "$work" && /usr/bin/time -f "%e %M" "$tumble" run "$scene.toml" -o "$scene.csv" -q 2>&1 >/dev/null | tail -1)
    t[$scene]+="$wall "
    m[$scene]+="$kib "
  done
  mujoco_rates+="$(mujoco_rk4_rate "$peers" "$work/peers.csv") "
done
read -r mj_min mj_med < <(echo "$mujoco_rates" | min_median)
steps=$((n * 200))
echo "# machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores; $(date -u +%F); ${TUMBLE:+another build of tumble (TUMBLE)}"
echo "# $n boxes, 200 rk4 steps, 3 samples to CSV; $repeats interleaved repetitions, medians (min in brackets)"
printf "%-44s %12s %12s\n" "what" "median" "min"
printf "%-44s %12.4g %12.4g\n" "MuJoCo 2.2.2 RK4, 10^4 boxes, body-steps/s" "$mj_med" "$mj_min"
for scene in boxes bodies; do
  read -r w_min w_med < <(echo "${t[$scene]}" | min_median)
  read -r k_min k_med < <(echo "${m[$scene]}" | min_median)
  label=$([ $scene = boxes ] && echo "[[body_tables]]" || echo "[[bodies]]")
  printf "%-44s %12.3f %12.3f\n" "$label: tumble run, wall s" "$w_med" "$w_min"
  printf "%-44s %12.0f %12.0f\n" "$label: peak MB" "$(calc "$k_med / 1024")" "$(calc "$k_min / 1024")"
  printf "%-44s %12.1f %12.1f\n" "$label: x MuJoCo RK4 (its median)" "$(calc "$steps / $mj_med / $w_med")" "$(calc "$steps / $mj_med / $w_min")"
done
