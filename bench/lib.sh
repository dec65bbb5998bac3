# Helpers the benchmark scripts source from the repository root (`source bench/lib.sh`).

# "min median" of the numbers on standard input (separated by blanks or lines).
min_median() { tr ' ' '\n' | grep . | sort -g | awk '{a[NR]=$1} END {print a[1], a[int((NR+1)/2)]}'; }

# Arithmetic on numbers like 6.04e+05 (bc reads no exponents): calc "2e7 / 4.5e5".
calc() { awk "BEGIN {printf \"%.6g\", $1}"; }

# Exits 2 unless every argument is an executable, naming how to build it.
require_built() {
  for p in "$@"; do
    [ -x "$p" ] || { echo "build the release preset first: bash scripts/build.sh release ($p)" >&2; exit 2; }
  done
}

# Exits 2 unless bench/peers' program is built.
require_peers() {
  [ -x "$1" ] || { echo "build the peers first: bash bench/peers/run.sh --sizes 1 --reps 1 (it builds $1)" >&2; exit 2; }
}

# MuJoCo 2.2.2's RK4 on 10^4 free boxes, body-steps/s, one run of bench/peers (PEERS CSV).
mujoco_rk4_rate() {
  "$1" "$2" --engines mujoco/rk4 --sizes 10000 --reps 1 --no-accuracy |
    awk '/mujoco\/rk4/ {for (i = 1; i <= NF; i++) if ($i ~ /^[0-9.]+e\+[0-9]+$/) {print $i; exit}}'
}
