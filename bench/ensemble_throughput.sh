#!/usr/bin/env bash
# Monte Carlo studies against the engine they run on and against MuJoCo, in one run, on one thread:
#  - the plate study (bench/studies/plate_tumbling.toml: 4000 runs, rk4, h = 1e-3 s, 5 s, samples every
#    10 ms, a flip event, extrema, final values, drifts; draws on ω, an edge and the attitude);
#  - the T-handle study of examples/t_handle_ensemble.toml as bench/ensemble_scaling.sh runs it (20 s,
#    splitting, h = 0.02 s, a sample every step), on 1 and 2 threads;
#  - the engine alone: batch_throughput's rk4 rate for 10^4 free boxes (the plate study's batches, 256
#    runs at a time, is of that order), one step per call as a study with events takes them;
#  - MuJoCo 2.2.2's RK4 on 10⁴ free boxes (bench/peers, built by bench/peers/run.sh).
# REPEATS interleaved repetitions of each; min and median. Prints a table with the ratios; the study
# tables of 1 and 2 threads must be identical (checked).
#   bash bench/ensemble_throughput.sh [REPEATS] [OUT.csv]       (default 3, no CSV)
#   TUMBLE=path/to/tumble bash bench/ensemble_throughput.sh     (another build of tumble, for an A/B)
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/lib.sh
repeats=${1:-3}
csv=${2:-}
tumble=${TUMBLE:-build/release/bin/tumble}
engine=build/release/bin/batch_throughput
peers=build/peers/bin/peers
require_built "$tumble" "$engine"
require_peers "$peers"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp bench/studies/plate_tumbling.toml "$work/plate.toml"
cp examples/meshes/t_handle.stl "$work/"
sed -e 's/^duration = .*/duration = 20.0/' -e 's/^timestep = .*/timestep = 0.02/' \
    -e 's/^integrator = .*/integrator = "splitting"/' -e 's/^output_interval = .*/output_interval = 0.02/' \
    -e 's|mesh = "meshes/t_handle.stl"|mesh = "t_handle.stl"|' -e "s/^runs = .*/runs = 10000/" \
    -e 's/^trajectories = .*//' examples/t_handle_ensemble.toml > "$work/t_handle.toml"

seconds() {  # wall time of a command, in s
  local start end
  start=$(date +%s.%N)
  "$@" > /dev/null
  end=$(date +%s.%N)
  echo "$end - $start" | bc
}

declare -A t
engine_rates="" mujoco_rates=""
for ((r = 0; r < repeats; r++)); do
  t[plate]+="$(seconds "$tumble" ensemble "$work/plate.toml" -o "$work/plate.csv" --threads 1 -q --fresh) "
  t[th1]+="$(seconds "$tumble" ensemble "$work/t_handle.toml" -o "$work/th1.csv" --threads 1 -q --fresh) "
  t[th2]+="$(seconds "$tumble" ensemble "$work/t_handle.toml" -o "$work/th2.csv" --threads 2 -q --fresh) "
  # The engine: rk4 on 10^4 boxes, one step per call (column 6: the median of its repetitions).
  engine_rates+="$("$engine" "$work/engine.csv" 1 10000 rk4 1 1 | awk '$1 == "rk4" && $2 == 10000 && $4 == 1 {print $6}' | tail -1) "
  mujoco_rates+="$(mujoco_rk4_rate "$peers" "$work/peers.csv") "
done
cmp -s "$work/th1.csv" "$work/th2.csv" || { echo "FAIL: 1 and 2 threads wrote different tables" >&2; exit 1; }

read -r plate_min plate_med < <(echo "${t[plate]}" | min_median)
read -r th1_min th1_med < <(echo "${t[th1]}" | min_median)
read -r th2_min th2_med < <(echo "${t[th2]}" | min_median)
read -r eng_min eng_med < <(echo "$engine_rates" | min_median)
read -r mj_min mj_med < <(echo "$mujoco_rates" | min_median)
plate_steps=$((4000 * 5000))
plate_rate=$(calc "$plate_steps / $plate_med")
echo "# machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores; $(date -u +%F); ${TUMBLE:+another build of tumble (TUMBLE)}${TUMBLE:-build/release/bin/tumble}"
echo "# $repeats interleaved repetitions, medians (min in brackets); one thread unless said"
printf "%-44s %14s %14s\n" "what" "median" "min"
printf "%-44s %14.3f %14.3f\n" "plate study: 4000 runs, s" "$plate_med" "$plate_min"
printf "%-44s %14.4g %14.4g\n" "plate study: body-steps/s" "$plate_rate" "$(calc "$plate_steps / $plate_min")"
printf "%-44s %14.4g %14.4g\n" "engine rk4, 10^4 boxes, body-steps/s" "$eng_med" "$eng_min"
printf "%-44s %14.4g %14.4g\n" "MuJoCo 2.2.2 RK4, 10^4 boxes, body-steps/s" "$mj_med" "$mj_min"
printf "%-44s %14.1f\n" "plate study / MuJoCo RK4" "$(calc "$plate_rate / $mj_med")"
printf "%-44s %13.1f%%\n" "plate study / engine" "$(calc "100 * $plate_rate / $eng_med")"
printf "%-44s %14.0f %14.0f\n" "T-handle study, 10^4 runs: runs/s" "$(calc "10000 / $th1_med")" "$(calc "10000 / $th1_min")"
printf "%-44s %14.0f %14.0f\n" "  the same on 2 threads: runs/s" "$(calc "10000 / $th2_med")" "$(calc "10000 / $th2_min")"
printf "%-44s %14.2f\n" "  2 threads / 1 thread" "$(calc "$th1_med / $th2_med")"
if [ -n "$csv" ]; then
  {
    echo "quantity,median,min"
    echo "plate_seconds,$plate_med,$plate_min"
    echo "plate_body_steps_per_s,$plate_rate,$(calc "$plate_steps / $plate_min")"
    echo "engine_rk4_body_steps_per_s,$eng_med,$eng_min"
    echo "mujoco_rk4_body_steps_per_s,$mj_med,$mj_min"
    echo "t_handle_runs_per_s_1_thread,$(calc "10000 / $th1_med"),$(calc "10000 / $th1_min")"
    echo "t_handle_runs_per_s_2_threads,$(calc "10000 / $th2_med"),$(calc "10000 / $th2_min")"
  } > "$csv"
fi
