#!/usr/bin/env bash
# Runs per second of a T-handle ensemble (examples/t_handle_ensemble.toml at 20 s per run, splitting at
# h = 0.02 s: exact for the free handle, so every step is within rounding of the exact solution, far
# below 1e-6 rad), on 1 thread, 2 threads and 2 MPI ranks of 1 thread, side by side: REPEATS
# interleaved repetitions of each, min and median wall time. Prints a table and writes CSV.
#   bash bench/ensemble_scaling.sh [RUNS] [REPEATS] [OUT.csv]      (defaults 10000 3, no CSV)
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-10000}
repeats=${2:-3}
csv=${3:-}
tumble=build/release/bin/tumble
[ -x "$tumble" ] || { echo "build the release preset first: bash scripts/build.sh release" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp examples/meshes/t_handle.stl "$work/"
sed -e 's/^duration = .*/duration = 20.0/' -e 's/^timestep = .*/timestep = 0.02/' \
    -e 's/^integrator = .*/integrator = "splitting"/' -e 's/^output_interval = .*/output_interval = 0.02/' \
    -e 's|mesh = "meshes/t_handle.stl"|mesh = "t_handle.stl"|' -e "s/^runs = .*/runs = $runs/" \
    -e 's/^trajectories = .*//' examples/t_handle_ensemble.toml > "$work/study.toml"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader
configs=("1 thread" "2 threads" "2 MPI ranks")
command_of() {
  case "$1" in
    "1 thread") echo "$tumble ensemble $work/study.toml -o $work/t1.csv --threads 1 -q" ;;
    "2 threads") echo "$tumble ensemble $work/study.toml -o $work/t2.csv --threads 2 -q" ;;
    "2 MPI ranks") echo "mpirun -np 2 --oversubscribe $tumble ensemble $work/study.toml -o $work/m2.csv --threads 1 -q" ;;
  esac
}
declare -A times
for ((r = 0; r < repeats; r++)); do
  for c in "${configs[@]}"; do
    command -v mpirun >/dev/null || [ "$c" != "2 MPI ranks" ] || continue
    start=$(date +%s.%N)
    $(command_of "$c") --fresh >/dev/null
    end=$(date +%s.%N)
    times[$c]+="$(echo "$end - $start" | bc) "
  done
done
cmp -s "$work/t1.csv" "$work/t2.csv" && { [ ! -f "$work/m2.csv" ] || cmp -s "$work/t1.csv" "$work/m2.csv"; } ||
  { echo "FAIL: the tables differ between configurations" >&2; exit 1; }
echo "# machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores; $(date -u +%F)"
echo "# $runs runs of the T-handle, 20 s each, splitting h = 0.02 s, events and extrema per run; $repeats interleaved repetitions"
echo "# the tables of every configuration are identical (checked)"
printf "%-12s %10s %10s %12s %12s %9s\n" config min_s median_s runs_per_s_min runs_per_s_med speedup
[ -n "$csv" ] && echo "config,runs,repeats,min_s,median_s,runs_per_s_median,speedup_median" > "$csv"
base=""
for c in "${configs[@]}"; do
  [ -n "${times[$c]:-}" ] || continue
  read -r min med < <(echo "${times[$c]}" | tr ' ' '\n' | grep . | sort -g | awk '{a[NR]=$1} END {print a[1], a[int((NR+1)/2)]}')
  [ -z "$base" ] && base=$med
  speed=$(echo "scale=3; $base / $med" | bc)
  printf "%-12s %10.3f %10.3f %12.0f %12.0f %9s\n" "$c" "$min" "$med" "$(echo "$runs / $min" | bc -l)" \
    "$(echo "$runs / $med" | bc -l)" "${speed}x"
  [ -n "$csv" ] && echo "$c,$runs,$repeats,$min,$med,$(echo "$runs / $med" | bc -l),$speed" >> "$csv"
done
