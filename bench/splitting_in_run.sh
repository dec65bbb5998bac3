#!/usr/bin/env bash
# splitting against rk4 inside `tumble run` (issue 21: splitting ≤ 3× rk4 per body-step): N tumbling
# boxes (a [[body_tables]] scene, gravity), DURATION s at h = 1 ms, a sample every 0.1 s to CSV. The
# stepping time of an integrator is its whole run less a run of the same scene with --duration 0 (set-up,
# the first sample, the files), all four interleaved, REPEATS times; medians (min in brackets).
#   bash bench/splitting_in_run.sh [REPEATS] [N] [DURATION]        (defaults 5, 10000, 2)
#   TUMBLE=path/to/tumble bash bench/splitting_in_run.sh            (another build of tumble)
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/lib.sh
repeats=${1:-5}
n=${2:-10000}
duration=${3:-2}
tumble=$(realpath "${TUMBLE:-build/release/bin/tumble}")
setup=build/release/bin/scene_setup
require_built "$tumble" "$setup"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$setup" --write "$work" "$n" "$duration" 0.1

wall() {  # wall seconds of one run
  (cd "$work" && /usr/bin/time -f "%e" "$tumble" run boxes.toml -o out.csv -q "$@" 2>&1 >/dev/null | tail -1)
}
declare -A t
for ((r = 0; r < repeats; r++)); do
  for integrator in rk4 splitting; do
    full=$(wall --integrator "$integrator")
    zero=$(wall --integrator "$integrator" --duration 0)
    t[$integrator]+="$(calc "$full - $zero") "
  done
done
steps=$(calc "$n * $duration * 1000")
echo "# machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores; $(date -u +%F); ${TUMBLE:+another build of tumble (TUMBLE)}"
echo "# $n boxes, $duration s at h = 1 ms, samples every 0.1 s to CSV; stepping = whole run - --duration 0 run; $repeats interleaved repetitions"
printf "%-36s %12s %12s %16s\n" "integrator" "median s" "min s" "body-steps/s"
for integrator in rk4 splitting; do
  read -r mn md < <(echo "${t[$integrator]}" | min_median)
  printf "%-36s %12.3f %12.3f %16.4g\n" "$integrator" "$md" "$mn" "$(calc "$steps / $md")"
done
read -r _ rk4_med < <(echo "${t[rk4]}" | min_median)
read -r _ sp_med < <(echo "${t[splitting]}" | min_median)
printf "%-36s %12.2f\n" "splitting / rk4 per body-step" "$(calc "$sp_med / $rk4_med")"
